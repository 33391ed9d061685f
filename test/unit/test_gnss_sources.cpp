// Byte sources: URI parsing, file replay pacing, and the live sources against local peers
// (a pseudo-terminal for serial, loopback sockets for UDP and TCP).
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <vector>
#include <string>

#include "acc_identification/gnss/byte_source.h"
#include "acc_identification/gnss/log_pacer.h"
#include "acc_identification/gnss/nmea_decoder.h"
#include "acc_identification/gnss/nmea_writer.h"


namespace
{
const std::string kFixture = std::string(ACC_GNSS_TEST_DATA) + "/drive_10s.nmea";
const std::string kVtg = "$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06\r\n";

/// Reads from source until want bytes arrived or max_s passed; returns what came.
std::string readFor(acc::ByteSource& source, std::size_t want, double max_s)
{
  std::string got;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(max_s);
  char buffer[4096];
  while (got.size() < want && std::chrono::steady_clock::now() < end)
  {
    const acc::ReadResult r = source.read(buffer, sizeof buffer, 0.05);
    if (r.status == acc::ReadStatus::kEnd)
      break;
    got.append(buffer, r.size);
  }
  return got;
}

/// A loopback port that is free now.
int freePort(int type)
{
  const int fd = ::socket(AF_INET, type, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t length = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &length);
  ::close(fd);
  return ntohs(a.sin_port);
}

sockaddr_in loopback(int port)
{
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return a;
}
}  // namespace

TEST(SourceUri, Forms)
{
  acc::SourceUri uri;
  std::string error;
  ASSERT_TRUE(acc::parseSourceUri("serial:///dev/ttyACM0?baud=115200", uri, error)) << error;
  EXPECT_EQ(uri.scheme, "serial");
  EXPECT_EQ(uri.path, "/dev/ttyACM0");
  EXPECT_EQ(uri.query.at("baud"), "115200");
  ASSERT_TRUE(acc::parseSourceUri("udp://:10110", uri, error));
  EXPECT_EQ(uri.host, "");
  EXPECT_EQ(uri.port, 10110);
  ASSERT_TRUE(acc::parseSourceUri("tcp://192.168.1.5:2101", uri, error));
  EXPECT_EQ(uri.host, "192.168.1.5");
  EXPECT_EQ(uri.port, 2101);
  ASSERT_TRUE(acc::parseSourceUri("file:///tmp/x.nmea?rate=0", uri, error));
  EXPECT_EQ(uri.path, "/tmp/x.nmea");
  EXPECT_EQ(uri.query.at("rate"), "0");

  EXPECT_FALSE(acc::parseSourceUri("/dev/ttyACM0", uri, error));
  EXPECT_FALSE(acc::parseSourceUri("udp://:99999", uri, error));
  EXPECT_FALSE(acc::parseSourceUri("tcp://:2101", uri, error));
  EXPECT_FALSE(acc::parseSourceUri("file://relative.nmea", uri, error));
  EXPECT_FALSE(acc::parseSourceUri("ftp://host:21", uri, error));
  EXPECT_NE(error.find("unknown scheme"), std::string::npos);
  // Found when the URI is read, not retried for ever when the socket opens.
  EXPECT_FALSE(acc::parseSourceUri("udp://localhost:10110", uri, error));
  EXPECT_NE(error.find("must be an IPv4 address"), std::string::npos) << error;
  // A query key the scheme does not read is a typo, not a default taken without a word.
  EXPECT_FALSE(acc::parseSourceUri("file:///tmp/x.nmea?Rate=0", uri, error));
  EXPECT_NE(error.find("file takes only ?rate=..., not 'Rate'"), std::string::npos) << error;
  EXPECT_FALSE(acc::parseSourceUri("udp://:10110?baud=9600", uri, error));
  EXPECT_NE(error.find("udp takes no query parameter"), std::string::npos) << error;
  EXPECT_EQ(acc::makeByteSource("serial:///dev/ttyACM0?baud=12345", error), nullptr);
  EXPECT_EQ(acc::makeByteSource("file:///nonexistent.nmea", error), nullptr);
  EXPECT_EQ(acc::makeByteSource("file://" + kFixture + "?rate=fast", error), nullptr);
}

TEST(FileSource, AsFastAsPossibleThenEnd)
{
  std::string error;
  auto source = acc::makeByteSource("file://" + kFixture + "?rate=0", error);
  ASSERT_NE(source, nullptr) << error;
  int fixes = 0;
  acc::NmeaDecoder decoder(nullptr, [&](const acc::GnssFix&) { ++fixes; });
  char buffer[512];
  acc::ReadResult r;
  while ((r = source->read(buffer, sizeof buffer, 0.1)).status != acc::ReadStatus::kEnd)
    decoder.feed(buffer, r.size, 0.0);
  decoder.finish(0.0);
  EXPECT_EQ(fixes, 100);
  EXPECT_EQ(source->read(buffer, sizeof buffer, 0.1).status, acc::ReadStatus::kEnd);
}

namespace
{
/// A line of the fixture and when it is due at some rate (nullopt: untimed, or not paced).
struct DueLine
{
  std::string line;
  std::optional<double> offset_s;
};

std::vector<DueLine> schedule(const std::string& text, double rate)
{
  acc::LogPacer pacer(rate);
  std::vector<DueLine> lines;
  std::size_t begin = 0;
  while (begin < text.size())
  {
    const std::size_t end = text.find_first_of("\r\n", begin);
    const std::string line = text.substr(begin, end == std::string::npos ? std::string::npos : end + 1 - begin);
    if (line.find('$') != std::string::npos)
      lines.push_back({line, pacer.dueOffsetS(line)});
    begin = end == std::string::npos ? text.size() : end + 1;
  }
  return lines;
}

std::string fixtureText()
{
  std::ifstream in(kFixture, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
}  // namespace

// Pacing is arithmetic on the log's own times (LogPacer): checked without a wall clock.
TEST(LogPacer, LinesAreDueAtTheirLogTimeOverTheRate)
{
  const auto lines = schedule(fixtureText(), 20.0);  // 9.9 s of log (10:15:30.0 to 10:15:39.9) in 0.495 s
  ASSERT_EQ(lines.size(), 600u);
  double previous_s = 0.0;
  std::size_t timed = 0;
  for (const DueLine& due : lines)
  {
    const bool has_time = due.line.rfind("$GNRMC", 0) == 0 || due.line.rfind("$GNGGA", 0) == 0;
    if (has_time)
    {
      ASSERT_TRUE(due.offset_s.has_value()) << due.line;
    }
    if (due.line.rfind("$GNVTG", 0) == 0 || due.line.rfind("$GNGSA", 0) == 0)
    {
      EXPECT_FALSE(due.offset_s.has_value()) << due.line;  // untimed: due with the line before
    }
    if (!due.offset_s)
      continue;
    ++timed;
    EXPECT_GE(*due.offset_s, previous_s) << due.line;  // never earlier than the line before
    previous_s = *due.offset_s;
    // The log's own time over the rate: 10:15:35.00 is 5 s after the first line.
    if (due.line.find(",101535.00,") != std::string::npos)
    {
      EXPECT_NEAR(*due.offset_s, 5.0 / 20.0, 1e-9) << due.line;
    }
  }
  EXPECT_GE(timed, 200u);
  EXPECT_DOUBLE_EQ(*lines.front().offset_s, 0.0);
  EXPECT_NEAR(previous_s, 9.9 / 20.0, 1e-9);
  EXPECT_FALSE(acc::LogPacer(0.0).dueOffsetS(lines.front().line));  // rate 0: not paced
}

TEST(LogPacer, UntimedLinesFollowTheLineBeforeAndMidnightUnwraps)
{
  acc::LogPacer pacer(2.0);
  EXPECT_NEAR(*pacer.dueOffsetS("$GNRMC,235959.80,A,4507.80000,N,00827.00000,E,40.000,57.30,110526,,,A*7E\r\n"), 0.0,
              1e-9);
  EXPECT_FALSE(pacer.dueOffsetS(kVtg));  // no time: due with the line before it
  EXPECT_NEAR(*pacer.dueOffsetS("$GNGGA,000000.00,4507.80020,N,00827.00020,E,1,12,0.8,120.0,M,,M,,*67\r\n"),
              0.2 / 2.0, 1e-9);  // across midnight: 0.2 s of log at 2x
}

namespace
{
/// A GGA of this time of day (hhmmss.ss), its checksum right.
std::string ggaAt(const std::string& hhmmss)
{
  const std::string body = "GNGGA," + hhmmss + ",4507.80020,N,00827.00020,E,1,12,0.8,120.0,M,,M,,";
  return "$" + body + "*" + acc::nmeaChecksum(body) + "\r\n";
}
}  // namespace

// A receiver's clock reset in a log is not replayed as a burst (the lines behind the latest all
// due at once, putting the reset stream back beside the other receiver's: 30 s of data paired 30 s
// apart, gaps of 600 m published as valid), and a line that does not parse does not pace: one
// stamped an hour ahead with a bad checksum stalled the replay for that hour.
TEST(LogPacer, AClockJumpIsPacedOnAndALineThatDoesNotParseDoesNotPace)
{
  acc::LogPacer pacer(2.0);
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101500.00")), 0.0, 1e-12);
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101501.00")), 0.5, 1e-12);
  std::string corrupt = ggaAt("111501.00");
  corrupt[corrupt.size() - 3] = corrupt[corrupt.size() - 3] == '0' ? '1' : '0';  // its checksum wrong
  EXPECT_FALSE(pacer.dueOffsetS(corrupt));  // due with the line before, not in an hour
  EXPECT_FALSE(pacer.dueOffsetS("$GNGGA,111501.00,4507.8\r\n"));  // cut short: malformed
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101502.00")), 1.0, 1e-12);
  EXPECT_EQ(pacer.clockJumps(), 0u);
  // The clock goes back 30 s: the stream goes on at its pace from there.
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101432.00")), 1.0, 1e-12);
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101433.00")), 1.5, 1e-12);
  EXPECT_EQ(pacer.clockJumps(), 1u);
  EXPECT_EQ(pacer.lastClockJump(), "10:15:02.00 -> 10:14:32.00");
  // A time a little behind the latest (a log's own reordering) is due at once, no jump.
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101432.50")), 1.5, 1e-12);
  EXPECT_EQ(pacer.clockJumps(), 1u);
  // A valid line an hour ahead is a jump too, not an hour's wait; and so is the way back.
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("111434.00")), 1.5, 1e-12);
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101434.00")), 1.5, 1e-12);
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101435.00")), 2.0, 1e-12);
  EXPECT_EQ(pacer.clockJumps(), 3u);
  // A silence within kLongestWaitS is waited for: a receiver that stopped sending for 5 minutes.
  EXPECT_NEAR(*pacer.dueOffsetS(ggaAt("101935.00")), 2.0 + 150.0, 1e-9);
  EXPECT_EQ(pacer.clockJumps(), 3u);
}

TEST(FileSource, PacesLogsWithCarriageReturnLineEndings)
{
  // The fixture's first 2 s with '\r' alone as line ending: every line still timed and paced.
  std::string text = fixtureText().substr(0, 120 * 70);
  text = text.substr(0, text.rfind("\r\n$GNRMC") + 2);
  std::string cr_only;
  for (char c : text)
    if (c != '\n')
      cr_only += c;
  const auto lines = schedule(cr_only, 4.0);
  std::size_t epochs = 0;
  double last_s = 0.0;
  for (const DueLine& due : lines)
  {
    if (due.line.rfind("$GNGGA", 0) != 0)
      continue;
    ++epochs;
    ASSERT_TRUE(due.offset_s.has_value()) << due.line;  // '\r' alone still ends a timed line
    EXPECT_NEAR(*due.offset_s, 0.1 * static_cast<double>(epochs - 1) / 4.0, 1e-9);  // epoch by epoch at 4x
    last_s = *due.offset_s;
  }
  ASSERT_GT(epochs, 10u);
  EXPECT_GT(last_s, 0.0);
  // And the source delivers every epoch of it.
  const std::string path = ::testing::TempDir() + "gnss_cr_only.nmea";
  std::ofstream(path, std::ios::binary) << cr_only;
  std::string error;
  auto source = acc::makeByteSource("file://" + path + "?rate=40", error);
  ASSERT_NE(source, nullptr) << error;
  int fixes = 0;
  acc::NmeaDecoder decoder(nullptr, [&](const acc::GnssFix&) { ++fixes; });
  char buffer[512];
  acc::ReadResult r;
  while ((r = source->read(buffer, sizeof buffer, 0.02)).status != acc::ReadStatus::kEnd)
    decoder.feed(buffer, r.size, 0.0);
  decoder.finish(0.0);
  EXPECT_EQ(static_cast<std::size_t>(fixes), epochs);
  std::remove(path.c_str());
}

TEST(SerialSource, ReadsAPseudoTerminalAndSurvivesItsDisappearance)
{
  int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const std::string slave = ::ptsname(master);
  std::string error;
  auto source = acc::makeByteSource("serial://" + slave + "?baud=115200", error);
  ASSERT_NE(source, nullptr) << error;
  EXPECT_EQ(readFor(*source, 1, 0.1), "");  // opens, nothing yet
  ASSERT_TRUE(source->isOpen()) << source->state();
  ASSERT_EQ(::write(master, kVtg.data(), kVtg.size()), static_cast<ssize_t>(kVtg.size()));
  EXPECT_EQ(readFor(*source, kVtg.size(), 2.0), kVtg);
  ::close(master);  // the device goes away (as a USB receiver unplugged)
  readFor(*source, 1, 0.3);
  EXPECT_FALSE(source->isOpen());
  EXPECT_NE(source->state().find("retrying"), std::string::npos) << source->state();
}

namespace
{
/// A pseudo-terminal whose device can go away and come back under one path, as a USB receiver's
/// /dev/serial/by-id link does when it is unplugged and plugged in again (socat's PTY,link= makes
/// the same): the path is a symbolic link to the pty's slave.
class ReplugablePty
{
public:
  explicit ReplugablePty(std::string path) : path_(std::move(path)) {}
  ~ReplugablePty() { unplug(); }
  bool plug()
  {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0)
      return false;
    return ::symlink(::ptsname(master_), path_.c_str()) == 0;
  }
  void unplug()
  {
    ::unlink(path_.c_str());
    if (master_ >= 0)
      ::close(master_);
    master_ = -1;
  }
  bool write(const std::string& text) const
  {
    return ::write(master_, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  }

private:
  std::string path_;
  int master_ = -1;
};
}  // namespace

// The receiver unplugged and plugged in again: the path disappears and comes back (a new device
// behind it); the source counts the outage, reopens the path and reads again.
TEST(SerialSource, ReopensThePathWhenTheDeviceComesBack)
{
  const std::string path = ::testing::TempDir() + "acc_gps_replug_" + std::to_string(::getpid());
  ReplugablePty device(path);
  ASSERT_TRUE(device.plug());
  std::string error;
  auto source = acc::makeByteSource("serial://" + path + "?baud=115200", error);
  ASSERT_NE(source, nullptr) << error;
  EXPECT_EQ(readFor(*source, 1, 0.1), "");
  ASSERT_TRUE(source->isOpen()) << source->state();
  ASSERT_TRUE(device.write(kVtg));
  EXPECT_EQ(readFor(*source, kVtg.size(), 2.0), kVtg);

  device.unplug();  // the path is gone
  readFor(*source, 1, 0.5);
  EXPECT_FALSE(source->isOpen());
  const std::uint64_t reopens_before = source->reopenCount();

  ASSERT_TRUE(device.plug());  // back, as a new pty
  // The source retries with back-off: within a few seconds it has the device again.
  std::string got;
  for (int attempt = 0; attempt < 50 && got.empty(); ++attempt)
  {
    readFor(*source, 1, 0.1);
    if (source->isOpen())
    {
      ASSERT_TRUE(device.write(kVtg));
      got = readFor(*source, kVtg.size(), 2.0);
    }
  }
  EXPECT_TRUE(source->isOpen()) << source->state();
  EXPECT_EQ(got, kVtg);
  EXPECT_GT(source->reopenCount(), reopens_before);
}

TEST(UdpSource, SeveralSentencesInOneDatagram)
{
  const int port = freePort(SOCK_DGRAM);
  std::string error;
  auto source = acc::makeByteSource("udp://127.0.0.1:" + std::to_string(port), error);
  ASSERT_NE(source, nullptr) << error;
  readFor(*source, 1, 0.1);  // binds
  ASSERT_TRUE(source->isOpen()) << source->state();
  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  const sockaddr_in to = loopback(port);
  const std::string datagram = kVtg + kVtg;
  ::sendto(sender, datagram.data(), datagram.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  ::close(sender);
  EXPECT_EQ(readFor(*source, datagram.size(), 2.0), datagram);
}

TEST(UdpSource, ASecondSourceOnTheSamePortIsRefusedNotGivenTheData)
{
  const int port = freePort(SOCK_DGRAM);
  std::string error;
  auto first = acc::makeByteSource("udp://127.0.0.1:" + std::to_string(port), error);
  auto second = acc::makeByteSource("udp://127.0.0.1:" + std::to_string(port), error);
  ASSERT_NE(first, nullptr) << error;
  ASSERT_NE(second, nullptr) << error;
  readFor(*first, 1, 0.1);  // binds
  readFor(*second, 1, 0.1);
  ASSERT_TRUE(first->isOpen()) << first->state();
  EXPECT_FALSE(second->isOpen());
  EXPECT_NE(second->state().find("bind udp port"), std::string::npos) << second->state();
  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  const sockaddr_in to = loopback(port);
  ::sendto(sender, kVtg.data(), kVtg.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  ::close(sender);
  EXPECT_EQ(readFor(*first, kVtg.size(), 2.0), kVtg);
}

TEST(TcpSource, ReconnectsWhenTheServerDropsTheConnection)
{
  const int port = freePort(SOCK_STREAM);
  const int server = ::socket(AF_INET, SOCK_STREAM, 0);
  const int yes = 1;
  ::setsockopt(server, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address = loopback(port);
  ASSERT_EQ(::bind(server, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::listen(server, 2), 0);
  std::string error;
  auto source = acc::makeByteSource("tcp://127.0.0.1:" + std::to_string(port), error);
  ASSERT_NE(source, nullptr) << error;
  for (int round = 0; round < 2; ++round)
  {
    readFor(*source, 1, round == 0 ? 0.1 : 1.5);  // connects (after the back-off the second time)
    const int peer = ::accept(server, nullptr, nullptr);
    ASSERT_GE(peer, 0);
    ASSERT_EQ(::write(peer, kVtg.data(), kVtg.size()), static_cast<ssize_t>(kVtg.size()));
    EXPECT_EQ(readFor(*source, kVtg.size(), 2.0), kVtg);
    ::close(peer);
    readFor(*source, 1, 0.2);  // sees the end of the connection
    EXPECT_FALSE(source->isOpen());
  }
  EXPECT_EQ(source->reopenCount(), 1u);
  ::close(server);
}
