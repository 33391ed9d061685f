#pragma once

#include <cmath>
#include <cstdint>

#include <ros/time.h>

namespace acc
{
/// The largest whole second ros::Time holds: its seconds are an unsigned 32-bit count.
constexpr double kLargestRosTimeS = 4294967295.0;

/// The package's one conversion of seconds since the Unix epoch to ros::Time (every node and the
/// bag writer use it). Rounded to the microsecond: a double near 1.6e9 s carries about 0.2 us of
/// noise, and NMEA times are centiseconds, so 10:15:30.3 stays .300000000.
///
/// A time ros::Time cannot hold (NaN, infinite, negative, from 2^32 s = 2106-02-07 on) gives
/// false and time = ros::Time() (zero, "unset"), never the exception ros::Time(double) throws:
/// one bad stamp must not end a node. Callers decide what such a sample is worth (the driver and
/// relative_state_node count it and do not publish it).
inline bool toRosTime(double seconds_since_epoch, ros::Time& time)
{
  time = ros::Time();
  // Compared before any conversion: NaN fails every comparison, so it is rejected here too.
  if (!(seconds_since_epoch >= 0.0 && seconds_since_epoch < kLargestRosTimeS + 1.0))
  {
    return false;
  }
  const auto microseconds = static_cast<std::int64_t>(std::llround(seconds_since_epoch * 1e6));
  const std::int64_t whole_seconds = microseconds / 1000000;
  if (whole_seconds > static_cast<std::int64_t>(kLargestRosTimeS))
  {
    return false;  // rounded up to 2^32 s
  }
  time = ros::Time(static_cast<std::uint32_t>(whole_seconds), static_cast<std::uint32_t>(microseconds % 1000000) * 1000u);
  return true;
}

/// The same where an unset stamp is a fine answer (a message field that says "unknown"):
/// ros::Time() when the time cannot be held.
inline ros::Time toRosTime(double seconds_since_epoch)
{
  ros::Time time;
  toRosTime(seconds_since_epoch, time);
  return time;
}

}  // namespace acc
