// The identifier's drive so far, bounded: memory stays level however long the drive, every
// sample let go of is counted, and what stays is what pins the model (every speed band, the
// strongest manoeuvres).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "acc_identification/calibration/drive_record.h"

namespace
{
constexpr double kStepS = 0.1;  // 10 Hz

/// A follower at speed_mps, swinging by swing_mps with a 20 s period (0: steady).
acc::WindowSample driving(double t, double speed_mps, double swing_mps, bool valid = true)
{
  const double v = speed_mps + swing_mps * std::sin(2.0 * M_PI * t / 20.0);
  return acc::WindowSample{t, 5.0 + 1.5 * v, v, v, valid};
}

acc::DriveRecord record(std::size_t max_samples)
{
  acc::DriveBound bound;
  bound.max_samples = max_samples;
  return acc::DriveRecord(0.5, 20, 30.0, 5, bound);
}

std::size_t samplesIn(const std::vector<acc::CarFollowingRun>& segments)
{
  std::size_t n = 0;
  for (const auto& segment : segments) n += segment.size();
  return n;
}

TEST(DriveRecord, AThreeHourDriveStaysWithinTheBoundAndEverySampleLetGoIsCounted)
{
  acc::DriveRecord drive = record(36000);
  std::size_t largest = 0;
  for (long k = 0; k < 108000; ++k)
  {
    drive.add(driving(k * kStepS, 25.0, (k / 6000) % 3 == 0 ? 2.0 : 0.2));
    largest = std::max(largest, drive.size());
    ASSERT_EQ(drive.samplesTaken(), drive.size() + drive.samplesLetGoThisDrive()) << "at sample " << k;
  }
  EXPECT_EQ(drive.samplesTaken(), 108000u);
  EXPECT_LE(largest, 36000u + 600u);  // the bound, plus at most the newest block
  EXPECT_GE(drive.size(), 36000u - 600u);
  EXPECT_EQ(drive.samplesLetGo(), 108000u - drive.size());
  EXPECT_GT(drive.blocksLetGo(), 100u);
  // The newest sample is always kept, and the kept data are simulated in pieces that never cross
  // what was let go of.
  EXPECT_NEAR(drive.window().endTimeS(), 107999 * kStepS, 1e-6);
  const auto segments = drive.segments();
  EXPECT_EQ(samplesIn(segments), drive.size());
  for (const auto& segment : segments)
  {
    for (std::size_t i = 1; i < segment.size(); ++i)
    {
      ASSERT_LE(segment.time_s[i] - segment.time_s[i - 1], 0.5);
    }
  }
}

TEST(DriveRecord, KeepsASpeedBandSeenOnlyBrieflyAndLetsGoOfSteadyCruisingFirst)
{
  acc::DriveRecord drive = record(6000);  // ten minutes
  long k = 0;
  for (; k < 3000; ++k) drive.add(driving(k * kStepS, 11.0, 0.0));  // five steady minutes at 11 m/s
  // Then an hour at 31 m/s: steady, but with a strong manoeuvre in minute 20 and minute 40.
  for (; k < 39000; ++k)
  {
    const long minute = (k - 3000) / 600;
    drive.add(driving(k * kStepS, 31.0, minute == 20 || minute == 40 ? 3.0 : 0.0));
  }
  std::set<long> speeds_kept;
  bool manoeuvre_20 = false, manoeuvre_40 = false;
  for (const acc::WindowSample& s : drive.window().samples())
  {
    speeds_kept.insert(std::lround(s.follower_speed_mps / 10.0));
    const long minute = (std::lround(s.time_s / kStepS) - 3000) / 600;
    manoeuvre_20 = manoeuvre_20 || minute == 20;
    manoeuvre_40 = manoeuvre_40 || minute == 40;
  }
  EXPECT_TRUE(speeds_kept.count(1)) << "the 11 m/s band was let go of";
  EXPECT_TRUE(speeds_kept.count(3));
  EXPECT_TRUE(manoeuvre_20 && manoeuvre_40) << "a manoeuvre was let go of before steady cruising";
  EXPECT_LE(drive.size(), 6600u);
}

TEST(DriveRecord, BlocksWithoutValidDataGoFirst)
{
  std::deque<acc::WindowSample> samples;
  for (long k = 0; k < 1800; ++k) samples.push_back(driving(k * kStepS, 20.0, 0.0, k < 600 || k >= 1200));
  samples.push_back(driving(1800 * kStepS, 20.0, 0.0));  // opens a fourth block, the newest
  const acc::DriveBound bound;
  const auto blocks = acc::driveBlocks(samples, bound);
  ASSERT_EQ(blocks.size(), 3u);  // the newest block is never a candidate
  const auto chosen = acc::chooseBlockToLetGo(blocks, bound);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(chosen->first, 600u);
  EXPECT_EQ(chosen->count, 600u);
}

TEST(DriveRecord, NothingToLetGoOfButTheNewestBlock)
{
  std::deque<acc::WindowSample> samples;
  for (long k = 0; k < 100; ++k) samples.push_back(driving(k * kStepS, 20.0, 1.0));
  EXPECT_TRUE(acc::driveBlocks(samples, acc::DriveBound{}).empty());
  EXPECT_FALSE(acc::chooseBlockToLetGo({}, acc::DriveBound{}).has_value());
  acc::DriveRecord drive = record(10);
  for (long k = 0; k < 100; ++k) drive.add(driving(k * kStepS, 20.0, 1.0));
  EXPECT_EQ(drive.size(), 100u);  // over the bound by less than a block: kept, nothing to choose
  EXPECT_EQ(drive.samplesLetGo(), 0u);
}

TEST(DriveRecord, ZeroKeepsEverySample)
{
  acc::DriveRecord drive = record(0);
  for (long k = 0; k < 20000; ++k) drive.add(driving(k * kStepS, 20.0, 0.0));
  EXPECT_EQ(drive.size(), 20000u);
  EXPECT_EQ(drive.samplesLetGo(), 0u);
}

TEST(DriveRecord, ATimeResetStartsANewDriveAndItsCounts)
{
  acc::DriveRecord drive = record(1200);
  for (long k = 0; k < 6000; ++k) drive.add(driving(k * kStepS, 20.0, 0.5));
  EXPECT_GT(drive.samplesLetGoThisDrive(), 0u);
  const std::uint64_t let_go_before = drive.samplesLetGo();
  acc::SlidingWindow::AddResult last = acc::SlidingWindow::AddResult::kAdded;
  for (long k = 0; k < 5; ++k) last = drive.add(driving(k * kStepS, 20.0, 0.5));  // a bag loop
  EXPECT_EQ(last, acc::SlidingWindow::AddResult::kRestarted);
  EXPECT_EQ(drive.samplesTaken(), 5u);
  EXPECT_EQ(drive.size(), 5u);
  EXPECT_EQ(drive.samplesLetGoThisDrive(), 0u);
  EXPECT_EQ(drive.samplesLetGo(), let_go_before);  // the total stays
}

TEST(DriveRecord, ARestartForANewSettingStartsANewDriveAndKeepsTheTotals)
{
  acc::DriveRecord drive = record(1200);
  for (long k = 0; k < 6000; ++k) drive.add(driving(k * kStepS, 20.0, 0.5));
  const std::uint64_t let_go_before = drive.samplesLetGo();
  ASSERT_GT(let_go_before, 0u);
  drive.restart();
  EXPECT_EQ(drive.size(), 0u);
  EXPECT_EQ(drive.samplesTaken(), 0u);
  EXPECT_EQ(drive.samplesLetGoThisDrive(), 0u);
  for (long k = 6000; k < 6010; ++k) drive.add(driving(k * kStepS, 20.0, 0.5));  // time goes on
  EXPECT_EQ(drive.samplesTaken(), 10u);
  EXPECT_DOUBLE_EQ(drive.startTimeS(), 600.0);
  EXPECT_EQ(drive.samplesLetGo(), let_go_before);
}

TEST(SlidingWindowLetGo, AShortCutLeavesASplitPointSoNoStepCrossesIt)
{
  acc::SlidingWindow window(1.0e9, 0.5, 5);
  for (long k = 0; k < 100; ++k) window.add(driving(k * kStepS, 20.0, 0.0));
  // Three samples (0.3 s) out of the middle: the neighbours are 0.4 s apart, within max_gap_s.
  EXPECT_EQ(window.letGo(50, 3), 2u);
  const auto segments = window.segments();
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].size(), 50u);
  EXPECT_EQ(segments[1].size(), 47u);
  // A long cut opens a hole wider than max_gap_s: no split point needed.
  EXPECT_EQ(window.letGo(10, 30), 30u);
  EXPECT_EQ(window.segments().size(), 3u);
  // The newest sample is never let go of.
  EXPECT_EQ(window.letGo(window.size() - 1, 1), 0u);
}

}  // namespace
