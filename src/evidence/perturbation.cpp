#include "acc_identification/evidence/perturbation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool finiteAt(const std::vector<double>& time_s, const std::vector<double>& values, std::size_t i)
{
  return std::isfinite(time_s[i]) && std::isfinite(values[i]);
}

/// [first, end) index ranges where the first car's speed is below the threshold.
std::vector<std::pair<std::size_t, std::size_t>> belowThreshold(const std::vector<double>& time_s,
                                                                const std::vector<double>& speed_mps,
                                                                double threshold_mps)
{
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  bool inside = false;
  for (std::size_t i = 0; i < speed_mps.size(); ++i)
  {
    if (!finiteAt(time_s, speed_mps, i))
      continue;  // a missing sample neither starts nor ends a drop
    const bool below = speed_mps[i] < threshold_mps;
    if (below && !inside)
      ranges.push_back({i, i + 1});
    if (below)
      ranges.back().second = i + 1;
    inside = below;
  }
  return ranges;
}

/// Drops closer than merge_within_s joined; drops shorter than min_duration_s removed.
std::vector<std::pair<std::size_t, std::size_t>> mergeRanges(const std::vector<std::pair<std::size_t, std::size_t>>& ranges,
                                                             const std::vector<double>& time_s,
                                                             const PerturbationCriteria& criteria)
{
  std::vector<std::pair<std::size_t, std::size_t>> merged;
  for (const auto& range : ranges)
  {
    if (!merged.empty() && time_s[range.first] - time_s[merged.back().second - 1] < criteria.merge_within_s)
      merged.back().second = range.second;
    else
      merged.push_back(range);
  }
  std::vector<std::pair<std::size_t, std::size_t>> kept;
  for (const auto& range : merged)
  {
    if (time_s[range.second - 1] - time_s[range.first] >= criteria.min_duration_s)
      kept.push_back(range);
  }
  return kept;
}

/// Why the data do not hold the perturbation whole at its ends ("" when they do; a cut window is
/// judged by judgeCutWindows).
std::string describeIncomplete(bool onset_near_median, bool recovered, const std::vector<double>& time_s)
{
  const auto at = [](double t) { return printfText("%.1f s", t); };
  if (!onset_near_median)
    return "the first car's speed is already below its median where the data begin (" + at(time_s.front()) +
           "): no onset, the dip is cut off";
  if (!recovered)
    return "the first car's speed is still below its median when the data end (" + at(time_s.back()) +
           "): the dip is cut off";
  return "";
}

/// Index one past the last sample with time < limit_s, from `from` on.
std::size_t indexBefore(const std::vector<double>& time_s, std::size_t from, double limit_s)
{
  std::size_t i = from;
  while (i < time_s.size() && !(time_s[i] >= limit_s))
    ++i;
  return i;
}
}  // namespace

double finiteMedian(std::vector<double> values)
{
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }), values.end());
  if (values.empty())
    return kNaN;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  double median = values[mid];
  if (values.size() % 2 == 0)
    median = 0.5 * (median + *std::max_element(values.begin(), values.begin() + mid));
  return median;
}

std::vector<Perturbation> findPerturbations(const std::vector<double>& time_s, const std::vector<double>& lead_speed_mps,
                                            const PerturbationCriteria& criteria)
{
  std::vector<Perturbation> found;
  const double median = finiteMedian(lead_speed_mps);
  if (!std::isfinite(median))
    return found;
  const auto drops =
      mergeRanges(belowThreshold(time_s, lead_speed_mps, median - criteria.drop_below_median_mps), time_s, criteria);
  const auto near_median = [&](std::size_t i) {
    return finiteAt(time_s, lead_speed_mps, i) && lead_speed_mps[i] >= median - criteria.onset_below_median_mps;
  };
  for (const auto& drop : drops)
  {
    Perturbation p;
    p.lead_median_mps = median;
    // The onset: walk back to where the first car was still near its median (braking starts there).
    p.onset = drop.first;
    while (p.onset > 0 && !near_median(p.onset))
      --p.onset;
    p.end = std::min(drop.second, time_s.size() - 1);
    const bool recovered = drop.second < time_s.size();
    // A speed that never came back near the median since the last drop: one perturbation, not a
    // second one with the same onset (its dip would be counted twice). An onset at the last drop's
    // end is a speed back near the median there (at 1 Hz, for one sample): a perturbation of its own.
    if (!found.empty() && p.onset < found.back().end)
    {
      p.onset = found.back().onset;
      found.pop_back();
    }
    p.onset_s = time_s[p.onset];
    p.end_s = time_s[p.end];
    p.window_end = indexBefore(time_s, p.end, p.end_s + criteria.extension_s);
    p.window_end_s = time_s[p.window_end - 1];
    p.window_cut = p.window_end >= time_s.size();
    p.incomplete = describeIncomplete(near_median(p.onset), recovered, time_s);
    found.push_back(p);
  }
  judgeCutWindows(found, time_s, {{"the first car", &lead_speed_mps, 1}}, criteria);
  return found;
}

namespace
{
/// The car's mean speed over the pre-window before the onset (NaN without a finite sample).
double preWindowMeanMps(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                        const Perturbation& perturbation, const PerturbationCriteria& criteria)
{
  double sum = 0.0;
  std::size_t count = 0;
  const double pre_start_s = perturbation.onset_s - criteria.pre_window_s;
  for (std::size_t i = std::min(perturbation.onset + 1, speed_mps.size()); i-- > 0;)
  {
    if (std::isfinite(time_s[i]) && time_s[i] < pre_start_s)
      break;
    if (finiteAt(time_s, speed_mps, i))
    {
      sum += speed_mps[i];
      ++count;
    }
  }
  return count == 0 ? kNaN : sum / static_cast<double>(count);
}
}  // namespace

bool windowCovered(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                   const Perturbation& perturbation, const PerturbationCriteria& criteria)
{
  const std::size_t end = std::min(perturbation.window_end, speed_mps.size());
  if (!perturbation.incomplete.empty() || end <= perturbation.onset + 1 ||
      !finiteAt(time_s, speed_mps, perturbation.onset) || !finiteAt(time_s, speed_mps, end - 1))
    return false;
  std::size_t previous = perturbation.onset;
  for (std::size_t i = perturbation.onset + 1; i < end; ++i)
  {
    if (!finiteAt(time_s, speed_mps, i))
      continue;
    if (time_s[i] - time_s[previous] > criteria.max_bridged_hole_s)
      return false;
    previous = i;
  }
  return true;
}

namespace
{
/// Whether the speed rose again by kCutDipRecoveredShare of its dip after its lowest sample in
/// [onset, end): true too where the car has no finite sample in the window or before it (nothing of
/// its is measured).
bool recoveringFromItsDip(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                         const Perturbation& perturbation, const PerturbationCriteria& criteria)
{
  const double pre_mps = preWindowMeanMps(time_s, speed_mps, perturbation, criteria);
  const std::size_t end = std::min(perturbation.window_end, speed_mps.size());
  std::size_t lowest = end;
  for (std::size_t i = perturbation.onset; i < end; ++i)
    if (finiteAt(time_s, speed_mps, i) && (lowest == end || speed_mps[i] < speed_mps[lowest]))
      lowest = i;
  if (!std::isfinite(pre_mps) || lowest == end)
    return true;
  const double risen_mps = speed_mps[lowest] + kCutDipRecoveredShare * std::max(0.0, pre_mps - speed_mps[lowest]);
  for (std::size_t i = lowest + 1; i < end; ++i)
    if (finiteAt(time_s, speed_mps, i) && speed_mps[i] > risen_mps)
      return true;
  return false;
}
}  // namespace

void judgeCutWindows(std::vector<Perturbation>& perturbations, const std::vector<double>& time_s,
                     const std::vector<MeasuredSpeed>& cars, const PerturbationCriteria& criteria)
{
  for (Perturbation& p : perturbations)
  {
    if (!p.window_cut || !p.incomplete.empty())
      continue;
    for (const MeasuredSpeed& car : cars)
    {
      if (car.speed_mps == nullptr || recoveringFromItsDip(time_s, *car.speed_mps, p, criteria))
        continue;
      p.first_cut_order = car.order;
      p.cut_note = "the data end at " + printfText("%.1f s", time_s.back()) + ", before the dip window does (" +
                   printfText("%.1f s", p.end_s + criteria.extension_s) + "), with " + car.name +
                   "'s speed not yet rising again from its lowest: its dip and those behind it may be cut off";
      if (&car == &cars.front())
        p.incomplete = p.cut_note;
      break;
    }
  }
}

double dipDepthMps(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                   const Perturbation& perturbation, const PerturbationCriteria& criteria)
{
  if (!windowCovered(time_s, speed_mps, perturbation, criteria))
    return kNaN;
  const double pre_mps = preWindowMeanMps(time_s, speed_mps, perturbation, criteria);
  double minimum = std::numeric_limits<double>::infinity();
  for (std::size_t i = perturbation.onset; i < perturbation.window_end && i < speed_mps.size(); ++i)
  {
    if (finiteAt(time_s, speed_mps, i))
      minimum = std::min(minimum, speed_mps[i]);
  }
  if (!std::isfinite(pre_mps) || !std::isfinite(minimum))
    return kNaN;
  return pre_mps - minimum;
}

double distanceLostM(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                     const Perturbation& perturbation, const PerturbationCriteria& criteria)
{
  const double pre_mps = preWindowMeanMps(time_s, speed_mps, perturbation, criteria);
  // A window not covered: the loss there is unknown, not zero.
  if (!std::isfinite(pre_mps) || !windowCovered(time_s, speed_mps, perturbation, criteria))
    return kNaN;
  const std::size_t end = std::min(perturbation.window_end, speed_mps.size());
  double lost_m = 0.0;
  std::size_t previous = perturbation.onset;
  for (std::size_t i = perturbation.onset + 1; i < end; ++i)
  {
    if (!finiteAt(time_s, speed_mps, i))
      continue;
    const double step_s = time_s[i] - time_s[previous];
    lost_m += 0.5 * step_s * (std::max(0.0, pre_mps - speed_mps[previous]) + std::max(0.0, pre_mps - speed_mps[i]));
    previous = i;
  }
  return lost_m;
}

namespace
{
/// The least-squares slope of the speed over [t_i, t_i + span] (samples before `end`): a
/// straight line through every sample, not the two end points, so white speed noise adds less to
/// a peak taken over many spans. NaN when a sample at either end is missing, a hole inside is
/// longer than criteria.max_bridged_hole_s, or the span runs past `end`.
double rateOverSpan(const std::vector<double>& time_s, const std::vector<double>& speed_mps, std::size_t i,
                    std::size_t end, const PerturbationCriteria& criteria)
{
  if (!finiteAt(time_s, speed_mps, i))
    return kNaN;
  // (A microsecond of tolerance: 0.1 s steps do not add up to exactly one second.)
  const std::size_t last = indexBefore(time_s, i, time_s[i] + criteria.acceleration_span_s - 1e-6);
  if (last >= end || !finiteAt(time_s, speed_mps, last))
    return kNaN;
  double sum_t = 0.0, sum_v = 0.0, sum_tt = 0.0, sum_tv = 0.0, previous_s = time_s[i];
  std::size_t n = 0;
  for (std::size_t k = i; k <= last; ++k)
  {
    if (!finiteAt(time_s, speed_mps, k))
      continue;
    if (time_s[k] - previous_s > criteria.max_bridged_hole_s)
      return kNaN;
    previous_s = time_s[k];
    const double t = time_s[k] - time_s[i], v = speed_mps[k];
    sum_t += t;
    sum_v += v;
    sum_tt += t * t;
    sum_tv += t * v;
    ++n;
  }
  const double count = static_cast<double>(n), spread = count * sum_tt - sum_t * sum_t;
  return spread > 0.0 ? (count * sum_tv - sum_t * sum_v) / spread : kNaN;
}

/// The steepest braking and recovery slopes around the minimum at `lowest` (see DipShape).
void peakRates(const std::vector<double>& time_s, const std::vector<double>& speed_mps, const Perturbation& perturbation,
               std::size_t lowest, std::size_t end, const PerturbationCriteria& criteria, DipShape* shape)
{
  // Braking spans may start up to a span before the onset (the first car's onset is where its
  // speed has already left the median by a little) and end at the minimum; recovery spans start there.
  std::size_t first = perturbation.onset;
  while (first > 0 && std::isfinite(time_s[first - 1]) &&
         time_s[first - 1] >= perturbation.onset_s - criteria.acceleration_span_s - 1e-6)
    --first;
  double braking = -std::numeric_limits<double>::infinity(), recovery = -std::numeric_limits<double>::infinity();
  for (std::size_t i = first; i < end; ++i)
  {
    const double rate = rateOverSpan(time_s, speed_mps, i, i < lowest ? lowest + 1 : end, criteria);
    if (!std::isfinite(rate))
      continue;
    if (i < lowest)
      braking = std::max(braking, -rate);
    else
      recovery = std::max(recovery, rate);
  }
  if (std::isfinite(braking))
    shape->braking_mps2 = braking;
  if (std::isfinite(recovery))
    shape->recovery_mps2 = recovery;
}

/// The time at which the speed crosses `level` between the finite samples `from` and `to`
/// (linear interpolation); NaN across a hole longer than the bridged one.
double crossingTime(const std::vector<double>& time_s, const std::vector<double>& speed_mps, std::size_t from,
                    std::size_t to, double level, const PerturbationCriteria& criteria)
{
  const double step_s = time_s[to] - time_s[from];
  if (step_s > criteria.max_bridged_hole_s)
    return kNaN;
  const double change = speed_mps[to] - speed_mps[from];
  const double share = change == 0.0 ? 0.0 : (level - speed_mps[from]) / change;
  return time_s[from] + std::clamp(share, 0.0, 1.0) * step_s;
}

/// The dip's full width at half depth (see DipShape): from the first crossing below the level to
/// the first crossing back above it after the minimum.
double halfDepthWidthS(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                       const Perturbation& perturbation, std::size_t lowest, std::size_t end, double level,
                       const PerturbationCriteria& criteria)
{
  // The speed is below the level at the minimum at the latest (the level lies above it).
  double down_s = kNaN;
  std::size_t previous = perturbation.onset;
  for (std::size_t i = perturbation.onset; i <= lowest; ++i)
  {
    if (!finiteAt(time_s, speed_mps, i))
      continue;
    if (speed_mps[i] < level)
    {
      down_s = i == perturbation.onset ? time_s[i] : crossingTime(time_s, speed_mps, previous, i, level, criteria);
      break;
    }
    previous = i;
  }
  if (std::isnan(down_s))
    return kNaN;  // the crossing lies in a hole
  previous = lowest;
  for (std::size_t i = lowest + 1; i < end; ++i)
  {
    if (!finiteAt(time_s, speed_mps, i))
      continue;
    if (speed_mps[i] >= level)
      return crossingTime(time_s, speed_mps, previous, i, level, criteria) - down_s;
    previous = i;
  }
  return kNaN;  // still below half its dip at the window's end
}
}  // namespace

DipShape dipShape(const std::vector<double>& time_s, const std::vector<double>& speed_mps,
                  const Perturbation& perturbation, const PerturbationCriteria& criteria)
{
  DipShape shape;
  // As for the distance lost: a window not covered may hide the dip, so it is unknown.
  if (!windowCovered(time_s, speed_mps, perturbation, criteria))
    return shape;
  const std::size_t end = std::min(perturbation.window_end, speed_mps.size());
  std::size_t lowest = perturbation.onset;
  for (std::size_t i = perturbation.onset; i < end; ++i)
  {
    if (finiteAt(time_s, speed_mps, i) && speed_mps[i] < speed_mps[lowest])
      lowest = i;
  }
  peakRates(time_s, speed_mps, perturbation, lowest, end, criteria, &shape);
  const double pre_mps = preWindowMeanMps(time_s, speed_mps, perturbation, criteria);
  if (std::isfinite(pre_mps) && pre_mps > speed_mps[lowest])
    shape.width_s = halfDepthWidthS(time_s, speed_mps, perturbation, lowest, end, 0.5 * (pre_mps + speed_mps[lowest]),
                                    criteria);
  return shape;
}

}  // namespace acc
