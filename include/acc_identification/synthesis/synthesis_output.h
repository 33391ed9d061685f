#pragma once

#include <string>

#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"
#include "acc_identification/synthesis/synthesis.h"

namespace acc
{
/// Reads "--effect NAME=V1[,V2]" (the diagnosis catalogue's names and parameter order, e.g.
/// actuation_lag=0.5, acceleration_limits=1.5,3.0) into settings, keeping the effects set
/// before. Returns false with a message when the name is unknown, the count of values is not the
/// effect's, a value is not a finite number, or the effect was already given.
bool addEffectOption(const std::string& text, EffectSettings* settings, std::string* error);

/// The effects switched on in settings, in catalogue order (none: empty).
std::vector<EffectKind> effectsOn(const EffectSettings& settings);

/// Canonical CSV (time_s,space_gap_m,follower_speed_mps,leader_speed_mps), each number the
/// shortest decimal that reads back as the same double, so that the file holds the simulation
/// exactly. False with a message when it cannot be written.
bool writeTruthCsv(const std::string& path, const CarFollowingRun& run, std::string* error);

/// The options as JSON: {"parameters": {"k1_per_s2", "k2_per_s", "tau_e_s", "eta_m"},
/// "effects": {name: {parameter: value}}, "profile", "seed", "gnss_errors", "geometry", ...}.
std::string synthesisJson(const SynthesisOptions& options, const std::string& setting_name);

}  // namespace acc
