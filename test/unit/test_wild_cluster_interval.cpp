// Intervals from the inverted wild cluster bootstrap-t (wild_cluster_interval.h): with five
// clusters they cover a known median, share and ratio about as often as they say, where the
// percentile bootstrap that resamples the clusters whole (the package's intervals until
// 2026-11-29, kept here only as the reference it replaced) covers far less often; and their ends
// behave.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "acc_identification/evidence/clustered_ratio.h"
#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/evidence/wild_cluster_bootstrap.h"
#include "acc_identification/evidence/wild_cluster_interval.h"
#include "acc_identification/model/portable_uniform.h"
#include "acc_identification/model/sample_statistics.h"

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
/// Five clusters of 1-4 links (the cars behind one perturbation): each link's follower dip is its
/// leader's (uniform 1-4 m/s) times the cluster's ratio, log-normal with mean kRatio and a
/// spread like the ZalaZone links', times a link's own log-normal factor of mean 1. Ratios and
/// dips are independent, so the ratio of the expected sums is kRatio.
constexpr double kRatio = 0.9;

struct Draw
{
  std::vector<std::vector<double>> values;
  std::vector<RatioCluster> trials;
};

/// The percentile bootstrap over clusters resampled whole: the replicates' (1 - confidence) / 2
/// and (1 + confidence) / 2 quantiles of a statistic of the picked clusters.
template <typename Statistic>
std::pair<double, double> percentileInterval(std::size_t clusters, std::uint64_t seed, Statistic statistic)
{
  std::mt19937_64 engine(seed);
  std::vector<std::size_t> picks(clusters);
  std::vector<double> values;
  for (std::size_t r = 0; r < 1999; ++r)
  {
    for (std::size_t& pick : picks)
      pick = static_cast<std::size_t>(uniformBelow(engine, clusters));
    values.push_back(statistic(picks));
  }
  return {interpolatedQuantile(values, 0.025), interpolatedQuantile(values, 0.975)};
}

/// The ratio of sums over the picked clusters.
std::pair<double, double> percentileRatioInterval(const std::vector<RatioCluster>& clusters, std::uint64_t seed)
{
  return percentileInterval(clusters.size(), seed, [&](const std::vector<std::size_t>& picks) {
    double top = 0.0, bottom = 0.0;
    for (std::size_t k : picks)
    {
      top += clusters[k].numerator;
      bottom += clusters[k].denominator;
    }
    return top / bottom;
  });
}

RatioCluster drawDipCluster(std::mt19937_64& engine, std::size_t links)
{
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> leader_dip(1.0, 4.0);
  constexpr double kClusterSpread = 0.15, kLinkSpread = 0.1;
  const double cluster_ratio = kRatio * std::exp(kClusterSpread * normal(engine) - 0.5 * kClusterSpread * kClusterSpread);
  RatioCluster cluster{0.0, 0.0, links};
  for (std::size_t i = 0; i < links; ++i)
  {
    const double dip = leader_dip(engine);
    cluster.denominator += dip;
    cluster.numerator += dip * cluster_ratio * std::exp(kLinkSpread * normal(engine) - 0.5 * kLinkSpread * kLinkSpread);
  }
  return cluster;
}

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

TEST(WildClusterInterval, CoversAMedianAShareAndARatioAsOftenAsItSaysWithFiveClusters)
{
  std::mt19937_64 engine(7), dip_engine(11);
  const std::size_t datasets = 200;
  std::size_t median_wild = 0, median_percentile = 0, share_wild = 0, share_percentile = 0, ratio_wild = 0,
              ratio_percentile = 0;
  for (std::size_t d = 0; d < datasets; ++d)
  {
    const Draw draw = drawClusters(engine, d);
    median_wild += covers(wildClusterMedianInterval(draw.values, 0.95, 1999, d), kMedian);
    std::vector<double> pooled;
    median_percentile += covers(percentileInterval(5, d,
                                                   [&](const std::vector<std::size_t>& picks) {
                                                     pooled.clear();
                                                     for (std::size_t k : picks)
                                                       pooled.insert(pooled.end(), draw.values[k].begin(),
                                                                     draw.values[k].end());
                                                     return finiteMedian(pooled);
                                                   }),
                                kMedian);
    share_wild += covers(wildClusterShareInterval(draw.trials, 0.95, 1999, d), kShare);
    share_percentile += covers(percentileRatioInterval(draw.trials, d), kShare);
    std::vector<RatioCluster> dips;
    for (std::size_t g = 0; g < 5; ++g)
      dips.push_back(drawDipCluster(dip_engine, 1 + (g + d) % 4));
    ratio_wild += covers(wildClusterRatioInterval(dips, 0.95, 1999, d), kRatio);
    ratio_percentile += covers(percentileRatioInterval(dips, d), kRatio);
  }
  const auto rate = [&](std::size_t n) { return static_cast<double>(n) / static_cast<double>(datasets); };
  std::printf("coverage of 95 %% intervals over five clusters: median %.3f (percentile %.3f), share %.3f (%.3f), "
              "ratio %.3f (%.3f)\n",
              rate(median_wild), rate(median_percentile), rate(share_wild), rate(share_percentile), rate(ratio_wild),
              rate(ratio_percentile));
  EXPECT_GT(rate(median_wild), 0.90);
  EXPECT_GT(rate(share_wild), 0.86);
  EXPECT_GT(rate(ratio_wild), 0.90);
  EXPECT_LT(rate(median_percentile), rate(median_wild) - 0.04);
  EXPECT_LT(rate(share_percentile), rate(share_wild) - 0.04);
  EXPECT_LT(rate(ratio_percentile), rate(ratio_wild) - 0.04);
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

// Two clusters never bound a ratio at 95 % (their smallest p is 3/36): dips give [0, inf), a
// ratio that may be negative the whole line. Six that agree bound it on both sides; clusters that
// all show the same ratio get no interval rather than a point.
TEST(WildClusterInterval, TheRatioIsBoundedOnlyWhereTheClustersBoundIt)
{
  const auto two = wildClusterRatioInterval({{3.0, 2.0, 1}, {1.8, 1.5, 1}}, 0.95, 999, 1);
  EXPECT_EQ(two.first, 0.0);
  EXPECT_TRUE(std::isinf(two.second) && two.second > 0.0);
  const auto signed_two = wildClusterRatioInterval({{3.0, 2.0, 1}, {-0.5, 1.5, 1}}, 0.95, 999, 1);
  EXPECT_TRUE(std::isinf(signed_two.first) && signed_two.first < 0.0);
  EXPECT_TRUE(std::isinf(signed_two.second) && signed_two.second > 0.0);
  // Differences (a model's dip less the car's) may be negative whatever the data show: the same
  // two clusters of positive numerators are not held above 0 then.
  const auto differences =
      wildClusterRatioInterval({{3.0, 2.0, 1}, {1.8, 1.5, 1}}, 0.95, 999, 1, RatioNumerators::differences);
  EXPECT_TRUE(std::isinf(differences.first) && differences.first < 0.0);
  const std::vector<RatioCluster> six{{3.0, 2.0, 1}, {5.4, 3.5, 1}, {1.9, 1.2, 1},
                                      {5.6, 4.0, 1}, {4.0, 2.6, 1}, {4.5, 3.1, 1}};
  const auto bounded = wildClusterRatioInterval(six, 0.95, 999, 1);
  const double ratio = 24.4 / 16.4;
  EXPECT_GT(bounded.first, 1.0);
  EXPECT_LT(bounded.first, ratio);
  EXPECT_GT(bounded.second, ratio);
  EXPECT_LT(bounded.second, 2.0);
  // The ends are where the test turns: just inside is kept, just outside rejected.
  const auto pvalue = [&](double r, bool too_small) {
    std::vector<double> excess;
    for (const RatioCluster& c : six)
      excess.push_back(too_small ? c.numerator - r * c.denominator : r * c.denominator - c.numerator);
    return wildClusterTest(excess, std::vector<std::size_t>(6, 1), 999, 1).p_value;
  };
  EXPECT_GT(pvalue(bounded.first + 1e-3, true), 0.025);
  EXPECT_LE(pvalue(bounded.first - 1e-3, true), 0.025);
  EXPECT_GT(pvalue(bounded.second - 1e-3, false), 0.025);
  EXPECT_LE(pvalue(bounded.second + 1e-3, false), 0.025);
  const auto same = wildClusterRatioInterval({{3.0, 2.0, 1}, {3.75, 2.5, 1}, {1.5, 1.0, 1}}, 0.95, 999, 1);
  EXPECT_TRUE(std::isnan(same.first) && std::isnan(same.second));
}

TEST(WildClusterInterval, SaysNothingFromOneClusterAndRefusesBadInput)
{
  EXPECT_TRUE(std::isnan(wildClusterMedianInterval({{1.0, 2.0, 3.0}, {NAN}}, 0.95, 999, 1).first));
  EXPECT_TRUE(std::isnan(wildClusterShareInterval({{1, 2, 2}}, 0.95, 999, 1).second));
  EXPECT_THROW(wildClusterMedianInterval({{1.0}, {2.0}}, 1.0, 999, 1), std::invalid_argument);
  EXPECT_THROW(wildClusterShareInterval({{3, 2, 2}, {1, 2, 2}}, 0.95, 999, 1), std::invalid_argument);
  EXPECT_TRUE(std::isnan(wildClusterRatioInterval({{1.0, 2.0, 2}}, 0.95, 999, 1).first));
  EXPECT_THROW(wildClusterRatioInterval({{1.0, 0.0, 1}, {1.0, 1.0, 1}}, 0.95, 999, 1), std::invalid_argument);
  EXPECT_THROW(wildClusterRatioInterval({{NAN, 1.0, 1}, {1.0, 1.0, 1}}, 0.95, 999, 1), std::invalid_argument);
}

}  // namespace acc
