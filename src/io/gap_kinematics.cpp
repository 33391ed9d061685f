#include "acc_identification/io/gap_kinematics.h"

#include <cmath>

#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// One window: the measured gap change and the change the speeds say, from `first` to `last`.
struct Window
{
  const CarFollowingRun* run = nullptr;
  std::size_t first = 0, last = 0;
  double gap_change_m = 0.0, speed_change_m = 0.0;
  double mismatch() const { return gap_change_m - speed_change_m; }
};

/// Consecutive windows of at least window_s within the run; the integral by trapezoids.
void addWindows(const CarFollowingRun& run, double window_s, std::vector<Window>* windows)
{
  std::size_t first = 0;
  double integral = 0.0;
  for (std::size_t k = 1; k < run.size(); ++k)
  {
    integral += gapChangeBySpeedsM(run, k);
    if (run.time_s[k] - run.time_s[first] >= window_s)
    {
      windows->push_back({&run, first, k, run.space_gap_m[k] - run.space_gap_m[first], integral});
      first = k;
      integral = 0.0;
    }
  }
}

/// The ratio's disagreement in words ("" when it is within bounds, or not judged).
std::string describeScale(const GapKinematics& k, const GapKinematicsOptions& options)
{
  if (!k.ratio_judged || (k.scale >= options.min_scale && k.scale <= options.max_scale))
    return "";
  return "the gap and the speeds disagree: over " + std::to_string(k.windows) + " windows of " +
         printfText("%g s the gap changes at %.2g", options.window_s, k.scale) +
         " of the rate the speed difference says (1 when the gap is in metres and the speeds in m/s; "
         "speeds in km/h give 0.28, a gap in feet 3.3): check the units" +
         (k.scale > 0.0 ? std::string()
                        : " (a ratio at or below 0 is no unit: the gap's sign, or a gap and speeds of different cars)");
}

void describeJumps(const GapKinematics& k, const GapKinematicsOptions& options, std::vector<std::string>* warnings)
{
  if (k.jump_windows == 0)
    return;
  warnings->push_back(k.worst_run +
                      printfText(": the gap changes by %+.1f m from t = %.1f s to %.1f s where the speeds say %+.1f m",
                                 k.worst_gap_change_m, k.worst_start_s, k.worst_end_s, k.worst_speed_change_m) +
                      " (a lost target, a car cutting in, a sign or unit error?); " + std::to_string(k.jump_windows) +
                      " of " + std::to_string(k.windows) +
                      printfText(" windows are off by more than %g m", options.max_window_mismatch_m));
}

/// The windows' ratio, spread, mismatch and worst window into k, and their warnings.
void summarizeWindows(const std::vector<Window>& windows, const GapKinematicsOptions& options, GapKinematics* k)
{
  double gap_times_speed = 0.0, speed_squared = 0.0, speed_sum = 0.0, mismatch_squared = 0.0;
  const Window* worst = &windows.front();
  for (const Window& w : windows)
  {
    gap_times_speed += w.gap_change_m * w.speed_change_m;
    speed_squared += w.speed_change_m * w.speed_change_m;
    speed_sum += w.speed_change_m;
    mismatch_squared += w.mismatch() * w.mismatch();
    if (std::abs(w.mismatch()) > options.max_window_mismatch_m)
      ++k->jump_windows;
    if (std::abs(w.mismatch()) > std::abs(worst->mismatch()))
      worst = &w;
  }
  const double n = static_cast<double>(windows.size());
  k->scale = speed_squared > 0.0 ? gap_times_speed / speed_squared : GapKinematics::kNaN;
  k->relative_motion_m = std::sqrt(std::max(0.0, speed_squared / n - (speed_sum / n) * (speed_sum / n)));
  k->rms_mismatch_m = std::sqrt(mismatch_squared / n);
  k->worst_run = worst->run->name;
  k->worst_start_s = worst->run->time_s[worst->first];
  k->worst_end_s = worst->run->time_s[worst->last];
  k->worst_gap_change_m = worst->gap_change_m;
  k->worst_speed_change_m = worst->speed_change_m;
  k->ratio_judged = k->relative_motion_m >= options.min_relative_motion_m;
  k->unit_error = describeScale(*k, options);
  if (!k->unit_error.empty())
    k->warnings.push_back(k->unit_error);
  describeJumps(*k, options, &k->warnings);
}
}  // namespace

GapKinematics checkGapKinematics(const std::vector<CarFollowingRun>& runs, const GapKinematicsOptions& options)
{
  std::vector<Window> windows;
  for (const CarFollowingRun& run : runs)
    addWindows(run, options.window_s, &windows);
  GapKinematics k;
  k.windows = windows.size();
  if (!windows.empty())
    summarizeWindows(windows, options, &k);
  return k;
}
}  // namespace acc
