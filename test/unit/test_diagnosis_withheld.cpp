// The withheld-effect suite in miniature: data made with one effect (or none), only the data
// handed to the diagnosis; it must name the effect, say none when there is none, and recover the
// magnitude. The larger grid runs with `diagnose --withheld-suite` (see docs/DIAGNOSIS.md).
#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/diagnosis/withheld_effect_suite.h"

namespace aci = acc_identification;

namespace
{
aci::DiagnosisOptions quickOptions()
{
  aci::DiagnosisOptions options;
  options.selection.resamples = 500;
  return options;
}

aci::WithheldOutcome run(aci::EffectKind truth, std::vector<double> values, aci::SyntheticLeadProfile profile,
                         std::uint32_t seed)
{
  aci::WithheldCase c;
  c.truth = truth;
  c.truth_values = values;
  c.profile = profile;
  c.seed = seed;
  return aci::runWithheldCase(c, quickOptions());
}
}  // namespace

TEST(WithheldEffects, SaysNoneWhenThereIsNone)
{
  for (auto profile : {aci::SyntheticLeadProfile::steps, aci::SyntheticLeadProfile::oscillation})
  {
    const auto outcome = run(aci::EffectKind::none, {}, profile, 11);
    EXPECT_EQ(outcome.dominant, aci::EffectKind::none) << aci::leadProfileName(profile) << ": named "
                                                       << aci::effectName(outcome.dominant);
  }
}

struct Expectation
{
  aci::EffectKind truth;
  std::vector<double> values;
  aci::SyntheticLeadProfile profile;
  double magnitude_tolerance;  ///< absolute, on the first parameter
};

class WithheldEffectTest : public ::testing::TestWithParam<Expectation>
{
};

TEST_P(WithheldEffectTest, NamesTheEffectAndRecoversItsMagnitude)
{
  const Expectation& e = GetParam();
  const auto outcome = run(e.truth, e.values, e.profile, 21);
  EXPECT_EQ(outcome.dominant, e.truth) << "named " << aci::effectName(outcome.dominant);
  EXPECT_NEAR(outcome.recovered_magnitude, e.values.front(), e.magnitude_tolerance);
  EXPECT_LT(outcome.effect_test_rmse_speed_mps, outcome.base_test_rmse_speed_mps);
  // The uncertainty is finite, and covers the truth except for the Euler half-step bias of the
  // timing effects (about 0.05 s, documented), which is allowed for.
  ASSERT_TRUE(std::isfinite(outcome.recovered_standard_error));
  EXPECT_GT(outcome.recovered_standard_error, 0.0);
  const double bias = e.truth == aci::EffectKind::reaction_delay || e.truth == aci::EffectKind::sensor_time_offset ? 0.06 : 0.0;
  EXPECT_LT(std::abs(outcome.recovered_magnitude - e.values.front()) - bias, 4.0 * outcome.recovered_standard_error)
      << "recovered " << outcome.recovered_magnitude << " +- " << outcome.recovered_standard_error;
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, WithheldEffectTest,
    ::testing::Values(
        Expectation{aci::EffectKind::actuation_lag, {0.8}, aci::SyntheticLeadProfile::steps, 0.15},
        Expectation{aci::EffectKind::reaction_delay, {0.8}, aci::SyntheticLeadProfile::steps, 0.15},
        Expectation{aci::EffectKind::acceleration_limits, {1.0, 2.0}, aci::SyntheticLeadProfile::dip, 0.15},
        Expectation{aci::EffectKind::sensor_time_offset, {1.0}, aci::SyntheticLeadProfile::oscillation, 0.25},
        Expectation{aci::EffectKind::speed_dependent_time_gap, {0.02}, aci::SyntheticLeadProfile::steps, 0.005},
        Expectation{aci::EffectKind::set_speed_cruise, {25.0, 0.4}, aci::SyntheticLeadProfile::steps, 1.0}),
    [](const ::testing::TestParamInfo<Expectation>& info) { return aci::effectName(info.param.truth); });

TEST(WithheldEffects, AnExploratoryEffectIsNamedWhenAskedFor)
{
  aci::WithheldCase c;
  c.truth = aci::EffectKind::leader_acceleration_feedforward;
  c.truth_values = {0.4};
  c.profile = aci::SyntheticLeadProfile::oscillation;
  c.seed = 5;
  aci::DiagnosisOptions options = quickOptions();
  options.candidates.push_back(aci::EffectKind::leader_acceleration_feedforward);
  const auto outcome = aci::runWithheldCase(c, options);
  EXPECT_EQ(outcome.dominant, aci::EffectKind::leader_acceleration_feedforward)
      << "named " << aci::effectName(outcome.dominant);
  EXPECT_NEAR(outcome.recovered_magnitude, 0.4, 0.1);
}
