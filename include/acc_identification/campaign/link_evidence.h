#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/campaign/campaign_inputs.h"
#include "acc_identification/evidence/empirical_response.h"
#include "acc_identification/campaign/group_identification.h"
#include "acc_identification/campaign/platoon_check.h"
#include "acc_identification/campaign/platoon_diagnosis.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/diagnosis/augmented_stability.h"
#include "acc_identification/diagnosis/determined_effects.h"
#include "acc_identification/diagnosis/final_model_bootstrap.h"
#include "acc_identification/calibration/refit_bootstrap.h"

namespace acc
{
/// What the data show of one car (vehicle, setting) as a link of a platoon, without a model and
/// beside its models: its dips against those of the car directly ahead, its empirical frequency
/// response against the base and the diagnosed model's |Gamma(jw)|, and the string stability of
/// the diagnosed model where it is defined.
struct LinkEvidence
{
  std::string vehicle;
  std::string setting;
  /// Follower dip / dip of the car directly ahead, over every perturbation of every platoon run
  /// where the car follows (model-free).
  DipRatioEstimate dip_ratio;
  /// Welch's |Gamma(jw)| from the car's and its leader's measured speeds (every run's pair
  /// segments, none straddled), with coherence and band (model-free).
  EmpiricalResponse response;
  double operating_speed_mps = 0.0;  ///< median follower speed: where the models are linearised
  /// |Gamma| at response.frequency_rad_s of the group's base model (identifyAcc on all its runs)
  /// and of its diagnosed model (the campaign's chosen candidate fitted on all its runs).
  std::vector<double> model_gain_base;
  std::vector<double> model_gain_diagnosed;
  /// Frequency ranges [rad/s] up to 2 rad/s where the empirical gain is informative (coherence at
  /// least 0.5 over at least 4 effective segments) and the model's lies outside its band: where the
  /// model departs from the data.
  std::vector<std::pair<double, double>> base_departs_rad_s;
  std::vector<std::pair<double, double>> diagnosed_departs_rad_s;
  /// The diagnosed model: its candidate, its fit on all the group's runs (base parameters, effect
  /// values, settings and standard errors), and its small-signal stability (for an asymmetric law,
  /// held to every branch: augmented_stability.h).
  PlatoonCandidate diagnosed;
  bool base_available = false;  ///< the group has a base fit (its |Gamma| is then known)
  bool diagnosed_available = false;
  AugmentedFit diagnosed_fit;
  AugmentedStability diagnosed_small_signal;
  /// The refitting bootstrap of the diagnosed model (bootstrapDiagnosedModel) when the group's
  /// runs are short (ShortRunsBootstrapOptions): intervals for its sizes that hold on
  /// short data, where the sandwich's standard errors run short. None otherwise.
  std::optional<RefitBootstrap> diagnosed_bootstrap;
  /// Simulated propagation: ten identical cars with the diagnosed model behind each platoon run's
  /// real first car, from equilibrium; the tenth car's dip over the first car's, median over the
  /// perturbations (NaN without one). Above 1: the model amplifies these real perturbations.
  double long_platoon_dip_ratio = 0.0;
  std::size_t long_platoon_perturbations = 0;
  /// The first of the ten cars (1-based) whose simulation ran away (left the simulator's bounds:
  /// a dip grown past standstill into the absurd) behind some run's first car; 0 when none did.
  /// That run's perturbations then give no ratio, and the text says so instead of a silent NaN.
  std::size_t long_platoon_ran_away_at_car = 0;
  /// The first of the ten cars (1-based) whose gap to the car ahead reached 0 (a collision) or whose
  /// speed went below 0 (the law has no floor: it drives backwards) behind some run's first car; 0
  /// when none did. The ratio is still the model's, but such a chain amplifies whatever it says.
  std::size_t long_platoon_breaks_down_at_car = 0;
  std::string long_platoon_breakdown;  ///< where and how ("car 7 in dynamic_part16: its gap reaches -25.9 m ...")
  bool long_platoon_collides = false;  ///< that breakdown is a collision (else driving backwards)
  /// Perturbations whose tenth car was still slowing when the next perturbation began: no ratio
  /// (it would be cut short), counted here.
  std::size_t long_platoon_unfinished = 0;
  std::string note;  ///< what could not be computed, and why
};

/// Which links collectLinkDips takes: platoons[run].perturbations[perturbation], the follower at
/// `position`.
using LinkDipFilter = std::function<bool(std::size_t run, std::size_t perturbation, int position)>;

/// The car's dips and those of the car directly ahead, perturbation by perturbation, over every
/// platoon run of its setting where it follows (only the links `include` takes; all when empty):
/// what linkDipRatio reads.
void collectLinkDips(const std::vector<PlatoonCheck>& platoons, const std::string& vehicle, const std::string& setting,
                     std::vector<double>* follower, std::vector<double>* leader, const LinkDipFilter& include = {});

/// The level at which a diagnosed model's effect sizes are called determined (the diagnosis's own
/// default, DiagnosisOptions::selection.alpha).
constexpr double kDiagnosedSizeAlpha = 0.05;

/// How precisely the group's runs pin each effect of the diagnosed model, in the order of
/// diagnosed.effects: its size against its none value, determined above the Bonferroni quantile
/// over the model's effects at kDiagnosedSizeAlpha (effectSizeIn). None where the model was not
/// fitted (the group has no base fit).
std::vector<EffectSize> diagnosedEffectSizes(const LinkEvidence& evidence);

/// A coherence averaged over fewer effective Welch segments is biased towards 1 (exactly 1 from one
/// segment): below this many the empirical response is not read.
constexpr double kMinEffectiveSegments = 4.0;

/// Whether the car's empirical frequency response rests on enough segments to be read.
inline bool responseRead(const LinkEvidence& evidence)
{
  return evidence.response.effective_segments >= kMinEffectiveSegments;
}

/// Number of identical cars in the simulated long platoon.
constexpr int kLongPlatoonCars = 10;

/// After its data, the long platoon's first car keeps its last speed this long [s], so that a
/// perturbation near the end can reach the tenth car and pass (each car passes it on a time gap
/// and a delay later: some 20-40 s down ten cars).
constexpr double kLongPlatoonTailS = 120.0;

/// How the campaign refits a bootstrap replicate of a car's diagnosed model: as it fitted the car.
/// The base model as calibrate's bootstrap refits it (refitBaseModel from base_fit, the group's
/// base fit, with options' starts), then the candidate by fitCandidate from that base and from
/// diagnosed_fit. Not diagnose's chain (refitAsDiagnosed), whose starts differ.
AugmentedRefit refitAsCampaignFitted(const PlatoonCandidate& candidate, const AccParameters& base_fit,
                                     const AugmentedFit& diagnosed_fit, const RefitBootstrapOptions& options);

/// candidate fitted on all the group's runs as fitCandidate fits every candidate (warm-started from
/// the group's base fit; a timing effect also from cold starts), result must be fitted: the
/// diagnosed model, and the part of it SUMO carries (campaign_sumo_export.h).
AugmentedFit fitOnAllRuns(const PlatoonCandidate& candidate, const CampaignGroup& group, const GroupResult& result);

/// Ten identical cars with evidence's diagnosed model behind the real first car of each platoon
/// run at setting (its data, then kLongPlatoonTailS at its last speed), from equilibrium at its
/// first speed: sets the tenth car's dip over the first car's (median over the perturbations; the
/// tenth car's dip taken from the onset to the next perturbation's onset, since the wave reaches
/// it long after the first car's dip window), how many perturbations gave one, those cut short,
/// and the first car whose simulation ran away or broke down (collided, drove backwards).
void simulateLongPlatoon(const CampaignInputs& inputs, const std::string& setting,
                         const PlatoonCheckOptions& platoon_options, LinkEvidence* evidence);

/// The evidence of every group (same order as result.groups), after the platoon check and its
/// diagnosis (result.platoons, result.effect_selection). Groups run on options.threads.
std::vector<LinkEvidence> gatherLinkEvidence(const CampaignInputs& inputs, const std::vector<GroupResult>& groups,
                                             const std::vector<PlatoonCheck>& platoons,
                                             const PlatoonCandidate& diagnosed, std::size_t threads,
                                             const PlatoonCheckOptions& platoon_options,
                                             const ShortRunsBootstrapOptions& bootstrap = {});

}  // namespace acc
