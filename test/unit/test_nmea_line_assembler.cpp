// Line assembly: bytes as serial ports, datagrams and TCP deliver them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "acc_identification/gnss/nmea_line_assembler.h"


namespace
{
std::vector<std::string> feedAll(acc::NmeaLineAssembler& assembler, const std::vector<std::string>& chunks)
{
  std::vector<std::string> lines;
  for (const auto& chunk : chunks)
    assembler.feed(chunk.data(), chunk.size(), [&](std::string_view line) { lines.emplace_back(line); });
  return lines;
}

const std::string kVtg = "$GPVTG,77.52,T,,M,0.004,N,0.008,K,A*06";
const std::string kGst = "$GPGST,082356.00,1.8,,,,1.7,1.3,2.2*7E";
}  // namespace

TEST(NmeaLineAssembler, TwoSentencesInOneRead)
{
  acc::NmeaLineAssembler assembler;
  const auto lines = feedAll(assembler, {kVtg + "\r\n" + kGst + "\r\n"});
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], kVtg);
  EXPECT_EQ(lines[1], kGst);
  EXPECT_EQ(assembler.strayBytes(), 0u);
}

TEST(NmeaLineAssembler, SentenceSplitAcrossReads)
{
  acc::NmeaLineAssembler assembler;
  const std::string whole = kVtg + "\r\n";
  for (std::size_t cut = 0; cut <= whole.size(); ++cut)
  {
    const auto lines = feedAll(assembler, {whole.substr(0, cut), whole.substr(cut)});
    ASSERT_EQ(lines.size(), 1u) << "cut at " << cut;
    EXPECT_EQ(lines[0], kVtg);
  }
  // Byte by byte, as a slow serial port.
  std::vector<std::string> bytes;
  for (char c : whole + whole)
    bytes.emplace_back(1, c);
  EXPECT_EQ(feedAll(assembler, bytes).size(), 2u);
}

TEST(NmeaLineAssembler, LineEndingsAndStrayBytes)
{
  acc::NmeaLineAssembler assembler;
  const auto lines = feedAll(assembler, {"\xb5\x62\x01\x07junk" + kVtg + "\n" + kGst + "\r" + "\n\n\r" + kVtg + "\r\n"});
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], kVtg);
  EXPECT_EQ(lines[1], kGst);
  EXPECT_EQ(lines[2], kVtg);
  EXPECT_EQ(assembler.strayBytes(), 8u);
}

TEST(NmeaLineAssembler, DollarInsideLineHandsOutTheBrokenLine)
{
  acc::NmeaLineAssembler assembler;
  const auto lines = feedAll(assembler, {"$GPGGA,0927" + kVtg + "\r\n"});
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "$GPGGA,0927");
  EXPECT_EQ(lines[1], kVtg);
}

TEST(NmeaLineAssembler, OverlongGarbageIsCountedAndDiscarded)
{
  acc::NmeaLineAssembler assembler;
  const std::string garbage = "$" + std::string(5000, 'x');
  const auto lines = feedAll(assembler, {garbage + "\r\n" + kVtg + "\r\n"});
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], kVtg);
  EXPECT_EQ(assembler.overlongLines(), 1u);
}

TEST(NmeaLineAssembler, FinishHandsOutUnterminatedLine)
{
  acc::NmeaLineAssembler assembler;
  EXPECT_TRUE(feedAll(assembler, {kVtg}).empty());
  std::vector<std::string> lines;
  assembler.finish([&](std::string_view line) { lines.emplace_back(line); });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], kVtg);
}

TEST(NmeaLineAssembler, DoubledDollarStartsOneLine)
{
  // ST Teseo LIV4F (gpsd regression log st-teseo-liv4f) starts every sentence with "$$".
  acc::NmeaLineAssembler assembler;
  const std::string rmc = "$GNRMC,135806.000,A,4723.00484,N,00045.88150,E,0.5,120.9,210325,,,A,C*11";
  const auto lines = feedAll(assembler, {"$" + rmc + "\r\n$" + kVtg.substr(0, 10), kVtg.substr(10) + "\r\n"});
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], rmc);
  EXPECT_EQ(lines[1], kVtg);
  EXPECT_EQ(assembler.cutLines(), 0u);
}

TEST(NmeaLineAssembler, EncapsulationSentencesAreLines)
{
  // AIS (!AIVDM, !AIVDO) interleaved with NMEA (gpsd regression log saab-r4): republished raw,
  // not dropped as stray bytes. A '!' inside a '$' line is text.
  acc::NmeaLineAssembler assembler;
  const std::string ais = "!AIVDM,1,1,,B,13aGhtw0R<OJf=6LgQ?Ad1FF05`L,0*24";
  const auto lines = feedAll(assembler, {ais + "\n$GPTXT,01,01,02,HELLO!*00\n" + kGst + "\n"});
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], ais);
  EXPECT_EQ(lines[1], "$GPTXT,01,01,02,HELLO!*00");
  EXPECT_EQ(assembler.strayBytes(), 0u);
}

TEST(NmeaLineAssembler, EveryInputLineIsAccountedFor)
{
  // Stray-only lines (a line's tail at the start of a capture, binary), a line cut by a '$',
  // an overlong line: input lines = lines out - cuts + stray lines + overlong lines.
  acc::NmeaLineAssembler assembler;
  const std::string input = "4.4343,N,01025.5386,E,200002,A,D*48\r\n" + kVtg + "\r\n\xb5\x62\x01\x07\r\n" +
                            "$GPGGA,0927" + kGst + "\r\n$" + std::string(300, 'x') + "\r\n\r\n" + kVtg;
  const auto lines = feedAll(assembler, {input});
  std::vector<std::string> last;
  assembler.finish([&](std::string_view line) { last.emplace_back(line); });
  const std::uint64_t out = lines.size() + last.size();
  EXPECT_EQ(out, 4u);  // VTG, the cut GGA, GST, last VTG
  EXPECT_EQ(assembler.strayLines(), 2u);
  EXPECT_EQ(assembler.cutLines(), 1u);
  EXPECT_EQ(assembler.overlongLines(), 1u);
  EXPECT_EQ(out - assembler.cutLines() + assembler.strayLines() + assembler.overlongLines(), 6u);
}

TEST(NmeaLineAssembler, AccountingHoldsOnRandomBytes)
{
  // Random streams of start characters, line ends, text and long runs, fed in random pieces.
  std::uint32_t state = 12345;
  const auto next = [&state] { return state = state * 1664525u + 1013904223u; };
  const char alphabet[] = {'$', '!', '\r', '\n', 'G', ',', '*', '\x01'};
  for (int round = 0; round < 2000; ++round)
  {
    std::string input;
    const int pieces = static_cast<int>(next() % 40);
    for (int i = 0; i < pieces; ++i)
      input += next() % 16 == 0 ? std::string(next() % 600, 'x') : std::string(1, alphabet[next() % 8]);
    std::uint64_t expected = 0;  // non-empty runs between line ends
    bool in_line = false;
    for (const char c : input)
    {
      if (c == '\r' || c == '\n')
        in_line = false;
      else if (!in_line)
        in_line = true, ++expected;
    }
    acc::NmeaLineAssembler assembler;
    std::uint64_t out = 0;
    for (std::size_t at = 0; at < input.size();)
    {
      const std::size_t size = std::min<std::size_t>(1 + next() % 50, input.size() - at);
      assembler.feed(input.data() + at, size, [&](std::string_view) { ++out; });
      at += size;
    }
    assembler.finish([&](std::string_view) { ++out; });
    ASSERT_EQ(out - assembler.cutLines() + assembler.strayLines() + assembler.overlongLines(), expected)
        << "round " << round;
  }
}
