#include "acc_identification/calibration/held_out_side_comparison.h"
#include "acc_identification/model/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "acc_identification/calibration/side_fits.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
double sampleStepS(const HeldOutSegments& segments)
{
  return segments.duration_s / static_cast<double>(std::max<std::size_t>(1, segments.scored_samples));
}

/// The bootstrap's block length in samples: the options' fixed length, or five correlation times
/// of d; at most 1/min_blocks of the held-out time, at least one sample.
std::size_t blockSamplesFor(const std::vector<double>& difference, const HeldOutSegments& segments,
                            const HeldOutComparisonOptions& options)
{
  const double step_s = sampleStepS(segments);
  double block_s = options.block_length_s;
  if (!(block_s > 0.0))
    block_s = correlationBlockLengthS(difference, segments.scored_lengths, step_s, 5.0, options.min_block_length_s,
                                      options.max_block_length_s);
  block_s = std::min(block_s, segments.duration_s / static_cast<double>(std::max<std::size_t>(1, options.min_blocks)));
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(block_s / step_s)));
}
}  // namespace

HeldOutSegments heldOutSegmentsOf(const std::vector<CarFollowingRun>& held_out)
{
  HeldOutSegments segments;
  for (const CarFollowingRun& run : held_out)
  {
    if (run.size() < 2)
      continue;
    segments.scored_lengths.push_back(run.size() - 1);
    segments.scored_samples += run.size() - 1;
    segments.duration_s += run.durationS();
  }
  return segments;
}

std::string heldOutShortage(const HeldOutSegments& segments, const HeldOutComparisonOptions& options)
{
  if (segments.scored_samples >= options.min_held_out_samples && segments.duration_s >= options.min_held_out_duration_s)
    return "";
  return "too few held-out samples (" + std::to_string(segments.scored_samples) + " over " +
         significant(segments.duration_s) + " s; need " + std::to_string(options.min_held_out_samples) +
         " samples and " + significant(options.min_held_out_duration_s) + " s)";
}

std::vector<double> squared(const std::vector<double>& errors)
{
  std::vector<double> out(errors.size());
  for (std::size_t i = 0; i < errors.size(); ++i)
    out[i] = errors[i] * errors[i];
  return out;
}

HeldOutSides scoreHeldOutSides(const HeldOutErrors& stable, const HeldOutErrors& unstable,
                               const std::string& model_name)
{
  HeldOutSides sides;
  sides.stable_squared = squared(stable.error);
  sides.unstable_squared = squared(unstable.error);
  sides.stable_rmse_speed_mps = rootMeanOf(sides.stable_squared);
  sides.unstable_rmse_speed_mps = rootMeanOf(sides.unstable_squared);
  sides.divergence = heldOutDivergence(stable, unstable, model_name);
  return sides;
}

namespace
{
std::vector<double> differenceOf(const std::vector<double>& a, const std::vector<double>& b)
{
  std::vector<double> d(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    d[i] = a[i] - b[i];
  return d;
}
}  // namespace

HeldOutSideComparison::HeldOutSideComparison(const std::vector<double>& stable_squared_errors,
                                             const std::vector<double>& unstable_squared_errors,
                                             const HeldOutSegments& segments, const HeldOutComparisonOptions& options)
  : difference_(differenceOf(stable_squared_errors, unstable_squared_errors))
  , mean_difference_(meanOf(difference_))
  , better_side_squared_errors_(mean_difference_ <= 0.0 ? stable_squared_errors : unstable_squared_errors)
  , block_samples_(blockSamplesFor(difference_, segments, options))
  , block_length_s_(static_cast<double>(block_samples_) * sampleStepS(segments))
  , bootstrap_(segments.scored_lengths, block_samples_, options.bootstrap_replicates, options.seed)
  , p_value_stable_rejected_(bootstrap_.pValueMeanPositive(difference_))
  , p_value_unstable_rejected_(bootstrap_.pValueMeanNegative(difference_))
  , replicates_(options.bootstrap_replicates)
  , seed_(options.seed)
{
}

double HeldOutSideComparison::pValueWorseThanBetterSide(const std::vector<double>& squared_errors) const
{
  return bootstrap_.pValueMeanPositive(differenceOf(squared_errors, better_side_squared_errors_));
}

void HeldOutSideComparison::report(HeldOutVerdict& result) const
{
  result.p_value_stable_rejected = p_value_stable_rejected_;
  result.p_value_unstable_rejected = p_value_unstable_rejected_;
  result.mean_squared_error_difference = mean_difference_;
  result.block_length_s = block_length_s_;
  result.bootstrap_replicates = replicates_;
  result.seed = seed_;
}

SideDecision decideSides(HeldOutVerdict& result, bool unstable_strictly_inside, bool stable_strictly_inside)
{
  const bool reject_stable = result.p_value_stable_rejected <= result.alpha;
  const bool reject_unstable = result.p_value_unstable_rejected <= result.alpha;
  if (reject_stable && unstable_strictly_inside)
  {
    result.verdict = StabilityVerdict::Unstable;
    result.p_value = result.p_value_stable_rejected;
    return SideDecision::Decided;
  }
  if (reject_unstable && stable_strictly_inside)
  {
    result.verdict = StabilityVerdict::Stable;
    result.p_value = result.p_value_unstable_rejected;
    return SideDecision::Decided;
  }
  result.verdict = StabilityVerdict::Undecided;
  result.p_value = std::min(result.p_value_stable_rejected, result.p_value_unstable_rejected);
  return reject_stable || reject_unstable ? SideDecision::RejectedWinnerNotInside : SideDecision::NeitherRejected;
}

std::string describeComparison(const HeldOutVerdict& result, double stable_test_rmse_mps, const std::string& stable_label,
                               double unstable_test_rmse_mps, const std::string& unstable_label)
{
  std::ostringstream why;
  why << "held-out speed RMSE best stable " << significant(stable_test_rmse_mps) << " m/s (" << stable_label
      << "), best unstable " << significant(unstable_test_rmse_mps) << " m/s (" << unstable_label
      << "), mean paired squared-error difference " << significant(result.mean_squared_error_difference)
      << " m^2/s^2 over " << result.held_out_samples
      << " samples; p(stable rejected) = " << significant(result.p_value_stable_rejected)
      << ", p(unstable rejected) = " << significant(result.p_value_unstable_rejected) << " (moving-block bootstrap, "
      << result.bootstrap_replicates << " replicates, blocks of " << significant(result.block_length_s) << " s)";
  return why.str();
}

std::string verdictText(const HeldOutVerdict& result, const std::string& separator)
{
  if (!std::isfinite(result.p_value_stable_rejected) || !std::isfinite(result.p_value_unstable_rejected))
    return "NOT TESTED (no p-values)";
  return (result.verdict == StabilityVerdict::Undecided ? "" : "string ") + verdictInCapitals(result.verdict) + separator +
         pValuesText(result);
}

std::string pValuesText(const HeldOutVerdict& result)
{
  if (!std::isfinite(result.p_value_stable_rejected) || !std::isfinite(result.p_value_unstable_rejected))
    return "(not tested, no p-values)";
  char text[120];
  std::snprintf(text, sizeof text, "(p (H0: stable) = %.3g; p (H0: unstable) = %.3g)", result.p_value_stable_rejected,
                result.p_value_unstable_rejected);
  return text;
}

}  // namespace acc
