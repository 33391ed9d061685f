// The gap against the integrated speeds (io/gap_kinematics.h): agreement, a unit error, a jump.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "acc_identification/io/gap_kinematics.h"
#include "acc_identification/io/run_csv.h"
#include "oscillating_run.h"

namespace
{
/// 120 s at 10 Hz: the leader oscillates by 3 m/s with a 30 s period, the follower lags it by 2 s,
/// and the gap is the integral of the difference (exact to the trapezoid), plus 0.3 m of
/// alternating noise.
acc::CarFollowingRun consistentRun()
{
  acc::CarFollowingRun run = acc_test::oscillatingRun({120.0, 20.0, 3.0, 30.0, 2.0, 30.0});
  for (std::size_t k = 0; k < run.size(); ++k)
    run.space_gap_m[k] += k % 2 == 0 ? 0.3 : -0.3;
  return run;
}

TEST(GapKinematics, AGapThatFollowsTheSpeedsPasses)
{
  const acc::GapKinematics k = acc::checkGapKinematics({consistentRun()});
  EXPECT_EQ(k.windows, 12u);
  EXPECT_NEAR(k.scale, 1.0, 0.05);
  EXPECT_GT(k.relative_motion_m, 3.0);
  EXPECT_LT(k.rms_mismatch_m, 0.7);
  EXPECT_EQ(k.jump_windows, 0u);
  EXPECT_TRUE(k.warnings.empty()) << k.warnings.front();
}

TEST(GapKinematics, SpeedsInKilometresPerHourAreAUnitError)
{
  acc::CarFollowingRun run = consistentRun();
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    run.leader_speed_mps[k] *= 3.6;
    run.follower_speed_mps[k] *= 3.6;
  }
  const acc::GapKinematics k = acc::checkGapKinematics({run});
  EXPECT_NEAR(k.scale, 1.0 / 3.6, 0.02);
  ASSERT_GE(k.warnings.size(), 1u);
  EXPECT_NE(k.warnings[0].find("the gap changes at 0.28 of the rate the speed difference says"), std::string::npos)
      << k.warnings[0];
  EXPECT_NE(k.warnings[0].find("check the units"), std::string::npos) << k.warnings[0];
  EXPECT_TRUE(k.ratio_judged);
  EXPECT_EQ(k.unit_error, k.warnings[0]);
}

// The readers refuse such a run rather than fit it, and say why (a fit to a gap in metres and
// speeds in km/h reads each speed change 3.6 times too large).
TEST(GapKinematics, TheReadersRefuseARunWhoseUnitsDisagree)
{
  acc::CarFollowingRun run = consistentRun();
  std::ostringstream log;
  acc::RunFileContents contents;
  contents.runs = {run};
  EXPECT_NO_THROW(acc::reportAndTakeRuns("metres.csv", contents, log));
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    run.leader_speed_mps[k] *= 3.6;
    run.follower_speed_mps[k] *= 3.6;
  }
  contents.runs = {run};
  try
  {
    acc::reportAndTakeRuns("kmh.csv", contents, log);
    ADD_FAILURE() << "a run whose gap and speeds disagree by a unit was taken";
  }
  catch (const acc::RunReadError& error)
  {
    const std::string what = error.what();
    EXPECT_NE(what.find("kmh.csv: the gap and the speeds disagree"), std::string::npos) << what;
    EXPECT_NE(what.find("check the units: not used"), std::string::npos) << what;
  }
}

// An OpenACC file read pair by pair (--all-pairs): one pair whose gap is in feet among four in
// metres passed the file's pooled check (ratio 1.5, within its bounds) and entered the fit.
// Refused naming the pair, as that pair alone (--follower) is.
TEST(GapKinematics, APairInOtherUnitsAmongSeveralIsRefused)
{
  acc::RunFileContents contents;
  for (int pair = 0; pair < 5; ++pair)
  {
    acc::CarFollowingRun run = consistentRun();
    if (pair == 3)
      for (double& gap_m : run.space_gap_m)
        gap_m *= 3.28084;
    contents.runs.push_back(run);
    contents.run_pairs.push_back(static_cast<std::size_t>(pair));
    contents.pairs.push_back({pair + 1, pair + 2, "CAR_" + std::to_string(pair + 1), "CAR_" + std::to_string(pair + 2)});
  }
  const acc::GapKinematics pooled = acc::checkGapKinematics(contents.runs);
  EXPECT_TRUE(pooled.unit_error.empty()) << "the pooled check alone sees no unit error: " << pooled.scale;
  std::ostringstream log;
  try
  {
    acc::reportAndTakeRuns("platoon.csv", contents, log);
    ADD_FAILURE() << "a pair whose gap is in feet was taken";
  }
  catch (const acc::RunReadError& error)
  {
    const std::string what = error.what();
    EXPECT_NE(what.find("platoon.csv: CAR_5 behind CAR_4, positions 5/4: the gap and the speeds disagree"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("check the units: not used"), std::string::npos) << what;
  }
  contents.runs[3] = consistentRun();
  EXPECT_EQ(acc::reportAndTakeRuns("platoon.csv", contents, log).size(), 5u);
}

TEST(GapKinematics, AGapThatJumpsIsNamedWithItsWindow)
{
  acc::CarFollowingRun run = consistentRun();
  for (std::size_t k = 455; k < 655; ++k)  // 45.5-65.4 s: the gap reads 25 m short
    run.space_gap_m[k] -= 25.0;
  const acc::GapKinematics k = acc::checkGapKinematics({run});
  EXPECT_EQ(k.jump_windows, 2u);
  ASSERT_EQ(k.warnings.size(), 1u);  // the ratio over all windows is not a unit error
  EXPECT_EQ(k.worst_start_s, 40.0);
  EXPECT_NE(k.warnings[0].find("synthetic: the gap changes by -35.1 m from t = 40.0 s to 50.0 s where the speeds say -10.1 m"),
            std::string::npos)
      << k.warnings[0];
  EXPECT_NE(k.warnings[0].find("2 of 12 windows are off by more than 10 m"), std::string::npos) << k.warnings[0];
}

TEST(GapKinematics, SteadyFollowingDoesNotJudgeTheRatio)
{
  acc::CarFollowingRun run = consistentRun();
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    run.leader_speed_mps[k] = 3.6 * 20.0;  // km/h, but the cars never move against each other
    run.follower_speed_mps[k] = 3.6 * 20.0;
    run.space_gap_m[k] = 30.0 + (k % 2 == 0 ? 0.3 : -0.3);
  }
  const acc::GapKinematics k = acc::checkGapKinematics({run});
  EXPECT_LT(k.relative_motion_m, 3.0);
  EXPECT_FALSE(k.ratio_judged);
  EXPECT_TRUE(k.unit_error.empty());
  EXPECT_TRUE(k.warnings.empty());
}

TEST(GapKinematics, RunsShorterThanAWindowGiveNoWindow)
{
  acc::CarFollowingRun run = consistentRun().slice(0, 50);
  const acc::GapKinematics k = acc::checkGapKinematics({run});
  EXPECT_EQ(k.windows, 0u);
  EXPECT_TRUE(std::isnan(k.scale));
  EXPECT_TRUE(k.warnings.empty());
}
}  // namespace
