#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/ros/identifier_ros.h"


namespace
{
TEST(IdentifierMessage, IdentifiableWindowCarriesEverything)
{
  acc::IdentificationOptions options;
  options.multistart.starts = 8;
  const auto run = acc::synthesizeRun(acc::paperMinimumSetting(), 120.0, 0.1, 25.0, 5);
  const auto result = acc::identifyAcc({run}, options);
  ASSERT_TRUE(result.identifiable) << result.note;
  const auto m = acc::toMessage(result, 1000.0, 1120.0);
  EXPECT_DOUBLE_EQ(m.header.stamp.toSec(), 1120.0);
  EXPECT_DOUBLE_EQ(m.window_start.toSec(), 1000.0);
  EXPECT_EQ(m.samples, run.size());
  EXPECT_EQ(m.segments, 1u);
  EXPECT_DOUBLE_EQ(m.k1_per_s2, result.calibration.parameters.k1_per_s2);
  EXPECT_DOUBLE_EQ(m.eta_std_error, result.uncertainty.standard_error.eta_m);
  // The factor of the 95 % intervals: Student's t of the window's blocks, wider than the normal's
  // 1.96, and the one calibrate's interval uses.
  ASSERT_GE(result.uncertainty.blocks, 2u);
  EXPECT_GT(m.std_error_t95, 1.96);
  EXPECT_DOUBLE_EQ(m.std_error_t95, acc::intervalFactor95(result.uncertainty.blocks));
  const acc::QuantityEstimate* margin = result.quantities->find("stability_margin");
  ASSERT_TRUE(margin != nullptr && margin->held_by_bound.empty());
  EXPECT_NEAR(m.stability_margin + m.std_error_t95 * m.stability_margin_std_error, margin->interval_95_high, 1e-12);
  EXPECT_DOUBLE_EQ(m.lambda2, result.stability.lambda2);
  EXPECT_EQ(m.string_stable, result.stability.string_stable ? acc_identification::AccParameters::STRING_STABLE
                                                             : acc_identification::AccParameters::STRING_UNSTABLE);
  EXPECT_EQ(m.model_adequate, acc_identification::AccParameters::MODEL_ADEQUACY_NOT_ASSESSED);
  EXPECT_TRUE(m.identifiable);
  EXPECT_TRUE(m.identifiability_note.empty());
  EXPECT_FALSE(m.optimizer_status.empty());
}

TEST(IdentifierMessage, UnidentifiableWindowSaysSoInsteadOfPublishingNoise)
{
  acc::Identification result;
  result.samples = 50;
  result.segments = 1;
  result.note = "too little data";
  const auto m = acc::toMessage(result, 1000.0, 1005.0);
  EXPECT_FALSE(m.identifiable);
  EXPECT_EQ(m.identifiability_note, "too little data");
  EXPECT_EQ(m.optimizer_status, "NOT_SOLVED");
  EXPECT_TRUE(std::isnan(m.k1_per_s2));
  EXPECT_TRUE(std::isnan(m.tau_e_std_error));
  EXPECT_TRUE(std::isnan(m.std_error_t95));
  EXPECT_TRUE(std::isnan(m.lambda2));
  // lambda2 NaN: unknown, not "unstable".
  EXPECT_EQ(m.string_stable, acc_identification::AccParameters::STRING_STABILITY_UNKNOWN);
}

// The drive fit's adequacy, tri-state, with its reasons: adequate on the truth's own data, not
// adequate with the numbers when the model misses, not assessed without data.
TEST(IdentifierMessage, ModelAdequacyIsATriStateWithReasons)
{
  const auto run = acc::synthesizeRun(acc::paperMinimumSetting(), 300.0, 0.1, 25.0, 5);
  acc_identification::AccParameters m;
  acc::setModelAdequacy(acc::assessModelAdequacy(acc::paperMinimumSetting(), {run}), m);
  EXPECT_EQ(m.model_adequate, acc_identification::AccParameters::MODEL_ADEQUATE) << m.model_adequacy_reasons;
  EXPECT_TRUE(m.model_adequacy_reasons.empty());
  acc::AccParameters wrong = acc::paperMinimumSetting();
  wrong.eta_m += 15.0;
  acc::setModelAdequacy(acc::assessModelAdequacy(wrong, {run}), m);
  EXPECT_EQ(m.model_adequate, acc_identification::AccParameters::MODEL_NOT_ADEQUATE);
  EXPECT_NE(m.model_adequacy_reasons.find("gap RMSE"), std::string::npos) << m.model_adequacy_reasons;
  acc::setModelAdequacy(acc::assessModelAdequacy(wrong, {}), m);
  EXPECT_EQ(m.model_adequate, acc_identification::AccParameters::MODEL_ADEQUACY_NOT_ASSESSED);
  EXPECT_FALSE(m.model_adequacy_reasons.empty());
}
}  // namespace

namespace
{
/// Issue "the verdict on real drives": each quantity is NaN only where the data do not determine
/// it, the drive so far is published beside the window, and the verdict with its p-value.
/// A window of Table II's minimum setting identified from a synthetic run, with one quantity
/// pretended not determined (as real drives leave some), and the run it came from.
acc::OnlineUpdate windowWithout(const std::string& quantity, const std::string& reason, acc::CarFollowingRun* run)
{
  acc::IdentificationOptions options;
  options.multistart.starts = 8;
  *run = acc::synthesizeRun(acc::paperMinimumSetting(), 300.0, 0.1, 25.0, 5);
  acc::OnlineUpdate update;
  update.window = acc::identifyAcc({*run}, options);
  update.window_quantities =
      acc::assessQuantities(update.window.calibration.parameters, update.window.uncertainty, {*run}, acc::ParameterBounds{});
  for (auto& q : update.window_quantities->quantities)
  {
    if (q.name == quantity)
    {
      q.determined = false;
      q.reason = reason;
    }
  }
  return update;
}

TEST(IdentifierMessage, QuantitiesOneByOneTheDriveAndTheVerdict)
{
  acc::CarFollowingRun run;
  // Pretend the data pin everything but tau_e (as real steady drives do).
  acc::OnlineUpdate update = windowWithout("tau_e", "tau_e = 0 +- 0.67 s: standard error too large", &run);
  ASSERT_TRUE(update.window.solved);
  update.drive = update.window;
  update.drive_quantities = update.window_quantities;
  update.drive_samples = run.size();
  acc::StabilityTestResult test;
  test.verdict = acc::StabilityVerdict::Unstable;
  test.p_value = 0.004;
  test.tested = true;
  test.margin_low = -1.8;
  test.margin_high = -0.9;
  test.reason = "the stable model predicts worse";
  update.stability = test;
  update.stability_drive_samples = run.size();

  const auto m = acc::toMessage(update, 1000.0, 1300.0, 900.0);
  EXPECT_TRUE(std::isnan(m.tau_e_s));
  EXPECT_TRUE(std::isnan(m.tau_e_std_error));
  EXPECT_DOUBLE_EQ(m.k1_per_s2, update.window.calibration.parameters.k1_per_s2);  // k1 still published
  EXPECT_FALSE(std::isnan(m.equilibrium_gap_m));
  EXPECT_GT(m.equilibrium_speed_mps, 15.0);
  EXPECT_FALSE(m.identifiable);  // not all four
  EXPECT_NE(m.identifiability_note.find("tau_e = 0 +- 0.67 s"), std::string::npos);
  EXPECT_TRUE(std::isnan(m.lambda2));  // needs tau_e
  EXPECT_EQ(m.drive_samples, run.size());
  EXPECT_DOUBLE_EQ(m.drive_start.toSec(), 900.0);
  EXPECT_TRUE(std::isnan(m.drive_tau_e_s));
  EXPECT_DOUBLE_EQ(m.drive_std_error_t95, acc::intervalFactor95(update.drive.uncertainty.blocks));
  EXPECT_EQ(m.stability_verdict, "unstable");
  EXPECT_DOUBLE_EQ(m.stability_p_value, 0.004);
  EXPECT_DOUBLE_EQ(m.stability_margin_high, -0.9);
  EXPECT_EQ(m.stability_samples, run.size());
  EXPECT_EQ(m.drive_note.find("Euler step"), std::string::npos) << "no check ran";

  // The drive fit's Euler step check, when one ran, ends the drive's note on one line.
  acc::EulerStepBias check;
  check.median_step_s = 1.0;
  check.reason = "every start of the refit diverged";
  update.euler_step = check;
  const auto checked = acc::toMessage(update, 1000.0, 1300.0, 900.0);
  EXPECT_NE(checked.drive_note.find("Euler step (the paper's calibration simulates at the data's own step, median 1 s): "
                                    "not assessed: every start of the refit diverged"),
            std::string::npos)
      << checked.drive_note;
  EXPECT_EQ(checked.drive_note.find('\n'), std::string::npos);
  // A report of two lines: joined by "; ", the second's indent gone.
  check.assessed = true;
  check.reason.clear();
  check.substeps = 10;
  check.bias.k1_per_s2 = -0.012;
  check.corrected.k1_per_s2 = 0.072;
  check.material = true;
  check.material_because = "k1 -20 % (4.1 standard errors)";
  update.euler_step = check;
  const std::string note = acc::toMessage(update, 1000.0, 1300.0, 900.0).drive_note;
  EXPECT_NE(note.find("MATERIAL: k1 -20 % (4.1 standard errors); corrected (fit - bias): k1 0.0720"), std::string::npos)
      << note;
  EXPECT_EQ(note.find('\n'), std::string::npos) << note;
  EXPECT_EQ(note.find("  "), std::string::npos) << note;
}

TEST(IdentifierMessage, NoVerdictYetIsUndecidedWithNaNAndTimesOutOfRangeNeverThrow)
{
  acc::OnlineUpdate update;
  update.window.note = "too little data";
  acc_identification::AccParameters m;
  EXPECT_NO_THROW(m = acc::toMessage(update, std::numeric_limits<double>::infinity(), 1e12,
                                     std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(m.stability_verdict, "undecided");
  EXPECT_TRUE(std::isnan(m.stability_p_value));
  EXPECT_EQ(m.header.stamp.toSec(), 0.0);
  EXPECT_EQ(m.window_start.toSec(), 0.0);
}
}  // namespace

namespace
{
/// The node applies the batch readers' plausibility bounds: a sample the pairing marked valid but
/// with a 1e9 m/s follower speed is a split point, as a CSV row or a bag message would be.
// The node publishes the sequential verdict's look when there is one: its verdict, anytime-valid
// p-value, e-values, when it was decided, and no margin interval (NaN).
TEST(IdentifierMessage, SequentialLookIsThePublishedVerdict)
{
  acc::OnlineUpdate update;
  acc::SequentialLook look;
  look.time_s = 420.0;
  look.samples = 4200;
  look.blocks_scored = 39;
  look.verdict = acc::StabilityVerdict::Unstable;
  look.p_value = 0.03;
  look.e_value_unstable = 33.0;
  look.e_value_stable = 0.2;
  look.decided_at_s = 410.0;
  look.stable_fit_margin = 0.0;
  look.unstable_fit_margin = -0.6;
  look.reason = "sequential";
  update.sequential = look;
  const auto m = acc::toMessage(update, 100.0, 420.0, 0.0);
  EXPECT_EQ(m.stability_verdict, "unstable");
  EXPECT_DOUBLE_EQ(m.stability_p_value, 0.03);
  EXPECT_DOUBLE_EQ(m.stability_e_value_unstable, 33.0);
  EXPECT_DOUBLE_EQ(m.stability_e_value_stable, 0.2);
  EXPECT_DOUBLE_EQ(m.stability_decided_at_s, 410.0);
  EXPECT_FALSE(m.stability_reversed);
  EXPECT_EQ(m.stability_blocks_scored, 39u);
  EXPECT_EQ(m.stability_samples, 4200u);
  EXPECT_DOUBLE_EQ(m.stability_unstable_fit_margin, -0.6);
  EXPECT_TRUE(std::isnan(m.stability_margin_low));
  EXPECT_EQ(m.stability_reason, "sequential");
  // Before the first look: undecided, and every sequential number NaN.
  const auto none = acc::toMessage(acc::OnlineUpdate{}, 100.0, 420.0, 0.0);
  EXPECT_EQ(none.stability_verdict, "undecided");
  EXPECT_TRUE(std::isnan(none.stability_e_value_unstable));
  EXPECT_TRUE(std::isnan(none.stability_decided_at_s));
}

TEST(IdentifierSamples, ImplausibleValuesAreSplitPointsLikeInBatch)
{
  acc_identification::RelativeState message;
  message.header.stamp = ros::Time(1000.0);
  message.valid = true;
  message.space_gap_m = 30.0;
  message.follower_speed_mps = 20.0;
  message.leader_speed_mps = 20.5;
  std::string why;
  EXPECT_TRUE(acc::toWindowSample(message, why).valid);
  EXPECT_TRUE(why.empty());
  message.follower_speed_mps = 1e9;
  const acc::WindowSample sample = acc::toWindowSample(message, why);
  EXPECT_FALSE(sample.valid);
  EXPECT_NE(why.find("follower_speed_mps 1e+09 outside [-1, 100] m/s"), std::string::npos) << why;
  message.valid = false;  // already invalid: the pairing said why, nothing more to add
  EXPECT_FALSE(acc::toWindowSample(message, why).valid);
  EXPECT_TRUE(why.empty());
}

/// eta does not enter the linearised dynamics: a window that pins k1, k2 and tau_e but not eta
/// (the ZalaZone drive of the demo) still publishes lambda2 and the band, yet is not "identifiable".
TEST(IdentifierMessage, Lambda2NeedsTheDynamicsNotEta)
{
  acc::CarFollowingRun run;
  const acc::OnlineUpdate update = windowWithout("eta", "eta = 0.3 +- 1.3 m: standard error too large", &run);
  ASSERT_TRUE(update.window.solved);
  const auto m = acc::toMessage(update, 1000.0, 1300.0, 900.0);
  EXPECT_TRUE(std::isnan(m.eta_m));
  EXPECT_FALSE(m.identifiable);
  EXPECT_DOUBLE_EQ(m.lambda2, update.window.stability.lambda2);
  EXPECT_FALSE(std::isnan(m.amplified_band_upper_rad_s));
  EXPECT_EQ(m.string_stable, acc_identification::AccParameters::STRING_UNSTABLE);  // Table II's minimum setting
}

}  // namespace
