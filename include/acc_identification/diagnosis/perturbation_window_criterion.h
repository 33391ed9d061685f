#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/evidence/perturbation_windows.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
/// diagnose's pair-level judge beside the whole-run held-out MSE: how each effect's model predicts
/// the follower inside its leader's perturbations on the held-out parts, where a braking passed on
/// shows and the whole-run MSE barely sees it. The campaign's platoon diagnosis judges the same
/// windows at pair level (perturbation_windows.h, one engine).
struct PerturbationWindowOptions
{
  PerturbationCriteria perturbation;  ///< how a leader's perturbation and its window are found
  double alpha = 0.05;                 ///< family-wise, over the effects (wildClusterMaxT)
  double min_relative_improvement = 0.10;  ///< of the base model's mean window MSE
  std::size_t replicates = 1999;       ///< wild cluster bootstrap patterns drawn beyond seven perturbations
  std::uint64_t seed = 20240601;
};

/// One effect's model on the perturbation windows, against the base model.
struct PerturbationWindowScore
{
  EffectKind effect = EffectKind::none;
  double window_rmse_speed_mps = std::numeric_limits<double>::quiet_NaN();  ///< root of the mean window MSE
  PairedLossComparison versus_base;  ///< losses: window MSE [m^2/s^2], one cluster per perturbation
  double family_p_value = 1.0;       ///< versus_base's p within the family of all effects (max-t)
  bool significant = false;          ///< family_p_value <= alpha and at least the minimum improvement
};

struct PerturbationWindowCriterion
{
  std::size_t perturbations = 0;  ///< of the leaders in the held-out parts, with a scored window
  double base_window_rmse_speed_mps = std::numeric_limits<double>::quiet_NaN();
  std::vector<PerturbationWindowScore> effects;  ///< in the order given
  EffectKind named = EffectKind::none;  ///< the significant effect with the lowest window MSE
  std::string rule;                     ///< the rule in words
  std::string reason;                   ///< why nothing could be judged ("" when it could)
};

/// The held-out predictions of one model: one simulation per held-out part, in order.
using HeldOutPredictions = std::pair<EffectKind, const std::vector<SimulatedFollower>*>;

/// Finds the leader's perturbations in every held-out part (findPerturbations), scores the base
/// model and each effect's model by their speed MSE over each window (a simulation that ran away
/// before the window's end scores at the divergence bound, as the whole-run ranking does) and
/// compares each with the base model paired over perturbations (comparePairedLosses), all of them
/// as one family (wildClusterMaxT).
PerturbationWindowCriterion judgeOnPerturbationWindows(const std::vector<CarFollowingRun>& held_out,
                                                       const std::vector<SimulatedFollower>& base,
                                                       const std::vector<HeldOutPredictions>& effects,
                                                       const PerturbationWindowOptions& options = {});

/// The rule in words, for reports and JSON.
std::string perturbationWindowRule(const PerturbationWindowOptions& options, std::size_t candidates);

}  // namespace acc
