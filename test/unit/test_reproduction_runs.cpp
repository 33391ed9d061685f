#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "acc_identification/model/acc_model.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/reproduction/equilibrium_regression.h"
#include "acc_identification/reproduction/parameter_file.h"
#include "acc_identification/reproduction/run_comparison.h"


namespace
{
/// A run made by the model itself: the leader steps between several speeds, the follower is the
/// Euler simulation of p. Long holds so that the follower reaches equilibrium at each speed.
acc::CarFollowingRun syntheticRun(const acc::AccParameters& p)
{
  acc::CarFollowingRun run;
  run.name = "synthetic";
  const double h = 0.1;
  const double speeds[] = {15.0, 20.0, 25.0, 18.0};
  for (int k = 0; k < 4 * 3000; ++k)
  {
    run.time_s.push_back(k * h);
    run.leader_speed_mps.push_back(speeds[k / 3000]);
  }
  run.follower_speed_mps.assign(run.size(), 15.0);
  run.space_gap_m.assign(run.size(), acc::equilibriumSpaceGapM(p, 15.0));
  const auto sim = acc::simulateFollower(p, run);
  run.follower_speed_mps = sim.speed_mps;
  run.space_gap_m = sim.space_gap_m;
  return run;
}

std::string writeTemp(const std::string& name, const std::string& text)
{
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}
}  // namespace

TEST(ReproductionRuns, TrainTestErrorsAreZeroForTheTrueModelAndNotForAnother)
{
  const acc::AccParameters truth = acc::paperMinimumSetting();
  const auto run = syntheticRun(truth);
  const auto exact = acc::trainTestErrors(run, acc::simulateFollower(truth, run), 0.5);
  EXPECT_EQ(exact.split_index, run.size() / 2);
  EXPECT_NEAR(exact.split_time_s, run.time_s[run.size() / 2], 1e-12);
  EXPECT_LT(exact.train_speed_rmse_mps + exact.test_speed_rmse_mps, 1e-9);
  EXPECT_LT(exact.train_gap_rmse_m + exact.test_gap_rmse_m, 1e-9);
  const auto other = acc::trainTestErrors(run, acc::simulateFollower(acc::paperMaximumSetting(), run), 0.5);
  EXPECT_GT(other.train_speed_rmse_mps, 0.05);
  EXPECT_GT(other.test_gap_rmse_m, 1.0);
  EXPECT_THROW(acc::trainTestErrors(run, acc::simulateFollower(truth, run), 1.0), std::invalid_argument);
  EXPECT_EQ(exact.train_samples + exact.test_samples, run.size());
}

// A simulation that blew up before the split scores its train part up to the blow-up and leaves
// the test part without a sample: NaN, never the 0 that reads as a perfect fit.
TEST(ReproductionRuns, APartWithoutASampleHasNoErrorRatherThanZero)
{
  const acc::AccParameters truth = acc::paperMinimumSetting();
  const auto run = syntheticRun(truth);
  acc::SimulatedFollower sim = acc::simulateFollower(acc::paperMaximumSetting(), run);
  sim.diverged = true;
  sim.diverged_at_index = 3;
  const auto cut = acc::trainTestErrors(run, sim, 0.5);
  EXPECT_EQ(cut.train_samples, 3u);
  EXPECT_EQ(cut.test_samples, 0u);
  EXPECT_TRUE(std::isnan(cut.test_speed_rmse_mps));
  EXPECT_TRUE(std::isnan(cut.test_gap_rmse_m));
  EXPECT_TRUE(std::isfinite(cut.train_speed_rmse_mps));
}

// Fig. 5: steady samples of a run of the model sit on its line eta + tau_e v.
TEST(ReproductionRuns, EquilibriumLineOfSteadySamplesRecoversEtaAndTau)
{
  const acc::AccParameters truth = acc::paperMaximumSetting();
  const auto run = syntheticRun(truth);
  const auto steady = acc::steadyFollowingSamples(run, 0.05, 0.01);
  ASSERT_GT(steady.size(), 3000u);
  ASSERT_LT(steady.size(), run.size());
  const auto line = acc::fitGapSpeedLine(run, steady);
  EXPECT_NEAR(line.slope_s, truth.tau_e_s, 0.02);
  EXPECT_NEAR(line.intercept_m, truth.eta_m, 0.4);
  EXPECT_LT(acc::rmsFromEquilibriumLine(truth, run, steady), 0.3);
  EXPECT_GT(acc::rmsFromEquilibriumLine(acc::paperMinimumSetting(), run, steady), 10.0);
  EXPECT_THROW(acc::fitGapSpeedLine(run, {1}), std::invalid_argument);
}

TEST(ReproductionRuns, ParameterFileReadsCalibrateJsonAndExplainsProblems)
{
  const std::string good = writeTemp("nexo_min.json",
                                     R"({"parameters": {"k1_per_s2": 0.08, "k2_per_s": 0.4, "tau_e_s": 0.9,
                                         "eta_m": 5.5}, "rmse": {"speed_mps": 0.2}})");
  const auto setting = acc::readParameterFile(good);
  EXPECT_EQ(setting.name, "nexo_min");
  EXPECT_DOUBLE_EQ(setting.parameters.k1_per_s2, 0.08);
  EXPECT_DOUBLE_EQ(setting.parameters.k2_per_s, 0.4);
  EXPECT_DOUBLE_EQ(setting.parameters.tau_e_s, 0.9);
  EXPECT_DOUBLE_EQ(setting.parameters.eta_m, 5.5);
  EXPECT_THROW(acc::readParameterFile(writeTemp("p1.json", "{not json")), acc::ParameterFileError);
  EXPECT_THROW(acc::readParameterFile(writeTemp("p2.json", R"({"k1_per_s2": 1})")), acc::ParameterFileError);
  EXPECT_THROW(acc::readParameterFile(writeTemp("p3.json", R"({"parameters": {"k1_per_s2": 1, "k2_per_s": "x",
                                       "tau_e_s": 1, "eta_m": 1}})")),
               acc::ParameterFileError);
  EXPECT_THROW(acc::readParameterFile(testing::TempDir() + "missing.json"), acc::ParameterFileError);
}

// A calibration whose data do not pin k1, k2 or tau_e draws dynamics they do not determine: said
// (platoon fig7 on the Casale part5 fit printed a 11.6-fold amplification without a word); eta
// alone undetermined moves no figure's dynamics and is not.
TEST(ReproductionRuns, AParameterFileWhoseDynamicsItsDataDoNotPinIsSaid)
{
  const auto file = [](const std::string& name, bool k2_determined, bool eta_determined) {
    return writeTemp(name, std::string(R"({"parameters": {"k1_per_s2": 0.08, "k2_per_s": 0.4, "tau_e_s": 0.9, "eta_m": 5.5},
        "identifiable": false, "identifiable_quantities": {"quantities": {
        "k1": {"determined": true, "reason": "k1 fine"},
        "k2": {"determined": )") + (k2_determined ? "true" : "false") + R"(, "reason": "k2 = 0.08 +- 0.08 1/s"},
        "tau_e": {"determined": true, "reason": "tau_e fine"},
        "eta": {"determined": )" + (eta_determined ? "true" : "false") + R"(, "reason": "eta at its bound"}}}})");
  };
  const std::string loose = acc::describeUndeterminedParameterFile(file("loose.json", false, false));
  EXPECT_NE(loose.find("loose.json: the data it was fitted on do not determine its dynamics (k2 = 0.08 +- 0.08 1/s)"),
            std::string::npos)
      << loose;
  EXPECT_EQ(acc::describeUndeterminedParameterFile(file("eta_only.json", true, false)), "");
  EXPECT_EQ(acc::describeUndeterminedParameterFile(writeTemp("plain.json", R"({"parameters": {}})")), "");
}
