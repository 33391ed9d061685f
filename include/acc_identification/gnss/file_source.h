#pragma once

#include <chrono>
#include <cstdint>
#include <fstream>
#include <string>

#include "acc_identification/gnss/byte_source.h"
#include "acc_identification/gnss/log_pacer.h"

namespace acc
{
/// Replays a log of NMEA lines paced by the sentences' own UTC times: a line is released
/// (time - first time) / rate after the first timed line, on the host's steady clock (not the
/// ROS clock, so it also works under /use_sim_time). Lines without time (VTG, GSV, ...) follow
/// the line before them. rate = 0: as fast as possible. Midnight in the log is unwrapped; a clock
/// jump (LogPacer) is neither caught up in a burst nor waited for, and state() says how many.
/// At end of file read() returns kEnd.
class FileSource : public ByteSource
{
public:
  FileSource(const std::string& path, double rate);

  ReadResult read(char* buffer, std::size_t capacity, double timeout_s) override;
  std::string description() const override;
  std::string state() const override;
  bool isOpen() const override { return in_.is_open(); }
  std::uint64_t reopenCount() const override { return 0; }

private:
  using Clock = std::chrono::steady_clock;
  /// Reads the next line into line_ and computes when it is due; false at end of file.
  bool loadLine();

  std::string path_;
  double rate_;
  std::ifstream in_;
  std::string state_;
  std::string line_;         ///< next line with its "\n", waiting for its time
  std::size_t line_offset_ = 0;
  bool has_line_ = false;
  bool started_ = false;     ///< first timed line seen
  LogPacer pacer_;
  Clock::time_point wall_start_;  ///< when the first timed line was due
  Clock::time_point due_;
};

}  // namespace acc
