#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "acc_identification/model/paper_settings.h"
#include "acc_identification/model/platoon_simulation.h"
#include "acc_identification/reproduction/lead_profiles.h"
#include "acc_identification/reproduction/lead_inputs.h"
#include "acc_identification/reproduction/platoon_metrics.h"
#include "acc_identification/reproduction/platoon_responses.h"


namespace
{
constexpr double kStep = 0.1;

// Fig. 7 of the paper: 20 m/s for 20 s, then a 1 m/s sinusoid at 0.204 rad/s, 10 followers.
acc::SinusoidResponse figureSeven(const acc::AccParameters& p)
{
  const double w = 0.204;
  const auto lead = acc::sinusoidLeadProfile(20.0, 1.0, w, 20.0, 620.0, kStep);
  const auto platoon = acc::simulatePlatoon(p, lead, kStep, 10);
  const std::size_t last_five_periods = static_cast<std::size_t>(std::round(5.0 * 2.0 * M_PI / w / kStep));
  return acc::measureSinusoidResponse(platoon, p, w, lead.size() - last_five_periods);
}

// Fig. 8: lead profile I, a long platoon (its first 15 followers are the paper's 15-vehicle one).
acc::DisturbanceResponse figureEight(const acc::AccParameters& p, std::size_t followers)
{
  const auto lead = acc::withFinalHold(acc::leadProfile('I', kStep), 600.0, kStep);
  return acc::measureDisturbanceResponse(acc::simulatePlatoon(p, lead, kStep, followers));
}
}  // namespace

TEST(PlatoonMetrics, SinusoidFitIsExactForAPureSinusoidWhateverTheWindow)
{
  std::vector<double> signal;
  for (int k = 0; k < 2000; ++k)
  {
    signal.push_back(3.0 + 1.7 * std::sin(0.3 * k * 0.05 + 0.4));
  }
  EXPECT_NEAR(acc::fittedSinusoidAmplitude(signal, 0.05, 0.3, 0, 2000), 1.7, 1e-9);
  EXPECT_NEAR(acc::fittedSinusoidAmplitude(signal, 0.05, 0.3, 123, 1500), 1.7, 1e-9);
  EXPECT_THROW(acc::fittedSinusoidAmplitude(signal, 0.05, 0.3, 10, 12), std::invalid_argument);
  EXPECT_THROW(acc::fittedSinusoidAmplitude(signal, 0.05, 0.3, 10, 2001), std::invalid_argument);
}

TEST(PlatoonMetrics, GrowthOnsetFindsWhereADecayingDisturbanceTurns)
{
  const auto turns = acc::findGrowthOnset({10.0, 8.0, 6.0, 5.0, 5.5, 7.0, 11.0, 12.0});
  EXPECT_TRUE(turns.decays_at_first);
  EXPECT_EQ(turns.smallest_at, 3u);
  ASSERT_TRUE(turns.growth_starts_at);
  EXPECT_EQ(*turns.growth_starts_at, 3u);
  ASSERT_TRUE(turns.exceeds_lead_at);
  EXPECT_EQ(*turns.exceeds_lead_at, 6u);

  const auto decays = acc::findGrowthOnset({10.0, 8.0, 6.0, 5.0});
  EXPECT_TRUE(decays.decays_at_first);
  EXPECT_FALSE(decays.growth_starts_at);
  EXPECT_FALSE(decays.exceeds_lead_at);

  const auto grows = acc::findGrowthOnset({1.0, 1.5, 2.0});
  EXPECT_FALSE(grows.decays_at_first);
  EXPECT_EQ(grows.smallest_at, 1u);
  EXPECT_EQ(grows.exceeds_lead_at.value_or(0), 1u);
  EXPECT_THROW(acc::findGrowthOnset({1.0}), std::invalid_argument);
}

// Fig. 2: k1 = k2 = 0.5, eta = 8. tau_e = 0.75 s overshoots more at every follower; 3.2 s never
// leaves the lead's speed range.
TEST(ReproductionPlatoon, FigureTwoStepOvershootsOnlyForTheUnstableTimeGap)
{
  const auto lead = acc::stepDownUpLeadProfile(25.0, 5.0, 20.0, 60.0, 200.0, kStep);
  const auto unstable = acc::measureDisturbanceResponse(
      acc::simulatePlatoon(acc::paperFigure2Setting(0.75), lead, kStep, 9));
  const auto stable = acc::measureDisturbanceResponse(
      acc::simulatePlatoon(acc::paperFigure2Setting(3.2), lead, kStep, 9));
  EXPECT_EQ(unstable.by_peak_to_peak.exceeds_lead_at.value_or(0), 1u);
  EXPECT_FALSE(unstable.by_peak_to_peak.growth_starts_at == std::nullopt);
  EXPECT_GT(unstable.per_vehicle.back().rise_above_reference_mps, 1.0);
  for (std::size_t i = 1; i < stable.per_vehicle.size(); ++i)
  {
    EXPECT_GE(stable.per_vehicle[i].minimum_speed_mps, 20.0 - 1e-6) << i;
    EXPECT_LE(stable.per_vehicle[i].maximum_speed_mps, 25.0 + 1e-6) << i;
  }
}

// Fig. 7: the minimum setting amplifies the 0.204 rad/s oscillation, the maximum damps it, and
// the ratio over n vehicles is |Gamma|^n (exactly that of the Euler recursion the simulation runs).
TEST(ReproductionPlatoon, FigureSevenAmplitudeRatioIsGammaToTheN)
{
  const auto min = figureSeven(acc::paperMinimumSetting());
  const auto max = figureSeven(acc::paperMaximumSetting());
  EXPECT_GT(min.last_to_first_follower, 1.0);
  EXPECT_LT(max.last_to_first_follower, 1.0);
  for (const auto* r : {&min, &max})
  {
    EXPECT_NEAR(r->amplitude_mps[0], 1.0, 1e-6);
    EXPECT_NEAR(r->last_follower_to_lead / std::pow(r->euler_gain, 10), 1.0, 1e-3);
    EXPECT_NEAR(r->last_to_first_follower / std::pow(r->euler_gain, 9), 1.0, 1e-3);
    // The continuous model's |Gamma|^n is close: at h = 0.1 s the Euler gain is ~0.05 dB higher per
    // vehicle at this frequency, 6 % over ten vehicles.
    EXPECT_NEAR(r->last_follower_to_lead / std::pow(r->model_gain, 10), 1.0, 0.08);
    for (std::size_t i = 1; i < r->amplitude_mps.size(); ++i)
    {
      EXPECT_NEAR(r->amplitude_mps[i] / r->amplitude_mps[i - 1], r->euler_gain, 1e-3) << i;
    }
  }
  EXPECT_GT(min.last_follower_to_lead, 3.0);  // about 1.11 dB per vehicle over 10 vehicles
  EXPECT_LT(max.last_follower_to_lead, 0.6);
}

// Fig. 8, minimum setting: the dips grow from the first follower on; the linear model's speeds
// go negative inside the 15-vehicle platoon (the paper does not mention it).
TEST(ReproductionPlatoon, FigureEightMinimumSettingAmplifiesFromTheFirstFollower)
{
  const auto r = figureEight(acc::paperMinimumSetting(), 15);
  EXPECT_FALSE(r.by_drop.decays_at_first);
  EXPECT_EQ(r.by_drop.exceeds_lead_at.value_or(0), 1u);
  for (std::size_t i = 1; i < r.per_vehicle.size(); ++i)
  {
    EXPECT_GT(r.per_vehicle[i].drop_below_reference_mps, r.per_vehicle[i - 1].drop_below_reference_mps) << i;
  }
  EXPECT_GT(r.per_vehicle.back().drop_below_reference_mps / r.per_vehicle[0].drop_below_reference_mps, 2.5);
  ASSERT_TRUE(r.first_negative_speed_vehicle);
  EXPECT_LE(*r.first_negative_speed_vehicle, 15u);
  EXPECT_TRUE(r.last_follower_settled);
}

// Fig. 8, maximum setting: the dip first decays, then grows behind follower ~11 and exceeds the
// lead's dip only past 50 followers (the paper: growth "beyond about 30 vehicles").
TEST(ReproductionPlatoon, FigureEightMaximumSettingDecaysThenGrows)
{
  const auto r = figureEight(acc::paperMaximumSetting(), 70);
  EXPECT_TRUE(r.last_follower_settled);
  EXPECT_TRUE(r.by_drop.decays_at_first);
  ASSERT_TRUE(r.by_drop.growth_starts_at);
  EXPECT_GE(*r.by_drop.growth_starts_at, 8u);
  EXPECT_LE(*r.by_drop.growth_starts_at, 14u);
  ASSERT_TRUE(r.by_drop.exceeds_lead_at);
  EXPECT_GT(*r.by_drop.exceeds_lead_at, 45u);
  EXPECT_LT(*r.by_drop.exceeds_lead_at, 60u);
  // The 15-vehicle platoon's last follower dips less than the lead: the paper's "initially dampens".
  EXPECT_LT(r.per_vehicle[15].drop_below_reference_mps, 0.7 * r.per_vehicle[0].drop_below_reference_mps);
  // Peak-to-peak (which counts the overshoot above cruise) turns earlier.
  ASSERT_TRUE(r.by_peak_to_peak.growth_starts_at);
  EXPECT_LT(*r.by_peak_to_peak.growth_starts_at, *r.by_drop.growth_starts_at);
}

TEST(ReproductionPlatoon, SinusoidLeadHoldsThenOscillates)
{
  const auto lead = acc::sinusoidLeadProfile(20.0, 1.0, 0.204, 20.0, 100.0, kStep);
  ASSERT_EQ(lead.size(), 1001u);
  EXPECT_DOUBLE_EQ(lead[200], 20.0);
  EXPECT_NEAR(lead[300], 20.0 + std::sin(0.204 * 10.0), 1e-9);
  const auto held = acc::withFinalHold(lead, 10.0, kStep);
  EXPECT_EQ(held.size(), 1101u);
  EXPECT_DOUBLE_EQ(held.back(), lead.back());
  EXPECT_THROW(acc::sinusoidLeadProfile(20.0, 1.0, 0.2, 0.0, 10.0, 0.0), std::invalid_argument);
}
