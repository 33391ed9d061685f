#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/calibration/held_out_side_comparison.h"
#include "acc_identification/calibration/margin_constrained_fit.h"
#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/calibration/quantity_identifiability.h"
#include "acc_identification/calibration/side_fits.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
/// The string-stability test: does the data decide whether a platoon of these ACC followers is
/// string stable (margin m = k1 tau_e^2 + 2 k2 tau_e - 2 >= 0), even where k1, k2, tau_e and eta
/// are not determined one by one?
///
/// Method (see testStringStability()):
///  1. Training and held-out data: the first and the second half of each run (the paper's
///     protocol), or segments given explicitly.
///  2. On the training data: the unconstrained optimum U (calibrateMultistart), and the best fit
///     on the other side of m = 0 (fitWithMarginConstraint: NLopt SLSQP with the margin as a
///     nonlinear constraint, multistart from U's projections onto m = 0 and Halton points).
///     best_stable = the best fit with m >= 0, best_unstable = the best with m <= 0; one is U.
///  3. On the held-out data, each model simulated from each held-out segment's own measured
///     start: paired squared speed errors d_t = e_stable(t)^2 - e_unstable(t)^2 (each segment's
///     first sample, the measured start, is left out), mean D. A moving-block bootstrap of d_t
///     (MovingBlockBootstrap; blocks within segments) gives two one-sided p-values:
///     p_value_stable_rejected (H0: the stable model predicts at least as well, E d <= 0) and
///     p_value_unstable_rejected (H0: E d >= 0).
///  4. The margins the data allow: for margins m0 of a grid, the best training fit with m = m0
///     (fitWithMarginConstraint with an equality constraint), fitted outwards from m = 0, each
///     warm-started from its neighbour's fit or from U (projected onto m0); m0 is allowed unless
///     its held-out squared errors exceed those of the better held-out side fit significantly
///     (the same bootstrap draws, one-sided, alpha). A direction stops after a few rejected
///     margins in a row beyond its side fit; each end of the allowed margins is then refined by
///     bisection. The side fits are points of this profile (at m = 0 the side fit on the boundary,
///     if one is), with the verdict's own p-values, so the side fit the test does not reject is
///     always allowed. [margin_low, margin_high] spans the allowed margins. Should a profile fit
///     beat a side fit on the training data, it replaces it and steps 3-4 are made again (once).
///  5. Verdict: "unstable" when p_value_stable_rejected <= alpha, "stable" when
///     p_value_unstable_rejected <= alpha, and only if the interval agrees (unstable: all allowed
///     margins < 0; stable: all > 0); otherwise "undecided" with the reason. A winner on the
///     boundary m = 0 (which belongs to both closed sides) therefore never decides.
///
/// Steps 1, 3 and the rule of step 5 are the engine shared with the augmented models' test
/// (held_out_side_comparison.h); this test plugs in its side search (step 2) and the margin
/// profile (step 4).
///
/// Cost: one multistart calibration of the training halves plus about ten local solves; with the
/// defaults about the time of one calibration of all the data (bench/bench_string_stability_verdict.cpp).
///
/// Typical use (the calibrate tool, the identifier node):
///   acc::StabilityTestOptions options;            // alpha 0.05, 999 replicates, fixed seed
///   options.warm_starts = {all_data_fit};         // optional
///   const acc::StabilityTestResult test = acc::testStringStability(runs, options);
///   json["stability_test"] = acc::toJson(test);   // with "identifiable_quantities" inside
///   if (test.verdict == acc::StabilityVerdict::Unstable) ...
struct StabilityTestOptions : HeldOutComparisonOptions
{
  ParameterBounds bounds;
  /// The unconstrained fit on the training data, with warm_starts first (e.g. the fit on all the
  /// data, or the previous window's).
  MultistartOptions multistart;
  std::vector<AccParameters> warm_starts;
  /// The fit on the other side of m = 0.
  ConstrainedFitOptions constrained;
  /// The fits with m = m0 of the margin profile: from the better of two warm starts (the
  /// neighbouring m0's fit and U, each projected onto m0), no Halton points.
  ConstrainedFitOptions profile = defaultProfileOptions();
  /// Margins m0 of the profile (0 is added; values outside [leastMargin, largestMargin] of the
  /// bounds are dropped). Empty: the interval is spanned by the two side fits alone.
  std::vector<double> margin_grid = defaultMarginGrid();
  /// The profile leaves the grid in each direction from 0 once this many margins in a row beyond
  /// that direction's side fit are rejected (0: every margin of the grid is fitted).
  std::size_t profile_stop_after_rejections = 3;
  /// Each end of the allowed margins is then refined by this many bisections between it and the
  /// rejected margin next to it (an end at the grid's edge is not).
  std::size_t interval_bisections = 5;

  /// Below these the test is not run and the verdict is "undecided" with the reason.
  std::size_t min_training_samples = 300;
  /// Standard deviation of the training follower speed below which there are no speed changes
  /// to learn the dynamics from (GNSS noise alone gives about 0.06 m/s).
  double min_training_speed_std_mps = 0.1;

  /// Also report assessQuantities() of the training fit on the training data.
  bool with_quantities = true;
  QuantityCriteria quantity_criteria;

  /// -2, -1.5, -1, -0.75, -0.5, -0.35, -0.2, -0.1, -0.05, 0, 0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1,
  /// 1.5, 2, 3, 4, 6, 8, 12, 16, 20: fine near the boundary, coarse far from it.
  static std::vector<double> defaultMarginGrid();
  /// ConstrainedFitOptions with no Halton starts, one local solve from the better warm start, at
  /// most 100 evaluations, relative f tolerance 1e-8.
  static ConstrainedFitOptions defaultProfileOptions();
};

/// One point of the margin profile.
struct MarginProfilePoint
{
  double margin = 0.0;
  AccParameters parameters;
  double train_rmse_speed_mps = 0.0;
  double test_rmse_speed_mps = 0.0;
  /// p-value of H0: this model predicts the held-out data at least as well as the better side fit.
  double p_value = 1.0;
  bool allowed = false;
  bool fitted = false;  ///< false: no feasible fit at this margin (then not allowed)
};

/// The verdict, its p-values and the comparison's numbers (HeldOutVerdict), and the base model's
/// own: both side fits, the margins allowed and the profile behind them.
struct StabilityTestResult : HeldOutVerdict
{
  bool tested = false;                     ///< the fits and the bootstrap ran (else see reason)

  SideFit best_stable;
  SideFit best_unstable;

  /// The margins the held-out data allow (the allowed margins tried that lie farthest out; each
  /// true end lies between it and the next margin tried beyond it). +inf (high) when the largest
  /// margin tried is still allowed and below the bounds' largest margin (78 by default): the
  /// interval is open there (null in JSON); likewise -inf below, though with the default grid the
  /// bounds' least margin (-2: tau_e = 0) closes it. Both infinite when the test did not run.
  double margin_low = -std::numeric_limits<double>::infinity();
  double margin_high = std::numeric_limits<double>::infinity();
  /// The allowed margins as runs of neighbouring allowed profile points, by increasing margin:
  /// one piece [margin_low, margin_high] unless rejected margins lie between allowed ones (a
  /// second valley of the fit, often with k1 near 0), which the span alone would count as allowed.
  std::vector<std::array<double, 2>> margin_allowed_pieces;
  std::string margin_interval_note;
  std::vector<MarginProfilePoint> margin_profile;  ///< by increasing margin

  std::size_t training_samples = 0;
  std::size_t held_out_segments = 0;

  std::optional<IdentifiableQuantities> quantities;  ///< of the training fit U (with_quantities)
  /// Cost: objective passes over the training data of each stage, and the wall time of it all.
  std::size_t unconstrained_evaluations = 0;
  std::size_t constrained_evaluations = 0;
  std::size_t profile_evaluations = 0;
  double solve_time_s = 0.0;
};

/// The paper's protocol: each run's first half (samples [0, n/2)) trains, its second half
/// ([n/2, n), simulated from its own measured start) is held out. Never throws on data problems:
/// short, flat or invalid data give "undecided" with the reason.
StabilityTestResult testStringStability(const std::vector<CarFollowingRun>& runs,
                                        const StabilityTestOptions& options = {});

/// The same with training and held-out segments given explicitly.
StabilityTestResult testStringStability(const std::vector<CarFollowingRun>& training,
                                        const std::vector<CarFollowingRun>& held_out,
                                        const StabilityTestOptions& options);

/// The "stability_test" object: {verdict ("stable" | "unstable" | "undecided"), p_value,
/// p_value_hypothesis ("stable" | "unstable": the H0 p_value tests; null when not tested),
/// p_value_stable_rejected, p_value_unstable_rejected, alpha, tested,
/// mean_squared_error_difference, best_stable: {parameters: {k1, k2, tau_e, eta}, margin,
/// train_rmse_speed, test_rmse_speed, unconstrained_optimum, status} (null when no fit was made),
/// best_unstable: {...}, margin_interval: [low, high] (null for an infinite end),
/// margin_allowed_pieces, margin_interval_note, margin_profile: [{margin, fitted, train_rmse_speed, test_rmse_speed,
/// p_value, allowed}], bootstrap: {replicates, block_length_s, seed}, training_samples,
/// held_out_samples, held_out_segments, reason, solve_time_s[, identifiable_quantities (see
/// toJson(const IdentifiableQuantities&))]}. RMSEs in m/s. NaN and infinities as null.
nlohmann::json toJson(const StabilityTestResult& result);
/// margin_allowed_pieces as [[low, high], ...] (null for an open end); [] when the test did not run.
nlohmann::json marginPiecesJson(const StabilityTestResult& result);

/// The verdict, its p-values, both side fits, the margins allowed and why, as lines of text.
void printStabilityTest(const StabilityTestResult& result, std::ostream& out);

/// The runs of neighbouring allowed points of a margin profile (sorted by margin), the outer ends
/// set to low and high (the span's ends, closed at the bounds or opened): margin_allowed_pieces.
std::vector<std::array<double, 2>> allowedMarginPieces(const std::vector<MarginProfilePoint>& points, double low,
                                                       double high);

/// The allowed margins as text: "[-2.000, -0.500]", or "[-2.000, +0.000] and [+3.000, +4.500]"
/// when rejected margins lie between (StabilityTestResult::margin_allowed_pieces).
std::string allowedMarginsText(const StabilityTestResult& result);

/// The null hypothesis result.p_value tests: "stable" for an unstable verdict, "unstable" for a
/// stable one, and for "undecided" the one whose p-value is the smaller (the p-value reported).
std::string pValueHypothesis(const StabilityTestResult& result);

}  // namespace acc
