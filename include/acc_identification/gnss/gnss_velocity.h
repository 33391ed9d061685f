#pragma once

#include "acc_identification/gnss/gnss_fix.h"

namespace acc
{
/// Horizontal velocity in the local ENU frame at the antenna (x east, y north, z up) [m/s].
struct EnuVelocity
{
  double east_mps = 0.0;
  double north_mps = 0.0;
};

/// From speed over ground and course (clockwise from true north, radians):
/// east = v sin(course), north = v cos(course). Requires kValidSpeed and kValidCourse; a fix
/// with speed but no course (receivers leave course empty at standstill) gives zero only when
/// the speed is zero, else nothing.
bool enuVelocity(const GnssFix& fix, EnuVelocity& velocity);

}  // namespace acc
