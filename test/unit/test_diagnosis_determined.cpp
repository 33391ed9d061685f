// Effects determined by the training data (determined_effects.h): pinned away from none where one
// is hidden, nothing where none is, and what an effect at a bound or below the resolution is.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "acc_identification/diagnosis/determined_effects.h"
#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/validation/withheld_effect_suite.h"

namespace
{
acc::DiagnosisResult diagnoseHidden(acc::EffectKind truth, std::vector<double> values, std::uint32_t seed)
{
  acc::WithheldCase c;
  c.truth = truth;
  c.truth_values = std::move(values);
  c.seed = seed;
  acc::DiagnosisOptions options;
  options.with_stability_test = false;
  options.forward_selection = false;
  return acc::diagnoseRuns({acc::synthesizeWithheldRun(c)}, options);
}

TEST(DeterminedEffects, TheThresholdIsTheBonferroniNormalQuantile)
{
  EXPECT_NEAR(acc::determinedThreshold(0.05, 1), 1.95996, 1e-4);
  EXPECT_NEAR(acc::determinedThreshold(0.05, 4), 2.49771, 1e-4);
  EXPECT_TRUE(std::isnan(acc::neutralValue(acc::EffectKind::acceleration_limits)));
  EXPECT_TRUE(std::isnan(acc::neutralValue(acc::EffectKind::set_speed_cruise)));
  EXPECT_EQ(acc::neutralValue(acc::EffectKind::sensor_time_offset), 0.0);
}

TEST(DeterminedEffects, AHiddenClockOffsetIsDeterminedWithItsSizeAndNothingIsWhereNoneIsHidden)
{
  const acc::DiagnosisResult offset = diagnoseHidden(acc::EffectKind::sensor_time_offset, {0.8}, 3);
  const auto found = std::find_if(offset.determined.begin(), offset.determined.end(),
                                  [](const acc::DeterminedEffect& e) { return e.effect == acc::EffectKind::sensor_time_offset; });
  ASSERT_NE(found, offset.determined.end());
  EXPECT_NEAR(found->value, 0.8, 3.0 * found->standard_error + 0.05);
  EXPECT_GT(found->z, acc::determinedThreshold(0.05, 4));
  EXPECT_FALSE(acc::describeDeterminedEffect(*found).empty());

  for (std::uint32_t seed : {4u, 5u, 6u})
  {
    const acc::DiagnosisResult none = diagnoseHidden(acc::EffectKind::none, {}, seed);
    EXPECT_TRUE(none.determined.empty()) << acc::describeDeterminedEffect(none.determined.front());
  }
}

TEST(DeterminedEffects, AValueAtABoundOrBelowTheResolutionOrWithoutAnErrorIsNotDetermined)
{
  acc::AugmentedFit base;
  auto fit = [](acc::EffectKind kind, double value, double standard_error) {
    acc::AugmentedFit f;
    f.effect = kind;
    f.effects = {kind};
    f.effect_values = {value};
    f.standard_errors = {0.01, 0.01, 0.01, 0.1, standard_error};
    return f;
  };
  const double upper = acc::candidateEffect(acc::EffectKind::sensor_time_offset).parameters.front().upper;
  const std::vector<acc::AugmentedFit> fits = {
      fit(acc::EffectKind::sensor_time_offset, upper, 0.01),     // at its bound
      fit(acc::EffectKind::reaction_delay, 0.05, 0.001),         // below one 0.1 s sample
      fit(acc::EffectKind::actuation_lag, 0.8, std::nan("")),    // no standard error
      fit(acc::EffectKind::speed_dependent_time_gap, 0.02, 0.001),  // 20 errors from none: determined
  };
  const auto determined = acc::determinedEffects(base, fits, 0.1, 0.05);
  ASSERT_EQ(determined.size(), 1u);
  EXPECT_EQ(determined.front().effect, acc::EffectKind::speed_dependent_time_gap);
  EXPECT_NEAR(determined.front().z, 20.0, 1e-9);
}

// In a chain step's model the added effect's parameters follow the earlier effects'; its size is
// judged there (the asymmetric response's against a ratio of 1), and an effect without a none
// value or not in the model is not judged.
TEST(DeterminedEffects, AnEffectsSizeIsFoundAfterTheEffectsBeforeIt)
{
  acc::AugmentedFit chain;
  chain.effect = acc::EffectKind::speed_dependent_gains;
  chain.effects = {acc::EffectKind::speed_dependent_gains, acc::EffectKind::asymmetric_response,
                   acc::EffectKind::acceleration_limits};
  chain.effect_values = {-0.01, 0.5, 2.5, 1.5, 3.0};  // g; closing and short-gap ratios; the two limits
  chain.standard_errors = {0.01, 0.01, 0.1, 1.0, 0.022, 0.2, 1.6, 0.1, 0.1};
  const acc::EffectSize gains = acc::effectSizeIn(chain, acc::EffectKind::speed_dependent_gains, 2.64);
  EXPECT_NEAR(gains.z, 0.01 / 0.022, 1e-12);
  EXPECT_FALSE(gains.determined);
  const acc::EffectSize response = acc::effectSizeIn(chain, acc::EffectKind::asymmetric_response, 2.4);
  EXPECT_DOUBLE_EQ(response.value, 0.5);
  EXPECT_DOUBLE_EQ(response.standard_error, 0.2);
  EXPECT_NEAR(response.z, 2.5, 1e-12);
  EXPECT_TRUE(response.determined);
  EXPECT_FALSE(acc::effectSizeIn(chain, acc::EffectKind::asymmetric_response, 2.64).determined);
  const acc::EffectSize limits = acc::effectSizeIn(chain, acc::EffectKind::acceleration_limits, 2.64);
  EXPECT_DOUBLE_EQ(limits.value, 1.5);
  EXPECT_TRUE(std::isnan(limits.z));
  EXPECT_FALSE(limits.determined);
  EXPECT_TRUE(std::isnan(acc::effectSizeIn(chain, acc::EffectKind::reaction_delay, 2.64).value));
  chain.effect_values[1] = acc::candidateEffect(acc::EffectKind::asymmetric_response).parameters.front().upper;
  const acc::EffectSize at_bound = acc::effectSizeIn(chain, acc::EffectKind::asymmetric_response, 0.1);
  EXPECT_TRUE(at_bound.at_bound);
  EXPECT_FALSE(at_bound.determined);
}
}  // namespace

// On short data a size is also read against its refitting bootstrap: an interval that holds the
// none value says so (the TOYOTA_RAV4 at L's delay: z 2.4, interval [0, 3] s), one that does not
// says nothing more, and no interval (or no none value) leaves it unset.
TEST(DeterminedEffects, AShortFitsSizeIsReadAgainstItsBootstrapInterval)
{
  const auto bootstrapWith = [](const std::string& name, double low, double high) {
    acc::RefitBootstrap bootstrap;
    acc::BootstrapQuantity q;
    q.name = name;
    q.interval_95_low = low;
    q.interval_95_high = high;
    bootstrap.quantities.push_back(q);
    return bootstrap;
  };
  const acc::EffectKind delay = acc::EffectKind::reaction_delay;
  const std::string delay_name = acc::candidateEffect(delay).parameters.front().name;
  acc::EffectSize size;
  size.z = 2.4;
  size.determined = true;
  acc::judgeByBootstrap(delay, bootstrapWith(delay_name, 0.0, 3.0), &size);
  EXPECT_EQ(size.bootstrap_interval_holds_none, std::optional<bool>(true));
  EXPECT_EQ(acc::bootstrapVerdictText(size), "; its bootstrap interval holds none");
  EXPECT_TRUE(size.determined);  // the standard error's decision stays

  acc::EffectSize pinned;
  acc::judgeByBootstrap(delay, bootstrapWith(delay_name, 0.40, 0.91), &pinned);
  EXPECT_EQ(pinned.bootstrap_interval_holds_none, std::optional<bool>(false));
  EXPECT_EQ(acc::bootstrapVerdictText(pinned), "");

  acc::EffectSize none;
  acc::judgeByBootstrap(delay, bootstrapWith(delay_name, std::nan(""), std::nan("")), &none);
  acc::judgeByBootstrap(delay, bootstrapWith("k2_per_s", 0.0, 3.0), &none);
  const acc::EffectKind limits = acc::EffectKind::acceleration_limits;  // vanishes only at infinity
  acc::judgeByBootstrap(limits, bootstrapWith(acc::candidateEffect(limits).parameters.front().name, 0.0, 1e9), &none);
  EXPECT_FALSE(none.bootstrap_interval_holds_none.has_value());
}
