#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "acc_identification/evidence/clustered_median.h"

// The median pools every value; the interval weighs whole clusters (wildClusterMedianInterval).
// One cluster of nine 0.1 and two of one 0.5 each: three clusters cannot reject a median of 0.5,
// so the interval reaches it. Taken as eleven independent values it would stop at 0.1
// (test_wild_cluster_interval).
TEST(ClusteredMedian, PoolsTheValuesAndWeighsWholeClusters)
{
  const std::vector<std::vector<double>> clusters{std::vector<double>(9, 0.1), {0.5, NAN}, {0.5}};
  const acc::ClusteredMedian m = acc::clusteredMedian(clusters, 1999, 7);
  EXPECT_EQ(m.clusters, 3u);
  EXPECT_EQ(m.observations, 11u);
  EXPECT_DOUBLE_EQ(m.median, 0.1);
  EXPECT_DOUBLE_EQ(m.lower, 0.1);
  EXPECT_DOUBLE_EQ(m.upper, 0.5);
  const acc::ClusteredMedian again = acc::clusteredMedian(clusters, 1999, 7);
  EXPECT_EQ(again.lower, m.lower);
  EXPECT_EQ(again.upper, m.upper);
}

TEST(ClusteredMedian, SaysNothingOfItsSpreadFromOneClusterAndRefusesABadConfidence)
{
  const acc::ClusteredMedian one = acc::clusteredMedian({{1.0, 2.0, 3.0}}, 999, 1);
  EXPECT_DOUBLE_EQ(one.median, 2.0);
  EXPECT_TRUE(std::isnan(one.lower) && std::isnan(one.upper));
  EXPECT_TRUE(std::isnan(acc::clusteredMedian({}, 999, 1).median));
  EXPECT_THROW(acc::clusteredMedian({{1.0}, {2.0}}, 999, 1, 0.0), std::invalid_argument);
}
