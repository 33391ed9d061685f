// The synthetic runs of the calibration's tests and benchmarks (synthesis/synthetic_runs.h):
// portable seeded noise, and a truth finer than the fit's Euler recursion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/normal_source.h"
#include "acc_identification/model/paper_settings.h"

namespace
{
double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    worst = std::max(worst, std::abs(a[k] - b[k]));
  }
  return worst;
}
}  // namespace

// The seed's acc::NormalSource stream makes the data: three uniforms for the leader's phases,
// then per sample follower speed, gap and leader speed errors. The same on every platform.
TEST(SyntheticRuns, NoiseIsTheSeedsPortableNormalNumbers)
{
  const acc::MeasurementNoise noise;
  const auto noisy = acc::synthesizeRun(acc::paperMinimumSetting(), 30.0, 0.1, 22.0, 5, noise);
  const auto exact = acc::synthesizeRun(acc::paperMinimumSetting(), 30.0, 0.1, 22.0, 5, {0.0, 0.0});
  ASSERT_EQ(noisy.size(), 301u);
  acc::NormalSource normal(5);
  for (int i = 0; i < 3; ++i)
  {
    normal.uniformOpenClosed();
  }
  for (std::size_t k = 0; k < noisy.size(); ++k)
  {
    ASSERT_NEAR(noisy.follower_speed_mps[k] - exact.follower_speed_mps[k], noise.speed_std_mps * normal.standardNormal(), 1e-9) << k;
    ASSERT_NEAR(noisy.space_gap_m[k] - exact.space_gap_m[k], noise.gap_std_m * normal.standardNormal(), 1e-9) << k;
    ASSERT_NEAR(noisy.leader_speed_mps[k] - exact.leader_speed_mps[k], noise.speed_std_mps * normal.standardNormal(), 1e-9) << k;
  }
}

// No inverse crime: the noise-free data are not the fit's own Euler recursion at the data step
// (which would make recovery exact by construction), yet close to it, as a real car's record
// would be to a good model.
TEST(SyntheticRuns, TruthIsFinerThanTheFitsEulerRecursion)
{
  for (const acc::AccParameters& p : {acc::paperMinimumSetting(), acc::paperMaximumSetting()})
  {
    const auto exact = acc::synthesizeRun(p, 300.0, 0.1, 25.0, 3, {0.0, 0.0});
    EXPECT_EQ(exact.follower_speed_mps.front(), exact.leader_speed_mps.front());  // from equilibrium
    const auto replay = acc::simulateFollower(p, exact);
    ASSERT_FALSE(replay.diverged);
    const double speed_difference = maxAbsDifference(replay.speed_mps, exact.follower_speed_mps);
    const double gap_difference = maxAbsDifference(replay.space_gap_m, exact.space_gap_m);
    EXPECT_GT(speed_difference, 1e-3);
    EXPECT_LT(speed_difference, 0.1);  // well below the 0.06 m/s noise's range
    EXPECT_GT(gap_difference, 1e-3);
    EXPECT_LT(gap_difference, 0.5);
  }
}
