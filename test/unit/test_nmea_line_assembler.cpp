// Line assembly: bytes as serial ports, datagrams and TCP deliver them.
#include <gtest/gtest.h>

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
