#pragma once

#include <string>
#include <vector>

#include "acc_identification/gnss/gnss_fix.h"
#include "acc_identification/gnss/nmea_statistics.h"

namespace acc
{
/// A whole NMEA log decoded: one fix per epoch and the counts of what was rejected.
struct NmeaLogResult
{
  std::vector<GnssFix> fixes;
  NmeaStatistics statistics;
  std::string error;  ///< non-empty when the file could not be read
};

/// Reads a log of NMEA lines (any line endings) through the same decoder as the driver node.
/// receive_time_s of each fix is the time of its epoch (there is no host clock in a log).
NmeaLogResult readNmeaLog(const std::string& path);

}  // namespace acc
