// A gap that saw-tooths sample by sample (io/gap_sawtooth.h): found, told apart from noise of any
// size and from a rate error that does not come back, and cut out of the runs the reader reads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "acc_identification/io/gap_kinematics.h"
#include "acc_identification/io/gap_sawtooth.h"
#include "acc_identification/io/run_csv.h"
#include "oscillating_run.h"

namespace
{
/// 60 s: the leader oscillates by 2 m/s with a 20 s period, the follower lags it by 1.5 s.
acc::CarFollowingRun followingRun()
{
  return acc_test::oscillatingRun({});
}

/// Rows [first, end) read as OpenACC run 26's first seconds do: the gap drifts by step_m per
/// sample and is set back to the truth every fourth sample (there every third or fourth).
void addSawtooth(acc::CarFollowingRun* run, std::size_t first, std::size_t end, double step_m)
{
  for (std::size_t k = first; k < end; ++k)
    run->space_gap_m[k] += step_m * static_cast<double>((k - first) % 4);
}

TEST(GapSawtooth, NoiseOfAnySizeIsNotASawtooth)
{
  acc::CarFollowingRun run = followingRun();
  std::mt19937 generator(7);
  std::normal_distribution<double> noise_m(0.0, 1.0);  // far above any receiver's or radar's
  for (double& gap : run.space_gap_m)
    gap += noise_m(generator);
  const acc::GapSawtooth s = acc::checkGapSawtooth({run});
  EXPECT_EQ(s.windows, 30u);
  EXPECT_EQ(s.sawtooth_windows, 0u);
  EXPECT_TRUE(s.spans.empty());
}

TEST(GapSawtooth, AHeldOrExtrapolatedPositionIsNamedWithItsStretch)
{
  acc::CarFollowingRun run = followingRun();
  addSawtooth(&run, 0, 80, 1.0);      // 0-7.9 s: the gap grows 10 m/s, about the cars' speed (11 m/s)
  addSawtooth(&run, 400, 440, -0.5);  // 40-43.9 s: shrinks 5 m/s, not the cars' speed (12 m/s)
  const acc::GapSawtooth s = acc::checkGapSawtooth({run});
  EXPECT_EQ(s.sawtooth_windows, 6u);  // 0-2-4-6-8 s and 40-42-44 s
  ASSERT_EQ(s.spans.size(), 2u);
  EXPECT_EQ(s.spans[0].run, "synthetic");
  // Off from the first step that drifts (sample 1) to the last reset (sample 80, back to the truth).
  EXPECT_EQ(s.spans[0].first_sample, 1u);
  EXPECT_EQ(s.spans[0].end_sample, 81u);
  EXPECT_NEAR(s.spans[0].start_s, 0.1, 1e-9);
  EXPECT_NEAR(s.spans[0].end_s, 8.0, 1e-9);
  EXPECT_NEAR(s.spans[0].median_step_mismatch_m, 1.0, 0.01);
  EXPECT_EQ(s.spans[0].held_position, "follower");
  EXPECT_NEAR(s.spans[1].start_s, 40.1, 1e-9);
  EXPECT_NEAR(s.spans[1].median_step_mismatch_m, -0.5, 0.01);
  EXPECT_EQ(s.spans[1].held_position, "");
  const std::string held = acc::describeSawtoothSpan(s.spans[0]);
  EXPECT_EQ(held.rfind("the gap saw-tooths from t = 0.1 s to 8.0 s: it steps +1.00 m per sample (median) beyond "
                       "what the speeds say (the follower's position held between its updates",
                       0),
            0u)
      << held;
  const std::string other = acc::describeSawtoothSpan(s.spans[1]);
  EXPECT_NE(other.find("-0.50 m per sample (median) beyond what the speeds say and steps back"), std::string::npos)
      << other;
}

// Where the saw-tooth starts and ends inside a window, the window boundaries cut its first and
// last teeth: the span reaches them through the mismatched steps. Fails without the extension.
TEST(GapSawtooth, TheSpanReachesTheTeethItsWindowsCut)
{
  acc::CarFollowingRun run = followingRun();
  addSawtooth(&run, 115, 173, 0.82);  // 11.5-17.2 s, the windows 10-12 ... 16-18 s
  const acc::GapSawtooth s = acc::checkGapSawtooth({run});
  ASSERT_EQ(s.spans.size(), 1u);
  EXPECT_EQ(s.spans[0].first_sample, 116u);  // the first step that drifts
  EXPECT_EQ(s.spans[0].end_sample, 174u);    // through the reset at sample 173
}

TEST(GapSawtooth, AStillLeaderPositionShrinksTheGap)
{
  acc::CarFollowingRun run = followingRun();
  addSawtooth(&run, 200, 260, -1.1);  // 20-25.9 s: the leader's position stands still at 11 m/s
  const acc::GapSawtooth s = acc::checkGapSawtooth({run});
  ASSERT_EQ(s.spans.size(), 1u);
  EXPECT_EQ(s.spans[0].held_position, "leader");
}

TEST(GapSawtooth, ARateErrorThatDoesNotComeBackIsLeftToTheWindows)
{
  acc::CarFollowingRun run = followingRun();
  for (std::size_t k = 0; k < run.size(); ++k)
    run.space_gap_m[k] += 0.6 * static_cast<double>(k);  // the gap opens at 6 m/s the speeds do not show
  const acc::GapSawtooth s = acc::checkGapSawtooth({run});
  EXPECT_EQ(s.sawtooth_windows, 0u);
  const acc::GapKinematics k = acc::checkGapKinematics({run});
  EXPECT_GT(k.jump_windows, 0u);
}

// The reader rebuilds the stretch from the fixes and the speeds, counts and lists it: its gap is
// metres off while every value is plausible. Fails when the reader keeps the measured gap, drops
// the rows, or says nothing.
TEST(GapSawtooth, TheReaderRebuildsItAndSaysSo)
{
  const acc::CarFollowingRun truth = followingRun();
  acc::CarFollowingRun run = truth;
  addSawtooth(&run, 100, 180, 0.82);
  const std::string path = (std::filesystem::temp_directory_path() / "acc_sawtooth_run.csv").string();
  acc::writeRunCsv(path, run);
  const acc::RunFileContents contents = acc::readRunFile(path);
  std::remove(path.c_str());
  EXPECT_EQ(contents.rejected_rows, 0u);
  EXPECT_EQ(contents.sawtooth_rows, 80u);  // samples 101-180 (10.1-18.0 s), file lines 103-182
  ASSERT_EQ(contents.sawtooth_spans.size(), 1u);
  EXPECT_EQ(contents.sawtooth_spans[0].resets, 20u);
  EXPECT_EQ(contents.sawtooth_spans[0].run, "acc_sawtooth_run");
  ASSERT_EQ(contents.runs.size(), 1u);
  ASSERT_EQ(contents.runs[0].size(), truth.size());
  for (std::size_t k = 0; k < truth.size(); ++k)
    ASSERT_NEAR(contents.runs[0].space_gap_m[k], truth.space_gap_m[k], 1e-9) << "sample " << k;
  ASSERT_EQ(contents.problems.size(), 1u);
  EXPECT_NE(contents.problems[0].find("acc_sawtooth_run.csv:103: the gap saw-tooths from t = 10.1 s to 18.0 s"),
            std::string::npos)
      << contents.problems[0];
  EXPECT_NE(contents.problems[0].find("; lines 103-182: the gap of its 80 samples rebuilt from the fixes after its 20 "
                                      "resets and the speeds between them"),
            std::string::npos)
      << contents.problems[0];
  EXPECT_NE(acc::describeRowCounts(path, contents).find(", the gap of 80 rows rebuilt where it saw-tooths"),
            std::string::npos);
  // The 10 s windows of the kinematic check average the saw-tooth away: only this check sees it.
  EXPECT_EQ(acc::checkGapKinematics({run}).jump_windows, 0u);
}

// Between fixes the speeds carry the gap; at each fix it starts again from the measured gap, so a
// speed error does not accumulate over the stretch. Fails when only the first fix is kept (the
// follower's 0.3 m/s error would add up to 2.4 m over 8 s).
TEST(GapSawtooth, EachFreshFixRestartsTheRebuiltGap)
{
  const acc::CarFollowingRun truth = followingRun();
  acc::CarFollowingRun run = truth;
  addSawtooth(&run, 100, 180, 0.82);
  for (std::size_t k = 100; k < 180; ++k)
    run.follower_speed_mps[k] -= 0.3;  // the speed wrong by 0.3 m/s, the gap's fixes right
  const acc::GapSawtooth s = acc::checkGapSawtooth({run});
  ASSERT_EQ(s.spans.size(), 1u);
  acc::rebuildSawtoothGap(s.spans[0], &run);
  double worst_m = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k)
    worst_m = std::max(worst_m, std::abs(run.space_gap_m[k] - truth.space_gap_m[k]));
  EXPECT_LT(worst_m, 0.1);  // three steps of 0.03 m at most
  acc::CarFollowingRun shorter = truth.slice(0, 150);  // the span reaches sample 180
  EXPECT_THROW(acc::rebuildSawtoothGap(s.spans[0], &shorter), std::out_of_range);
}

TEST(GapSawtooth, AShortRunIsNotJudged)
{
  acc::CarFollowingRun run = followingRun().slice(0, 15);
  addSawtooth(&run, 0, 15, 0.82);
  const acc::GapSawtooth s = acc::checkGapSawtooth({run});
  EXPECT_EQ(s.windows, 0u);
  EXPECT_TRUE(s.spans.empty());
}
}  // namespace
