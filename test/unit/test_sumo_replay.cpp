// SUMO replays against SUMO itself (Debian's sumo 1.15, headless, over TraCI): a model identified
// on a real run, exported and replayed behind the run's real leader, agrees with the package's
// simulation where SUMO's law and the model coincide; where they do not, the package's replica of
// SUMO's law accounts for every step.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <filesystem>
#include <sstream>

#include <unistd.h>

#include "acc_identification/calibration/identification.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/sumo/sumo_replay.h"
#include "acc_identification/sumo/sumo_replay_report.h"

namespace acc
{
namespace
{
SumoReplayOptions replayOptions()
{
  SumoReplayOptions options;
  options.driver_script = ACC_SUMO_DRIVER;
  return options;
}

std::string vtypeFile(const std::vector<SumoExport>& exports, const std::string& name)
{
  const std::string path =
      (std::filesystem::temp_directory_path() / ("acc_test_sumo_replay_" + std::to_string(::getpid()) + name)).string();
  writeSumoAdditional(exports, path, "test");
  return path;
}

CarFollowingRun casaleRun(const std::string& part)
{
  std::vector<CarFollowingRun> runs = readRuns(std::string(ACC_CASALE_DIR) + "/" + part + ".csv");
  EXPECT_EQ(runs.size(), 1u);
  return runs.front();
}

/// Casale part 5 (105 s, 28-39 m/s, gaps 31-53 m): every step in SUMO's gap control above
/// 15 m/s, so SUMO's law is the identified model's, bar the position update.
TEST(SumoReplay, IdentifiedModelAgreesWithSumoInTheGapControlRegime)
{
  const CarFollowingRun run = casaleRun("part5");
  IdentificationOptions options;
  options.multistart.starts = 20;
  const Identification identification = identifyAcc({run}, options);
  ASSERT_TRUE(identification.solved);
  const AccParameters& p = identification.calibration.parameters;
  const SumoExport exported = exportToSumo("nexo", p, {}, {}, observedAccelerationLimits({run}));
  const std::string path = vtypeFile({exported}, "pair.add.xml");
  const SumoPairReplay replay = replayPairInSumo(run, readSumoAccVTypes(path).front(), path, replayOptions());
  std::remove(path.c_str());
  EXPECT_EQ(replay.samples, run.size());
  EXPECT_LT(replay.rmse_speed_sumo_vs_model_mps, 0.05);
  EXPECT_LT(replay.rmse_speed_sumo_vs_replica_mps, 1e-6);  // SUMO's law is read right
  EXPECT_EQ(replay.counts.law_coincides, replay.counts.steps) << toJson(replay).dump(2);
  EXPECT_EQ(replay.counts.safe_speed_override, 0u);
  // SUMO is as far from the measured car as the model is.
  EXPECT_NEAR(replay.rmse_speed_sumo_vs_measured_mps, replay.rmse_speed_model_vs_measured_mps, 0.05);
  EXPECT_NEAR(replay.rmse_speed_model_vs_measured_mps, identification.calibration.rmse_speed_mps, 1e-4);
}

/// Below 15 m/s SUMO 1.15 adds up to 2 m to the desired gap: SUMO and the model part, and the
/// replica of SUMO's law still matches SUMO step for step, naming the margin as the cause.
TEST(SumoReplay, BelowFifteenMetresPerSecondTheMarginIsTheDifference)
{
  CarFollowingRun run;
  run.name = "slow";
  for (int k = 0; k < 1200; ++k)
  {
    const double t = 0.1 * k;
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(10.0 + 2.0 * std::sin(0.1 * t));
  }
  const AccParameters p{0.08, 0.45, 1.3, 6.0};
  run.space_gap_m.assign(run.size(), p.eta_m + p.tau_e_s * 10.0);
  run.follower_speed_mps.assign(run.size(), 10.0);
  const std::string path = vtypeFile({exportToSumo("slow_car", p, {}, {}, {5.0, 8.0})}, "slow.add.xml");
  const SumoPairReplay replay = replayPairInSumo(run, readSumoAccVTypes(path).front(), path, replayOptions());
  std::remove(path.c_str());
  EXPECT_LT(replay.rmse_speed_sumo_vs_replica_mps, 1e-6);
  EXPECT_EQ(replay.counts.below_15_mps, replay.counts.steps);
  EXPECT_EQ(replay.counts.law_coincides, 0u);
  EXPECT_GT(replay.rmse_gap_sumo_vs_model_m, 1.0);  // the 2 m margin opens the gap
  ASSERT_FALSE(replay.explanation.empty());
  EXPECT_NE(replay.explanation.front().find("15 m/s"), std::string::npos) << replay.explanation.front();
}

TEST(SumoReplay, PlatoonDipsInSumoMatchThePackagesChainWhereTheLawsCoincide)
{
  CarFollowingRun run;
  run.name = "braking";
  for (int k = 0; k < 1200; ++k)
  {
    const double t = 0.1 * k;
    // 30 m/s, a 4 m/s braking over 6 s at 40 s, back up by 60 s.
    double u = 30.0;
    if (t > 40.0 && t <= 46.0)
      u -= 4.0 * (t - 40.0) / 6.0;
    else if (t > 46.0 && t <= 60.0)
      u -= 4.0 * (60.0 - t) / 14.0;
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(u);
  }
  run.space_gap_m.assign(run.size(), 40.0);
  run.follower_speed_mps.assign(run.size(), 30.0);
  const std::string path = vtypeFile({exportToSumo("stable", {0.1, 0.6, 1.5, 5.0}, {}, {}, {5.0, 8.0}),
                                      exportToSumo("unstable", {0.05, 0.1, 1.2, 5.0}, {}, {}, {5.0, 8.0})},
                                     "platoon.add.xml");
  const std::vector<SumoAccVType> vtypes = readSumoAccVTypes(path);
  const SumoPlatoonReplay replay =
      replayPlatoonInSumo(equilibriumPlatoon(run, {vtypes[0], vtypes[1], vtypes[1]}), path, replayOptions());
  std::remove(path.c_str());
  ASSERT_EQ(replay.perturbations.size(), 1u);
  ASSERT_EQ(replay.perturbations[0].positions.size(), 3u);
  for (const SumoPlatoonDip& dip : replay.perturbations[0].positions)
  {
    EXPECT_NEAR(dip.sumo_dip_mps, dip.replica_dip_mps, 1e-6) << dip.vtype_id;
    // The position updates differ (SUMO moves by the new speed): 1-2 % of a dip along a chain
    // that amplifies it.
    EXPECT_NEAR(dip.sumo_dip_mps, dip.model_dip_mps, 0.02 * dip.model_dip_mps + 0.01) << dip.vtype_id;
  }
  // The weakly damped cars amplify the braking, in SUMO as in the package.
  EXPECT_GT(replay.perturbations[0].positions[2].sumo_dip_mps, replay.perturbations[0].positions[1].sumo_dip_mps);
}

/// A delayed model exported with SUMO's action step (2 d): SUMO holds its decisions between action
/// steps, which the replica does too, step for step; the delayed model and SUMO pass the braking on
/// alike, and far more than SUMO without the action step.
TEST(SumoReplay, TheDelayAsAnActionStepIsHeldAsSumoHoldsIt)
{
  CarFollowingRun run;
  run.name = "braking";
  for (int k = 0; k < 900; ++k)
  {
    const double t = 0.1 * k;
    double u = 25.0;
    if (t > 30.0 && t <= 34.0)
      u -= 5.0 * (t - 30.0) / 4.0;
    else if (t > 34.0 && t <= 44.0)
      u -= 5.0 * (44.0 - t) / 10.0;
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(u);
  }
  const AccParameters p{0.05, 0.6, 0.8, 8.0};
  run.space_gap_m.assign(run.size(), p.eta_m + p.tau_e_s * 25.0);
  run.follower_speed_mps.assign(run.size(), 25.0);
  SumoExport delayed = exportToSumo("delayed", p, {EffectKind::reaction_delay}, {0.8}, {5.0, 8.0});
  ASSERT_NEAR(delayed.vtype.action_step_length_s, 1.6, 1e-12);
  SumoExport prompt = exportToSumo("prompt", p, {EffectKind::reaction_delay}, {0.8}, {5.0, 8.0});
  prompt.vtype.action_step_length_s = std::numeric_limits<double>::quiet_NaN();
  const std::string path = vtypeFile({delayed, prompt}, "delay.add.xml");
  const std::vector<SumoAccVType> vtypes = readSumoAccVTypes(path);
  const SumoPlatoonReplay with_step = replayPlatoonInSumo(equilibriumPlatoon(run, {vtypes[0]}), path, replayOptions());
  const SumoPlatoonReplay without = replayPlatoonInSumo(equilibriumPlatoon(run, {vtypes[1]}), path, replayOptions());
  std::remove(path.c_str());
  ASSERT_EQ(with_step.perturbations.size(), 1u);
  EXPECT_LT(with_step.rmse_speed_sumo_vs_replica_mps[0], 1e-6);
  EXPECT_GT(with_step.steps[0].held, 800u);  // 15 of every 16 steps
  const SumoPlatoonDip& held = with_step.perturbations[0].positions[0];
  const SumoPlatoonDip& prompt_dip = without.perturbations[0].positions[0];
  EXPECT_NEAR(held.sumo_dip_mps, held.model_dip_mps, 0.15 * held.model_dip_mps);
  EXPECT_GT(held.model_dip_mps - prompt_dip.sumo_dip_mps, 0.1);  // the delay deepens the dip
}

TEST(SumoReplay, UnknownIdsAndNonUniformRunsAreRefused)
{
  const CarFollowingRun run = casaleRun("part4");
  const std::string path = vtypeFile({exportToSumo("one", {0.08, 0.45, 1.3, 6.0}, {}, {}, {})}, "ids.add.xml");
  std::ostringstream out;
  try
  {
    replayRunInSumo({run}, path, {"two"}, replayOptions(), out);
    FAIL() << "an unknown vType id was accepted";
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_NE(std::string(error.what()).find("it has: one"), std::string::npos) << error.what();
  }
  std::remove(path.c_str());
  CarFollowingRun uneven = run.slice(0, 50);
  uneven.time_s[10] += 0.05;
  EXPECT_THROW(uniformStepS(uneven), std::runtime_error);
  EXPECT_NE(nonUniformStepReason(uneven).find("a --max-gap below that step splits the run there"), std::string::npos);
  EXPECT_EQ(nonUniformStepReason(run.slice(0, 50)), "");
}

}  // namespace
}  // namespace acc
