// The same recording given twice (io/repeated_recording.h): a copy, an excerpt and a partial
// overlap are found where they start; different drives, a standstill, a held value and noise-free
// drives that share only their leader's profile are not.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "acc_identification/io/repeated_recording.h"
#include "acc_identification/model/normal_source.h"
#include "oscillating_run.h"

namespace
{
/// A measured speed: 12 m/s, a slow wave, and the paper's 0.06 m/s of noise from this seed.
std::vector<double> measuredSpeeds(std::size_t samples, std::uint64_t seed)
{
  acc::NormalSource noise(seed);
  std::vector<double> speeds;
  for (std::size_t k = 0; k < samples; ++k)
    speeds.push_back(12.0 + 2.0 * std::sin(0.02 * static_cast<double>(k)) + 0.06 * noise.standardNormal());
  return speeds;
}

std::vector<double> rows(const std::vector<double>& series, std::size_t first, std::size_t end)
{
  return {series.begin() + static_cast<long>(first), series.begin() + static_cast<long>(end)};
}

/// A run of measured speeds (the follower's and the leader's from their own seeds).
acc::CarFollowingRun measuredRun(std::size_t samples, std::uint64_t seed)
{
  acc::CarFollowingRun run;
  run.follower_speed_mps = measuredSpeeds(samples, seed);
  run.leader_speed_mps = measuredSpeeds(samples, seed + 1000);
  for (std::size_t k = 0; k < samples; ++k)
  {
    run.time_s.push_back(0.1 * static_cast<double>(k));
    run.space_gap_m.push_back(20.0);
  }
  return run;
}

acc::CarFollowingRun rowsOf(const acc::CarFollowingRun& run, std::size_t first, std::size_t end)
{
  acc::CarFollowingRun part;
  part.time_s = rows(run.time_s, first, end);
  part.follower_speed_mps = rows(run.follower_speed_mps, first, end);
  part.leader_speed_mps = rows(run.leader_speed_mps, first, end);
  part.space_gap_m = rows(run.space_gap_m, first, end);
  return part;
}
}  // namespace

TEST(RepeatedRecording, AnExcerptIsFoundWhereItStarts)
{
  const std::vector<double> drive = measuredSpeeds(3000, 1);
  acc::RepeatedRecordingIndex index;
  index.add({measuredSpeeds(3000, 2)}, 7);
  index.add({drive}, 8);
  const auto repeat = index.find({rows(drive, 1234, 1600)});
  ASSERT_TRUE(repeat);
  EXPECT_EQ(repeat->id, 8u);
  // The first indexed stretch at or after row 1234 is at 1240: found there, 6 rows into the excerpt.
  EXPECT_EQ(repeat->earlier_row, 1240u);
  EXPECT_EQ(repeat->later_row, 6u);
}

TEST(RepeatedRecording, DifferentDrivesAreNotTheSameRecording)
{
  acc::RepeatedRecordingIndex index;
  for (std::uint64_t seed = 1; seed <= 20; ++seed)
    index.add({measuredSpeeds(3000, seed)}, seed);
  for (std::uint64_t seed = 21; seed <= 40; ++seed)
    EXPECT_FALSE(index.find({measuredSpeeds(3000, seed)})) << seed;
}

TEST(RepeatedRecording, AnyOverlapOfTheIndexedLengthIsFoundWhateverItsAlignment)
{
  // Every tenth stretch is indexed: a shared stretch of 100 + 10 - 1 samples holds one whole.
  const std::vector<double> drive = measuredSpeeds(1000, 3);
  acc::RepeatedRecordingIndex index;
  index.add({drive}, 0);
  for (std::size_t first = 300; first < 310; ++first)
  {
    std::vector<double> other = measuredSpeeds(600, 4);
    const std::vector<double> shared = rows(drive, first, first + acc::kRepeatedRecordingMinSamples + 9);
    std::copy(shared.begin(), shared.end(), other.begin() + 200);
    EXPECT_TRUE(index.find({other})) << first;
  }
  // One sample shorter, a stretch that starts just after an indexed one is not found.
  std::vector<double> other = measuredSpeeds(600, 4);
  const std::vector<double> shared = rows(drive, 301, 301 + acc::kRepeatedRecordingMinSamples + 8);
  std::copy(shared.begin(), shared.end(), other.begin() + 200);
  EXPECT_FALSE(index.find({other}));
}

TEST(RepeatedRecording, AStandstillOrAHeldValueDecidesNothing)
{
  std::vector<double> standing(2000, 0.0), held = measuredSpeeds(2000, 5);
  std::fill(held.begin() + 500, held.begin() + 1500, 13.37);  // a recorder holding its last value
  acc::RepeatedRecordingIndex index;
  index.add({standing}, 0);
  index.add({held}, 1);
  std::vector<double> other = measuredSpeeds(2000, 6);
  std::fill(other.begin() + 100, other.begin() + 900, 0.0);
  std::fill(other.begin() + 1000, other.begin() + 1900, 13.37);
  EXPECT_FALSE(index.find({other}));
  EXPECT_FALSE(index.find({standing}));
}

TEST(RepeatedRecording, MinusZeroEqualsZeroAndStretchesWithNanAreSkipped)
{
  std::vector<double> drive = measuredSpeeds(1000, 8);
  drive[120] = 0.0;
  drive[50] = std::numeric_limits<double>::quiet_NaN();  // the first stretches cannot decide
  acc::RepeatedRecordingIndex index;
  index.add({drive}, 0);
  std::vector<double> copy = drive;
  copy[120] = -0.0;
  const auto repeat = index.find({copy});
  ASSERT_TRUE(repeat);
  EXPECT_EQ(repeat->later_row, 60u);  // the first indexed stretch without the NaN
}

TEST(RepeatedRecording, ARecordingRepeatsOnlyWhenEveryVaryingSeriesDoesAtOneShift)
{
  // Noise-free simulations share their leader's profile and differ in their followers.
  const acc::CarFollowingRun a = acc_test::oscillatingRun({});
  acc_test::Oscillation later;
  later.follower_delay_s = 1.2;
  const acc::CarFollowingRun b = acc_test::oscillatingRun(later);
  acc::RepeatedRecordingIndex index;
  index.add({a.leader_speed_mps, a.follower_speed_mps}, 0);
  EXPECT_FALSE(index.find({b.leader_speed_mps, b.follower_speed_mps}));
  // Both series repeat, but at two shifts: not one recording.
  const std::vector<double> drive = measuredSpeeds(1000, 9), other = measuredSpeeds(1000, 10);
  index.add({drive, other}, 1);
  EXPECT_FALSE(index.find({rows(drive, 100, 400), rows(other, 200, 500)}));
  // The second series equal only in its later half (a partial copy): the first row where the
  // recordings meet decides, and a shift refuted there is not tried again further on.
  std::vector<double> partly = rows(measuredSpeeds(1000, 11), 0, 300);
  const std::vector<double> copied_half = rows(other, 400, 700);
  partly.insert(partly.end(), copied_half.begin(), copied_half.end());
  EXPECT_FALSE(index.find({rows(drive, 100, 700), partly}));
  const auto repeat = index.find({rows(drive, 100, 400), rows(other, 100, 400)});
  ASSERT_TRUE(repeat);
  EXPECT_EQ(repeat->id, 1u);
  // A series that does not vary where the two overlap (a car at standstill) is not asked to.
  std::vector<double> parked(300, 0.0);
  EXPECT_TRUE(index.find({rows(drive, 100, 400), parked}));
  // An earlier recording whose first series is empty (a car without speeds) still has its rows: a
  // series that stands still where the match is found is compared where it moves.
  std::vector<double> stood = measuredSpeeds(1000, 31), unrelated = measuredSpeeds(1000, 32);
  std::fill(stood.begin() + 100, stood.begin() + 250, 5.0);
  std::fill(unrelated.begin() + 100, unrelated.begin() + 250, 5.0);
  acc::RepeatedRecordingIndex with_empty;
  with_empty.add({{}, drive, stood}, 0);
  EXPECT_TRUE(with_empty.find({rows(drive, 100, 400), rows(stood, 100, 400)}));
  EXPECT_FALSE(with_empty.find({rows(drive, 100, 400), rows(unrelated, 100, 400)}));
}

TEST(RepeatedRecording, APartialOverlapIsFoundFromEitherSide)
{
  const std::vector<double> leader = measuredSpeeds(2000, 11), follower = measuredSpeeds(2000, 12);
  acc::RepeatedRecordingIndex index;
  index.add({rows(leader, 500, 2000), rows(follower, 500, 2000)}, 0);
  // Starts 500 rows before the earlier export and ends inside it.
  const auto repeat = index.find({rows(leader, 0, 1000), rows(follower, 0, 1000)});
  ASSERT_TRUE(repeat);
  EXPECT_EQ(repeat->earlier_row, 0u);
  EXPECT_EQ(repeat->later_row, 500u);
}

TEST(RepeatedRecording, RunsAreComparedWithinAndAcrossInputs)
{
  const acc::CarFollowingRun drive = measuredRun(2000, 13);
  // One drive given twice in one input (appended after itself) is a repeat too.
  const auto twice = acc::findRepeatedRun({drive, drive}, {0, 0});
  ASSERT_TRUE(twice);
  EXPECT_EQ(twice->later, 1u);
  EXPECT_EQ(twice->earlier, 0u);
  const auto repeat = acc::findRepeatedRun({measuredRun(2000, 14), drive, rowsOf(drive, 300, 900)}, {0, 0, 1});
  ASSERT_TRUE(repeat);
  EXPECT_EQ(repeat->later, 2u);
  EXPECT_EQ(repeat->earlier, 1u);
  EXPECT_EQ(repeat->where.earlier_row, 300u);
  // A run with the follower of one drive behind the leader of another is not a repeat, nor are
  // different drives of one input.
  acc::CarFollowingRun mixed = measuredRun(2000, 15);
  mixed.follower_speed_mps = drive.follower_speed_mps;
  EXPECT_FALSE(acc::findRepeatedRun({drive, mixed}, {0, 1}));
  EXPECT_FALSE(acc::findRepeatedRun({drive, measuredRun(2000, 16), measuredRun(2000, 17)}, {0, 0, 0}));
  // Said as one input's, or as another's.
  const std::vector<acc::CarFollowingRun> runs{drive, rowsOf(drive, 300, 900)};
  EXPECT_NE(acc::describeRepeatedRun(runs, {0, 0}, {"a.csv", "a.csv"}).find("one drive given twice in this input"),
            std::string::npos);
  EXPECT_NE(acc::describeRepeatedRun(runs, {0, 1}, {"a.csv", "b.csv"}).find("a copy, an excerpt"), std::string::npos);
}

// A file's neighbouring pairs share a car: the follower of the first leads the second. When the
// second's follower hardly changes its speed (whole km/h, held values), the shared car's speeds
// alone repeat: within one input that is no repeat (both series must vary and repeat); across
// inputs a steady series decides nothing, as before.
TEST(RepeatedRecording, NeighbouringPairsOfOneFileAreNoRepeatWhereOneCarIsSteady)
{
  const acc::CarFollowingRun first = measuredRun(2000, 18);  // car 2 behind car 1
  acc::CarFollowingRun second = first;                        // car 3 behind car 2
  second.leader_speed_mps = first.follower_speed_mps;
  for (std::size_t k = 0; k < second.size(); ++k)  // held at 1 Hz: 10 changes in 100 samples
    second.follower_speed_mps[k] = first.follower_speed_mps[k - k % 10] - 0.5;
  EXPECT_FALSE(acc::findRepeatedRun({first, second}, {0, 0}));
  EXPECT_TRUE(acc::findRepeatedRun({first, second}, {0, 1}));
}

// Within one input, a repeat at other time stamps is no drive given twice: a noise-free Newell
// platoon's second pair is its first, 12 samples later; so is a periodic noise-free drive's
// second piece. Across inputs the same runs are a repeat.
TEST(RepeatedRecording, WithinOneInputARepeatAtOtherTimesIsNot)
{
  const acc::CarFollowingRun drive = measuredRun(2000, 19);
  acc::CarFollowingRun later = rowsOf(drive, 12, 2000);
  for (double& t : later.time_s)
    t += 1.2;  // the same values 12 samples later
  EXPECT_FALSE(acc::findRepeatedRun({drive, later}, {0, 0}));
  EXPECT_TRUE(acc::findRepeatedRun({drive, later}, {0, 1}));
}
