#include "acc_identification/ros/stability_look_schedule.h"

namespace acc
{
StabilityLookSchedule::StabilityLookSchedule(double look_period_s) : look_period_s_(look_period_s) {}

StabilityLookSchedule::Decision StabilityLookSchedule::decide(double now_s, std::uint64_t drive_samples, bool catch_up,
                                                              bool all_looks_published)
{
  Decision decision;
  const bool grown = drive_samples != last_look_samples_;
  const bool stalled = catch_up || drive_samples == previous_period_samples_;
  // The last samples came in a period whose look was due: that look was made as if more would come.
  // The data stopped since: the look at every sample is still owed, though the count has not grown.
  const bool final_look_owed = stalled && !grown && !last_look_data_stopped_ && last_look_samples_ > 0;
  if (catch_up && !grown && !final_look_owed && all_looks_published)
  {
    decision.run_period = false;
    return decision;
  }
  const bool due = now_s - last_look_s_ >= look_period_s_ || now_s < last_look_s_;
  previous_period_samples_ = drive_samples;
  if ((grown && (due || stalled)) || final_look_owed)
  {
    decision.look = true;
    decision.data_stopped = stalled;
    last_look_s_ = now_s;
    last_look_samples_ = drive_samples;
    last_look_data_stopped_ = stalled;
  }
  return decision;
}
}  // namespace acc
