#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/held_out_side_comparison.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/model/follower_effects.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
/// Signed string-stability index of an augmented model (any effect of the catalogue):
///   index = k1 * min over w of (1 - |Gamma(j w)|^2) / w^2,
/// w on a logarithmic grid of 2000 frequencies from 1e-3 to 20 rad/s (10 Hz data show nothing faster), Gamma the
/// augmented transfer function (augmentedTransferGain). index >= 0 exactly when |Gamma| <= 1 on
/// the grid, i.e. when the model is string stable. For the paper's model
///   k1 (1 - |Gamma|^2) / w^2 = k1 (w^2 + k1 m) / D(w),  D = (k1 - w^2)^2 + (k2 + k1 tau_e)^2 w^2,
/// with m = k1 tau_e^2 + 2 k2 tau_e - 2 the margin, so its sign is the sign of m and its value
/// tends to m as w -> 0: the index is the augmented counterpart of the margin, used where only its
/// sign matters (the side constraints of the test below). 0 when k1 = 0.
double augmentedStabilityIndex(const AccParameters& p, const EffectSettings& effects, double operating_speed_mps);

/// The string-stability test of the model the diagnosis chose (an augmented model, or the base
/// model when no effect is significant), the counterpart of calibration/string_stability_verdict.h:
///  1. the chosen fit U (trained on the first parts) is on one side of the boundary; the best fit
///     on the other side is searched on the same training data: NLopt SLSQP on the unit-scaled
///     box of the base and effect parameters, with the exact gradient of the training MSE (the
///     simulator's sensitivities) and side * augmentedStabilityIndex >= 0 as a nonlinear
///     inequality constraint (its gradient by differences of the index's least term: the envelope
///     theorem), from U, from U moved onto the base
///     model's boundary (tau_e solving k1 tau^2 + 2 k2 tau = 2), from Halton points of the base
///     start box (the effect at U's values) and, when the model extends a nested one already
///     tested (a forward-selection step), from the nested test's best model on this side with the
///     new effect off, so a larger model's side is never fitted worse than its nested model's.
///     The best feasible point wins. (A derivative-free search, COBYLA, stopped far from the
///     side's optimum on the seven- and eight-parameter chain models, and the verdict moved
///     with its evaluation budget.)
///  2. both models are simulated on the held-out parts (each from its own measured start); the
///     paired squared speed errors d_t = e_stable(t)^2 - e_unstable(t)^2 (each part's first
///     sample, the measured start, left out) are resampled by a moving-block bootstrap
///     (MovingBlockBootstrap, blocks of block_length_s within parts): p_value_stable_rejected
///     tests H0 "the stable model predicts at least as well", p_value_unstable_rejected the
///     mirror.
///  3. "unstable" when p_value_stable_rejected <= alpha and the better model is strictly unstable
///     (index < 0); "stable" in the mirror case; otherwise "undecided" with the reason (also
///     when the held-out data are too short, the parts fitted on too steady (`excitation`), or no
///     fit exists on one side).
/// Steps 2 and 3 are the engine shared with the base model's test (held_out_side_comparison.h); this
/// test plugs in its side search (step 1). Unlike the base model's test there is no interval of
/// allowed margins: the augmented index is a sign, not a calibrated scale.
struct AugmentedStabilityTestOptions : HeldOutComparisonOptions
{
  /// Blocks of 30 s (shortened so that the held-out data hold at least min_blocks), fixed rather
  /// than from the correlation: the diagnosis compares many models on the same draws.
  AugmentedStabilityTestOptions() { block_length_s = 30.0; }
  /// The side fit: Halton starts besides U and its projection, evaluations per start (each a
  /// simulation with sensitivities), and the relative change of the training MSE that stops a start.
  std::size_t halton_starts = 12;
  int max_evaluations_per_start = 400;
  double relative_x_tolerance = 1e-6;
  double relative_mse_tolerance = 1e-10;
  /// Threads for the side search's starts (0: every core); the result does not depend on it.
  std::size_t threads = 1;
  /// The parts fitted on must have what calibrate fits on (its speed spread, samples and seconds):
  /// on a steady drive both sides' best models are the same ridge of eta + tau_e v, and the side
  /// that predicts a steady held-out part better says nothing of what the car does to a braking.
  /// calibrate gives no verdict on such data; neither does this test.
  IdentifiabilityCriteria excitation;
};

/// One side's best model.
struct AugmentedSideFit
{
  bool found = false;  ///< false when no point of that side was found (the rest is then unset)
  AccParameters base;
  std::vector<double> effect_values;  ///< in the catalogue's order, effect after effect (as the chosen fit)
  EffectSettings settings;
  double stability_index = std::numeric_limits<double>::quiet_NaN();
  double peak_gain_db = std::numeric_limits<double>::quiet_NaN();
  double train_rmse_speed_mps = std::numeric_limits<double>::quiet_NaN();
  double test_rmse_speed_mps = std::numeric_limits<double>::quiet_NaN();
};

/// The verdict, its p-values and the comparison's numbers (HeldOutVerdict), and the two side models.
struct AugmentedStabilityTestResult : HeldOutVerdict
{
  EffectKind effect = EffectKind::none;  ///< the chosen fit's effect (the last added, for a combination)
  std::vector<EffectKind> effects;       ///< every effect of the chosen model (effectsOf)
  AugmentedSideFit best_stable, best_unstable;
  std::size_t side_fit_evaluations = 0;
};

/// Runs the test for `chosen` (fitted on `train`; one effect or several, effectsOf(chosen)) with the data of the diagnosis: `train` the
/// first parts, `test` the held-out parts, operating_speed_mps the linearisation speed. bounds:
/// the search box of the base parameters (the diagnosis's own). nested: the same test of a model
/// whose effects are a subset of chosen's (the previous forward-selection step), or nullptr.
AugmentedStabilityTestResult testAugmentedStringStability(const AugmentedFit& chosen,
                                                          const std::vector<CarFollowingRun>& train,
                                                          const std::vector<CarFollowingRun>& test,
                                                          double operating_speed_mps,
                                                          const AugmentedCalibrationOptions& bounds,
                                                          const AugmentedStabilityTestOptions& options = {},
                                                          const AugmentedStabilityTestResult* nested = nullptr);

/// The result as JSON: {effect, effects, verdict, p_value, p_value_stable_rejected,
/// p_value_unstable_rejected, alpha, best_stable: {parameters, effect_parameters, stability_index,
/// peak_gain_db, train_rmse_speed, test_rmse_speed}, best_unstable: {...}, held_out_samples,
/// block_length_s, reason}; non-finite numbers as null.
nlohmann::json toJson(const AugmentedStabilityTestResult& result);

}  // namespace acc
