// The selection rule on squared errors whose truth is known, and the augmented calibration.
#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/diagnosis/effect_selection.h"
#include "acc_identification/validation/withheld_effect_suite.h"
#include "acc_identification/model/normal_source.h"


namespace
{
/// Squared values of an AR(1) series (correlated like model errors), scaled.
acc::SquaredErrorsByRun correlatedSquares(std::uint32_t seed, double scale, std::size_t n = 3000)
{
  acc::NormalSource noise(seed);  // the same series with every standard library
  std::vector<double> run(n);
  double x = 0.0;
  for (double& value : run)
  {
    x = 0.95 * x + std::sqrt(1 - 0.95 * 0.95) * noise.standardNormal();
    value = scale * x * x;
  }
  return {run};
}

acc::SquaredErrorsByRun scaled(const acc::SquaredErrorsByRun& a, double factor, const acc::SquaredErrorsByRun& jitter,
                               double jitter_scale)
{
  acc::SquaredErrorsByRun out = a;
  for (std::size_t t = 0; t < out[0].size(); ++t)
  {
    out[0][t] = factor * a[0][t] + jitter_scale * jitter[0][t];
  }
  return out;
}
}  // namespace

TEST(EffectSelection, NamesAClearImprovementAndNothingForNoise)
{
  const auto base = correlatedSquares(1, 1.0);
  const auto noise = correlatedSquares(2, 0.05);
  const auto good = scaled(base, 0.4, noise, 1.0);      // 60 % less error
  const auto useless = scaled(base, 1.0, noise, 0.02);  // slightly worse
  const auto result = acc::selectEffect(base, {useless, good},
                                        {acc::EffectKind::set_speed_cruise, acc::EffectKind::actuation_lag}, 0.1,
                                        acc::SelectionOptions{});
  EXPECT_EQ(result.dominant, acc::EffectKind::actuation_lag);
  ASSERT_EQ(result.plausible.size(), 1u);
  EXPECT_TRUE(result.distinguishable);
  EXPECT_FALSE(result.significant[0]);
  EXPECT_TRUE(result.significant[1]);
  EXPECT_NEAR(result.versus_base[1].relative, 0.6 - 0.05 / 1.0, 0.05);

  const auto none = acc::selectEffect(base, {useless}, {acc::EffectKind::set_speed_cruise}, 0.1, acc::SelectionOptions{});
  EXPECT_EQ(none.dominant, acc::EffectKind::none);
  EXPECT_TRUE(none.plausible.empty());
}

TEST(EffectSelection, ReportsTheSetWhenTwoEffectsCannotBeToldApart)
{
  const auto base = correlatedSquares(3, 1.0);
  const auto a = scaled(base, 0.5, correlatedSquares(4, 0.05), 1.0);
  const auto b = scaled(base, 0.5, correlatedSquares(5, 0.05), 1.0);
  const auto result = acc::selectEffect(base, {a, b}, {acc::EffectKind::actuation_lag, acc::EffectKind::reaction_delay},
                                        0.1, acc::SelectionOptions{});
  EXPECT_NE(result.dominant, acc::EffectKind::none);
  EXPECT_EQ(result.plausible.size(), 2u);
  EXPECT_FALSE(result.distinguishable);
  EXPECT_TRUE(result.has_runner_up);
}

TEST(EffectSelection, AShortBlockSeesLessUncertaintyThanALongOne)
{
  // The rule must account for correlation: with 0.1 s blocks the bound is tighter than with 30 s.
  const auto base = correlatedSquares(6, 1.0);
  const auto candidate = scaled(base, 0.97, correlatedSquares(7, 0.3), 0.1);
  acc::SelectionOptions short_blocks;
  short_blocks.block_length_s = 0.1;
  acc::SelectionOptions long_blocks;
  long_blocks.block_length_s = 30.0;
  const auto s = acc::selectEffect(base, {candidate}, {acc::EffectKind::actuation_lag}, 0.1, short_blocks);
  const auto l = acc::selectEffect(base, {candidate}, {acc::EffectKind::actuation_lag}, 0.1, long_blocks);
  EXPECT_GT(l.versus_base[0].upper_bound - l.versus_base[0].lower_bound,
            1.5 * (s.versus_base[0].upper_bound - s.versus_base[0].lower_bound));
}

TEST(AugmentedCalibration, RecoversTheBaseParametersFromCleanData)
{
  acc::WithheldCase c;
  c.speed_noise_std_mps = 0.0;
  c.gap_noise_std_m = 0.0;
  c.duration_s = 200.0;
  c.truth_substeps = 1;  // made by the very recursion that is fitted: the fit must be exact
  const acc::CarFollowingRun run = acc::synthesizeWithheldRun(c);
  const acc::AugmentedFit fit = acc::calibrateAugmented(acc::EffectKind::none, {run}, acc::AugmentedCalibrationOptions{});
  EXPECT_LT(std::sqrt(fit.train_mse_speed), 1e-3);
  EXPECT_NEAR(fit.base.k1_per_s2, c.base.k1_per_s2, 0.005);
  EXPECT_NEAR(fit.base.k2_per_s, c.base.k2_per_s, 0.02);
  EXPECT_NEAR(fit.base.tau_e_s, c.base.tau_e_s, 0.05);
  ASSERT_EQ(fit.standard_errors.size(), 4u);
}

TEST(AugmentedCalibration, NeverEndsWorseThanTheBaseFitItStartsFrom)
{
  acc::WithheldCase c;
  c.duration_s = 150.0;
  const acc::CarFollowingRun run = acc::synthesizeWithheldRun(c);
  const acc::AugmentedCalibrationOptions options;
  const acc::AugmentedFit base = acc::calibrateAugmented(acc::EffectKind::none, {run}, options);
  for (const acc::CandidateEffect& effect : acc::candidateEffects())
  {
    const acc::AugmentedFit fit = acc::calibrateAugmented(effect.kind, {run}, options, &base);
    EXPECT_LE(fit.train_mse_speed, base.train_mse_speed * (1.0 + 1e-6)) << effect.name;
    EXPECT_EQ(fit.effect_values.size(), effect.parameters.size());
  }
}

TEST(AugmentedCalibration, RejectsInvalidSegmentsWithAMessage)
{
  acc::CarFollowingRun bad;
  bad.name = "bad";
  bad.time_s = {0.0};
  bad.space_gap_m = {1.0};
  bad.follower_speed_mps = {1.0};
  bad.leader_speed_mps = {1.0};
  EXPECT_THROW(acc::calibrateAugmented(acc::EffectKind::none, {bad}, {}), std::invalid_argument);
}

TEST(EffectSelection, AnEffectBelowTheDataResolutionIsNeverNamed)
{
  const auto base = correlatedSquares(8, 1.0);
  const auto good = scaled(base, 0.4, correlatedSquares(9, 0.05), 1.0);
  const auto result = acc::selectEffect(base, {good}, {acc::EffectKind::sensor_time_offset}, 0.1,
                                        acc::SelectionOptions{}, {false});
  EXPECT_EQ(result.dominant, acc::EffectKind::none);
  EXPECT_FALSE(result.significant[0]);
  EXPECT_TRUE(acc::isResolvable(acc::EffectKind::sensor_time_offset, {-0.2}, 0.1));
  EXPECT_FALSE(acc::isResolvable(acc::EffectKind::sensor_time_offset, {0.05}, 0.1));
  EXPECT_FALSE(acc::isResolvable(acc::EffectKind::actuation_lag, {0.05}, 0.1));
  EXPECT_TRUE(acc::isResolvable(acc::EffectKind::speed_dependent_time_gap, {0.0001}, 0.1));
}
