#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/paper_settings.h"


namespace
{
std::vector<acc::CarFollowingRun> twoSegments()
{
  // Two segments with different steps (10 Hz and 5 Hz) and speeds: pooled, each from its start.
  return {acc::synthesizeRun(acc::paperMinimumSetting(), 200.0, 0.1, 25.0, 1),
          acc::synthesizeRun(acc::paperMinimumSetting(), 150.0, 0.2, 15.0, 2)};
}

/// The speed MSE of simulateFollower (the reference recursion), pooled over runs.
double referenceMse(const acc::AccParameters& p, const std::vector<acc::CarFollowingRun>& runs)
{
  double sum = 0.0;
  std::size_t n = 0;
  for (const auto& run : runs)
  {
    const auto sim = acc::simulateFollower(p, run);
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      sum += std::pow(run.follower_speed_mps[k] - sim.speed_mps[k], 2);
    }
    n += run.size();
  }
  return sum / static_cast<double>(n);
}

TEST(CalibrationObjective, AgreesWithTheReferenceSimulationToRounding)
{
  const auto runs = twoSegments();
  const acc::CalibrationObjective objective(runs);
  for (const acc::AccParameters& theta : {acc::AccParameters{0.08, 0.44, 0.52, 0}, acc::AccParameters{0.3, 0.1, 2.0, 0},
                                          acc::AccParameters{0.01, 1.2, 0.1, 0}})
  {
    const auto value = objective.evaluate(theta.k1_per_s2, theta.k2_per_s, theta.tau_e_s, true);
    ASSERT_FALSE(value.diverged);
    acc::AccParameters with_eta = theta;
    with_eta.eta_m = value.eta_m;
    const double reference = referenceMse(with_eta, runs);
    EXPECT_NEAR(value.mse_speed_mps2, reference, 1e-10 * reference + 1e-14)
        << "k1 " << theta.k1_per_s2 << " k2 " << theta.k2_per_s << " tau " << theta.tau_e_s;
  }
}

TEST(CalibrationObjective, ClosedFormEtaIsTheBestEta)
{
  const auto runs = twoSegments();
  const acc::CalibrationObjective objective(runs);
  const auto value = objective.evaluate(0.1, 0.5, 0.7, false);
  ASSERT_GT(value.eta_m, 0.5);
  acc::AccParameters p{0.1, 0.5, 0.7, value.eta_m};
  const double at_best = referenceMse(p, runs);
  for (double delta : {-0.1, -0.01, -0.001, 0.001, 0.01, 0.1})
  {
    p.eta_m = value.eta_m + delta;
    EXPECT_GT(referenceMse(p, runs), at_best) << "eta moved by " << delta;
  }
}

TEST(CalibrationObjective, EtaIsClippedToItsBounds)
{
  // A follower that keeps a gap shorter than tau_e v alone wants a negative eta: it gets 0, and the
  // objective is the reference's at eta = 0.
  const auto runs = twoSegments();
  const acc::CalibrationObjective objective(runs);
  const auto value = objective.evaluate(0.08, 0.44, 3.0, true);
  EXPECT_EQ(value.eta_m, 0.0);
  EXPECT_NEAR(value.mse_speed_mps2, referenceMse({0.08, 0.44, 3.0, 0.0}, runs), 1e-10 * value.mse_speed_mps2);
}

TEST(CalibrationObjective, GradientMatchesCentralDifferences)
{
  const auto runs = twoSegments();
  const acc::CalibrationObjective objective(runs);
  for (const acc::AccParameters& theta : {acc::AccParameters{0.08, 0.44, 0.52, 0}, acc::AccParameters{0.2, 0.2, 1.5, 0},
                                          acc::AccParameters{0.05, 0.9, 3.0, 0}})
  {
    const auto value = objective.evaluate(theta.k1_per_s2, theta.k2_per_s, theta.tau_e_s, true);
    const double base[3] = {theta.k1_per_s2, theta.k2_per_s, theta.tau_e_s};
    for (int i = 0; i < 3; ++i)
    {
      const double step = 1e-6 * std::max(1.0, base[i]);
      double plus[3] = {base[0], base[1], base[2]}, minus[3] = {base[0], base[1], base[2]};
      plus[i] += step;
      minus[i] -= step;
      const double numeric = (objective.evaluate(plus[0], plus[1], plus[2], false).mse_speed_mps2 -
                              objective.evaluate(minus[0], minus[1], minus[2], false).mse_speed_mps2) /
                             (2.0 * step);
      EXPECT_NEAR(value.gradient[i], numeric, 1e-5 * std::abs(numeric) + 1e-7)
          << "parameter " << i << " at k1 " << base[0] << " k2 " << base[1] << " tau " << base[2];
    }
  }
}

TEST(CalibrationObjective, DivergentParametersGiveAFinitePenaltyNotNaN)
{
  const auto runs = twoSegments();
  const acc::CalibrationObjective objective(runs);
  // Pure spring (no damping, k1 > 0): the Euler map's determinant 1 + h^2 k1 exceeds 1 and
  // the oscillation grows without bound over these runs.
  const auto value = objective.evaluate(2.0, 0.0, 0.0, true);
  EXPECT_TRUE(value.diverged);
  EXPECT_TRUE(std::isfinite(value.mse_speed_mps2));
  EXPECT_EQ(value.mse_speed_mps2, acc::kDivergedMseMps2);
  for (double g : value.gradient)
  {
    EXPECT_TRUE(std::isfinite(g));
  }
  EXPECT_TRUE(acc::simulateFollower({2.0, 0.0, 0.0, value.eta_m}, runs[0]).diverged);
}

TEST(CalibrationObjective, RejectsSegmentsThatCannotBeSimulated)
{
  acc::CarFollowingRun bad;
  bad.name = "one-sample";
  bad.time_s = {0.0};
  bad.space_gap_m = {10.0};
  bad.follower_speed_mps = {10.0};
  bad.leader_speed_mps = {10.0};
  EXPECT_THROW(acc::CalibrationObjective({bad}), std::invalid_argument);
  EXPECT_THROW(acc::CalibrationObjective({}), std::invalid_argument);
}
}  // namespace
