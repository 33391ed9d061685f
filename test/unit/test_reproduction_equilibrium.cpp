// The science behind the platoon tool's figures that used to live in the tool: the equilibrium
// regression of Fig. 5 (per run and pooled), the short platoon and step excursion of Figs. 2
// and 8, |Gamma|^N of Fig. 7 and the closed-form check of Fig. 1.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "acc_identification/model/acc_model.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/model/platoon_simulation.h"
#include "acc_identification/reproduction/equilibrium_regression.h"
#include "acc_identification/reproduction/lambda2_map.h"
#include "acc_identification/reproduction/lead_inputs.h"
#include "acc_identification/reproduction/platoon_responses.h"

namespace
{
/// A run that sits exactly on the line eta + tau_e v of p at each held speed, with a few unsteady
/// samples (leader faster than the follower) in between.
acc::CarFollowingRun onTheLine(const acc::AccParameters& p, const std::vector<double>& speeds_mps)
{
  acc::CarFollowingRun run;
  run.name = "on the line";
  for (double v : speeds_mps)
  {
    for (int i = 0; i < 50; ++i)
    {
      run.time_s.push_back(0.1 * static_cast<double>(run.time_s.size()));
      run.follower_speed_mps.push_back(v);
      run.leader_speed_mps.push_back(i < 5 ? v + 2.0 : v);  // the first 5 of each hold unsteady
      run.space_gap_m.push_back(acc::equilibriumSpaceGapM(p, v));
    }
  }
  return run;
}
}  // namespace

TEST(EquilibriumRegression, OneRunRecoversItsLineAndMeasuresEachSetting)
{
  const acc::AccParameters truth = acc::paperMaximumSetting();
  const auto run = onTheLine(truth, {15.0, 20.0, 25.0});
  const auto r = acc::regressEquilibrium(run, {truth, acc::paperMinimumSetting()}, 0.5, 0.1);
  EXPECT_EQ(r.steady, acc::steadyFollowingSamples(run, 0.5, 0.1));
  EXPECT_LT(r.steady.size(), run.size());
  ASSERT_TRUE(r.line.has_value());
  EXPECT_NEAR(r.line->slope_s, truth.tau_e_s, 1e-9);
  EXPECT_NEAR(r.line->intercept_m, truth.eta_m, 1e-7);
  ASSERT_EQ(r.rms_from_line_m.size(), 2u);
  EXPECT_NEAR(r.rms_from_line_m[0], 0.0, 1e-9);
  EXPECT_GT(r.rms_from_line_m[1], 10.0);
  EXPECT_TRUE(r.no_line_reason.empty());
}

TEST(EquilibriumRegression, OneSpeedGivesNoLineButStillTheDistances)
{
  const acc::AccParameters truth = acc::paperMinimumSetting();
  const auto r = acc::regressEquilibrium(onTheLine(truth, {20.0}), {truth}, 0.5, 0.1);
  EXPECT_FALSE(r.line.has_value());
  EXPECT_NE(r.no_line_reason.find("more than one speed"), std::string::npos) << r.no_line_reason;
  ASSERT_EQ(r.rms_from_line_m.size(), 1u);
  EXPECT_NEAR(r.rms_from_line_m[0], 0.0, 1e-9);
}

// Each run alone holds one speed (no line), pooled they pin it: why Fig. 5 pools the campaign.
TEST(EquilibriumRegression, PoolingRunsOfOneSpeedEachPinsTheLine)
{
  const acc::AccParameters truth = acc::paperMaximumSetting();
  const std::vector<acc::CarFollowingRun> runs{onTheLine(truth, {14.0}), onTheLine(truth, {27.0})};
  const auto pooled_run = acc::pooledSteadySamples(runs, 0.5, 0.1);
  const std::size_t steady_each = acc::steadyFollowingSamples(runs[0], 0.5, 0.1).size();
  ASSERT_EQ(pooled_run.size(), 2 * steady_each);
  EXPECT_EQ(pooled_run.follower_speed_mps.front(), 14.0);
  EXPECT_EQ(pooled_run.follower_speed_mps.back(), 27.0);
  const auto pooled = acc::regressPooledEquilibrium(runs, {truth}, 0.5, 0.1);
  EXPECT_EQ(pooled.steady.size(), pooled_run.size());
  ASSERT_TRUE(pooled.line.has_value());
  EXPECT_NEAR(pooled.line->slope_s, truth.tau_e_s, 1e-9);
  EXPECT_NEAR(pooled.line->intercept_m, truth.eta_m, 1e-7);
  EXPECT_FALSE(acc::regressEquilibrium(runs[0], {truth}, 0.5, 0.1).line.has_value());
}

TEST(PlatoonResponses, FirstFollowersIsTheShortPlatoonOfTheSameSimulation)
{
  const auto lead = acc::stepDownUpLeadProfile(25.0, 5.0, 20.0, 60.0, 120.0, 0.1);
  const auto platoon = acc::simulatePlatoon(acc::paperMinimumSetting(), lead, 0.1, 8);
  const auto shorter = acc::firstFollowers(platoon, 3);
  ASSERT_EQ(shorter.vehicleCount(), 4u);
  EXPECT_EQ(shorter.speed_mps[3], platoon.speed_mps[3]);
  EXPECT_EQ(shorter.space_gap_m.size(), 4u);
  EXPECT_EQ(acc::firstFollowers(platoon, 20).vehicleCount(), platoon.vehicleCount());
}

// Fig. 2: the unstable time gap overshoots the cruise speed, the stable one stays in the lead's range.
TEST(PlatoonResponses, StepExcursionIsZeroInsideTheLeadsRange)
{
  const auto lead = acc::stepDownUpLeadProfile(25.0, 5.0, 20.0, 60.0, 200.0, 0.1);
  const auto unstable = acc::measureDisturbanceResponse(
      acc::simulatePlatoon(acc::paperFigure2Setting(0.75), lead, 0.1, 9));
  const auto stable =
      acc::measureDisturbanceResponse(acc::simulatePlatoon(acc::paperFigure2Setting(3.2), lead, 0.1, 9));
  const auto u = acc::lastFollowerStepExcursion(unstable, 20.0);
  EXPECT_GT(u.overshoot_above_cruise_mps, 1.0);
  EXPECT_GT(u.undershoot_below_low_speed_mps, 0.0);
  EXPECT_DOUBLE_EQ(u.undershoot_below_low_speed_mps, 20.0 - unstable.per_vehicle.back().minimum_speed_mps);
  const auto s = acc::lastFollowerStepExcursion(stable, 20.0);
  EXPECT_LT(s.undershoot_below_low_speed_mps, 1e-6);
  EXPECT_LT(s.overshoot_above_cruise_mps, 1e-6);
}

TEST(PlatoonResponses, SinusoidGainOverThePlatoonIsTheGainToTheN)
{
  const double w = 0.204;
  const auto lead = acc::sinusoidLeadProfile(20.0, 1.0, w, 20.0, 300.0, 0.1);
  const auto platoon = acc::simulatePlatoon(acc::paperMinimumSetting(), lead, 0.1, 6);
  const auto r = acc::measureSinusoidResponse(platoon, acc::paperMinimumSetting(), w, lead.size() / 2);
  EXPECT_DOUBLE_EQ(r.model_gain_over_platoon, std::pow(r.model_gain, 6));
  EXPECT_DOUBLE_EQ(r.euler_gain_over_platoon, std::pow(r.euler_gain, 6));
  EXPECT_GT(r.model_gain_over_platoon, 1.0);  // the minimum setting amplifies at this frequency
}

TEST(Lambda2Map, ClosedFormDisagreementsCountsDifferingVerdicts)
{
  acc::Lambda2MapGrid grid;
  grid.k1_points = grid.k2_points = 21;
  auto map = acc::lambda2Map(grid);
  EXPECT_EQ(acc::closedFormDisagreements(map), 0u);
  map[0].string_stable = !map[0].string_stable;
  map[7].string_stable = !map[7].string_stable;
  EXPECT_EQ(acc::closedFormDisagreements(map), 2u);
}
