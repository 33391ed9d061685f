// The live identifier's computation (online_identifier.h): the drive-so-far estimate converges to
// the batch calibration of the whole drive, and its verdict is the batch verdict.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "acc_identification/calibration/drive_record.h"
#include "acc_identification/calibration/online_identifier.h"
#include "acc_identification/calibration/sliding_window.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/paper_settings.h"

namespace
{
struct Replay
{
  acc::OnlineUpdate last;
  std::size_t updates = 0;
  std::size_t decided_updates = 0;
  double max_update_s = 0.0;
};

/// Feeds a run sample by sample into a window and a drive, as the node does, and updates every
/// period_s of data time; a hole longer than max_gap_s splits them (the node's ~max_gap_s).
Replay replay(const acc::CarFollowingRun& run, double window_s, double period_s, acc::OnlineIdentifier& identifier,
              double max_gap_s = 0.5)
{
  acc::SlidingWindow window(window_s, max_gap_s, 20), drive(1.0e9, max_gap_s, 20);
  Replay result;
  double next_update_s = run.time_s.front() + period_s;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    const acc::WindowSample sample{run.time_s[k], run.space_gap_m[k], run.follower_speed_mps[k],
                                   run.leader_speed_mps[k], true};
    window.add(sample);
    drive.add(sample);
    if (run.time_s[k] >= next_update_s || k + 1 == run.size())
    {
      result.last = identifier.update(window.segments(), drive.segments());
      ++result.updates;
      const double cost = result.last.window_cpu_s + result.last.drive_cpu_s;
      result.max_update_s = std::max(result.max_update_s, cost);
      if (result.last.stability && result.last.stability->verdict != acc::StabilityVerdict::Undecided)
        ++result.decided_updates;
      next_update_s += period_s;
    }
  }
  return result;
}
}  // namespace

TEST(OnlineIdentifier, DriveSoFarConvergesToTheBatchEstimateAndVerdict)
{
  const acc::AccParameters truth = acc::paperMinimumSetting();
  const acc::CarFollowingRun run = acc::synthesizeRun(truth, 900.0, 0.1, 20.0, 11);
  acc::OnlineIdentifierOptions options;
  options.window.multistart.starts = 8;
  options.stability_every_updates = 5;
  acc::OnlineIdentifier identifier(options);
  const Replay live = replay(run, 120.0, 30.0, identifier);

  // The batch calibration of the whole drive, as calibrate does it.
  acc::IdentificationOptions batch_options;
  const acc::Identification batch = acc::identifyAcc({run}, batch_options);
  ASSERT_TRUE(batch.solved);
  ASSERT_TRUE(live.last.drive.solved);
  const acc::AccParameters& online = live.last.drive.calibration.parameters;
  const acc::AccParameters& reference = batch.calibration.parameters;
  std::printf("  drive so far: k1 %.5f k2 %.5f tau_e %.5f eta %.4f, rmse %.6f m/s\n", online.k1_per_s2,
              online.k2_per_s, online.tau_e_s, online.eta_m, live.last.drive.calibration.rmse_speed_mps);
  std::printf("  batch:        k1 %.5f k2 %.5f tau_e %.5f eta %.4f, rmse %.6f m/s\n", reference.k1_per_s2,
              reference.k2_per_s, reference.tau_e_s, reference.eta_m, batch.calibration.rmse_speed_mps);
  // Same objective, same data: the continued solve reaches the batch optimum's value.
  EXPECT_NEAR(live.last.drive.calibration.rmse_speed_mps, batch.calibration.rmse_speed_mps,
              1e-4 * batch.calibration.rmse_speed_mps);
  EXPECT_NEAR(online.tau_e_s, reference.tau_e_s, 2.0 * batch.uncertainty.standard_error.tau_e_s + 1e-3);
  EXPECT_NEAR(online.k1_per_s2, reference.k1_per_s2, 2.0 * batch.uncertainty.standard_error.k1_per_s2 + 1e-4);
  EXPECT_EQ(live.last.drive_samples, run.size());

  // The verdict: decided before the end, and the batch test of the same samples agrees.
  ASSERT_TRUE(live.last.stability.has_value());
  EXPECT_GT(live.decided_updates, 0u);
  acc::StabilityTestOptions batch_test;
  batch_test.warm_starts = {reference};
  const acc::StabilityTestResult batch_verdict = acc::testStringStability({run}, batch_test);
  std::printf("  verdict live %s (p %.3g), batch %s (p %.3g); %zu of %zu updates decided; slowest update %.3f s\n",
              acc::toString(live.last.stability->verdict).c_str(), live.last.stability->p_value,
              acc::toString(batch_verdict.verdict).c_str(), batch_verdict.p_value, live.decided_updates, live.updates,
              live.max_update_s);
  EXPECT_EQ(live.last.stability->verdict, acc::StabilityVerdict::Unstable);
  EXPECT_EQ(batch_verdict.verdict, acc::StabilityVerdict::Unstable);
}

TEST(OnlineIdentifier, QuantitiesAreAssessedOneByOneAndTheDriveCanBeReset)
{
  const acc::CarFollowingRun run = acc::synthesizeRun(acc::paperMaximumSetting(), 300.0, 0.1, 20.0, 5);
  acc::OnlineIdentifierOptions options;
  options.window.multistart.starts = 4;
  options.stability_every_updates = 0;  // never
  acc::OnlineIdentifier identifier(options);
  const Replay live = replay(run, 120.0, 60.0, identifier);
  ASSERT_TRUE(live.last.window_quantities.has_value());
  ASSERT_TRUE(live.last.drive_quantities.has_value());
  EXPECT_NE(live.last.drive_quantities->find("stability_margin"), nullptr);
  EXPECT_FALSE(live.last.stability.has_value());  // the test never ran
  identifier.resetDrive();
  const acc::OnlineUpdate after = identifier.update({}, {});
  EXPECT_FALSE(after.drive.solved);
  EXPECT_FALSE(after.window.solved);
  EXPECT_FALSE(after.drive.note.empty());
}

namespace
{
/// run shifted to start at start_s (a second part of one drive).
acc::CarFollowingRun shifted(acc::CarFollowingRun run, double start_s)
{
  const double offset_s = start_s - run.time_s.front();
  for (double& t : run.time_s) t += offset_s;
  return run;
}
}  // namespace

// The node keeps the drive so far within ~drive_max_samples (an hour at 10 Hz) by letting go of
// whole blocks. On two hours at two cruise speeds, kept at one hour, what the data determine must
// still be determined, near the truth and near the fit of every sample, with the same verdict.
TEST(OnlineIdentifier, ABoundedDriveDeterminesWhatTheWholeDriveDoes)
{
  const acc::AccParameters truth = acc::paperMinimumSetting();
  const acc::CarFollowingRun slow = acc::synthesizeRun(truth, 3600.0, 0.1, 18.0, 21);
  const acc::CarFollowingRun fast = shifted(acc::synthesizeRun(truth, 3600.0, 0.1, 28.0, 22), slow.time_s.back() + 0.1);
  acc::DriveBound bound;  // the node's default: 36,000 samples
  acc::DriveRecord bounded(0.5, 20, 30.0, 5, bound);
  for (const acc::CarFollowingRun* run : {&slow, &fast})
  {
    for (std::size_t k = 0; k < run->size(); ++k)
    {
      bounded.add(acc::WindowSample{run->time_s[k], run->space_gap_m[k], run->follower_speed_mps[k],
                                    run->leader_speed_mps[k], true});
    }
  }
  ASSERT_LE(bounded.size(), bound.max_samples + 600u);
  EXPECT_EQ(bounded.samplesTaken(), slow.size() + fast.size());
  bool kept_slow = false, kept_fast = false;
  for (const acc::WindowSample& s : bounded.window().samples())
  {
    kept_slow = kept_slow || s.time_s < fast.time_s.front();
    kept_fast = kept_fast || s.time_s >= fast.time_s.front();
  }
  EXPECT_TRUE(kept_slow && kept_fast) << "a cruise speed was let go of entirely";

  const acc::Identification kept = acc::identifyAcc(bounded.segments(), acc::IdentificationOptions{});
  const acc::Identification whole = acc::identifyAcc({slow, fast}, acc::IdentificationOptions{});
  ASSERT_TRUE(kept.solved && whole.solved);
  const acc::AccParameters& p = kept.calibration.parameters;
  const acc::AccParameters& se = kept.uncertainty.standard_error;
  std::printf("  kept %zu of %zu samples: k1 %.5f+-%.5f k2 %.4f+-%.4f tau_e %.4f+-%.4f eta %.3f+-%.3f\n",
              kept.samples, whole.samples, p.k1_per_s2, se.k1_per_s2, p.k2_per_s, se.k2_per_s, p.tau_e_s, se.tau_e_s,
              p.eta_m, se.eta_m);
  const acc::AccParameters& w = whole.calibration.parameters;
  std::printf("  all %zu samples: k1 %.5f k2 %.4f tau_e %.4f eta %.3f\n", whole.samples, w.k1_per_s2, w.k2_per_s,
              w.tau_e_s, w.eta_m);
  EXPECT_TRUE(kept.identifiable) << kept.note;
  // The truth is simulated 10x finer than the 10 Hz Euler recursion the fit runs: besides three
  // standard errors, the recursion's own bias (up to 4 %, as the identifier rostest allows).
  const auto near_truth = [](double value, double truth_value, double standard_error) {
    return std::abs(value - truth_value) <= 3.0 * standard_error + 0.04 * std::abs(truth_value);
  };
  EXPECT_TRUE(near_truth(p.k1_per_s2, truth.k1_per_s2, se.k1_per_s2));
  EXPECT_TRUE(near_truth(p.k2_per_s, truth.k2_per_s, se.k2_per_s));
  EXPECT_TRUE(near_truth(p.tau_e_s, truth.tau_e_s, se.tau_e_s));
  // The fit of every sample has the same bias: the kept hour agrees with it to its own errors.
  EXPECT_NEAR(p.k1_per_s2, w.k1_per_s2, 3.0 * se.k1_per_s2);
  EXPECT_NEAR(p.k2_per_s, w.k2_per_s, 3.0 * se.k2_per_s);
  EXPECT_NEAR(p.tau_e_s, w.tau_e_s, 3.0 * se.tau_e_s);

  acc::StabilityTestOptions test = acc::OnlineIdentifierOptions::defaultStabilityOptions();
  test.warm_starts = {p};
  EXPECT_EQ(acc::testStringStability(bounded.segments(), test).verdict, acc::StabilityVerdict::Unstable);
}

// At 1 Hz the Euler step moves the fit by a quarter of k1 and the margin towards "stable": the
// drive's check runs with its test, and the same drive at 10 Hz skips it (3 % of k1).
TEST(OnlineIdentifier, ChecksTheEulerStepOfTheDriveWhereTheDataAreCoarse)
{
  const acc::AccParameters truth{0.1, 0.5, 1.0, 6.0};
  acc::OnlineIdentifierOptions options;
  options.window.multistart.starts = 8;
  options.stability_every_updates = 3;
  const acc::CarFollowingRun coarse = acc::synthesizeRun(truth, 600.0, 1.0, 15.0, 7, {0.02, 0.05});
  acc::OnlineIdentifier identifier(options);
  const Replay live = replay(coarse, 300.0, 60.0, identifier, 2.5);  // ~max_gap_s above the 1 s step
  ASSERT_TRUE(live.last.drive.solved);
  ASSERT_TRUE(live.last.euler_step.has_value());
  const acc::EulerStepBias& check = *live.last.euler_step;
  ASSERT_TRUE(check.assessed) << check.reason;
  std::printf("  1 Hz drive: k1 bias %+.4f, margin bias %+.4f, material: %s\n", check.bias.k1_per_s2,
              check.margin_bias, check.material_because.c_str());
  EXPECT_NEAR(check.median_step_s, 1.0, 1e-9);
  EXPECT_LT(check.bias.k1_per_s2, -0.15 * check.fit.k1_per_s2);  // a quarter low at 1 Hz
  EXPECT_GT(check.margin_bias, 0.05);
  EXPECT_TRUE(check.material);

  // The same check on demand agrees, and a 10 Hz drive skips it.
  const acc::CarFollowingRun fine = acc::synthesizeRun(truth, 300.0, 0.1, 15.0, 7, {0.02, 0.05});
  const acc::Identification fine_fit = acc::identifyAcc({fine}, options.window);
  EXPECT_FALSE(identifier.checkEulerStep({fine}, fine_fit).has_value());
  acc::OnlineIdentifierOptions always = options;
  always.euler_check_min_step_s = 0.0;
  EXPECT_TRUE(acc::OnlineIdentifier(always).checkEulerStep({fine}, fine_fit).has_value());
  identifier.resetDrive();
  EXPECT_FALSE(identifier.update({coarse}, {coarse}).euler_step.has_value()) << "the check of the previous drive is forgotten";
}
