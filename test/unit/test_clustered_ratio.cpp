#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "acc_identification/evidence/clustered_ratio.h"

// The ratio is of sums (a cluster of many cars weighs by its sums, not as one ratio), and the
// interval weighs whole clusters: two clusters of nine cars each bound nothing at 95 %, however
// many cars each holds, where the same eighteen cars taken as eighteen clusters would.
TEST(ClusteredRatio, IsARatioOfSumsWhoseIntervalWeighsWholeClusters)
{
  std::vector<acc::RatioCluster> cars;
  for (std::size_t i = 0; i < 9; ++i)
  {
    cars.push_back({1.0 + 0.01 * static_cast<double>(i), 1.1, 1});
    cars.push_back({0.1 + 0.01 * static_cast<double>(i), 0.2, 1});
  }
  acc::RatioCluster first{0.0, 0.0, 9}, second{0.0, 0.0, 9};
  for (std::size_t i = 0; i < cars.size(); ++i)
  {
    acc::RatioCluster& into = i % 2 == 0 ? first : second;
    into.numerator += cars[i].numerator;
    into.denominator += cars[i].denominator;
  }
  const acc::ClusteredRatio r = acc::clusteredRatioOfSums({first, second}, 1999, 7);
  EXPECT_DOUBLE_EQ(r.ratio, (first.numerator + second.numerator) / 11.7);
  EXPECT_EQ(r.clusters, 2u);
  EXPECT_EQ(r.observations, 18u);
  EXPECT_EQ(r.lower, 0.0);
  EXPECT_TRUE(std::isinf(r.upper));
  const acc::ClusteredRatio each = acc::clusteredRatioOfSums(cars, 1999, 7);
  EXPECT_DOUBLE_EQ(each.ratio, r.ratio);
  EXPECT_GT(each.lower, 0.0);
  EXPECT_LT(each.upper, 2.0);
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

// The reports' one text of a ratio: its interval where it has one, an unbounded end as inf.
TEST(ClusteredRatio, IsWrittenWithItsIntervalWhereItHasOne)
{
  acc::ClusteredRatio r;
  EXPECT_EQ(acc::ratioWithIntervalText(r), "NaN");
  r.ratio = 0.8812;
  EXPECT_EQ(acc::ratioWithIntervalText(r), "0.88");
  r.lower = 0.0;
  r.upper = std::numeric_limits<double>::infinity();
  EXPECT_EQ(acc::ratioWithIntervalText(r), "0.88 [0.00, inf]");
  r.lower = 0.7801;
  r.upper = 0.9799;
  EXPECT_EQ(acc::ratioWithIntervalText(r), "0.88 [0.78, 0.98]");
}
