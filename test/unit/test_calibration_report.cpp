#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/calibration/synthetic_runs.h"
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
  EXPECT_NE(table.str().find("string UNSTABLE"), std::string::npos) << table.str();
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
  report.quantities = acc::assessQuantities(report.calibration.parameters, report.uncertainty, {run});
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
  ASSERT_TRUE(json.contains("identifiable_quantities"));
  EXPECT_TRUE(json["identifiable_quantities"]["quantities"].contains("stability_margin"));

  std::ostringstream table;
  acc::printReport(report, table);
  EXPECT_NE(table.str().find("verdict: " + std::string(report.stability_test->verdict == acc::StabilityVerdict::Unstable
                                                            ? "UNSTABLE"
                                                            : report.stability_test->verdict ==
                                                                      acc::StabilityVerdict::Stable
                                                                  ? "STABLE"
                                                                  : "UNDECIDED")),
            std::string::npos)
      << table.str();
  EXPECT_NE(table.str().find("stability_margin"), std::string::npos);
}
