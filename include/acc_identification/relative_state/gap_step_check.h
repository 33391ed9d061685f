#pragma once

#include <limits>
#include <string>

namespace acc
{
/// The gap must stay where the relative (Doppler) speed takes it from the last valid sample, also
/// across the samples held invalid since. The jump check compares a sample only with a valid one at
/// most jump_reference_max_age_s old, so a step that lasts longer passes it; a step no speed
/// explains is one receiver's time labels off (a leap second applied by one receiver only: 25 m
/// at 25 m/s, every sample after it wrong), or a position error, not a gap. So a sample whose gap
/// is further than max_step_m (plus the speeds' own drift) from the anchor's gap plus the
/// integral of the relative speed since is held invalid, until the gap agrees again. The chain
/// from the anchor breaks (nothing is said) at a hole longer than max_bridged_hole_s, time going
/// back, or a sample without speeds.
class GapStepCheck
{
public:
  /// @param max_step_m          the largest step of the gap the speeds need not explain (a
  ///                            receiver's position correcting, e.g. RTK fixing) [m]
  /// @param max_bridged_hole_s  samples further apart break the chain [s]
  GapStepCheck(double max_step_m, double max_bridged_hole_s);

  /// Starts again from a valid sample.
  void anchor(double time_s, double gap_m, double relative_speed_mps);
  /// Integrates the relative speed up to this sample (every sample whose speeds are the cars', valid
  /// or not); then "" when its gap agrees with the anchor's carried by the speeds, or when nothing can
  /// be said; else why not. A sample whose speed was rejected (a jump no car makes) is not checked:
  /// its speed would carry the anchor's gap off for good, and the next sample's step bridges it.
  std::string check(double time_s, double gap_m, double relative_speed_mps);
  /// No anchor: nothing is said until the next one (a break in the data).
  void reset();

private:
  double max_step_m_;
  double max_bridged_hole_s_;
  bool anchored_ = false;
  double anchor_time_s_ = 0.0;
  double anchor_gap_m_ = 0.0;
  double last_time_s_ = 0.0;
  double last_relative_speed_mps_ = 0.0;
  double integral_m_ = 0.0;  ///< of the relative speed since the anchor (trapezoids)
};
}  // namespace acc
