#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace acc
{
/// Turns a byte stream (serial reads, datagrams, TCP segments, file chunks) into NMEA lines:
/// a line starts at '$' (or '!', the start of NMEA's encapsulation sentences such as AIS
/// !AIVDM) and ends at '\r' or '\n' (so \r\n, \r\r\n, \n and \r all work); a partial line is
/// kept across calls; several lines in one call come out one by one. A start character that
/// repeats the one before it ("$$GPRMC", as ST Teseo receivers send) starts the line once.
/// Bytes outside lines are counted as stray, and a line of stray bytes only (text, binary
/// protocol, the tail of a line cut at the start of the stream) as a stray line; a '$' inside
/// a line ends the broken line (it is still handed out, so that the parser counts it) and
/// starts a new one, counted as a cut ('!' inside a line is text); lines longer than
/// kMaxLineLength are discarded and counted. So every input line is accounted for:
///   non-empty input lines = lines handed out - cuts + stray lines + overlong lines.
/// Allocation-free.
class NmeaLineAssembler
{
public:
  /// NMEA allows 82 characters; u-blox PUBX lines reach about 130. Longer is garbage.
  static constexpr std::size_t kMaxLineLength = 255;

  /// Calls on_line(std::string_view line) for every completed line (without terminator). The
  /// view is valid only during the call.
  template <typename OnLine>
  void feed(const char* data, std::size_t size, OnLine&& on_line);

  std::uint64_t strayBytes() const { return stray_bytes_; }
  /// Input lines of stray bytes only (no '$' or '!' in them).
  std::uint64_t strayLines() const { return stray_lines_; }
  /// Lines started by a '$' inside another line (the earlier part was handed out or, when
  /// overlong, discarded): the extra lines one input line gave.
  std::uint64_t cutLines() const { return cut_lines_; }
  std::uint64_t overlongLines() const { return overlong_lines_; }
  /// Hands out a pending unterminated line (end of a file without final newline).
  template <typename OnLine>
  void finish(OnLine&& on_line);

private:
  /// A line end, or the end of the input: hands out the line, counts a stray one, starts afresh.
  template <typename OnLine>
  void endLine(OnLine& on_line);

  std::array<char, kMaxLineLength> buffer_{};
  std::size_t length_ = 0;
  bool in_line_ = false;
  bool discarding_ = false;  ///< inside an overlong line, until its end
  bool stray_line_ = false;  ///< stray bytes since the last line end, no line started yet
  std::uint64_t stray_bytes_ = 0;
  std::uint64_t stray_lines_ = 0;
  std::uint64_t cut_lines_ = 0;
  std::uint64_t overlong_lines_ = 0;
};

template <typename OnLine>
void NmeaLineAssembler::feed(const char* data, std::size_t size, OnLine&& on_line)
{
  for (std::size_t i = 0; i < size; ++i)
  {
    const char c = data[i];
    if (c == '$' || (c == '!' && !in_line_))
    {
      if (in_line_ && !discarding_ && length_ == 1 && buffer_[0] == c)
        continue;  // "$$": one start
      if (in_line_ && (discarding_ || length_ > 0))
      {
        ++cut_lines_;
        if (!discarding_)
          on_line(std::string_view(buffer_.data(), length_));
      }
      in_line_ = true;
      discarding_ = false;
      stray_line_ = false;
      buffer_[0] = c;
      length_ = 1;
    }
    else if (c == '\n' || c == '\r')
    {
      endLine(on_line);
    }
    else if (!in_line_)
    {
      ++stray_bytes_;
      stray_line_ = true;
    }
    else if (!discarding_)
    {
      if (length_ == kMaxLineLength)
      {
        ++overlong_lines_;
        discarding_ = true;
        length_ = 0;
      }
      else
      {
        buffer_[length_++] = c;
      }
    }
  }
}

template <typename OnLine>
void NmeaLineAssembler::finish(OnLine&& on_line)
{
  endLine(on_line);
}

template <typename OnLine>
void NmeaLineAssembler::endLine(OnLine& on_line)
{
  if (in_line_ && !discarding_)
    on_line(std::string_view(buffer_.data(), length_));  // at least its start character
  if (stray_line_)
    ++stray_lines_;
  in_line_ = false;
  discarding_ = false;
  stray_line_ = false;
  length_ = 0;
}

}  // namespace acc
