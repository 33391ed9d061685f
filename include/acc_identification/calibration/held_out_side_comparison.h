#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "acc_identification/calibration/side_fits.h"
#include "acc_identification/model/block_bootstrap.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
/// The engine both string-stability tests share: the base model's (string_stability_verdict.h,
/// which searches the other side of the margin m = 0 and adds the interval of allowed margins) and
/// the augmented models' (diagnosis/augmented_stability_verdict.h, which searches the other side of
/// the stability index). Each test plugs in its side search; this part is the same for both:
///  1. the held-out data must be long enough to judge (heldOutShortage);
///  2. the best stable and the best unstable model, each simulated on the held-out segments from
///     their own measured starts, give paired squared speed errors; d_t = e_stable^2 - e_unstable^2;
///  3. a moving-block bootstrap of d_t (blocks within segments; the block length fixed or from d's
///     correlation) gives p_value_stable_rejected (H0: E d <= 0, the stable model predicts at least
///     as well) and p_value_unstable_rejected (H0: E d >= 0);
///  4. the verdict (decideSides): "unstable" when p_value_stable_rejected <= alpha and the test
///     confirms the winning model lies strictly inside the unstable side, the mirror for "stable",
///     otherwise "undecided".
struct HeldOutComparisonOptions
{
  double alpha = 0.05;
  std::size_t bootstrap_replicates = 999;
  std::uint64_t seed = 20240601;
  /// Fixed block length [s]; 0: automatic, five correlation times of d_t (from its lag-1
  /// autocorrelation within segments) clamped to [min_block_length_s, max_block_length_s]. Either
  /// way at most 1/min_blocks of the held-out time.
  double block_length_s = 0.0;
  double min_block_length_s = 20.0;
  double max_block_length_s = 60.0;
  std::size_t min_blocks = 4;
  /// Below these the test is not run and the verdict is "undecided" with the reason.
  std::size_t min_held_out_samples = 300;
  double min_held_out_duration_s = 80.0;
};

/// What both tests report of the comparison. p-values are NaN (null in JSON) while not tested.
struct HeldOutVerdict
{
  StabilityVerdict verdict = StabilityVerdict::Undecided;
  /// The decided verdict's p-value; for "undecided" the smaller of the two.
  double p_value = std::numeric_limits<double>::quiet_NaN();
  double p_value_stable_rejected = std::numeric_limits<double>::quiet_NaN();    ///< H0: stable (E d <= 0)
  double p_value_unstable_rejected = std::numeric_limits<double>::quiet_NaN();  ///< H0: unstable (E d >= 0)
  double alpha = 0.05;
  /// D = mean of d_t over the held-out samples [m^2/s^2].
  double mean_squared_error_difference = std::numeric_limits<double>::quiet_NaN();
  std::size_t held_out_samples = 0;  ///< scored: all held-out samples but each segment's first
  double held_out_duration_s = 0.0;
  std::size_t bootstrap_replicates = 0;
  double block_length_s = 0.0;
  std::uint64_t seed = 0;
  std::string reason;  ///< why this verdict, in words
};

/// The held-out segments as the bootstrap sees them: each run's samples but its first (the
/// measured start of its simulation).
struct HeldOutSegments
{
  std::vector<std::size_t> scored_lengths;
  std::size_t scored_samples = 0;
  double duration_s = 0.0;
};

/// The segments of runs with at least two samples (shorter ones hold nothing to score).
HeldOutSegments heldOutSegmentsOf(const std::vector<CarFollowingRun>& held_out);

/// "" when the segments are long enough to judge, else why not, with the numbers.
std::string heldOutShortage(const HeldOutSegments& segments, const HeldOutComparisonOptions& options);

/// Squares of the errors, term by term.
std::vector<double> squared(const std::vector<double>& errors);

/// Step 2 for both tests: the two sides' held-out errors (heldOutErrors) as the comparison takes
/// them, with each side's held-out RMSE, and why they cannot be compared (heldOutDivergence; ""
/// when they can).
struct HeldOutSides
{
  std::vector<double> stable_squared;
  std::vector<double> unstable_squared;
  double stable_rmse_speed_mps = 0.0;
  double unstable_rmse_speed_mps = 0.0;
  std::string divergence;
};
HeldOutSides scoreHeldOutSides(const HeldOutErrors& stable, const HeldOutErrors& unstable,
                               const std::string& model_name = "");

/// Step 3: the bootstrap comparison of the two sides' held-out squared errors (one per scored
/// sample, the segments concatenated), and the scoring of further models against the better side.
class HeldOutSideComparison
{
public:
  /// The squared errors have one entry per scored sample of the segments (segments.scored_samples).
  HeldOutSideComparison(const std::vector<double>& stable_squared_errors,
                        const std::vector<double>& unstable_squared_errors, const HeldOutSegments& segments,
                        const HeldOutComparisonOptions& options);

  double meanDifference() const { return mean_difference_; }
  double pValueStableRejected() const { return p_value_stable_rejected_; }
  double pValueUnstableRejected() const { return p_value_unstable_rejected_; }
  double blockLengthS() const { return block_length_s_; }
  /// The stable side predicts at least as well (D <= 0).
  bool stableWins() const { return mean_difference_ <= 0.0; }
  /// p-value of H0 "a model with these held-out squared errors predicts at least as well as the
  /// better side", by the same bootstrap draws (the margin profile's test).
  double pValueWorseThanBetterSide(const std::vector<double>& squared_errors) const;
  /// The comparison's numbers into a test's result (not its verdict).
  void report(HeldOutVerdict& result) const;

private:
  std::vector<double> difference_;
  double mean_difference_ = 0.0;
  std::vector<double> better_side_squared_errors_;
  std::size_t block_samples_ = 1;
  double block_length_s_ = 0.0;
  MovingBlockBootstrap bootstrap_;
  double p_value_stable_rejected_ = 1.0;
  double p_value_unstable_rejected_ = 1.0;
  std::size_t replicates_ = 0;
  std::uint64_t seed_ = 0;
};

/// How decideSides ended.
enum class SideDecision
{
  Decided,                  ///< a side rejected and the winner strictly inside the other
  RejectedWinnerNotInside,  ///< a side rejected, but the winner is not strictly inside the other side
  NeitherRejected           ///< no p-value at or below alpha
};

/// Step 4: verdict and p_value of the result from its two p-values; the caller confirms whether
/// the model that wins on each side lies strictly inside it (the interval of allowed margins, or
/// the stability index), so that a winner on the boundary never decides.
SideDecision decideSides(HeldOutVerdict& result, bool unstable_strictly_inside, bool stable_strictly_inside);

/// "held-out speed RMSE best stable 0.71 m/s (index 0.2), best unstable ...; p(stable rejected) =
/// ..., p(unstable rejected) = ... (moving-block bootstrap, 999 replicates, blocks of 30 s)": the
/// numbers every reason starts with; the labels say where each side's model lies.
std::string describeComparison(const HeldOutVerdict& result, double stable_test_rmse_mps, const std::string& stable_label,
                               double unstable_test_rmse_mps, const std::string& unstable_label);

/// "(p (H0: stable) = 0.002; p (H0: unstable) = 0.97)": the p-values named by the hypothesis
/// each tests; "(not tested, no p-values)" when the comparison did not run (verdictText says NOT TESTED).
std::string pValuesText(const HeldOutVerdict& result);

/// The verdict and its p-values in words: "string UNSTABLE (p (H0: stable) = ...)", "UNDECIDED (...)",
/// or "NOT TESTED" for a test that did not run (as the reports and the campaign's headline count it:
/// a test that did not run decided nothing, and its default verdict, undecided, would say it did).
std::string verdictText(const HeldOutVerdict& result, const std::string& separator = " ");

}  // namespace acc
