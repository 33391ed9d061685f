#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace acc
{
/// ~source of the driver, a URI:
///   serial:///dev/ttyACM0?baud=115200   termios 8N1, reopened with back-off when the device goes
///   udp://:10110  or  udp://0.0.0.0:10110  listen for datagrams
///   tcp://host:port                       client, reconnects with back-off
///   file:///path/to/log.nmea?rate=R       replay; R = 1 real time, R > 1 faster, 0 as fast as possible
struct SourceUri
{
  std::string scheme;
  std::string host;
  int port = 0;
  std::string path;
  std::map<std::string, std::string> query;
};

/// Parses text into uri; false with a message in error when it is not one of the forms above.
bool parseSourceUri(const std::string& text, SourceUri& uri, std::string& error);

enum class ReadStatus
{
  kData,    ///< bytes were read
  kNoData,  ///< nothing within the timeout (or the source is closed and waiting to reopen)
  kEnd,     ///< the stream ended for good (end of a replayed file)
};

struct ReadResult
{
  ReadStatus status = ReadStatus::kNoData;
  std::size_t size = 0;
};

/// Where the driver's bytes come from. Implementations never throw on I/O trouble: they report
/// it in state(), count it, and keep trying (live sources) so that the node keeps running.
class ByteSource
{
public:
  virtual ~ByteSource() = default;
  /// Waits at most timeout_s for bytes and copies up to capacity of them into buffer.
  virtual ReadResult read(char* buffer, std::size_t capacity, double timeout_s) = 0;
  /// The URI it reads from.
  virtual std::string description() const = 0;
  /// "open", or what went wrong last and when it tries again.
  virtual std::string state() const = 0;
  virtual bool isOpen() const = 0;
  /// How many times the source was (re)opened after a failure or a disconnection.
  virtual std::uint64_t reopenCount() const = 0;
};

/// The source for a URI; nullptr with a message in error when the URI is not usable.
std::unique_ptr<ByteSource> makeByteSource(const std::string& uri, std::string& error);

}  // namespace acc
