#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/model/acc_model.h"
#include "acc_identification/model/follower_simulation.h"


namespace
{
acc::CarFollowingRun constantLeaderRun(double speed_mps, double gap_m, std::size_t samples, double step_s)
{
  acc::CarFollowingRun run;
  for (std::size_t k = 0; k < samples; ++k)
  {
    run.time_s.push_back(static_cast<double>(k) * step_s);
    run.leader_speed_mps.push_back(speed_mps);
    run.follower_speed_mps.push_back(speed_mps);
    run.space_gap_m.push_back(gap_m);
  }
  return run;
}
}  // namespace

TEST(FollowerSimulation, StaysAtEquilibrium)
{
  const acc::AccParameters p{0.0782, 0.4445, 0.5162, 8.3365};
  const auto run = constantLeaderRun(20.0, acc::equilibriumSpaceGapM(p, 20.0), 500, 0.1);
  const auto sim = acc::simulateFollower(p, run);
  ASSERT_FALSE(sim.diverged);
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    EXPECT_NEAR(sim.speed_mps[k], 20.0, 1e-9);
    EXPECT_NEAR(sim.space_gap_m[k], run.space_gap_m[0], 1e-9);
  }
}

TEST(FollowerSimulation, FollowsTheExplicitEulerRecursionWithTheDataStep)
{
  const acc::AccParameters p{0.2, 0.3, 1.2, 4.0};
  acc::CarFollowingRun run;
  run.time_s = {0.0, 0.1, 0.25, 0.3};  // non-uniform on purpose
  run.leader_speed_mps = {10.0, 11.0, 12.0, 12.0};
  run.follower_speed_mps = {9.0, 0.0, 0.0, 0.0};  // only v(0) is used
  run.space_gap_m = {15.0, 0.0, 0.0, 0.0};        // only s(0) is used
  const auto sim = acc::simulateFollower(p, run);
  double v = 9.0, s = 15.0;
  for (std::size_t k = 0; k + 1 < run.size(); ++k)
  {
    const double h = run.time_s[k + 1] - run.time_s[k];
    const double dv = run.leader_speed_mps[k] - v;
    const double a = 0.2 * (s - 4.0 - 1.2 * v) + 0.3 * dv;
    v += h * a;
    s += h * dv;
    EXPECT_DOUBLE_EQ(sim.speed_mps[k + 1], v);
    EXPECT_DOUBLE_EQ(sim.space_gap_m[k + 1], s);
  }
}

TEST(FollowerSimulation, ConvergesToTheNewEquilibriumAfterALeaderStep)
{
  const acc::AccParameters p{0.0131, 0.2692, 1.6881, 7.5699};
  auto run = constantLeaderRun(20.0, acc::equilibriumSpaceGapM(p, 20.0), 6000, 0.1);
  for (std::size_t k = 100; k < run.size(); ++k) run.leader_speed_mps[k] = 25.0;
  const auto sim = acc::simulateFollower(p, run);
  ASSERT_FALSE(sim.diverged);
  EXPECT_NEAR(sim.speed_mps.back(), 25.0, 0.01);
  EXPECT_NEAR(sim.space_gap_m.back(), acc::equilibriumSpaceGapM(p, 25.0), 0.1);
}

TEST(FollowerSimulation, FlagsDivergenceInsteadOfReturningNaN)
{
  // h (k2 + k1 tau) far above 2: explicit Euler explodes.
  const acc::AccParameters p{5.0, 40.0, 3.0, 2.0};
  auto run = constantLeaderRun(20.0, 30.0, 2000, 0.1);
  run.follower_speed_mps[0] = 15.0;
  const auto sim = acc::simulateFollower(p, run);
  ASSERT_TRUE(sim.diverged);
  EXPECT_GT(sim.diverged_at_index, 0u);
  EXPECT_LT(sim.diverged_at_index, run.size());
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    EXPECT_TRUE(std::isfinite(sim.speed_mps[k]));
    EXPECT_TRUE(std::isfinite(sim.space_gap_m[k]));
  }
}

TEST(FollowerSimulation, ScorableBlanksWhatADivergedSimulationMustNotScore)
{
  const acc::AccParameters p{5.0, 40.0, 3.0, 2.0};
  auto run = constantLeaderRun(20.0, 30.0, 2000, 0.1);
  run.follower_speed_mps[0] = 15.0;
  const auto sim = acc::scorable(acc::simulateFollower(p, run));
  ASSERT_TRUE(sim.diverged);
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    const bool kept = k < sim.diverged_at_index;
    EXPECT_EQ(std::isfinite(sim.speed_mps[k]), kept) << k;
    EXPECT_EQ(std::isfinite(sim.space_gap_m[k]), kept) << k;
  }
  // A simulation that did not diverge is left as it is.
  const auto calm = acc::simulateFollower({0.1, 0.5, 1.2, 5.0}, run);
  const auto same = acc::scorable(calm);
  EXPECT_EQ(same.speed_mps, calm.speed_mps);
  EXPECT_EQ(same.space_gap_m, calm.space_gap_m);
}

// A simulated car that collides or reverses is said, with where; one that diverges is judged up to
// its divergence only (the campaign's chain predictions and its long platoon both ask this).
TEST(FollowerSimulation, ABreakdownIsTheFirstCollisionOrReversalBeforeAnyDivergence)
{
  acc::SimulatedFollower sim;
  sim.speed_mps = {5.0, 2.0, -0.3, -1.0};
  sim.space_gap_m = {10.0, 6.0, 3.0, -1.0};
  const std::vector<double> time_s = {0.0, 0.1, 0.2, 0.3};
  bool collision = true;
  EXPECT_EQ(acc::describeBreakdown(sim, time_s, &collision),
            "its speed reaches -0.30 m/s (driving backwards) at t = 0.2 s");
  EXPECT_FALSE(collision);
  sim.space_gap_m[1] = 0.0;
  EXPECT_EQ(acc::describeBreakdown(sim, time_s, &collision), "its gap reaches 0.0 m (a collision) at t = 0.1 s");
  EXPECT_TRUE(collision);
  sim.diverged = true;
  sim.diverged_at_index = 1;
  EXPECT_EQ(acc::describeBreakdown(sim, time_s, &collision), "");
  EXPECT_FALSE(collision);
}
