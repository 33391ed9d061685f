#include "acc_identification/gnss/file_source.h"

#include <algorithm>
#include <cstring>
#include <thread>


namespace acc
{
FileSource::FileSource(const std::string& path, double rate)
  : path_(path), rate_(rate), in_(path, std::ios::binary), pacer_(rate)
{
  state_ = in_.is_open() ? "open" : "cannot open " + path;
}

std::string FileSource::state() const
{
  if (pacer_.clockJumps() == 0)
    return state_;
  return state_ + "; " + std::to_string(pacer_.clockJumps()) +
         " clock jump(s) in the log, paced as the receiver sent them (last " + pacer_.lastClockJump() + ")";
}

std::string FileSource::description() const { return "file://" + path_ + "?rate=" + std::to_string(rate_); }

bool FileSource::loadLine()
{
  // Up to and including the next '\n' or '\r', so that logs with any line ending are paced
  // line by line ("\r\n" gives the line and then an empty "\n", which the assembler skips).
  line_.clear();
  for (int c = in_.get(); c != std::char_traits<char>::eof(); c = in_.get())
  {
    line_ += static_cast<char>(c);
    if (c == '\n' || c == '\r')
      break;
  }
  if (line_.empty())
    return false;
  if (line_.back() != '\n' && line_.back() != '\r')
    line_ += '\n';  // last line without terminator
  line_offset_ = 0;
  has_line_ = true;
  const std::optional<double> offset_s = pacer_.dueOffsetS(line_);
  if (!offset_s)
    return true;  // untimed lines (or no pacing): due with the line before them
  if (!started_)
  {
    started_ = true;
    wall_start_ = Clock::now();
  }
  due_ = wall_start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(*offset_s));
  return true;
}

ReadResult FileSource::read(char* buffer, std::size_t capacity, double timeout_s)
{
  ReadResult result;
  if (!in_.is_open())
  {
    result.status = ReadStatus::kEnd;
    return result;
  }
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
  while (result.size < capacity)
  {
    if (!has_line_ && !loadLine())
    {
      if (result.size == 0)
      {
        result.status = ReadStatus::kEnd;
        state_ = "end of file";
      }
      break;
    }
    if (rate_ > 0.0 && started_ && Clock::now() < due_)
    {
      if (result.size > 0 || due_ > deadline)
      {
        if (result.size == 0)
          std::this_thread::sleep_until(deadline);
        break;
      }
      std::this_thread::sleep_until(due_);
    }
    const std::size_t count = std::min(capacity - result.size, line_.size() - line_offset_);
    std::memcpy(buffer + result.size, line_.data() + line_offset_, count);
    result.size += count;
    line_offset_ += count;
    has_line_ = line_offset_ < line_.size();
  }
  if (result.size > 0)
    result.status = ReadStatus::kData;
  return result;
}

}  // namespace acc
