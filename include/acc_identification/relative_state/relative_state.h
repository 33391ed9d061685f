#pragma once

#include <limits>
#include <string>

namespace acc
{
/// The leader/follower pair at one GNSS epoch: the ROS-free twin of msg/RelativeState.msg.
/// Distances in metres, speeds in m/s, times in seconds.
struct RelativeState
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  /// GNSS time of the pair (the follower's epoch), as GnssFix::gnss_time_s.
  double time_s = kNaN;
  bool has_date = false;

  double space_gap_m = kNaN;         ///< leader's rear bumper to follower's front bumper
  double follower_speed_mps = kNaN;
  double leader_speed_mps = kNaN;
  double relative_speed_mps = kNaN;  ///< leader minus follower (the paper's dv)
  double time_gap_s = kNaN;          ///< space_gap / follower_speed; NaN below the minimum speed

  double epoch_skew_s = kNaN;        ///< distance to the nearest leader epoch; 0 for an exact match
  double space_gap_sigma_m = kNaN;   ///< 1-sigma of the gap from the fixes' sigmas (GST)
  double gap_doppler_residual_m = kNaN;  ///< see GapDopplerConsistency
  bool valid = false;
  std::string invalid_reason;        ///< empty when valid
};

}  // namespace acc
