// The string-stability test of the diagnosis's chosen (augmented) model: the signed index agrees
// with the grid verdict of the augmented transfer function and tends to the paper's margin, and the
// test decides on synthetic runs whose truth is far from the boundary on either side.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "acc_identification/diagnosis/augmented_stability.h"
#include "acc_identification/diagnosis/augmented_stability_verdict.h"
#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/validation/withheld_effect_suite.h"
#include "acc_identification/model/halton_sequence.h"
#include "acc_identification/model/paper_settings.h"

namespace
{
double margin(const acc::AccParameters& p)
{
  return p.k1_per_s2 * p.tau_e_s * p.tau_e_s + 2.0 * p.k2_per_s * p.tau_e_s - 2.0;
}
}  // namespace

TEST(AugmentedStabilityIndex, HasTheSignOfTheMarginAndTendsToItForThePapersModel)
{
  const acc::EffectSettings none;
  for (const acc::AccParameters& p : {acc::AccParameters{0.5, 0.5, 3.2, 8.0}, acc::AccParameters{0.0782, 0.4445, 0.5162, 8.3},
                                      acc::AccParameters{0.0131, 0.2692, 1.6881, 7.6}, acc::AccParameters{0.1, 0.5, 1.5, 5.0}})
  {
    SCOPED_TRACE(margin(p));
    const double index = acc::augmentedStabilityIndex(p, none, 10.0);
    EXPECT_EQ(index >= 0.0, margin(p) >= 0.0);
    // The low-frequency limit of k1 (1 - |Gamma|^2) / w^2 is the margin itself.
    const double w = 1e-3;
    const double gain = acc::augmentedTransferGain(p, none, 10.0, w);
    EXPECT_NEAR(p.k1_per_s2 * (1.0 - gain * gain) / (w * w), margin(p), 1e-3 * std::max(1.0, std::abs(margin(p))));
    EXPECT_LE(index, p.k1_per_s2 * (1.0 - gain * gain) / (w * w) + 1e-9);  // a minimum over frequencies
  }
}

TEST(AugmentedStabilityIndex, AgreesWithTheTransferFunctionVerdictForLagsAndDelays)
{
  std::size_t disagreements = 0, unstable = 0, checked = 0;
  for (std::size_t i = 1; i <= 400; ++i)
  {
    const std::vector<double> h = acc::haltonSequencePoint(i, 5);
    const acc::AccParameters p{0.01 + 0.6 * h[0], 0.05 + 1.0 * h[1], 0.3 + 3.0 * h[2], 5.0};
    acc::EffectSettings e;
    const acc::EffectKind kind = i % 2 ? acc::EffectKind::actuation_lag : acc::EffectKind::reaction_delay;
    (kind == acc::EffectKind::actuation_lag ? e.actuation_lag_s : e.reaction_delay_s) = 1.5 * h[3];
    const bool stable_by_grid = acc::analyzeAugmentedStability(p, kind, e, 10.0).string_stable;
    const double index = acc::augmentedStabilityIndex(p, e, 10.0);
    if (std::abs(index) < 1e-6)
      continue;  // on the boundary the two grids may differ
    ++checked;
    unstable += !stable_by_grid;
    disagreements += stable_by_grid != (index >= 0.0);
    if (stable_by_grid != (index >= 0.0))
      ADD_FAILURE() << "k1 " << p.k1_per_s2 << " k2 " << p.k2_per_s << " tau " << p.tau_e_s << " lag "
                    << e.actuation_lag_s << " delay " << e.reaction_delay_s << ": grid stable " << stable_by_grid
                    << ", index " << index << ", peak "
                    << acc::analyzeAugmentedStability(p, kind, e, 10.0).peak_gain_db << " dB";
  }
  EXPECT_GT(checked, 350u);
  EXPECT_GT(unstable, 50u);  // both sides are exercised
  EXPECT_EQ(disagreements, 0u);
}

TEST(AugmentedStabilityIndex, ALongActuationLagMakesAStableModelUnstable)
{
  const acc::AccParameters p{0.5, 0.5, 3.2, 8.0};
  acc::EffectSettings lag;
  EXPECT_GT(acc::augmentedStabilityIndex(p, lag, 10.0), 0.0);
  lag.actuation_lag_s = 3.0;
  EXPECT_LT(acc::augmentedStabilityIndex(p, lag, 10.0), 0.0);
  EXPECT_FALSE(acc::analyzeAugmentedStability(p, acc::EffectKind::actuation_lag, lag, 10.0).string_stable);
}

namespace
{
acc::DiagnosisResult diagnoseSynthetic(const acc::AccParameters& truth, std::uint32_t seed)
{
  acc::WithheldCase c;
  c.truth = acc::EffectKind::actuation_lag;
  c.truth_values = {0.6};
  c.base = truth;
  c.duration_s = 600.0;
  c.seed = seed;
  acc::DiagnosisOptions options;
  options.candidates = {acc::EffectKind::actuation_lag};
  options.selection.resamples = 300;
  return acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, options);
}
}  // namespace

TEST(AugmentedStabilityTest, DecidesUnstableForAnUnstableTruthWithALag)
{
  // Table II's minimum setting (margin -1.52), with a 0.6 s actuation lag: clearly unstable.
  const acc::DiagnosisResult r = diagnoseSynthetic(acc::AccParameters{0.0782, 0.4445, 0.5162, 8.3}, 3);
  ASSERT_TRUE(r.stability_test.has_value());
  const acc::AugmentedStabilityTestResult& t = *r.stability_test;
  EXPECT_EQ(t.effect, acc::dominantModel(r).fit.effect);
  EXPECT_EQ(t.verdict, acc::StabilityVerdict::Unstable) << t.reason;
  EXPECT_LE(t.p_value, 0.05);
  ASSERT_TRUE(t.best_stable.found);
  ASSERT_TRUE(t.best_unstable.found);
  EXPECT_GE(t.best_stable.stability_index, 0.0);
  EXPECT_LT(t.best_unstable.stability_index, 0.0);
  EXPECT_GT(t.best_stable.test_rmse_speed_mps, t.best_unstable.test_rmse_speed_mps);
  const nlohmann::json j = acc::toJson(t);
  EXPECT_EQ(j["verdict"], "unstable");
  EXPECT_TRUE(j["best_stable"].contains("test_rmse_speed"));
}

TEST(AugmentedStabilityTest, NeverSaysUnstableForAStableTruthWithALag)
{
  // The Fig. 2 stable setting (margin +6.3) with a 0.6 s lag stays string stable (index > 0).
  const acc::AccParameters truth{0.5, 0.5, 3.2, 8.0};
  acc::EffectSettings lag;
  lag.actuation_lag_s = 0.6;
  ASSERT_GT(acc::augmentedStabilityIndex(truth, lag, 10.0), 0.0);
  for (std::uint32_t seed : {1u, 2u})
  {
    const acc::DiagnosisResult r = diagnoseSynthetic(truth, seed);
    ASSERT_TRUE(r.stability_test.has_value());
    EXPECT_NE(r.stability_test->verdict, acc::StabilityVerdict::Unstable) << r.stability_test->reason;
  }
}

TEST(AugmentedStabilityTest, ShortHeldOutDataAreUndecidedWithTheReason)
{
  acc::WithheldCase c;
  c.duration_s = 100.0;
  acc::DiagnosisOptions options;
  options.candidates = {acc::EffectKind::actuation_lag};
  options.selection.resamples = 200;
  const acc::DiagnosisResult r = acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, options);
  ASSERT_TRUE(r.stability_test.has_value());
  EXPECT_EQ(r.stability_test->verdict, acc::StabilityVerdict::Undecided);
  EXPECT_NE(r.stability_test->reason.find("too few held-out samples"), std::string::npos) << r.stability_test->reason;
}

TEST(AugmentedStabilityTest, TheSideSearchReachesTheSidesOptimumOnARealChainModel)
{
  // Casale part6 (25 min, real): its diagnosis ends with an eight-parameter model (speed-dependent
  // gains, asymmetric response, reaction delay). The default search for the best model on the
  // other side of the boundary must end within 0.5 % (training RMSE) of a search with twice the
  // starts and five times the evaluations per start, and no worse than the nested step's side.
  // The derivative-free search it replaced ended 24 % above (0.475 against 0.384 m/s), and the
  // verdict's p-value moved from 0.039 to 0.177 with its evaluation budget.
  testing::internal::CaptureStderr();
  const std::vector<acc::CarFollowingRun> runs = acc::readRuns(std::string(ACC_CASALE_DIR) + "/part6.csv");
  testing::internal::GetCapturedStderr();
  acc::DiagnosisOptions options;
  options.selection.resamples = 200;
  const acc::DiagnosisResult r = acc::diagnoseRuns(runs, options);
  ASSERT_EQ(r.selected_effects.size(), 3u);
  const acc::ForwardSelectionStep& last = r.selected_effects.back();
  const acc::ForwardSelectionStep& nested = r.selected_effects[1];
  ASSERT_TRUE(last.stability_test && nested.stability_test);
  // The chosen model is unstable: the search is for the best stable one.
  ASSERT_LT(acc::augmentedStabilityIndex(last.model.fit.base, last.model.fit.settings, r.operating_speed_mps), 0.0);
  const acc::AugmentedSideFit& searched = last.stability_test->best_stable;
  ASSERT_TRUE(searched.found);
  acc::AugmentedStabilityTestOptions thorough = options.stability_test;
  thorough.halton_starts *= 2;
  thorough.max_evaluations_per_start *= 5;
  const acc::AugmentedStabilityTestResult reference = acc::testAugmentedStringStability(
      last.model.fit, r.train, r.test, r.operating_speed_mps, options.calibration, thorough,
      &*nested.stability_test);
  ASSERT_TRUE(reference.best_stable.found);
  EXPECT_LE(searched.train_rmse_speed_mps, 1.005 * reference.best_stable.train_rmse_speed_mps)
      << searched.train_rmse_speed_mps << " against " << reference.best_stable.train_rmse_speed_mps;
  ASSERT_TRUE(nested.stability_test->best_stable.found);
  EXPECT_LE(searched.train_rmse_speed_mps, nested.stability_test->best_stable.train_rmse_speed_mps + 1e-12);
}
