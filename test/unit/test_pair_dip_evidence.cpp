// Model-free dip evidence of pair runs: perturbations of each run's leader found, the follower's
// dips against the leader's, and the ratio's interval deciding amplification.
#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/evidence/pair_dip_evidence.h"

namespace acc
{
namespace
{
/// A V-shaped dip of `depth_mps` from `cruise_mps`, starting at onset_s and lasting 8 s.
double vDip(double t_s, double onset_s, double depth_mps)
{
  const double into = t_s - onset_s;
  if (into <= 0.0 || into >= 8.0)
    return 0.0;
  return depth_mps * (1.0 - std::fabs(into - 4.0) / 4.0);
}

/// 200 s at 10 Hz, cruising at 20 m/s; the leader dips at 40, 100 and 160 s by 2, 3 and 2.5 m/s,
/// the follower 1.5 s later by `gain` times as much (the gap is not used by the evidence).
CarFollowingRun pairRun(double gain, const std::string& name)
{
  CarFollowingRun run;
  run.name = name;
  const double onsets[] = {40.0, 100.0, 160.0}, depths[] = {2.0, 3.0, 2.5};
  for (int i = 0; i < 2000; ++i)
  {
    const double t = 0.1 * i;
    double leader = 20.0, follower = 20.0;
    for (int k = 0; k < 3; ++k)
    {
      leader -= vDip(t, onsets[k], depths[k]);
      follower -= vDip(t, onsets[k] + 1.5, gain * depths[k]);
    }
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(leader);
    run.follower_speed_mps.push_back(follower);
    run.space_gap_m.push_back(30.0);
  }
  return run;
}

// Six perturbations decide it; the first run's three alone, each 1.4 times as deep, do not: the
// interval holds its coverage without assuming how the ratios scatter, and three perturbations
// cannot rule out that the car amplifies no more than it attenuates (the chance that three of
// three lie above 1 when the median ratio is 1 is 1/8).
TEST(PairDipEvidence, AFollowerThatDeepensEveryDipAmplifies)
{
  const PairDipEvidence evidence = pairDipEvidence({pairRun(1.4, "amplifying"), pairRun(1.4, "again")});
  ASSERT_EQ(evidence.dips.size(), 6u);
  EXPECT_NEAR(evidence.dips[1].leader_dip_mps, 3.0, 0.05);
  EXPECT_NEAR(evidence.dips[1].follower_dip_mps, 4.2, 0.1);
  EXPECT_NEAR(evidence.ratio.ratio_of_means, 1.4, 0.03);
  EXPECT_EQ(evidence.ratio.amplifies, DipAmplification::Amplifies) << evidence.ratio.reason;
  const PairDipEvidence three = pairDipEvidence({pairRun(1.4, "amplifying")});
  ASSERT_EQ(three.dips.size(), 3u);
  EXPECT_LT(three.ratio.lower, 1.0);
  EXPECT_EQ(three.ratio.amplifies, DipAmplification::Undecided) << three.ratio.reason;
}

// The follower's V-dips are the leader's, 1.4 times as deep and as long: it brakes and recovers
// 1.4 times as steeply and stays below half its dip exactly as long (4 s), so it passes the shape
// on at 1.4 with no widening.
TEST(PairDipEvidence, TheShapePassedOnIsTheRatioOfThePeakSlopesAndTheWidening)
{
  const PairDipEvidence evidence = pairDipEvidence({pairRun(1.4, "steeper")});
  ASSERT_EQ(evidence.dips.size(), 3u);
  EXPECT_NEAR(evidence.dips[1].leader_shape.braking_mps2, 0.75, 1e-6);
  EXPECT_NEAR(evidence.dips[1].follower_shape.recovery_mps2, 1.05, 1e-6);
  EXPECT_NEAR(evidence.dips[1].leader_shape.width_s, 4.0, 0.05);
  EXPECT_EQ(evidence.shape.braking.observations, 3u);
  EXPECT_NEAR(evidence.shape.braking.ratio, 1.4, 1e-6);
  EXPECT_NEAR(evidence.shape.recovery.ratio, 1.4, 1e-6);
  EXPECT_EQ(evidence.shape.widenings, 3u);
  EXPECT_NEAR(evidence.shape.median_widening_s, 0.0, 0.05);
}

TEST(PairDipEvidence, AFollowerThatSoftensEveryDipAttenuates)
{
  const PairDipEvidence evidence = pairDipEvidence({pairRun(0.7, "a"), pairRun(0.7, "b")});
  ASSERT_EQ(evidence.dips.size(), 6u);
  EXPECT_EQ(evidence.dips[3].run, "b");
  EXPECT_NEAR(evidence.ratio.ratio_of_means, 0.7, 0.03);
  EXPECT_EQ(evidence.ratio.amplifies, DipAmplification::Attenuates) << evidence.ratio.reason;
}

TEST(PairDipEvidence, SteadyDrivingSaysNothing)
{
  CarFollowingRun steady = pairRun(1.0, "steady");
  for (double& v : steady.leader_speed_mps)
    v = 20.0;
  const PairDipEvidence evidence = pairDipEvidence({steady});
  EXPECT_TRUE(evidence.dips.empty());
  EXPECT_EQ(evidence.ratio.amplifies, DipAmplification::Insufficient);
  EXPECT_EQ(evidence.ratio.count, 0u);
}

}  // namespace
}  // namespace acc
