#pragma once

#include <string>
#include <string_view>

#include "acc_identification/gnss/gnss_fix.h"

namespace acc
{
/// Writes NMEA 0183 as a u-blox receiver (NMEA 4.x) does: time hhmmss.ss, angles ddmm.mmmmm
/// (5 decimals of minutes, about 2 cm), speed in knots with 3 decimals, course with 2 decimals,
/// altitude with 1 decimal. Fields the fix does not hold (see GnssFix::valid_fields) are left
/// empty. Used to turn recorded trajectories into NMEA logs that the parser reads back.

/// Two upper-case hex digits of the XOR of body (the characters between '$' and '*').
std::string nmeaChecksum(std::string_view body);

/// "$<talker>GGA,...*hh" without line ending.
std::string formatGga(const GnssFix& fix, const std::string& talker = "GN");
/// "$<talker>RMC,...*hh" without line ending; the date field is empty when !fix.has_date.
std::string formatRmc(const GnssFix& fix, const std::string& talker = "GN");

}  // namespace acc
