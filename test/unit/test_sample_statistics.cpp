#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "acc_identification/model/sample_statistics.h"

TEST(SampleStatistics, NormalQuantilesMatchTheTablesTwoAndOneSided)
{
  // Abramowitz & Stegun 26.2: P(|Z| > 1.959964) = 0.05, P(Z > 1.644854) = 0.05, P(|Z| > 2.575829) = 0.01.
  EXPECT_NEAR(acc::twoSidedNormalQuantile(0.05), 1.959964, 1e-6);
  EXPECT_NEAR(acc::twoSidedNormalQuantile(0.10), 1.644854, 1e-6);
  EXPECT_NEAR(acc::twoSidedNormalQuantile(0.01), 2.575829, 1e-6);
  // Its own inverse: the tail beyond the quantile is the tail asked for.
  for (double tail : {1e-6, 0.0125, 0.3, 0.9})
    EXPECT_NEAR(std::erfc(acc::twoSidedNormalQuantile(tail) / std::sqrt(2.0)), tail, 1e-9 * tail) << tail;
  for (double bad : {0.0, 1.0, -0.1, std::nan("")})
    EXPECT_TRUE(std::isnan(acc::twoSidedNormalQuantile(bad))) << bad;
}

TEST(SampleStatistics, StudentTQuantilesMatchTheTables)
{
  // Student's t table, one-sided 0.05: 6.314 at 1, 2.015 at 5, 1.895 at 7, 1.812 at 10, 1.697 at 30.
  EXPECT_NEAR(acc::studentTUpperQuantile(0.05, 1.0), 6.313752, 1e-5);
  EXPECT_NEAR(acc::studentTUpperQuantile(0.05, 5.0), 2.015048, 1e-5);
  EXPECT_NEAR(acc::studentTUpperQuantile(0.05, 7.0), 1.894579, 1e-5);
  EXPECT_NEAR(acc::studentTUpperQuantile(0.05, 10.0), 1.812461, 1e-5);
  EXPECT_NEAR(acc::studentTUpperQuantile(0.025, 30.0), 2.042272, 1e-5);
  // Towards the normal's as the degrees grow.
  EXPECT_NEAR(acc::studentTUpperQuantile(0.05, 1e7), acc::twoSidedNormalQuantile(0.10), 1e-5);
  for (double bad : {0.0, -1.0, std::nan("")})
    EXPECT_TRUE(std::isnan(acc::studentTUpperQuantile(0.05, bad))) << bad;
  EXPECT_TRUE(std::isnan(acc::studentTUpperQuantile(1.0, 5.0)));
}

TEST(SampleStatistics, InterpolatedQuantileInterpolatesBetweenOrderStatistics)
{
  const std::vector<double> values{4.0, 1.0, 3.0, 2.0};
  EXPECT_DOUBLE_EQ(acc::interpolatedQuantile(values, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(acc::interpolatedQuantile(values, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(acc::interpolatedQuantile(values, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(acc::interpolatedQuantile(values, 2.0), 4.0);  // clamped
  EXPECT_DOUBLE_EQ(acc::interpolatedQuantile({}, 0.5), 0.0);
}
