// The selection rule on squared errors whose truth is known, and the augmented calibration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/diagnosis/determined_effects.h"
#include "acc_identification/diagnosis/effect_selection.h"
#include "acc_identification/evidence/perturbation_windows.h"
#include "acc_identification/model/follower_simulation.h"
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

// One sandwich for one model: the base model's standard errors from the diagnosis's fit (central
// differences) are calibrate's (exact sensitivities), start gap's noise and n / (n - p) included.
// On two noisy minutes the start gap is most of eta's error, so leaving it out fails the check.
TEST(AugmentedCalibration, TheBaseModelsStandardErrorsAreCalibratesStartGapIncluded)
{
  acc::WithheldCase c;
  c.duration_s = 120.0;
  c.gap_noise_std_m = 1.0;
  const acc::CarFollowingRun run = acc::synthesizeWithheldRun(c);
  const acc::AugmentedFit fit = acc::calibrateAugmented(acc::EffectKind::none, {run}, acc::AugmentedCalibrationOptions{});
  const acc::ParameterUncertainty calibrate = acc::estimateUncertainty(fit.base, {run}, 10.0);
  ASSERT_EQ(fit.standard_errors.size(), 4u);
  ASSERT_GT(calibrate.eta_start_gap_error_m, 0.5 * calibrate.standard_error.eta_m) << "the check could not fail";
  const double expected[4] = {calibrate.standard_error.k1_per_s2, calibrate.standard_error.k2_per_s,
                              calibrate.standard_error.tau_e_s, calibrate.standard_error.eta_m};
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(fit.standard_errors[i], expected[i], 0.03 * expected[i]) << "parameter " << i;
}

namespace
{
/// 200 s behind a leader at about 20 m/s that brakes to 16 m/s once (80-90 s, back by 100 s): the
/// follower of `truth` with a deterministic speed error added, so that no fit is exact.
acc::CarFollowingRun runWithOneBraking(const acc::AccParameters& truth)
{
  acc::CarFollowingRun run;
  run.name = "one braking";
  for (std::size_t k = 0; k <= 2000; ++k)
  {
    const double t = 0.1 * static_cast<double>(k);
    const double dip = t < 80.0 ? 0.0 : t < 90.0 ? 0.4 * (t - 80.0) : t < 100.0 ? 4.0 - 0.4 * (t - 90.0) : 0.0;
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(20.0 + 0.5 * std::sin(0.1 * t) - dip);
    run.follower_speed_mps.push_back(20.0);
    run.space_gap_m.push_back(truth.eta_m + truth.tau_e_s * 20.0);
  }
  const acc::SimulatedFollower sim = acc::simulateFollower(truth, run);
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    run.follower_speed_mps[k] = sim.speed_mps[k] + 0.2 * std::sin(1.3 * run.time_s[k]);
    run.space_gap_m[k] = sim.space_gap_m[k];
  }
  return run;
}
}  // namespace

// The brakings-weighted objective is the whole run's speed MSE plus the speed MSE inside the
// leader's perturbation windows, at the fitted point; on a run without a braking it is the speed
// objective. Fails when the window samples are weighted otherwise, or the windows are not the
// evidence's.
TEST(AugmentedCalibration, TheBrakingsWeightedObjectiveAddsTheWindowsMseToTheWholeRuns)
{
  const acc::AccParameters truth{0.1, 0.5, 1.2, 5.0};
  const acc::CarFollowingRun run = runWithOneBraking(truth);
  acc::AugmentedCalibrationOptions options;
  options.objective = acc::FitObjective::speed_and_windows;
  const acc::AugmentedFit fit = acc::calibrateAugmentedSet({}, {run}, options);
  ASSERT_TRUE(fit.usable());
  const std::vector<bool> inside = acc::insidePerturbationWindows(run.time_s, run.leader_speed_mps);
  const auto in_windows = static_cast<std::size_t>(std::count(inside.begin(), inside.end(), true));
  ASSERT_GT(in_windows, 150u);  // the braking's window: 5 s before it to 30 s after the leader is back
  ASSERT_LT(in_windows, run.size() / 2);
  // The whole run's speed MSE and the windows', written out here.
  auto mses = [&](const acc::AccParameters& p) {
    const acc::SimulatedFollower sim = acc::simulateFollower(p, fit.settings, run);
    double all = 0.0, windows = 0.0;
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      const double squared = std::pow(run.follower_speed_mps[k] - sim.speed_mps[k], 2);
      all += squared;
      windows += inside[k] ? squared : 0.0;
    }
    return std::make_pair(all / run.size(), windows / in_windows);
  };
  const auto [all, windows] = mses(fit.base);
  EXPECT_NEAR(fit.train_objective, all + windows, 1e-9 * fit.train_objective);
  EXPECT_NEAR(fit.train_mse_speed, all, 1e-12 * all);
  EXPECT_NEAR(fit.base.k2_per_s, truth.k2_per_s, 0.05);
  EXPECT_NEAR(fit.base.tau_e_s, truth.tau_e_s, 0.1);
  // It is that objective's minimum: no small move of a gain or the time gap lowers it.
  for (double step : {-1e-3, 1e-3})
    for (double acc::AccParameters::*parameter :
         {&acc::AccParameters::k1_per_s2, &acc::AccParameters::k2_per_s, &acc::AccParameters::tau_e_s})
    {
      acc::AccParameters moved = fit.base;
      moved.*parameter += step;
      const auto [moved_all, moved_windows] = mses(moved);
      EXPECT_GE(moved_all + moved_windows, fit.train_objective * (1.0 - 1e-9)) << step;
    }

  acc::CarFollowingRun steady = run;  // the same run without its braking
  for (std::size_t k = 0; k < steady.size(); ++k)
    steady.leader_speed_mps[k] = 20.0 + 0.5 * std::sin(0.1 * steady.time_s[k]);
  ASSERT_TRUE(acc::findPerturbations(steady.time_s, steady.leader_speed_mps).empty());
  const acc::AugmentedFit weighted = acc::calibrateAugmentedSet({}, {steady}, options);
  options.objective = acc::FitObjective::speed;
  const acc::AugmentedFit plain = acc::calibrateAugmentedSet({}, {steady}, options);
  EXPECT_EQ(weighted.train_objective, plain.train_objective);
  EXPECT_EQ(weighted.base.k1_per_s2, plain.base.k1_per_s2);
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

// Held at the free fit's own lag, the held fit is the free fit: the same base parameters and the
// same standard errors. Fails when the held coordinate moves, or when its standard errors are
// taken in the held box (a zero-width coordinate has no derivative: NaN).
TEST(AugmentedCalibration, HeldAtTheFreeOptimumItIsTheFreeFit)
{
  acc::WithheldCase c;
  c.truth = acc::EffectKind::actuation_lag;
  c.truth_values = {0.8};
  c.duration_s = 300.0;
  const acc::CarFollowingRun run = acc::synthesizeWithheldRun(c);
  const acc::AugmentedCalibrationOptions options;
  const acc::AugmentedFit base = acc::calibrateAugmented(acc::EffectKind::none, {run}, options);
  const acc::AugmentedFit free = acc::calibrateAugmented(acc::EffectKind::actuation_lag, {run}, options, &base);
  ASSERT_NEAR(free.effect_values[0], 0.8, 0.1);
  const acc::AugmentedFit held = acc::calibrateWithEffectHeld(acc::EffectKind::actuation_lag, free.effect_values,
                                                              {run}, options, &base);
  EXPECT_EQ(held.effect_values, free.effect_values);
  EXPECT_NEAR(held.train_mse_speed, free.train_mse_speed, 1e-6 * free.train_mse_speed);
  EXPECT_NEAR(held.base.tau_e_s, free.base.tau_e_s, 1e-3);
  EXPECT_NEAR(held.base.k2_per_s, free.base.k2_per_s, 1e-3);
  ASSERT_EQ(held.standard_errors.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i)
  {
    EXPECT_NEAR(held.standard_errors[i], free.standard_errors[i], 0.02 * free.standard_errors[i]) << i;
  }
}

// A car without a lag: the lag's own fit sits at 0, where exp(-dt / T) is flat and no standard
// error exists; held at 0.5 s the lag has one, and it is small on a clean drive (such a lag is
// measurable there). Fails when the held fit moves the lag or drops its column.
TEST(AugmentedCalibration, HeldAboveNoneALagHasTheStandardErrorItsOwnFitLacks)
{
  acc::WithheldCase c;
  c.duration_s = 300.0;
  const acc::CarFollowingRun run = acc::synthesizeWithheldRun(c);
  const acc::AugmentedCalibrationOptions options;
  const acc::AugmentedFit base = acc::calibrateAugmented(acc::EffectKind::none, {run}, options);
  const acc::AugmentedFit free = acc::calibrateAugmented(acc::EffectKind::actuation_lag, {run}, options, &base);
  ASSERT_LT(free.effect_values[0], 0.01);
  EXPECT_TRUE(std::isnan(free.standard_errors[4]));
  const acc::AugmentedFit held = acc::calibrateWithEffectHeld(acc::EffectKind::actuation_lag, {0.5}, {run}, options, &base);
  EXPECT_EQ(held.effect_values, std::vector<double>{0.5});
  EXPECT_GT(held.train_mse_speed, free.train_mse_speed);
  ASSERT_EQ(held.standard_errors.size(), 5u);
  EXPECT_GT(held.standard_errors[4], 0.0);
  EXPECT_LT(held.standard_errors[4], 0.5 / 2.64);
  EXPECT_THROW(acc::calibrateWithEffectHeld(acc::EffectKind::actuation_lag, {0.5, 1.0}, {run}, options),
               std::invalid_argument);
}

// A lag-free drive: the lag's fit sits at 0 without a standard error, so the diagnosis asks it at
// its typical size (0.8 s) instead, where a clean drive pins it (would be determined). A drive
// with a 0.8 s lag has a measured lag, and nothing is asked. Fails when the question is asked of a
// fit away from none, or not asked where the fit has no information.
TEST(DeterminedEffects, ALagFitAtNoneIsAskedAtItsTypicalSize)
{
  const acc::AugmentedCalibrationOptions options;
  const auto askFor = [&](const acc::WithheldCase& c) {
    const acc::CarFollowingRun run = acc::synthesizeWithheldRun(c);
    const acc::AugmentedFit base = acc::calibrateAugmented(acc::EffectKind::none, {run}, options);
    const acc::AugmentedFit lag = acc::calibrateAugmented(acc::EffectKind::actuation_lag, {run}, options, &base);
    return acc::unmeasuredEffects(base, {lag}, {run}, options, 2.64);
  };
  acc::WithheldCase lag_free;
  lag_free.duration_s = 300.0;
  const std::vector<acc::UnmeasuredEffect> asked = askFor(lag_free);
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0].effect, acc::EffectKind::actuation_lag);
  EXPECT_DOUBLE_EQ(asked[0].held_value, 0.8);
  EXPECT_GT(asked[0].standard_error, 0.0);
  EXPECT_TRUE(asked[0].would_be_determined);
  EXPECT_NE(acc::describeUnmeasuredEffect(asked[0]).find("would be determined"), std::string::npos);
  acc::WithheldCase lagged = lag_free;
  lagged.truth = acc::EffectKind::actuation_lag;
  lagged.truth_values = {0.8};
  EXPECT_TRUE(askFor(lagged).empty());
  // Only a fit at none without a standard error is asked: not one away from none that lacks one,
  // nor one at none that has one.
  const acc::CarFollowingRun run = acc::synthesizeWithheldRun(lag_free);
  const acc::AugmentedFit base = acc::calibrateAugmented(acc::EffectKind::none, {run}, options);
  acc::AugmentedFit away = acc::calibrateAugmented(acc::EffectKind::actuation_lag, {run}, options, &base);
  acc::AugmentedFit informed = away;
  away.effect_values = {1.2};
  informed.standard_errors.back() = 0.1;
  EXPECT_TRUE(acc::unmeasuredEffects(base, {away, informed}, {run}, options, 2.64).empty());
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

namespace
{
/// [resample][candidate]: `candidates` columns of standard normal draws; each column is
/// `shared` times one common draw plus sqrt(1 - shared^2) times its own (correlation shared^2).
std::vector<std::vector<double>> correlatedResamples(std::size_t resamples, std::size_t candidates, double shared,
                                                     std::uint32_t seed)
{
  acc::NormalSource noise(seed);
  std::vector<std::vector<double>> rows(resamples, std::vector<double>(candidates));
  for (auto& row : rows)
  {
    const double common = noise.standardNormal();
    for (double& value : row)
      value = shared * common + std::sqrt(1.0 - shared * shared) * noise.standardNormal();
  }
  return rows;
}
}  // namespace

TEST(EffectSelection, TheFamilyWiseLevelLiesBetweenBonferroniAndAlphaAsTheCandidatesMoveTogether)
{
  const double alpha = 0.05;
  const std::size_t K = 8;
  // Independent candidates: Sidak's 1 - (1 - alpha)^(1/K) = 0.0064, hardly above Bonferroni's 0.00625.
  const double independent = acc::familyWiseLevel(correlatedResamples(20000, K, 0.0, 1), alpha);
  EXPECT_GE(independent, alpha / K);
  EXPECT_LT(independent, 0.0075);
  // Identical candidates are one test: the level is alpha itself.
  EXPECT_NEAR(acc::familyWiseLevel(correlatedResamples(20000, K, 1.0, 2), alpha), alpha, 1e-3);
  // In between, in order.
  const double loose = acc::familyWiseLevel(correlatedResamples(20000, K, 0.7, 3), alpha);
  const double tight = acc::familyWiseLevel(correlatedResamples(20000, K, 0.97, 4), alpha);
  EXPECT_GT(loose, independent + 0.002);
  EXPECT_GT(tight, loose + 0.005);
  EXPECT_LT(tight, alpha);
  // One candidate: no family.
  EXPECT_EQ(acc::familyWiseLevel(correlatedResamples(100, 1, 0.0, 5), alpha), alpha);
  // A candidate without a finite improvement is never named and leaves the others' level alone,
  // also when only some of its resamples are NaN (which std::sort must never see).
  auto with_nan = correlatedResamples(20000, K, 0.97, 4);
  const auto extra = correlatedResamples(20000, 1, 0.0, 6);
  for (std::size_t b = 0; b < with_nan.size(); ++b)
    with_nan[b].push_back(b % 2 == 0 ? std::numeric_limits<double>::quiet_NaN() : extra[b][0]);
  EXPECT_GE(acc::familyWiseLevel(with_nan, alpha), tight - 1e-12);
}

TEST(EffectSelection, CandidatesThatMoveTogetherCostTheRuleNoPower)
{
  // An improvement the rule names at alpha but not at Bonferroni's alpha / 8 (both checked
  // first, so that the case decides something), offered as eight near-copies: the copies are one
  // test, and the rule names it, as it would with one candidate.
  const auto base = correlatedSquares(10, 1.0);
  const auto candidate = scaled(base, 0.8, correlatedSquares(11, 0.05), 4.2);  // 5 % less error, noisily
  acc::SelectionOptions bonferroni;
  bonferroni.alpha = 0.05 / 8;
  ASSERT_EQ(acc::selectEffect(base, {candidate}, {acc::EffectKind::actuation_lag}, 0.1, {}).dominant,
            acc::EffectKind::actuation_lag);
  ASSERT_EQ(acc::selectEffect(base, {candidate}, {acc::EffectKind::actuation_lag}, 0.1, bonferroni).dominant,
            acc::EffectKind::none);
  std::vector<acc::SquaredErrorsByRun> copies;
  for (std::uint32_t k = 0; k < 8; ++k)
    copies.push_back(scaled(candidate, 1.0, correlatedSquares(20 + k, 1e-4), 1.0));
  const auto result = acc::selectEffect(base, copies, std::vector<acc::EffectKind>(8, acc::EffectKind::actuation_lag),
                                        0.1, acc::SelectionOptions{});
  EXPECT_GT(result.level, 0.04);
  EXPECT_EQ(result.family_wise_alpha, 0.05);
  EXPECT_EQ(result.dominant, acc::EffectKind::actuation_lag);
}
