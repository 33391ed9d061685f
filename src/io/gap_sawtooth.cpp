#include "acc_identification/io/gap_sawtooth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "acc_identification/model/number_text.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
bool isSawtooth(const std::vector<double>& mismatches, double median, const GapSawtoothOptions& options)
{
  if (!(std::abs(median) > options.min_median_step_mismatch_m))
    return false;
  const auto near = std::count_if(mismatches.begin(), mismatches.end(), [&](double m) {
    return std::abs(m - median) <= options.near_median * std::abs(median);
  });
  return static_cast<double>(near) >= options.min_share_near_median * static_cast<double>(mismatches.size()) &&
         std::abs(meanOf(mismatches)) < options.max_mean_to_median * std::abs(median);
}

/// One saw-tooth window: where, its median step mismatch, and the rate and speed that tell a held
/// position from an extrapolated one.
struct SawtoothWindow
{
  double start_s = 0.0, end_s = 0.0;
  double median_m = 0.0;
  double median_rate_mps = 0.0;  ///< median_m over the window's median sample period
  double speed_mps = 0.0;        ///< the two cars' mean speed over the window
};

SawtoothWindow describeWindow(const CarFollowingRun& run, std::size_t first, std::size_t last, double median)
{
  std::vector<double> periods_s;
  double speed_sum = 0.0;
  for (std::size_t k = first + 1; k <= last; ++k)
  {
    periods_s.push_back(run.time_s[k] - run.time_s[k - 1]);
    speed_sum += 0.5 * (run.leader_speed_mps[k] + run.follower_speed_mps[k]);
  }
  return {run.time_s[first], run.time_s[last], median, median / interpolatedQuantile(periods_s, 0.5),
          speed_sum / static_cast<double>(last - first)};
}

/// Which car's position stood still between its updates, if the gap's extra rate is the cars' own
/// speed (within 25 %): the follower's when the gap grows, the leader's when it shrinks; else "".
std::string heldPosition(const SawtoothWindow& w)
{
  if (!(w.speed_mps > 1.0) || std::abs(std::abs(w.median_rate_mps) - w.speed_mps) > 0.25 * w.speed_mps)
    return "";
  return w.median_rate_mps > 0.0 ? "follower" : "leader";
}

/// The gap's step from sample k - 1 to k minus the step the speeds say [m]; 1 <= k < run.size().
double stepMismatchM(const CarFollowingRun& run, std::size_t k)
{
  return run.space_gap_m[k] - run.space_gap_m[k - 1] - gapChangeBySpeedsM(run, k);
}

/// The step mismatches of a run: [k] = stepMismatchM(run, k) for k >= 1; [0] = 0.
std::vector<double> stepMismatches(const CarFollowingRun& run)
{
  std::vector<double> mismatches(run.size(), 0.0);
  for (std::size_t k = 1; k < run.size(); ++k)
    mismatches[k] = stepMismatchM(run, k);
  return mismatches;
}

/// The samples of a saw-tooth window's steps (first + 1 ... last), extended through the
/// consecutive mismatched steps on either side.
std::pair<std::size_t, std::size_t> extendedSamples(const std::vector<double>& mismatches, std::size_t first,
                                                    std::size_t last, const GapSawtoothOptions& options)
{
  const auto mismatched = [&](std::size_t k) {
    return std::abs(mismatches[k]) > options.min_step_mismatch_to_extend_m;
  };
  std::size_t begin = first + 1, end = last + 1;
  while (begin > 1 && mismatched(begin - 1))
    --begin;
  while (end < mismatches.size() && mismatched(end))
    ++end;
  return {begin, end};
}

/// Adds a saw-tooth window of a run to the spans: it extends the last one when it reaches it, and
/// the span takes the sizes of its largest window.
void addSawtoothWindow(const CarFollowingRun& run, std::size_t run_index, const SawtoothWindow& w,
                       std::pair<std::size_t, std::size_t> samples, std::vector<GapSawtoothSpan>* spans)
{
  if (spans->empty() || spans->back().run_index != run_index || spans->back().end_sample < samples.first)
  {
    GapSawtoothSpan span;
    span.run = run.name;
    span.run_index = run_index;
    span.first_sample = samples.first;
    span.end_sample = samples.second;
    spans->push_back(span);
  }
  GapSawtoothSpan& span = spans->back();
  span.end_sample = std::max(span.end_sample, samples.second);
  span.start_s = run.time_s[span.first_sample];
  span.end_s = run.time_s[span.end_sample - 1];
  if (std::abs(w.median_m) > std::abs(span.median_step_mismatch_m))
  {
    span.median_step_mismatch_m = w.median_m;
    span.held_position = heldPosition(w);
  }
}

/// Whether step k goes against the span's drift: a reset to a fresh fix.
bool isReset(double mismatch_m, double median_m, const GapSawtoothOptions& options)
{
  return mismatch_m * median_m < 0.0 && std::abs(mismatch_m) > options.min_step_mismatch_to_extend_m;
}

void countResets(const std::vector<double>& mismatches, const GapSawtoothOptions& options, GapSawtoothSpan* span)
{
  span->resets = 0;
  for (std::size_t k = span->first_sample; k < span->end_sample; ++k)
    span->resets += isReset(mismatches[k], span->median_step_mismatch_m, options) ? 1 : 0;
}

void checkRun(const CarFollowingRun& run, std::size_t run_index, const GapSawtoothOptions& options,
              GapSawtooth* result)
{
  const std::vector<double> mismatches = stepMismatches(run);
  const std::size_t spans_before = result->spans.size();
  std::size_t first = 0;
  for (std::size_t k = 1; k < run.size(); ++k)
  {
    if (run.time_s[k] - run.time_s[first] < options.window_s)
      continue;
    ++result->windows;
    const std::vector<double> window(mismatches.begin() + static_cast<std::ptrdiff_t>(first) + 1,
                                     mismatches.begin() + static_cast<std::ptrdiff_t>(k) + 1);
    const double median = interpolatedQuantile(window, 0.5);
    if (isSawtooth(window, median, options))
    {
      ++result->sawtooth_windows;
      addSawtoothWindow(run, run_index, describeWindow(run, first, k, median),
                        extendedSamples(mismatches, first, k, options), &result->spans);
    }
    first = k;
  }
  for (std::size_t i = spans_before; i < result->spans.size(); ++i)
    countResets(mismatches, options, &result->spans[i]);
}
}  // namespace

GapSawtooth checkGapSawtooth(const std::vector<CarFollowingRun>& runs, const GapSawtoothOptions& options)
{
  GapSawtooth result;
  for (std::size_t i = 0; i < runs.size(); ++i)
    checkRun(runs[i], i, options, &result);
  return result;
}

std::string describeSawtoothSpan(const GapSawtoothSpan& span)
{
  std::string text = printfText("the gap saw-tooths from t = %.1f s to %.1f s: it steps %+.2f m per sample (median) "
                                "beyond what the speeds say",
                                span.start_s, span.end_s, span.median_step_mismatch_m);
  if (!span.held_position.empty())
    text += " (the " + span.held_position + "'s position held between its updates: the gap " +
            (span.held_position == "follower" ? "grows" : "shrinks") + " by the cars' own speed each sample)";
  return text + " and steps back (a position held, or extrapolated at a wrong rate, then reset): the gap there is " +
         "off by up to a few of its steps, the speeds are not affected";
}

void rebuildSawtoothGap(const GapSawtoothSpan& span, CarFollowingRun* run, const GapSawtoothOptions& options)
{
  if (span.first_sample == 0 || span.end_sample > run->size() || span.first_sample > span.end_sample)
    throw std::out_of_range("rebuildSawtoothGap: the span is not within the run");
  // Sample k is a fresh fix when the measured step onto it is a reset: read before any is rebuilt.
  std::vector<bool> fresh_fix;
  for (std::size_t k = span.first_sample; k < span.end_sample; ++k)
    fresh_fix.push_back(isReset(stepMismatchM(*run, k), span.median_step_mismatch_m, options));
  for (std::size_t k = span.first_sample; k < span.end_sample; ++k)
  {
    if (!fresh_fix[k - span.first_sample])
      run->space_gap_m[k] = run->space_gap_m[k - 1] + gapChangeBySpeedsM(*run, k);
  }
}

std::string describeGapRebuilt(const GapSawtoothSpan& span)
{
  return "the gap of its " + std::to_string(span.end_sample - span.first_sample) +
         " samples rebuilt from the fixes after its " + std::to_string(span.resets) +
         " resets and the speeds between them";
}
}  // namespace acc
