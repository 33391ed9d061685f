#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace acc
{
/// One line of an NMEA log with the time a receiver's host would have received it.
struct TimedNmeaLine
{
  double receive_time_s = 0.0;  ///< Unix seconds (UTC)
  std::string line;             ///< without its line terminator
};

/// How the receive time of a line is made from its GNSS time.
struct NmeaLineTiming
{
  /// From the epoch's measurement time to the end of its first sentence on the host [s]: u-blox
  /// receivers send an epoch's sentences a few tens of ms after the epoch.
  double first_sentence_latency_s = 0.04;
  /// Each further sentence of the same epoch arrives this much later [s] (about 75 characters
  /// at 38400 baud).
  double sentence_spacing_s = 0.02;
};

struct TimedNmeaLog
{
  std::vector<TimedNmeaLine> lines;  ///< every non-empty line of the file, in file order
  std::size_t untimed_lines = 0;     ///< no readable time: stamped just after the previous line
  std::string error;                 ///< non-empty when the file could not be read or has no date
};

/// Reads a log and stamps every non-empty line: GNSS time of day of the line (or of the previous
/// timed line when it has none), the UTC day from the RMC/ZDA dates (carried across midnight;
/// lines before the first date take the first date's day), plus the latency. Lines are kept
/// whatever their content, so a bag made from them loses nothing.
TimedNmeaLog readTimedNmeaLog(const std::string& path, const NmeaLineTiming& timing = NmeaLineTiming{});

}  // namespace acc
