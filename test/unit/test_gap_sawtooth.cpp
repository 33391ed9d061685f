// A gap that saw-tooths sample by sample (io/gap_sawtooth.h): found, told apart from noise of any
// size and from a rate error that does not come back, and reported through gap_kinematics.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "acc_identification/io/gap_kinematics.h"
#include "acc_identification/io/gap_sawtooth.h"
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
  EXPECT_TRUE(s.warnings.empty());
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
  EXPECT_NEAR(s.spans[0].start_s, 0.0, 1e-9);
  EXPECT_NEAR(s.spans[0].end_s, 8.0, 1e-9);
  EXPECT_NEAR(s.spans[0].median_step_mismatch_m, 1.0, 0.01);
  EXPECT_EQ(s.spans[0].held_position, "follower");
  EXPECT_NEAR(s.spans[1].start_s, 40.0, 1e-9);
  EXPECT_NEAR(s.spans[1].median_step_mismatch_m, -0.5, 0.01);
  EXPECT_EQ(s.spans[1].held_position, "");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("synthetic from t = 0.0 s to 8.0 s steps +1.00 m per sample (median) beyond what the "
                               "speeds say (the follower's position held between its updates"),
            std::string::npos)
      << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("synthetic from t = 40.0 s to 44.0 s steps -0.50 m per sample (median) beyond what the "
                               "speeds say, and steps back"),
            std::string::npos)
      << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("6 of 30 windows of 2 s"), std::string::npos) << s.warnings[0];
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

TEST(GapSawtooth, TheGapKinematicsWarningsCarryIt)
{
  acc::CarFollowingRun run = followingRun();
  addSawtooth(&run, 100, 180, 0.82);
  const acc::GapKinematics k = acc::checkGapKinematics({run});
  EXPECT_EQ(k.jump_windows, 0u);  // the 10 s windows average it away
  EXPECT_EQ(k.sawtooth.sawtooth_windows, 4u);
  ASSERT_EQ(k.warnings.size(), 1u);
  EXPECT_EQ(k.warnings[0].rfind("the gap saw-tooths: synthetic from t = 10.0 s to 18.0 s", 0), 0u) << k.warnings[0];
}

TEST(GapSawtooth, AShortRunIsNotJudged)
{
  acc::CarFollowingRun run = followingRun().slice(0, 15);
  addSawtooth(&run, 0, 15, 0.82);
  const acc::GapSawtooth s = acc::checkGapSawtooth({run});
  EXPECT_EQ(s.windows, 0u);
  EXPECT_TRUE(s.warnings.empty());
}
}  // namespace
