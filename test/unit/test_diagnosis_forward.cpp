// Effects in combination: models with several effects at once are fitted, and the forward
// selection adds effects to the dominant one while the rule finds one that improves on the current
// model. On data with two effects withheld it must name both and stop; with one, only that one;
// with none, nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/diagnosis/diagnosis_output.h"
#include "acc_identification/validation/withheld_effect_suite.h"

namespace
{
acc::DiagnosisOptions quickOptions(bool with_stability_test)
{
  acc::DiagnosisOptions options;
  options.selection.resamples = 500;
  options.with_stability_test = with_stability_test;
  return options;
}

/// An actuation lag of 0.8 s and acceleration limits of 1.5/3.0 m/s^2 hidden in one run.
acc::WithheldCase lagAndLimits()
{
  acc::WithheldCase c;
  c.truth = acc::EffectKind::actuation_lag;
  c.truth_values = {0.8};
  c.also_withheld = {{acc::EffectKind::acceleration_limits, {1.5, 3.0}}};
  c.profile = acc::SyntheticLeadProfile::steps;
  c.seed = 21;
  return c;
}

std::vector<acc::EffectKind> chainOf(const acc::DiagnosisResult& r)
{
  std::vector<acc::EffectKind> chain;
  for (const acc::ForwardSelectionStep& step : r.selected_effects)
    chain.push_back(step.added);
  return chain;
}

/// The chain and why it stopped, for failure messages.
std::string describeChain(const acc::DiagnosisResult& r)
{
  std::ostringstream out;
  out << "chain:";
  for (const acc::ForwardSelectionStep& step : r.selected_effects)
    out << " " << acc::effectName(step.added) << " (test RMSE " << step.model.test_rmse_speed_mps << ", -"
        << 100.0 * step.model.improvement.relative << "% of base MSE)";
  out << "; stopped: " << r.forward_stop_reason << "; last round:";
  if (!r.forward_rounds.empty())
  {
    const acc::SelectionResult& s = r.forward_rounds.back();
    for (std::size_t k = 0; k < s.candidates.size(); ++k)
      out << " " << acc::effectName(s.candidates[k]) << " " << 100.0 * s.versus_base[k].relative << "% (lb "
          << s.versus_base[k].lower_bound << ")";
  }
  return out.str();
}

bool contains(const std::vector<acc::EffectKind>& kinds, acc::EffectKind kind)
{
  return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
}
}  // namespace

TEST(CombinedEffects, SettingsSwitchOnEveryEffectAndOneEffectEqualsTheSingleSettings)
{
  const acc::EffectSettings both = acc::makeCombinedEffectSettings(
      {acc::EffectKind::actuation_lag, acc::EffectKind::acceleration_limits}, {0.6, 1.0, 2.0});
  EXPECT_EQ(both.actuation_lag_s, 0.6);
  EXPECT_EQ(both.max_acceleration_mps2, 1.0);
  EXPECT_EQ(both.max_deceleration_mps2, 2.0);
  EXPECT_EQ(both.reaction_delay_s, 0.0);
  const acc::EffectSettings one = acc::makeCombinedEffectSettings({acc::EffectKind::set_speed_cruise}, {25.0, 0.4});
  const acc::EffectSettings single = acc::makeEffectSettings(acc::EffectKind::set_speed_cruise, {25.0, 0.4});
  EXPECT_EQ(one.set_speed_mps, single.set_speed_mps);
  EXPECT_EQ(one.cruise_gain_per_s, single.cruise_gain_per_s);
  EXPECT_TRUE(std::isinf(one.max_acceleration_mps2));
  EXPECT_THROW(acc::makeCombinedEffectSettings({acc::EffectKind::actuation_lag}, {0.6, 1.0}), std::invalid_argument);
}

TEST(CombinedEffects, AFitOnTopOfAnotherIsNeverWorseOnTheTrainingDataAndKeepsItsOrder)
{
  acc::WithheldCase c;
  c.truth = acc::EffectKind::actuation_lag;
  c.truth_values = {0.6};
  c.also_withheld = {{acc::EffectKind::reaction_delay, {0.5}}};
  c.duration_s = 200.0;
  const std::vector<acc::CarFollowingRun> runs = {acc::synthesizeWithheldRun(c)};
  const acc::AugmentedCalibrationOptions options;
  const acc::AugmentedFit base = acc::calibrateAugmented(acc::EffectKind::none, runs, options);
  const acc::AugmentedFit lag = acc::calibrateAugmented(acc::EffectKind::actuation_lag, runs, options, &base);
  const acc::AugmentedFit both = acc::calibrateAugmentedSet(
      {acc::EffectKind::actuation_lag, acc::EffectKind::reaction_delay}, runs, options, &lag);
  EXPECT_EQ(lag.effects, std::vector<acc::EffectKind>{acc::EffectKind::actuation_lag});
  ASSERT_EQ(both.effects.size(), 2u);
  EXPECT_EQ(both.effect, acc::EffectKind::reaction_delay);
  ASSERT_EQ(both.effect_values.size(), 2u);
  ASSERT_EQ(both.standard_errors.size(), 6u);
  EXPECT_LE(both.train_mse_speed, lag.train_mse_speed);
  EXPECT_LT(both.train_mse_speed, 0.9 * lag.train_mse_speed);  // the delay is really there
  EXPECT_EQ(both.settings.actuation_lag_s, both.effect_values[0]);
  EXPECT_EQ(both.settings.reaction_delay_s, both.effect_values[1]);
}

TEST(ForwardSelection, NamesBothWithheldEffectsAndStops)
{
  // On the steps profile the lag explains about half of the base model's held-out error and the
  // limits most of the rest; the follower never comes closer than 9 m (no collision in the truth).
  const acc::WithheldCase c = lagAndLimits();
  const acc::DiagnosisResult r = acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, quickOptions(true));
  const std::vector<acc::EffectKind> chain = chainOf(r);
  ASSERT_EQ(chain.size(), 2u) << describeChain(r);
  EXPECT_TRUE(contains(chain, acc::EffectKind::actuation_lag)) << describeChain(r);
  EXPECT_TRUE(contains(chain, acc::EffectKind::acceleration_limits)) << describeChain(r);
  EXPECT_EQ(chain.front(), r.selection.dominant);
  // It stopped because nothing else was significant, not because of the length limit.
  ASSERT_EQ(r.forward_rounds.size(), 2u);
  EXPECT_EQ(r.forward_rounds.back().dominant, acc::EffectKind::none) << describeChain(r);
  // Each step improves the held-out fit, and the final model holds both truths' values.
  const acc::ModelDiagnosis& last = r.selected_effects.back().model;
  EXPECT_LT(last.test_rmse_speed_mps, r.selected_effects.front().model.test_rmse_speed_mps);
  EXPECT_LT(r.selected_effects.front().model.test_rmse_speed_mps, r.baseline.test_rmse_speed_mps);
  EXPECT_LT(last.test_rmse_speed_mps, 0.08);  // down to about the 0.06 m/s noise
  EXPECT_GT(last.improvement.lower_bound, 0.0);
  EXPECT_NEAR(last.fit.settings.actuation_lag_s, 0.8, 0.1);
  EXPECT_NEAR(last.fit.settings.max_acceleration_mps2, 1.5, 0.15);
  EXPECT_NEAR(last.fit.settings.max_deceleration_mps2, 3.0, 0.2);
  ASSERT_EQ(last.fit.standard_errors.size(), 4u + 3u);
  EXPECT_TRUE(std::isfinite(last.fit.standard_errors[4])) << "the lag's standard error";
  // Every step's model has its own string-stability test over all of its parameters.
  for (const acc::ForwardSelectionStep& step : r.selected_effects)
  {
    ASSERT_TRUE(step.stability_test.has_value());
    EXPECT_EQ(step.stability_test->effects, acc::effectsOf(step.model.fit));
  }
  const nlohmann::json j = acc::diagnosisToJson(r);
  ASSERT_EQ(j["selected_effects"].size(), 2u);
  EXPECT_EQ(j["selected_effects"][0]["effect"], acc::effectName(chain[0]));
  EXPECT_EQ(j["selected_effects"][1]["effect_parameters"].size(), 3u);
  EXPECT_TRUE(j["selected_effects"][1]["stability_test"].contains("verdict"));
  EXPECT_TRUE(j["selected_effects"][1]["improvement"].contains("lower_bound"));
}

TEST(ForwardSelection, NamesALagOnTopOfASpeedDependentTimeGap)
{
  acc::WithheldCase c;
  c.truth = acc::EffectKind::speed_dependent_time_gap;
  c.truth_values = {0.02};
  c.also_withheld = {{acc::EffectKind::actuation_lag, {0.6}}};
  c.profile = acc::SyntheticLeadProfile::steps;
  c.seed = 5;
  const acc::DiagnosisResult r = acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, quickOptions(false));
  const std::vector<acc::EffectKind> chain = chainOf(r);
  ASSERT_EQ(chain.size(), 2u) << describeChain(r);
  EXPECT_TRUE(contains(chain, acc::EffectKind::actuation_lag)) << describeChain(r);
  EXPECT_TRUE(contains(chain, acc::EffectKind::speed_dependent_time_gap)) << describeChain(r);
  EXPECT_EQ(r.forward_rounds.back().dominant, acc::EffectKind::none) << describeChain(r);
}

TEST(ForwardSelection, NamesOnlyTheOneEffectThatIsThere)
{
  acc::WithheldCase c;
  c.truth = acc::EffectKind::actuation_lag;
  c.truth_values = {0.6};
  c.profile = acc::SyntheticLeadProfile::dip;
  c.seed = 21;
  const acc::DiagnosisResult r = acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, quickOptions(false));
  EXPECT_EQ(chainOf(r), std::vector<acc::EffectKind>{acc::EffectKind::actuation_lag}) << describeChain(r);
  ASSERT_EQ(r.forward_rounds.size(), 1u);
  // Bonferroni over the remaining candidates (every default candidate but the lag).
  EXPECT_EQ(r.forward_rounds.front().candidates.size(), acc::DiagnosisOptions{}.candidates.size() - 1);
}

TEST(ForwardSelection, IsEmptyWhenNoEffectIsThere)
{
  acc::WithheldCase c;
  c.profile = acc::SyntheticLeadProfile::steps;
  c.seed = 11;
  const acc::DiagnosisResult r = acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, quickOptions(false));
  EXPECT_TRUE(r.selected_effects.empty()) << describeChain(r);
  EXPECT_TRUE(r.forward_rounds.empty());
  EXPECT_EQ(acc::diagnosisToJson(r)["selected_effects"].size(), 0u);
}

TEST(ForwardSelection, OffLeavesTheChainEmptyAndTheDominantEffectAsItWas)
{
  acc::WithheldCase c;
  c.truth = acc::EffectKind::actuation_lag;
  c.truth_values = {0.6};
  c.duration_s = 200.0;
  acc::DiagnosisOptions options = quickOptions(false);
  options.candidates = {acc::EffectKind::actuation_lag, acc::EffectKind::reaction_delay};
  options.forward_selection = false;
  const acc::DiagnosisResult off = acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, options);
  options.forward_selection = true;
  const acc::DiagnosisResult on = acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, options);
  EXPECT_TRUE(off.selected_effects.empty());
  EXPECT_EQ(off.selection.dominant, on.selection.dominant);
  ASSERT_EQ(off.effects.size(), on.effects.size());
  for (std::size_t k = 0; k < on.effects.size(); ++k)
  {
    EXPECT_EQ(off.effects[k].test_rmse_speed_mps, on.effects[k].test_rmse_speed_mps);
  }
}

TEST(ForwardSelection, TheResultIsTheSameOnOneThreadAndOnTwo)
{
  // The effect fits, each round's candidates and the side searches' starts run on a thread pool,
  // each stored by its index: the JSON of the whole diagnosis (fits, bootstrap bounds, chain,
  // stability test) must not depend on how many threads ran them.
  const acc::WithheldCase c = lagAndLimits();
  const std::vector<acc::CarFollowingRun> runs = {acc::synthesizeWithheldRun(c)};
  acc::DiagnosisOptions one_thread = quickOptions(true);
  one_thread.threads = 1;
  acc::DiagnosisOptions two_threads = one_thread;
  two_threads.threads = 2;
  const acc::DiagnosisResult serial = acc::diagnoseRuns(runs, one_thread);
  ASSERT_FALSE(serial.selected_effects.empty());
  EXPECT_EQ(acc::diagnosisToJson(serial).dump(), acc::diagnosisToJson(acc::diagnoseRuns(runs, two_threads)).dump());
}
