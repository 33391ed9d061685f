#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace acc
{
/// When each line of a recorded NMEA log is due in a replay at `rate` times real time: the offset
/// from the first timed line, (log time - first log time) / rate, on the log's own clock (its
/// sentences' UTC times, unwrapped across midnight). Pure arithmetic, so that the pacing is tested
/// without a wall clock; FileSource sleeps until each offset.
///
/// Only a line that parses paces the replay: a bad checksum or a malformed line can carry any
/// time, and one stamped an hour ahead would stall the replay for that hour. A clock jump in the
/// log, a time more than kBackwardToleranceS before the latest (a receiver's clock reset) or more
/// than kLongestWaitS after it, is neither replayed as a burst (the lines behind due at once,
/// which would put the reset stream back beside the other receiver's, 30 s of data paired 30 s
/// apart) nor waited for: the log's clock is anchored anew at the jump, which is due with the line
/// before it, so the stream keeps the pace the receiver sent it at, as a live link carries it.
/// Each jump is counted and the last one described.
class LogPacer
{
public:
  /// A time this much before the latest is the log's own reordering, paced as due at once.
  static constexpr double kBackwardToleranceS = 1.0;
  /// The longest silence of a log that is waited for (a receiver that stopped sending); a time
  /// further ahead is a clock jump.
  static constexpr double kLongestWaitS = 600.0;

  /// rate <= 0: as fast as possible (no line is ever due later than now).
  explicit LogPacer(double rate) : rate_(rate) {}
  /// The offset [s] at which this line is due, or nullopt when it has no time or does not parse
  /// (it is then due with the line before it) or when the replay is not paced.
  std::optional<double> dueOffsetS(const std::string& line);
  /// Clock jumps met so far, and the last one as "hh:mm:ss.ss -> hh:mm:ss.ss" ("" for none).
  std::uint64_t clockJumps() const { return clock_jumps_; }
  const std::string& lastClockJump() const { return last_clock_jump_; }

private:
  double rate_;
  bool started_ = false;       ///< first timed line seen
  double anchor_log_s_ = 0.0;  ///< unwrapped log time due at anchor_offset_s_
  double anchor_offset_s_ = 0.0;
  double last_time_s_ = 0.0;   ///< unwrapped log time of the latest timed line
  double last_offset_s_ = 0.0; ///< when the latest timed line was due
  double day_offset_s_ = 0.0;
  std::uint64_t clock_jumps_ = 0;
  std::string last_clock_jump_;
};
}  // namespace acc
