// Model adequacy against an effect the paper's model lacks: a synthetic ACC that also cruises at
// a set speed (the Casale symptom) makes the base model inadequate, with reasons; the same drive
// without the set speed does not. The lead profile "steps" drives the leader above the set speed.
#include <gtest/gtest.h>

#include <iostream>

#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/validation/withheld_effect_suite.h"

namespace
{
acc::ModelAdequacy baseModelAdequacy(acc::EffectKind truth, std::vector<double> values)
{
  acc::WithheldCase c;
  c.truth = truth;
  c.truth_values = std::move(values);
  c.profile = acc::SyntheticLeadProfile::steps;
  c.duration_s = 600.0;
  const std::vector<acc::CarFollowingRun> runs{acc::synthesizeWithheldRun(c)};
  acc::IdentificationOptions options;
  options.multistart.starts = 20;
  const acc::Identification id = acc::identifyAcc(runs, options);
  EXPECT_TRUE(id.solved) << id.note;
  const acc::ModelAdequacy adequacy =
      acc::assessModelAdequacy(id.calibration.parameters, runs, {}, id.uncertainty.standard_error);
  const acc::AdequacyChecks& k = adequacy.checks;
  std::cout << "truth " << acc::effectName(truth) << ": gap RMSE " << k.gap_rmse_m << " m (spread " << k.gap_spread_m
            << "), speed RMSE " << k.speed_rmse_mps << " m/s (spread " << k.speed_spread_mps
            << "), residual correlation " << k.residual_correlation_time_s << " s, response "
            << k.model_response_time_s << " s: " << acc::describeAdequacy(adequacy) << "\n";
  return adequacy;
}
}  // namespace

TEST(DiagnosisAdequacy, SetSpeedCruisingMakesTheBaseModelInadequate)
{
  for (const std::vector<double>& cruise : {std::vector<double>{25.0, 0.4}, std::vector<double>{24.0, 0.6}})
  {
    const acc::ModelAdequacy adequacy = baseModelAdequacy(acc::EffectKind::set_speed_cruise, cruise);
    EXPECT_TRUE(adequacy.assessed);
    EXPECT_FALSE(adequacy.adequate) << "set speed " << cruise[0];
    EXPECT_FALSE(adequacy.reasons.empty());
  }
}

TEST(DiagnosisAdequacy, SameDriveWithoutTheSetSpeedIsAdequate)
{
  const acc::ModelAdequacy adequacy = baseModelAdequacy(acc::EffectKind::none, {});
  EXPECT_TRUE(adequacy.adequate) << acc::describeAdequacy(adequacy);
}
