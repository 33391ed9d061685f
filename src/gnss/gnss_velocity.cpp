#include "acc_identification/gnss/gnss_velocity.h"

#include <cmath>

namespace acc
{
bool enuVelocity(const GnssFix& fix, EnuVelocity& velocity)
{
  if (!fix.has(GnssFix::kValidSpeed))
    return false;
  if (!fix.has(GnssFix::kValidCourse))
  {
    if (fix.speed_over_ground_mps != 0.0)
      return false;
    velocity = EnuVelocity{};
    return true;
  }
  // Course is a compass bearing (clockwise from north): north = cos, east = sin.
  velocity.east_mps = fix.speed_over_ground_mps * std::sin(fix.course_rad);
  velocity.north_mps = fix.speed_over_ground_mps * std::cos(fix.course_rad);
  return true;
}

}  // namespace acc
