#pragma once

#include <optional>
#include <string>

namespace acc
{
/// When each line of a recorded NMEA log is due in a replay at `rate` times real time: the offset
/// from the first timed line, (log time - first log time) / rate, on the log's own clock (its
/// sentences' UTC times, unwrapped across midnight). Pure arithmetic, so that the pacing is tested
/// without a wall clock; FileSource sleeps until each offset.
class LogPacer
{
public:
  /// rate <= 0: as fast as possible (no line is ever due later than now).
  explicit LogPacer(double rate) : rate_(rate) {}

  /// The offset [s] at which this line is due, or nullopt when it has no time (it is then due
  /// with the line before it) or when the replay is not paced.
  std::optional<double> dueOffsetS(const std::string& line);

private:
  double rate_;
  bool started_ = false;      ///< first timed line seen
  double log_start_s_ = 0.0;  ///< unwrapped log time of the first timed line
  double last_time_s_ = 0.0;  ///< unwrapped log time of the latest timed line
  double day_offset_s_ = 0.0;
};

}  // namespace acc
