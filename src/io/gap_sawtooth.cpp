#include "acc_identification/io/gap_sawtooth.h"

#include <algorithm>
#include <cmath>

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

/// Adds a saw-tooth window of run to the spans: it extends the last one when it follows it
/// directly, and the span takes the sizes of its largest window.
void addSawtoothWindow(const std::string& run, const SawtoothWindow& w, std::vector<GapSawtoothSpan>* spans)
{
  if (spans->empty() || spans->back().run != run || spans->back().end_s != w.start_s)
    spans->push_back({run, w.start_s, w.end_s, 0.0, ""});
  GapSawtoothSpan& span = spans->back();
  span.end_s = w.end_s;
  if (std::abs(w.median_m) > std::abs(span.median_step_mismatch_m))
  {
    span.median_step_mismatch_m = w.median_m;
    span.held_position = heldPosition(w);
  }
}

void checkRun(const CarFollowingRun& run, const GapSawtoothOptions& options, GapSawtooth* result)
{
  std::size_t first = 0;
  std::vector<double> mismatches;
  for (std::size_t k = 1; k < run.size(); ++k)
  {
    mismatches.push_back(run.space_gap_m[k] - run.space_gap_m[k - 1] - gapChangeBySpeedsM(run, k));
    if (run.time_s[k] - run.time_s[first] < options.window_s)
      continue;
    ++result->windows;
    const double median = interpolatedQuantile(mismatches, 0.5);
    if (isSawtooth(mismatches, median, options))
    {
      ++result->sawtooth_windows;
      addSawtoothWindow(run.name, describeWindow(run, first, k, median), &result->spans);
    }
    first = k;
    mismatches.clear();
  }
}

/// One warning for all spans (the first few named): what the gap does, and what it is not.
std::string describeSpans(const GapSawtooth& result, const GapSawtoothOptions& options)
{
  constexpr std::size_t kNamed = 3;
  std::string text = "the gap saw-tooths: ";
  for (std::size_t i = 0; i < std::min(kNamed, result.spans.size()); ++i)
  {
    const GapSawtoothSpan& s = result.spans[i];
    text += (i > 0 ? "; " : "") + s.run +
            printfText(" from t = %.1f s to %.1f s steps %+.2f m per sample (median) beyond what the speeds say",
                       s.start_s, s.end_s, s.median_step_mismatch_m);
    if (!s.held_position.empty())
      text += " (the " + s.held_position + "'s position held between its updates: the gap " +
              (s.held_position == "follower" ? "grows" : "shrinks") + " by the cars' own speed each sample)";
  }
  if (result.spans.size() > kNamed)
    text += "; and " + std::to_string(result.spans.size() - kNamed) + " more stretches";
  return text + ", and steps back (a position held, or extrapolated at a wrong rate, then reset: the " +
         "gap there is off by up to a few of its steps, the speeds are not affected); " +
         std::to_string(result.sawtooth_windows) +
         " of " + std::to_string(result.windows) + printfText(" windows of %g s", options.window_s);
}
}  // namespace

GapSawtooth checkGapSawtooth(const std::vector<CarFollowingRun>& runs, const GapSawtoothOptions& options)
{
  GapSawtooth result;
  for (const CarFollowingRun& run : runs)
    checkRun(run, options, &result);
  if (!result.spans.empty())
    result.warnings.push_back(describeSpans(result, options));
  return result;
}
}  // namespace acc
