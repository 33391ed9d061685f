#pragma once

#include <cmath>
#include <cstdint>

#include <ros/time.h>

namespace acc
{
/// The largest time ros::Time holds: its seconds are an unsigned 32-bit count.
constexpr double kLargestRosTimeS = 4294967295.0;

/// Seconds since the Unix epoch as ros::Time, rounded to the microsecond: a double near 1.6e9 s
/// carries about 0.2 us of noise, and NMEA times are centiseconds, so 10:15:30.3 stays
/// .300000000. A time ros::Time cannot hold (NaN, infinite, negative, from 2106 on) becomes 0,
/// "unset", instead of the exception ros::Time would throw: one bad stamp must not end a node.
inline ros::Time toRosTime(double seconds_since_epoch)
{
  if (!std::isfinite(seconds_since_epoch) || seconds_since_epoch < 0.0 || seconds_since_epoch >= kLargestRosTimeS)
  {
    return ros::Time();
  }
  const auto microseconds = static_cast<std::int64_t>(std::llround(seconds_since_epoch * 1e6));
  return ros::Time(static_cast<std::uint32_t>(microseconds / 1000000),
                   static_cast<std::uint32_t>(microseconds % 1000000) * 1000u);
}

}  // namespace acc
