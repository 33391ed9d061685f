#include <acc_identification/relative_state/gap_doppler_consistency.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Samples on a 10 Hz grid carry float noise in their times; a window is "full" within this.
constexpr double kTimeTolerance_s = 1e-3;
}  // namespace

GapDopplerConsistency::GapDopplerConsistency(double window_s, double max_spacing_s)
  : window_s_(window_s), max_spacing_s_(max_spacing_s)
{
}

void GapDopplerConsistency::reset()
{
  history_.clear();
  recent_.clear();
  recent_sum_squares_ = recent_sum_cross_ = recent_sum_integral_squares_ = 0.0;
}

double GapDopplerConsistency::add(double time_s, double gap_m, double relative_speed_mps)
{
  if (!std::isfinite(gap_m) || !std::isfinite(relative_speed_mps))
    return kNaN;
  Sample sample{time_s, gap_m, relative_speed_mps, 0.0};
  if (!history_.empty())
  {
    const Sample& last = history_.back();
    double step_s = time_s - last.time_s;
    if (step_s <= 0.0 || step_s > max_spacing_s_)
      history_.clear();  // time went back or the data broke: restart the window
    else
      sample.integral_m = last.integral_m + 0.5 * (last.relative_speed_mps + relative_speed_mps) * step_s;
  }
  history_.push_back(sample);
  // Keep the oldest sample that is still at least W back.
  while (history_.size() > 1 && time_s - history_[1].time_s >= window_s_ - kTimeTolerance_s)
    history_.pop_front();

  while (!recent_.empty() && recent_.front().time_s <= time_s - window_s_)
  {
    const Residual& old = recent_.front();
    recent_sum_squares_ -= old.residual_m() * old.residual_m();
    recent_sum_cross_ -= old.gap_change_m * old.doppler_integral_m;
    recent_sum_integral_squares_ -= old.doppler_integral_m * old.doppler_integral_m;
    recent_.pop_front();
  }
  const Sample& start = history_.front();
  double span_s = time_s - start.time_s;
  if (span_s < window_s_ - kTimeTolerance_s || span_s > window_s_ + max_spacing_s_)
    return kNaN;
  const Residual window{time_s, gap_m - start.gap_m, sample.integral_m - start.integral_m};
  const double residual_m = window.residual_m();
  recent_.push_back(window);
  recent_sum_squares_ += residual_m * residual_m;
  recent_sum_cross_ += window.gap_change_m * window.doppler_integral_m;
  recent_sum_integral_squares_ += window.doppler_integral_m * window.doppler_integral_m;
  return residual_m;
}

double GapDopplerConsistency::recentRms() const
{
  if (recent_.empty())
    return kNaN;
  return std::sqrt(std::max(0.0, recent_sum_squares_) / static_cast<double>(recent_.size()));
}

double GapDopplerConsistency::recentGapPerDopplerSlope() const
{
  // The running sums lose a little to round-off as windows come and go: 0 or less is none.
  if (recent_.empty() || !(recent_sum_integral_squares_ > 0.0))
    return kNaN;
  return recent_sum_cross_ / recent_sum_integral_squares_;
}

double GapDopplerConsistency::recentDopplerIntegralRms() const
{
  if (recent_.empty())
    return kNaN;
  return std::sqrt(std::max(0.0, recent_sum_integral_squares_) / static_cast<double>(recent_.size()));
}

bool receiversLookSwapped(double gap_per_doppler_slope, double doppler_integral_rms_m, std::size_t windows)
{
  constexpr std::size_t kMinWindows = 10;
  constexpr double kMinDopplerIntegralRmsM = 1.0;
  constexpr double kSwappedSlopeBelow = -0.5;
  return windows >= kMinWindows && doppler_integral_rms_m >= kMinDopplerIntegralRmsM &&
         gap_per_doppler_slope < kSwappedSlopeBelow;
}

ConsistencySummary gapDopplerConsistency(const std::vector<double>& time_s, const std::vector<double>& gap_m,
                                         const std::vector<double>& relative_speed_mps, double window_s,
                                         double max_spacing_s)
{
  GapDopplerConsistency check(window_s, max_spacing_s);
  double sum_squares = 0.0, sum_cross = 0.0, sum_integral_squares = 0.0;
  std::size_t windows = 0;
  std::size_t n = std::min(time_s.size(), std::min(gap_m.size(), relative_speed_mps.size()));
  for (std::size_t i = 0; i < n; ++i)
  {
    double residual_m = check.add(time_s[i], gap_m[i], relative_speed_mps[i]);
    if (std::isfinite(residual_m))
    {
      sum_squares += residual_m * residual_m;
      sum_cross += check.lastGapChangeM() * check.lastDopplerIntegralM();
      sum_integral_squares += check.lastDopplerIntegralM() * check.lastDopplerIntegralM();
      ++windows;
    }
  }
  ConsistencySummary summary{windows > 0 ? std::sqrt(sum_squares / static_cast<double>(windows)) : kNaN, windows};
  if (windows > 0)
  {
    summary.doppler_integral_rms_m = std::sqrt(sum_integral_squares / static_cast<double>(windows));
    summary.gap_per_doppler_slope = sum_integral_squares > 0.0 ? sum_cross / sum_integral_squares : kNaN;
  }
  return summary;
}

}  // namespace acc
