#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/calibration/margin_constrained_fit.h"
#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// The two side fits of the string-stability question, and how they are scored on data they were
/// not fitted to: shared by the fixed-sample test (string_stability_verdict.h) and the sequential verdict
/// (sequential_verdict.h), so both judge the same two models the same way.

/// One of the two side fits.
struct SideFit
{
  bool found = false;             ///< false when no fit exists on that side (then the rest is unset)
  AccParameters parameters;
  /// stabilityMargin(parameters): >= 0 for best_stable, <= 0 for best_unstable; a fit on the
  /// boundary m = 0 has |margin| of a few ulps.
  double margin = 0.0;
  double train_rmse_speed_mps = 0.0;
  double test_rmse_speed_mps = 0.0;  ///< over the held-out samples the test scores
  bool unconstrained_optimum = false;  ///< this is the training data's unconstrained optimum U
  std::string status;             ///< the optimiser's stop reason
};

/// The best string-stable and the best string-unstable fit to the objective's data.
struct SideFits
{
  SideFit stable;
  SideFit unstable;
  AccParameters unconstrained;  ///< U, the unconstrained optimum (one of the two sides)
  bool unconstrained_stable = false;
  std::size_t unconstrained_evaluations = 0;
  std::size_t constrained_evaluations = 0;
  /// Empty when both sides were found; else why not ("every start ... diverged", "no ... model").
  std::string failure;
};

/// U = calibrateMultistart(objective, multistart, warm_starts), then the best fit on the other
/// side of m = 0 (fitWithMarginConstraint, warm-started from U and other_side_warm_starts).
SideFits fitBothSides(const CalibrationObjective& objective, const MultistartOptions& multistart,
                      const ConstrainedFitOptions& constrained, const std::vector<AccParameters>& warm_starts,
                      const std::vector<AccParameters>& other_side_warm_starts = {});

/// The speed errors of one model on data it was not fitted to: each segment simulated from its
/// own measured start, every sample but the first (the measured start itself) from time
/// score_from_s on (the samples before it only bring the model's own state up to that time).
struct HeldOutErrors
{
  std::vector<double> error;
  bool diverged = false;
};

HeldOutErrors heldOutErrors(const AccParameters& p, const std::vector<CarFollowingRun>& held_out,
                            double score_from_s = -std::numeric_limits<double>::infinity());

/// The same for a model with effects (the diagnosis's augmented models): one scoring for both
/// string-stability tests.
HeldOutErrors heldOutErrors(const AccParameters& p, const EffectSettings& effects,
                            const std::vector<CarFollowingRun>& held_out,
                            double score_from_s = -std::numeric_limits<double>::infinity());

/// Why the two sides cannot be compared on the held-out data: "the best stable [model_name] model's
/// simulation diverges on the held-out data" (or unstable), "" when neither diverged. A diverged
/// prediction has no error to pair, and a verdict won by a model that blew up would say nothing
/// about string stability: both tests then leave the verdict undecided, untested, with this reason.
std::string heldOutDivergence(const HeldOutErrors& stable, const HeldOutErrors& unstable,
                              const std::string& model_name = "");

/// Standard deviation of the follower speed over all samples of the runs [m/s]: below about
/// 0.1 m/s (GNSS noise alone gives 0.06) there are no speed changes to tell the sides apart.
double followerSpeedStdMps(const std::vector<CarFollowingRun>& runs);

/// Lag-1 autocorrelation of the centred series within segments (segment_lengths sum to x.size()).
double lag1AutocorrelationWithinSegments(const std::vector<double>& x, const std::vector<std::size_t>& segment_lengths);

/// correlation_times correlation times of x as an AR(1) series (-mean_step_s / ln rho, rho its
/// lag-1 autocorrelation within segments), clamped to [min_s, max_s].
double correlationBlockLengthS(const std::vector<double>& x, const std::vector<std::size_t>& segment_lengths,
                               double mean_step_s, double correlation_times, double min_s, double max_s);

}  // namespace acc
