#include "acc_identification/relative_state/gap_step_check.h"

#include <cmath>

#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// How far the integral of two receivers' Doppler speed difference wanders from the gap's change
/// in 10 s [m]: 0.15-0.28 m RMS on the Casale runs (u-blox, 10 Hz); it grows as a random walk.
constexpr double kDopplerDriftPerTenSecondsM = 0.3;
}  // namespace

GapStepCheck::GapStepCheck(double max_step_m, double max_bridged_hole_s)
  : max_step_m_(max_step_m), max_bridged_hole_s_(max_bridged_hole_s)
{
}

void GapStepCheck::anchor(double time_s, double gap_m, double relative_speed_mps)
{
  anchored_ = std::isfinite(time_s) && std::isfinite(gap_m) && std::isfinite(relative_speed_mps);
  anchor_time_s_ = last_time_s_ = time_s;
  anchor_gap_m_ = gap_m;
  last_relative_speed_mps_ = relative_speed_mps;
  integral_m_ = 0.0;
}

void GapStepCheck::reset()
{
  anchored_ = false;
}

std::string GapStepCheck::check(double time_s, double gap_m, double relative_speed_mps)
{
  if (!anchored_)
    return "";
  const double step_s = time_s - last_time_s_;
  if (!(step_s > 0.0 && step_s <= max_bridged_hole_s_) || !std::isfinite(relative_speed_mps) || !std::isfinite(gap_m))
  {
    anchored_ = false;  // the chain from the anchor is broken: nothing to compare with
    return "";
  }
  integral_m_ += 0.5 * (last_relative_speed_mps_ + relative_speed_mps) * step_s;
  last_time_s_ = time_s;
  last_relative_speed_mps_ = relative_speed_mps;
  const double since_s = time_s - anchor_time_s_;
  const double expected_m = anchor_gap_m_ + integral_m_;
  const double allowed_m = max_step_m_ + kDopplerDriftPerTenSecondsM * std::sqrt(since_s / 10.0);
  const double unexplained_m = gap_m - expected_m;
  if (std::abs(unexplained_m) <= allowed_m)
    return "";
  return printfText("gap jump of %+.2f m since the last valid sample %.2f s before that the Doppler speeds do not "
                   "explain (they carry its %.2f m to %.2f m): one receiver's time labels off (a leap second "
                   "applied by one only), or a position error; held until the gap agrees again",
                   unexplained_m, since_s, anchor_gap_m_, expected_m);
}
}  // namespace acc
