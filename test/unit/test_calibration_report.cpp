#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "acc_identification/calibration/calibrate_runs.h"
#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/paper_settings.h"


namespace
{
TEST(CalibrationReport, SplitInHalfTrainsOnTheFirstHalfAndTestsOnTheSecond)
{
  const auto run = acc::synthesizeRun(acc::paperMinimumSetting(), 10.0, 0.1, 20.0, 3);
  ASSERT_EQ(run.size(), 101u);
  const auto [train, test] = acc::splitRunInHalf(run);
  EXPECT_EQ(train.size(), 50u);
  EXPECT_EQ(test.size(), 51u);
  EXPECT_DOUBLE_EQ(test.time_s.front(), run.time_s[50]);
  EXPECT_DOUBLE_EQ(test.space_gap_m.front(), run.space_gap_m[50]);  // simulated from its own start
  EXPECT_EQ(acc::describeRunProblem(train), "");
  EXPECT_EQ(acc::describeRunProblem(test), "");
}

TEST(CalibrationReport, JsonHasTheKeysOtherToolsRead)
{
  acc::CalibrationReport report;
  report.calibration.parameters = acc::paperMinimumSetting();
  report.calibration.status = "SUCCESS";
  report.uncertainty.standard_error = {0.001, 0.01, std::nan(""), 0.1};
  report.stability = acc::analyzeStringStability(report.calibration.parameters);
  report.runs.push_back({"part3", "/data/part3.csv", {100, 0.2, 1.5, false}, acc::FitQuality{100, 0.25, 1.4, false}});
  report.summary_train = {100, 0.2, 1.5, false};
  report.summary_test = acc::FitQuality{100, 0.25, 1.4, false};
  const auto json = acc::reportToJson(report);
  EXPECT_DOUBLE_EQ(json["parameters"]["k1_per_s2"].get<double>(), 0.0782);
  EXPECT_DOUBLE_EQ(json["parameters"]["k2_per_s"].get<double>(), 0.4445);
  EXPECT_DOUBLE_EQ(json["parameters"]["tau_e_s"].get<double>(), 0.5162);
  EXPECT_DOUBLE_EQ(json["parameters"]["eta_m"].get<double>(), 8.3365);
  EXPECT_TRUE(json["standard_errors"]["tau_e_s"].is_null());  // NaN is not JSON: null
  EXPECT_DOUBLE_EQ(json["standard_errors"]["eta_m"].get<double>(), 0.1);
  EXPECT_FALSE(json["stability"]["string_stable"].get<bool>());
  EXPECT_GT(json["stability"]["lambda2"].get<double>(), 0.0);
  for (const char* key : {"amplified_band_upper_rad_s", "peak_gain_db", "peak_frequency_rad_s"})
  {
    EXPECT_TRUE(json["stability"].contains(key)) << key;
  }
  for (const char* key : {"status", "starts", "evaluations", "solve_time_s"})
  {
    EXPECT_TRUE(json["objective"].contains(key)) << key;
  }
  ASSERT_EQ(json["runs"].size(), 1u);
  EXPECT_EQ(json["runs"][0]["name"], "part3");
  EXPECT_EQ(json["runs"][0]["path"], "/data/part3.csv");
  EXPECT_EQ(json["runs"][0]["train"]["samples"], 100);
  EXPECT_DOUBLE_EQ(json["runs"][0]["test"]["rmse_gap_m"].get<double>(), 1.4);
  EXPECT_DOUBLE_EQ(json["summary"]["test"]["rmse_speed_mps"].get<double>(), 0.25);
  std::ostringstream table;
  acc::printReport(report, table);
  EXPECT_NE(table.str().find("(point estimate string unstable)"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("part3"), std::string::npos);
}

TEST(CalibrationReport, TheTableNamesEveryRunWhole)
{
  acc::CalibrationReport report;
  report.calibration.parameters = acc::paperMinimumSetting();
  report.stability = acc::analyzeStringStability(report.calibration.parameters);
  const std::string long_names[] = {"dynamic_part12 TESLA_MODEL3#2", "dynamic_part12 TESLA_MODEL3#3"};
  for (const std::string& name : long_names)
  {
    acc::RunScore score;
    score.name = name;
    report.runs.push_back(score);
  }
  std::ostringstream table;
  acc::printReport(report, table);
  for (const std::string& name : long_names)
  {
    EXPECT_NE(table.str().find(name + " "), std::string::npos) << table.str();  // not cut at 28 characters
  }
}
}  // namespace

/// calibrate's JSON carries the string-stability test (issue: the verdict on real drives) and
/// what the data determine, under the documented keys, and the table names the verdict.
TEST(CalibrationReport, StabilityTestAndQuantitiesAreInTheJsonAndTheTable)
{
  const auto run = acc::synthesizeRun(acc::paperMinimumSetting(), 400.0, 0.1, 20.0, 7);
  acc::CalibrationReport report;
  report.calibration.parameters = acc::paperMinimumSetting();
  report.uncertainty = acc::estimateUncertainty(report.calibration.parameters, {run});
  report.stability = acc::analyzeStringStability(report.calibration.parameters);
  report.quantities = acc::assessQuantities(report.calibration.parameters, report.uncertainty, {run}, acc::ParameterBounds{});
  acc::StabilityTestOptions options;
  options.multistart.starts = 10;
  report.stability_test = acc::testStringStability({run}, options);

  const auto json = acc::reportToJson(report);
  ASSERT_TRUE(json.contains("stability_test"));
  const auto& test = json["stability_test"];
  for (const char* key : {"verdict", "p_value", "best_stable", "best_unstable", "margin_interval"})
  {
    EXPECT_TRUE(test.contains(key)) << key;
  }
  for (const char* key : {"parameters", "train_rmse_speed", "test_rmse_speed"})
  {
    EXPECT_TRUE(test["best_stable"].contains(key)) << key;
    EXPECT_TRUE(test["best_unstable"].contains(key)) << key;
  }
  EXPECT_EQ(test["verdict"], acc::toString(report.stability_test->verdict));
  EXPECT_EQ(test["p_value_hypothesis"], acc::pValueHypothesis(*report.stability_test));
  ASSERT_TRUE(json.contains("identifiable_quantities"));
  EXPECT_TRUE(json["identifiable_quantities"]["quantities"].contains("stability_margin"));

  std::ostringstream table;
  acc::printReport(report, table);
  EXPECT_NE(table.str().find("verdict: " + std::string(report.stability_test->verdict == acc::StabilityVerdict::Unstable
                                                            ? "string UNSTABLE"
                                                            : report.stability_test->verdict ==
                                                                      acc::StabilityVerdict::Stable
                                                                  ? "string STABLE"
                                                                  : "UNDECIDED")),
            std::string::npos)
      << table.str();
  // One verdict: the point estimate's lambda2 is labelled as such, the p-values by their hypothesis.
  EXPECT_NE(table.str().find("lambda2 of the point estimate = "), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("the verdict is the test's"), std::string::npos);
  EXPECT_NE(table.str().find("p (H0: stable) = "), std::string::npos);
  EXPECT_EQ(table.str().find("-> string UNSTABLE"), std::string::npos);
  EXPECT_NE(table.str().find("stability_margin"), std::string::npos);
}

// tau_e = 0 (a fit at its bound): lambda2 is +infinity, every low frequency grows. It was written
// null, which the JSON's readers take for "not determined", beside string_stable false.
TEST(CalibrationReport, AnInfiniteLambda2IsWrittenInfNotNull)
{
  acc::CalibrationReport report;
  report.calibration.parameters = {0.05, 0.3, 0.0, 5.0};
  report.stability = acc::analyzeStringStability(report.calibration.parameters);
  const auto json = acc::reportToJson(report);
  EXPECT_EQ(json["stability"]["lambda2"], "inf");
  EXPECT_EQ(json["stability"]["string_stable"], false);
  EXPECT_TRUE(json["stability"]["peak_gain_db"].is_number());
}

// lambda2 NaN (parameters not determined): string_stable is null, not a "false" that reads as
// unstable, and the text says "not determined".
TEST(CalibrationReport, StringStableIsNullWhereLambda2IsNaN)
{
  acc::CalibrationReport report;
  report.calibration.parameters = acc::paperMinimumSetting();
  report.stability.lambda2 = std::nan("");
  report.stability.string_stable = false;
  const auto json = acc::reportToJson(report);
  EXPECT_TRUE(json["stability"]["lambda2"].is_null());
  EXPECT_TRUE(json["stability"]["string_stable"].is_null());
  EXPECT_EQ(json["fitted"], true);
  std::ostringstream text;
  acc::printReport(report, text);
  EXPECT_NE(text.str().find("lambda2 of the point estimate: not determined"), std::string::npos) << text.str();
  EXPECT_FALSE(acc::knownStringStability(report.stability).has_value());
  report.stability = acc::analyzeStringStability(acc::paperMinimumSetting());
  EXPECT_EQ(acc::knownStringStability(report.stability), std::optional<bool>(false));
}

// The adequacy is written beside the verdict, in JSON and in words, with its pointer to diagnose.
TEST(CalibrationReport, ModelAdequacyIsWrittenBesideTheVerdict)
{
  const auto run = acc::synthesizeRun(acc::paperMinimumSetting(), 300.0, 0.1, 25.0, 3);
  acc::CalibrationReport report;
  acc::AccParameters wrong = acc::paperMinimumSetting();
  wrong.eta_m += 15.0;
  report.calibration.parameters = wrong;
  report.stability = acc::analyzeStringStability(wrong);
  report.model_adequacy = acc::assessModelAdequacy(wrong, {run});
  const auto json = acc::reportToJson(report);
  ASSERT_TRUE(json.contains("model_adequacy"));
  EXPECT_EQ(json["model_adequacy"]["adequate"], false);
  EXPECT_FALSE(json["model_adequacy"]["reasons"].empty());
  EXPECT_TRUE(json["model_adequacy"]["checks"]["gap_rmse_m"].is_number());
  std::ostringstream text;
  acc::printReport(report, text);
  EXPECT_NE(text.str().find("Model adequacy: NOT ADEQUATE (gap RMSE"), std::string::npos) << text.str();
  report.model_adequacy_data = "the runs it was fitted on";
  std::ostringstream named;
  acc::printReport(report, named);
  EXPECT_NE(named.str().find("Model adequacy (on the runs it was fitted on): NOT ADEQUATE"), std::string::npos);
  EXPECT_EQ(acc::reportToJson(report)["model_adequacy"]["data"], "the runs it was fitted on");
  EXPECT_NE(text.str().find("run `diagnose`"), std::string::npos);
}

// Valid data that cannot be fitted still get their JSON: fitted false, the reason, and what the
// data decide (steady following: the equilibrium gap at the observed speed).
TEST(CalibrationReport, UnfittableDataGetJsonWithTheReason)
{
  acc::CarFollowingRun steady;
  steady.name = "steady";
  for (int k = 0; k < 600; ++k)
  {
    steady.time_s.push_back(0.1 * k);
    steady.follower_speed_mps.push_back(25.0 + 0.05 * std::sin(0.3 * k));
    steady.leader_speed_mps.push_back(25.0);
    steady.space_gap_m.push_back(40.0 + 0.3 * std::cos(0.2 * k));
  }
  const acc::UnfittedDataSummary summary =
      acc::summarizeUnfittedData({steady}, "the follower speed spread is 0.04 m/s", 0.5);
  const auto json = acc::unfittedToJson(summary);
  EXPECT_EQ(json["fitted"], false);
  EXPECT_EQ(json["reason"], "the follower speed spread is 0.04 m/s");
  EXPECT_EQ(json["data"]["samples"], 600);
  EXPECT_NEAR(json["data"]["duration_s"].get<double>(), 59.9, 1e-9);
  EXPECT_NEAR(json["data"]["equilibrium_gap_m"].get<double>(), 40.0, 0.05);
  EXPECT_NEAR(json["data"]["follower_speed_mean_mps"].get<double>(), 25.0, 0.01);
  EXPECT_TRUE(json["parameters"].is_null());
  EXPECT_TRUE(json["stability"].is_null());
  // Not steady: no equilibrium gap, and the note says why.
  const auto moving = acc::unfittedToJson(acc::summarizeUnfittedData({steady}, "too short", 0.01));
  EXPECT_TRUE(moving["data"]["equilibrium_gap_m"].is_null());
  EXPECT_NE(moving["data"]["equilibrium_gap_note"].get<std::string>().find("not steady"), std::string::npos);
  std::ostringstream text;
  acc::printUnfitted(summary, text);
  EXPECT_NE(text.str().find("No fit: the follower speed spread"), std::string::npos) << text.str();
  // What the data decide without a model: their dips' evidence (none here: no perturbation).
  ASSERT_TRUE(json.contains("dip_evidence"));
  EXPECT_NE(text.str().find("Dips of the leader's perturbations"), std::string::npos) << text.str();
  EXPECT_EQ(text.str().find("string unstable for these inputs"), std::string::npos) << text.str();
  // Dips amplified beyond their interval are said in words, as what the data show for those inputs.
  acc::UnfittedDataSummary amplified = summary;
  amplified.dip_evidence->ratio.amplifies = acc::DipAmplification::Amplifies;
  std::ostringstream amplified_text;
  acc::printUnfitted(amplified, amplified_text);
  EXPECT_NE(amplified_text.str().find("string unstable for these inputs"), std::string::npos) << amplified_text.str();
  // A shape measure no perturbation gave is said in words, not printed as nan.
  acc::UnfittedDataSummary braking_only = summary;
  braking_only.dip_evidence->shape.braking = {2, 2, 1.3, 0.0, std::numeric_limits<double>::infinity(), 0.95, 999};
  std::ostringstream braking_text;
  acc::printUnfitted(braking_only, braking_text);
  EXPECT_NE(braking_text.str().find("passes on 1.30 [0.00, inf] of its leader's peak braking and none (no rate "
                                    "scored) of its peak recovery"),
            std::string::npos)
      << braking_text.str();
  EXPECT_NE(braking_text.str().find("no dip's width at half depth is known"), std::string::npos) << braking_text.str();
  EXPECT_EQ(braking_text.str().find("nan"), std::string::npos) << braking_text.str();
}

// Data a batch fit refuses still get the verdicts the identifier node would publish on them
// (--verdict-every): the node runs on them, so calibrate must say what it would show.
TEST(CalibrationReport, UnfittedDataStillGetTheNodesVerdictSequence)
{
  acc::CarFollowingRun steady;
  steady.name = "steady";
  for (int k = 0; k < 1200; ++k)
  {
    steady.time_s.push_back(0.1 * k);
    steady.follower_speed_mps.push_back(20.0 + 0.3 * std::sin(0.05 * k));
    steady.leader_speed_mps.push_back(20.0 + 0.3 * std::sin(0.05 * k + 0.3));
    steady.space_gap_m.push_back(30.0 + 0.5 * std::cos(0.05 * k));
  }
  acc::CalibrateSettings settings;
  settings.quiet = true;
  settings.starts = 5;
  settings.verdict_every_s = 10.0;
  std::ostringstream text, log;
  const acc::CalibrateOutcome outcome = acc::calibrateRuns({{steady, "steady.csv"}}, {}, settings, text, log);
  EXPECT_EQ(outcome.exit_status, acc::kExitValidDataNoFit) << text.str();
  EXPECT_EQ(outcome.json["fitted"], false);
  ASSERT_TRUE(outcome.json.contains("sequential_verdicts")) << outcome.json.dump(1);
  // A look every 10 s of the 119.9 s (11), and one where the data end.
  EXPECT_EQ(outcome.json["sequential_verdicts"][0]["verdict_sequence"].size(), 12u);
  EXPECT_NE(text.str().find("Sequential verdict"), std::string::npos) << text.str();
  // Without --verdict-every, none.
  settings.verdict_every_s = 0.0;
  EXPECT_FALSE(acc::calibrateRuns({{steady, "steady.csv"}}, {}, settings, text, log).json.contains(
      "sequential_verdicts"));
}

namespace
{
/// calibrateRuns' second opinion (calibrate_runs.h): asked exactly when the model does not
/// describe the data, and what it says is in the JSON and the text.
struct CountingOpinion
{
  int calls = 0;
  acc::SecondOpinionOf hook()
  {
    return [this](const std::vector<acc::CarFollowingRun>& runs) {
      ++calls;
      return acc::SecondOpinion{{{"runs", runs.size()}}, "SECOND OPINION\n"};
    };
  }
};

acc::CalibrateOutcome calibrateWith(const std::vector<acc::CarFollowingRun>& runs, CountingOpinion& opinion,
                                    std::ostringstream& text)
{
  std::vector<acc::CalibrationInput> inputs;
  for (const acc::CarFollowingRun& run : runs)
    inputs.push_back({run, run.name});
  acc::CalibrateSettings settings;
  settings.split_half = true;
  settings.starts = 20;
  settings.quiet = true;
  settings.second_opinion = opinion.hook();
  std::ostringstream log;
  return acc::calibrateRuns(inputs, {}, settings, text, log);
}

/// The outcome's JSON without its clocks (solve and wall times differ from run to run).
nlohmann::json withoutClocks(nlohmann::json json)
{
  if (json.is_object())
  {
    json.erase("solve_time_s");
    json.erase("wall_time_s");
  }
  if (json.is_structured())
    for (auto& item : json)
      item = withoutClocks(item);
  return json;
}

// One set of runs gives one answer: named in another order, the runs are fitted and resampled in
// the natural order of their names, so the p-values and intervals do not move (the bootstrap drew
// its blocks over the runs in the order given: part6..part3 gave p 0.066 where part3..part6 gave
// 0.063).
TEST(CalibrateRuns, TheOrderTheRunsAreGivenInChangesNothing)
{
  std::vector<acc::CarFollowingRun> runs;
  for (std::uint32_t seed : {12u, 3u, 5u})
  {
    runs.push_back(acc::synthesizeRun(acc::paperMinimumSetting(), 150.0, 0.1, 20.0, seed));
    runs.back().name = "drive" + std::to_string(seed);
  }
  CountingOpinion opinion;
  std::ostringstream text_given, text_reversed;
  const acc::CalibrateOutcome given = calibrateWith(runs, opinion, text_given);
  const acc::CalibrateOutcome reversed = calibrateWith({runs.rbegin(), runs.rend()}, opinion, text_reversed);
  ASSERT_TRUE(given.json["stability_test"]["tested"].get<bool>());
  EXPECT_EQ(withoutClocks(given.json), withoutClocks(reversed.json));
  EXPECT_EQ(given.json["runs"][0]["name"], "drive3");  // natural order: 3, 5, 12
  EXPECT_EQ(given.json["runs"][2]["name"], "drive12");
}

TEST(CalibrateRuns, AModelThatDescribesTheDataGetsNoSecondOpinion)
{
  CountingOpinion opinion;
  std::ostringstream text;
  const acc::CalibrateOutcome outcome =
      calibrateWith({acc::synthesizeRun(acc::paperMinimumSetting(), 600.0, 0.1, 20.0, 5)}, opinion, text);
  ASSERT_EQ(outcome.exit_status, 0);
  ASSERT_TRUE(outcome.json["model_adequacy"]["adequate"].get<bool>()) << outcome.json["model_adequacy"].dump();
  EXPECT_EQ(opinion.calls, 0);
  EXPECT_FALSE(outcome.json.contains("diagnosed_verdict"));
}

TEST(CalibrateRuns, AModelThatMissesGetsTheSecondOpinionInJsonAndText)
{
  CountingOpinion opinion;
  std::ostringstream text;
  // Casale part 4 (JRC OpenACC, CC BY 4.0): 115 s at 33-41 m/s, which the model misses by 25 m of gap.
  const acc::CalibrateOutcome outcome =
      calibrateWith(acc::readRuns(std::string(ACC_TEST_DATA_DIR) + "/casale_part4.csv"), opinion, text);
  ASSERT_EQ(outcome.exit_status, 0);
  ASSERT_FALSE(outcome.json["model_adequacy"]["adequate"].get<bool>());
  EXPECT_EQ(opinion.calls, 1);
  EXPECT_EQ(outcome.json["diagnosed_verdict"]["runs"], 1);  // the whole runs, not the halves
  EXPECT_NE(text.str().find("SECOND OPINION"), std::string::npos);
}

// --split half with a piece of three rows between two split points (empty cells four rows apart):
// the piece is left out, said in the JSON, and the rest is fitted and scored, each score under its
// own run's name. Fails when the piece refuses the whole input, as it once did, or when the names
// of the runs scored slip against them.
TEST(CalibrateRuns, APieceTooShortToHalveIsLeftOutAndSaidNotAReasonToRefuseTheRest)
{
  CountingOpinion opinion;
  std::ostringstream text;
  acc::CarFollowingRun whole = acc::synthesizeRun(acc::paperMinimumSetting(), 300.0, 0.1, 20.0, 5);
  whole.name = "drive";
  const acc::CarFollowingRun first = whole.slice(0, 1000, "#1");
  const acc::CarFollowingRun piece = whole.slice(1002, 1005, "#2");
  const acc::CarFollowingRun last = whole.slice(1007, whole.size(), "#3");
  const acc::CalibrateOutcome outcome = calibrateWith({first, piece, last}, opinion, text);
  ASSERT_EQ(outcome.exit_status, 0) << outcome.json.dump();
  ASSERT_EQ(outcome.json["runs_left_out"].size(), 1u);
  EXPECT_EQ(outcome.json["runs_left_out"][0], "run '" + piece.name + "' has 3 samples, too few to split in halves");
  EXPECT_EQ(outcome.run_names, (std::vector<std::string>{first.name, last.name}));
  ASSERT_EQ(outcome.training.size(), 2u);
  EXPECT_EQ(outcome.training[1].time_s.front(), last.time_s.front());
  EXPECT_NE(text.str().find(last.name), std::string::npos);
  EXPECT_EQ(text.str().find(piece.name + " "), std::string::npos) << text.str();
}
}  // namespace
