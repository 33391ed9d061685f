#pragma once

#include <array>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

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

/// The files synthesize writes (empty: not asked for).
struct SynthesisFiles
{
  std::string leader_log, follower_log;  ///< NMEA, talker GN
  std::string truth_csv;                 ///< writeTruthCsv
  std::string parameters_json;           ///< synthesisJson
};

/// Writes the drive's files, the implausibility warnings first (on log, as "warning: ..."); false
/// after saying on log ("error: ...") what could not be written.
bool writeSynthesisFiles(const SynthesizedDrive& drive, const SynthesisOptions& options,
                         const std::string& setting_name, const SynthesisFiles& files, std::ostream& log);

/// The follower's parameters as synthesize's options give them: a named setting (paper_settings.h),
/// values overriding single parameters of it, or all four values (k1, k2, tau_e, eta, in that
/// order; empty: not given). *setting_name becomes the setting's name, or "custom" once a value
/// is overridden. False with the message when a parameter has no value.
bool chooseParameters(const std::string& setting, const std::array<std::optional<double>, 4>& values,
                      AccParameters* parameters, std::string* setting_name, std::string* error);

/// Parameters far from a real ACC can make the follower drive into the leader or backwards. The
/// files are still written (tests may want them), but the user is told, with counts: one line per
/// kind ("the gap is negative (a collision) in 3 epochs, first at t = 12.5 s"); none when plausible.
std::vector<std::string> implausibilityWarnings(const CarFollowingRun& run);

/// The options as JSON: {"parameters": {"k1_per_s2", "k2_per_s", "tau_e_s", "eta_m"},
/// "effects": {name: {parameter: value}}, "profile", "seed", "gnss_errors", "geometry", ...}.
std::string synthesisJson(const SynthesisOptions& options, const std::string& setting_name);

}  // namespace acc
