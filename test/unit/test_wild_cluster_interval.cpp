// Intervals from the inverted wild cluster bootstrap-t (wild_cluster_interval.h): with five
// clusters they cover a known median and a known share about as often as they say, where the
// percentile bootstrap that resamples the clusters whole (the scores' intervals until 2026-11-29)
// covers far less often; and their ends behave.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "acc_identification/evidence/cluster_bootstrap.h"
#include "acc_identification/evidence/clustered_ratio.h"
#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/evidence/wild_cluster_interval.h"

namespace acc
{
namespace
{
/// Five clusters of 1-9 values that share a cluster effect (like every car of one perturbation):
/// log-normal around a population median of kMedian.
constexpr double kMedian = 0.2;
/// Five clusters of 1-5 trials whose success probability varies from cluster to cluster (logit
/// 0.85 + a standard normal effect): the population share is E[p] = 0.6689.
constexpr double kShare = 0.6689;

struct Draw
{
  std::vector<std::vector<double>> values;
  std::vector<RatioCluster> trials;
};

Draw drawClusters(std::mt19937_64& engine, std::size_t d)
{
  std::normal_distribution<double> normal(0.0, 1.0);
  Draw out;
  for (std::size_t g = 0; g < 5; ++g)
  {
    const double shared = normal(engine);
    out.values.emplace_back();
    for (std::size_t i = 0; i < 1 + (5 * g + d) % 9; ++i)
      out.values.back().push_back(kMedian * std::exp(std::sqrt(0.5) * shared + std::sqrt(0.5) * normal(engine)));
    const double p = 1.0 / (1.0 + std::exp(-(std::log(0.7 / 0.3) + normal(engine))));
    std::bernoulli_distribution success(p);
    const std::size_t n = 1 + (3 * g + d) % 5;
    double successes = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      successes += success(engine) ? 1.0 : 0.0;
    out.trials.push_back({successes, static_cast<double>(n), n});
  }
  return out;
}

bool covers(const std::pair<double, double>& interval, double truth)
{
  return interval.first <= truth && truth <= interval.second;
}
}  // namespace

TEST(WildClusterInterval, CoversAMedianAndAShareAsOftenAsItSaysWithFiveClusters)
{
  std::mt19937_64 engine(7);
  const std::size_t datasets = 200;
  std::size_t median_wild = 0, median_percentile = 0, share_wild = 0, share_percentile = 0;
  for (std::size_t d = 0; d < datasets; ++d)
  {
    const Draw draw = drawClusters(engine, d);
    median_wild += covers(wildClusterMedianInterval(draw.values, 0.95, 1999, d), kMedian);
    std::vector<double> pooled;
    median_percentile += covers(clusterBootstrapInterval(5, 1999, d, 0.95,
                                                         [&](const std::vector<std::size_t>& picks) {
                                                           pooled.clear();
                                                           for (std::size_t k : picks)
                                                             pooled.insert(pooled.end(), draw.values[k].begin(),
                                                                           draw.values[k].end());
                                                           return finiteMedian(pooled);
                                                         }),
                                kMedian);
    share_wild += covers(wildClusterShareInterval(draw.trials, 0.95, 1999, d), kShare);
    const ClusteredRatio percentile = clusteredRatioOfSums(draw.trials, 1999, d);
    share_percentile += covers({percentile.lower, percentile.upper}, kShare);
  }
  const auto rate = [&](std::size_t n) { return static_cast<double>(n) / static_cast<double>(datasets); };
  std::printf("coverage of 95 %% intervals over five clusters: median %.3f (percentile %.3f), share %.3f (%.3f)\n",
              rate(median_wild), rate(median_percentile), rate(share_wild), rate(share_percentile));
  EXPECT_GT(rate(median_wild), 0.90);
  EXPECT_GT(rate(share_wild), 0.86);
  EXPECT_LT(rate(median_percentile), rate(median_wild) - 0.04);
  EXPECT_LT(rate(share_percentile), rate(share_wild) - 0.04);
}

// The median's interval weighs whole clusters: one cluster of nine 0.1 and two of one 0.5 each
// reach 0.5, where the eleven values taken as independent clusters stop at 0.1.
TEST(WildClusterInterval, TheMedianWeighsWholeClustersAndEndsAtObservedValues)
{
  const std::vector<std::vector<double>> clusters{std::vector<double>(9, 0.1), {0.5, NAN}, {0.5}};
  const auto interval = wildClusterMedianInterval(clusters, 0.95, 999, 1);
  EXPECT_DOUBLE_EQ(interval.first, 0.1);
  EXPECT_DOUBLE_EQ(interval.second, 0.5);
  std::vector<std::vector<double>> single;
  for (const auto& cluster : clusters)
    for (double v : cluster)
      single.push_back({v});
  EXPECT_DOUBLE_EQ(wildClusterMedianInterval(single, 0.95, 999, 1).second, 0.1);
  // The mirror image bounds the other end.
  std::vector<std::vector<double>> mirrored;
  for (const auto& cluster : single)
    mirrored.push_back({0.6 - cluster.front()});
  EXPECT_DOUBLE_EQ(wildClusterMedianInterval(mirrored, 0.95, 999, 1).first, 0.5);
  std::mt19937_64 engine(3);
  const Draw draw = drawClusters(engine, 0);
  EXPECT_EQ(wildClusterMedianInterval(draw.values, 0.95, 99, 1), wildClusterMedianInterval(draw.values, 0.95, 999, 2))
      << "five clusters: every weight pattern visited, neither seed nor count matters";
}

// Two clusters all right reach a share of 1; clusters that all show the same share have no
// spread to weigh and get no interval rather than a point.
TEST(WildClusterInterval, TheShareHoldsItsEstimateAndSaysNothingWithoutSpread)
{
  const std::vector<RatioCluster> trials{{2, 3, 3}, {1, 2, 2}, {4, 4, 4}, {1, 3, 3}, {2, 2, 2}};
  const auto interval = wildClusterShareInterval(trials, 0.95, 999, 1);
  EXPECT_GT(interval.first, 0.0);
  EXPECT_LT(interval.first, 10.0 / 14.0);
  EXPECT_GT(interval.second, 10.0 / 14.0);
  EXPECT_DOUBLE_EQ(interval.second, 1.0);
  const auto all = wildClusterShareInterval({{3, 3, 3}, {2, 2, 2}, {1, 1, 1}}, 0.95, 999, 1);
  EXPECT_TRUE(std::isnan(all.first) && std::isnan(all.second));
  const auto halves = wildClusterShareInterval({{1, 2, 2}, {2, 4, 4}, {1, 2, 2}}, 0.95, 999, 1);
  EXPECT_TRUE(std::isnan(halves.first) && std::isnan(halves.second));
}

TEST(WildClusterInterval, SaysNothingFromOneClusterAndRefusesBadInput)
{
  EXPECT_TRUE(std::isnan(wildClusterMedianInterval({{1.0, 2.0, 3.0}, {NAN}}, 0.95, 999, 1).first));
  EXPECT_TRUE(std::isnan(wildClusterShareInterval({{1, 2, 2}}, 0.95, 999, 1).second));
  EXPECT_THROW(wildClusterMedianInterval({{1.0}, {2.0}}, 1.0, 999, 1), std::invalid_argument);
  EXPECT_THROW(wildClusterShareInterval({{3, 2, 2}, {1, 2, 2}}, 0.95, 999, 1), std::invalid_argument);
}

}  // namespace acc
