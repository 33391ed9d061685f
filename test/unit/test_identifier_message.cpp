#include <gtest/gtest.h>

#include <cmath>

#include "acc_identification/calibration/synthetic_runs.h"
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
  EXPECT_DOUBLE_EQ(m.lambda2, result.stability.lambda2);
  EXPECT_EQ(m.string_stable, result.stability.string_stable);
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
  EXPECT_TRUE(std::isnan(m.lambda2));
  EXPECT_FALSE(m.string_stable);
}
}  // namespace
