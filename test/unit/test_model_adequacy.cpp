// Model adequacy (calibration/model_adequacy.h): a model fitted to data it made passes every
// check; a model that misses the gap, sits at a bound, or leaves slow structure in its residuals
// fails with reasons that carry the numbers. The set-speed case is in test_diagnosis_adequacy.cpp
// (its synthesiser belongs to the diagnosis).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/normal_source.h"
#include "acc_identification/model/paper_settings.h"

namespace
{
bool anyReasonMentions(const acc::ModelAdequacy& adequacy, const std::string& word)
{
  for (const std::string& reason : adequacy.reasons)
  {
    if (reason.find(word) != std::string::npos)
      return true;
  }
  return false;
}

acc::AccParameters fitted(const std::vector<acc::CarFollowingRun>& runs)
{
  acc::IdentificationOptions options;
  options.multistart.starts = 20;
  const acc::Identification id = acc::identifyAcc(runs, options);
  EXPECT_TRUE(id.solved && !id.calibration.diverged) << id.note;
  return id.calibration.parameters;
}
}  // namespace

// The truth's own data, fitted as calibrate fits them: adequate, for both of the paper's
// settings and several seeds.
TEST(ModelAdequacy, ModelFittedToItsOwnDataIsAdequate)
{
  for (const acc::AccParameters& truth : {acc::paperMinimumSetting(), acc::paperMaximumSetting()})
  {
    for (std::uint32_t seed : {1u, 2u, 3u})
    {
      const std::vector<acc::CarFollowingRun> runs{acc::synthesizeRun(truth, 600.0, 0.1, 25.0, seed)};
      const acc::ModelAdequacy adequacy = acc::assessModelAdequacy(fitted(runs), runs);
      const acc::AdequacyChecks& c = adequacy.checks;
      std::cout << "synthetic truth tau_e " << truth.tau_e_s << " seed " << seed << ": gap RMSE " << c.gap_rmse_m
                << " m (spread " << c.gap_spread_m << "), speed RMSE " << c.speed_rmse_mps << " m/s (spread "
                << c.speed_spread_mps << "), residual correlation " << c.residual_correlation_time_s
                << " s, response " << c.model_response_time_s << " s\n";
      EXPECT_TRUE(adequacy.assessed);
      EXPECT_TRUE(adequacy.adequate) << acc::describeAdequacy(adequacy);
      EXPECT_EQ(acc::describeAdequacy(adequacy), "ADEQUATE");
    }
  }
}

// The same data judged by a model whose standstill gap is 15 m off: the gap is missed, and the
// reason carries the RMSE and the spread.
TEST(ModelAdequacy, ModelThatMissesTheGapIsNotAdequate)
{
  const acc::AccParameters truth = acc::paperMinimumSetting();
  const std::vector<acc::CarFollowingRun> runs{acc::synthesizeRun(truth, 600.0, 0.1, 25.0, 4)};
  acc::AccParameters wrong = truth;
  wrong.eta_m += 15.0;
  const acc::ModelAdequacy adequacy = acc::assessModelAdequacy(wrong, runs);
  EXPECT_TRUE(adequacy.assessed);
  EXPECT_FALSE(adequacy.adequate);
  EXPECT_TRUE(anyReasonMentions(adequacy, "gap RMSE")) << acc::describeAdequacy(adequacy);
  EXPECT_GT(adequacy.checks.gap_rmse_m, 10.0);
}

TEST(ModelAdequacy, ParameterAtABoundIsNamed)
{
  const std::vector<acc::CarFollowingRun> runs{acc::synthesizeRun(acc::paperMinimumSetting(), 300.0, 0.1, 25.0, 5)};
  acc::AccParameters at_bound = fitted(runs);
  at_bound.eta_m = acc::ParameterBounds{}.upper.eta_m;
  const acc::ModelAdequacy adequacy = acc::assessModelAdequacy(at_bound, runs);
  EXPECT_FALSE(adequacy.adequate);
  ASSERT_EQ(adequacy.checks.parameters_at_bound.size(), 1u);
  EXPECT_NE(adequacy.checks.parameters_at_bound[0].find("eta_m"), std::string::npos);
  EXPECT_TRUE(anyReasonMentions(adequacy, "upper bound 50"));
  // A parameter the data do not pin (standard error a fifth of its range) is listed, not held
  // against the model; one they pin is.
  const acc::ModelAdequacy loose = acc::assessModelAdequacy(at_bound, runs, {}, acc::AccParameters{0.01, 0.01, 0.01, 10.0});
  EXPECT_EQ(loose.checks.parameters_at_bound.size(), 1u);
  EXPECT_FALSE(anyReasonMentions(loose, "eta_m")) << acc::describeAdequacy(loose);
  const acc::ModelAdequacy pinned = acc::assessModelAdequacy(at_bound, runs, {}, acc::AccParameters{0.01, 0.01, 0.01, 0.5});
  EXPECT_TRUE(anyReasonMentions(pinned, "eta_m = 50 at its upper bound 50 +- 0.5"));
  EXPECT_FALSE(pinned.adequate);
}

// Within a thousandth of the range of an end is held by it; a step further in is not.
TEST(ModelAdequacy, ABoundHoldsAValueWithinItsFractionOfTheRange)
{
  EXPECT_EQ(acc::boundSide(0.0099, 0.0, 10.0, 0.001), acc::BoundSide::lower);
  EXPECT_EQ(acc::boundSide(0.0101, 0.0, 10.0, 0.001), acc::BoundSide::inside);
  EXPECT_EQ(acc::boundSide(9.9901, 0.0, 10.0, 0.001), acc::BoundSide::upper);
  EXPECT_EQ(acc::boundSide(-1.0, 0.0, 10.0, 0.001), acc::BoundSide::lower);  // beyond it too
  EXPECT_EQ(acc::atBoundText("lag_s", 9.995, 0.0, 10.0, 0.001), "lag_s = 9.995 at its upper bound 10");
  EXPECT_EQ(acc::atBoundText("lag_s", 5.0, 0.0, 10.0, 0.001), "");
}

// Complex roots decay at (k2 + k1 tau_e) / 2; real ones at the slower root; k1 = 0 at k2.
TEST(ModelAdequacy, ResponseTimeIsTheSlowestDecay)
{
  EXPECT_NEAR(acc::modelResponseTimeS({0.08, 0.45, 1.2, 4.0}), 1.0 / ((0.45 + 0.08 * 1.2) / 2.0), 1e-12);
  const double damping = 1.0 + 0.1 * 2.0, slow = (damping - std::sqrt(damping * damping - 0.4)) / 2.0;
  EXPECT_NEAR(acc::modelResponseTimeS({0.1, 1.0, 2.0, 4.0}), 1.0 / slow, 1e-12);
  EXPECT_NEAR(acc::modelResponseTimeS({0.0, 0.5, 1.0, 4.0}), 2.0, 1e-12);
  EXPECT_TRUE(std::isinf(acc::modelResponseTimeS({0.0, 0.0, 1.0, 4.0})));
}

// An AR(1) series with correlation time T (rho = exp(-h / T)) reads as T, within the 10 % lag
// steps and the sampling error of 60 000 samples; white noise reads as one step or less.
TEST(ModelAdequacy, CorrelationTimeOfAnAutoregressiveSeries)
{
  for (double correlation_s : {2.0, 20.0})
  {
    acc::NormalSource normal(7);
    const double h = 0.1, rho = std::exp(-h / correlation_s);
    std::vector<double> time(60000), value(60000);
    double x = 0.0;
    for (std::size_t k = 0; k < time.size(); ++k)
    {
      x = rho * x + std::sqrt(1.0 - rho * rho) * normal.standardNormal();
      time[k] = h * static_cast<double>(k);
      value[k] = x;
    }
    EXPECT_NEAR(acc::residualCorrelationTimeS({time}, {value}), correlation_s, 0.2 * correlation_s);
    for (double& v : value)
      v = normal.standardNormal();
    EXPECT_LE(acc::residualCorrelationTimeS({time}, {value}), h);
  }
}

TEST(ModelAdequacy, DipCheckDecidesOnlyWithEnoughPerturbations)
{
  const std::vector<acc::CarFollowingRun> runs{acc::synthesizeRun(acc::paperMinimumSetting(), 300.0, 0.1, 25.0, 6)};
  const acc::AccParameters p = fitted(runs);
  acc::ModelAdequacy few = acc::assessModelAdequacy(p, runs);
  ASSERT_TRUE(few.adequate) << acc::describeAdequacy(few);
  acc::addDipCheck(few, 2, 0.8);
  EXPECT_TRUE(few.adequate);
  acc::ModelAdequacy many = acc::assessModelAdequacy(p, runs);
  acc::addDipCheck(many, 12, 0.8);
  EXPECT_FALSE(many.adequate);
  EXPECT_TRUE(anyReasonMentions(many, "80.0 %"));
  acc::ModelAdequacy close = acc::assessModelAdequacy(p, runs);
  acc::addDipCheck(close, 12, 0.1);
  EXPECT_TRUE(close.adequate);
}

// The node judges the drive so far every period: a 3-hour drive (108 000 samples) must cost
// milliseconds, not the period. A generous bound (the scan is geometric in the lag), not a benchmark.
TEST(ModelAdequacy, AThreeHourDriveIsJudgedWellWithinAPeriod)
{
  const std::vector<acc::CarFollowingRun> drive{acc::synthesizeRun(acc::paperMinimumSetting(), 10800.0, 0.1, 25.0, 8)};
  const auto started = std::chrono::steady_clock::now();
  const acc::ModelAdequacy adequacy = acc::assessModelAdequacy(acc::paperMinimumSetting(), drive);
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::cout << "3-hour drive judged in " << 1000.0 * elapsed_s << " ms\n";
  EXPECT_TRUE(adequacy.adequate) << acc::describeAdequacy(adequacy);
  EXPECT_LT(elapsed_s, 0.5);
}

// Nothing to judge: "not assessed", adequate null in JSON (neither a pass nor a fail).
TEST(ModelAdequacy, NoDataIsNotAssessed)
{
  const acc::ModelAdequacy none = acc::assessModelAdequacy(acc::paperMinimumSetting(), {});
  EXPECT_FALSE(none.assessed);
  const nlohmann::json json = acc::toJson(none);
  EXPECT_TRUE(json["adequate"].is_null());
  EXPECT_FALSE(json["reasons"].empty());
  EXPECT_EQ(acc::describeAdequacy(none).rfind("not assessed", 0), 0u);
}
