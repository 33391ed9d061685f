#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "acc_identification/evidence/clustered_ratio.h"

// The ratio is of sums (a cluster of many cars weighs by its sums, not as one ratio), and the
// interval resamples whole clusters: with two clusters a replicate is AA, AB or BB, so the 95 %
// interval runs from one cluster's ratio to the other's, however many cars each holds.
TEST(ClusteredRatio, IsARatioOfSumsWhoseIntervalResamplesWholeClusters)
{
  const std::vector<acc::RatioCluster> clusters{{9.0, 10.0, 9}, {1.0, 2.0, 9}};
  const acc::ClusteredRatio r = acc::clusteredRatioOfSums(clusters, 1999, 7);
  EXPECT_DOUBLE_EQ(r.ratio, 10.0 / 12.0);
  EXPECT_EQ(r.clusters, 2u);
  EXPECT_EQ(r.observations, 18u);
  EXPECT_DOUBLE_EQ(r.lower, 0.5);
  EXPECT_DOUBLE_EQ(r.upper, 0.9);
  const acc::ClusteredRatio again = acc::clusteredRatioOfSums(clusters, 1999, 7);
  EXPECT_EQ(again.lower, r.lower);
  EXPECT_EQ(again.upper, r.upper);
}

TEST(ClusteredRatio, SaysNothingOfItsSpreadFromOneClusterAndRefusesANonPositiveDenominator)
{
  const acc::ClusteredRatio one = acc::clusteredRatioOfSums({{3.0, 2.0, 4}}, 999, 1);
  EXPECT_DOUBLE_EQ(one.ratio, 1.5);
  EXPECT_TRUE(std::isnan(one.lower));
  EXPECT_TRUE(std::isnan(one.upper));
  EXPECT_TRUE(std::isnan(acc::clusteredRatioOfSums({}, 999, 1).ratio));
  EXPECT_THROW(acc::clusteredRatioOfSums({{1.0, 0.0, 1}, {1.0, 1.0, 1}}, 999, 1), std::invalid_argument);
  EXPECT_THROW(acc::clusteredRatioOfSums({{1.0, 1.0, 1}}, 999, 1, 1.0), std::invalid_argument);
}
