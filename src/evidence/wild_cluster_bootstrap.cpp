#include "acc_identification/evidence/wild_cluster_bootstrap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "acc_identification/model/portable_uniform.h"

namespace acc
{
namespace
{
/// Webb's six-point weights: mean 0, variance 1, and 6^G sign-and-size patterns where Rademacher's
/// two points give only 2^G (32 with five clusters, too coarse for a p-value near 0.01).
const std::array<double, 6> kWebbWeights = {-std::sqrt(1.5), -1.0, -std::sqrt(0.5), std::sqrt(0.5), 1.0, std::sqrt(1.5)};

bool testable(const ClusteredDifferences& member, std::size_t family_clusters)
{
  return member.sums.size() >= 2 && member.sizes.size() == member.sums.size() &&
         member.clusters.size() == member.sums.size() &&
         std::all_of(member.clusters.begin(), member.clusters.end(), [&](std::size_t c) { return c < family_clusters; }) &&
         std::accumulate(member.sizes.begin(), member.sizes.end(), std::size_t{0}) > 0;
}

/// The member's pooled mean over its CR1 standard error, each cluster sum multiplied by the weight
/// of its family cluster; +-infinity where the clusters agree exactly (no spread), NaN for a mean
/// of 0 without spread.
double clusterT(const ClusteredDifferences& member, const std::vector<double>& weights)
{
  double total = 0.0, entries = 0.0;
  for (std::size_t c = 0; c < member.sums.size(); ++c)
  {
    total += weights[member.clusters[c]] * member.sums[c];
    entries += static_cast<double>(member.sizes[c]);
  }
  const double mean = total / entries;
  double squares = 0.0;
  for (std::size_t c = 0; c < member.sums.size(); ++c)
  {
    const double residual = weights[member.clusters[c]] * member.sums[c] - static_cast<double>(member.sizes[c]) * mean;
    squares += residual * residual;
  }
  const double clusters = static_cast<double>(member.sums.size());
  const double standard_error = std::sqrt(squares * clusters / (clusters - 1.0)) / entries;
  if (standard_error > 0.0)
    return mean / standard_error;
  if (mean == 0.0)
    return std::numeric_limits<double>::quiet_NaN();
  return mean > 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
}

/// Relative difference below which two t statistics are one (a tie).
constexpr double kTieTolerance = 1e-9;

/// Whether a weight pattern's t reaches the observed one. t is scale-free, so every pattern of
/// equal positive weights (three of Webb's six) gives the observed t in exact arithmetic, and
/// rounding puts it a few bits above or below: compared exactly, those ties were dropped at
/// random, and two clusters that both improve got p = 1 or 2 of 36 where the test's exact p is at
/// least 3 of 36, enough to name an effect on two brakings at 0.05.
bool reaches(double t, double observed)
{
  if (std::isinf(observed))
    return t >= observed;
  return t >= observed - kTieTolerance * std::abs(observed);
}
}  // namespace

std::size_t enumerableWeightPatterns(std::size_t family_clusters)
{
  std::size_t patterns = 1;
  for (std::size_t g = 0; g < family_clusters; ++g)
  {
    patterns *= kWebbWeights.size();
    if (patterns > kMaxEnumeratedWeightPatterns)
      return 0;
  }
  return patterns;
}

namespace
{
/// Calls visit(weights) once per weight pattern: every one of the `enumerable` patterns
/// (enumerableWeightPatterns) when there are so few, else (enumerable 0) `replicates` drawn from
/// std::mt19937_64(seed). Returns how many patterns were visited.
template <typename Visit>
std::size_t forEachWeightPattern(std::size_t family_clusters, std::size_t enumerable, std::size_t replicates,
                                 std::uint64_t seed, Visit visit)
{
  std::vector<double> weights(family_clusters);
  if (enumerable > 0)
  {
    std::vector<std::size_t> digits(family_clusters, 0);  // an odometer in base 6
    for (std::size_t k = 0; k < enumerable; ++k)
    {
      for (std::size_t g = 0; g < family_clusters; ++g)
        weights[g] = kWebbWeights[digits[g]];
      visit(weights);
      for (std::size_t g = 0; g < family_clusters && ++digits[g] == kWebbWeights.size(); ++g)
        digits[g] = 0;
    }
    return enumerable;
  }
  std::mt19937_64 engine(seed);
  for (std::size_t b = 0; b < replicates; ++b)
  {
    for (double& w : weights)
      w = kWebbWeights[static_cast<std::size_t>(uniformBelow(engine, kWebbWeights.size()))];
    visit(weights);
  }
  return replicates;
}
}  // namespace

std::vector<WildClusterTest> wildClusterMaxT(const std::vector<ClusteredDifferences>& family,
                                             std::size_t family_clusters, std::size_t replicates, std::uint64_t seed)
{
  std::vector<WildClusterTest> out(family.size());
  std::vector<std::size_t> members;  // those tested
  const std::vector<double> unweighted(family_clusters, 1.0);
  for (std::size_t m = 0; m < family.size(); ++m)
  {
    if (!testable(family[m], family_clusters))
      continue;
    out[m].t = clusterT(family[m], unweighted);
    if (!std::isnan(out[m].t) && replicates > 0)
      members.push_back(m);
  }
  if (members.empty())
    return out;
  std::vector<std::size_t> alone(family.size(), 0), in_family(family.size(), 0);
  std::vector<double> t(family.size());
  // The null imposed: under "mean 0" each cluster's residual is its whole sum, so a pattern's
  // statistic is the t of the weighted sums.
  const auto count_reaching = [&](const std::vector<double>& w) {
    double largest = -std::numeric_limits<double>::infinity();
    for (std::size_t m : members)
    {
      t[m] = clusterT(family[m], w);
      largest = std::max(largest, t[m]);
    }
    for (std::size_t m : members)
    {
      alone[m] += reaches(t[m], out[m].t);
      in_family[m] += reaches(largest, out[m].t);
    }
  };
  const std::size_t enumerable = enumerableWeightPatterns(family_clusters);
  const std::size_t visited = forEachWeightPattern(family_clusters, enumerable, replicates, seed, count_reaching);
  // Enumerated, the all-ones pattern is among those counted (its t is the member's own): the exact
  // share. Drawn, the observed statistic is added as one more replicate.
  const double extra = enumerable > 0 ? 0.0 : 1.0;
  for (std::size_t m : members)
  {
    out[m].p_value = (extra + static_cast<double>(alone[m])) / (extra + static_cast<double>(visited));
    out[m].family_p_value = (extra + static_cast<double>(in_family[m])) / (extra + static_cast<double>(visited));
  }
  return out;
}

WildClusterTest wildClusterTest(const std::vector<double>& cluster_sums, const std::vector<std::size_t>& cluster_sizes,
                                std::size_t replicates, std::uint64_t seed)
{
  ClusteredDifferences member;
  member.sums = cluster_sums;
  member.sizes = cluster_sizes;
  member.clusters.resize(cluster_sums.size());
  std::iota(member.clusters.begin(), member.clusters.end(), std::size_t{0});
  return wildClusterMaxT({member}, cluster_sums.size(), replicates, seed).front();
}

}  // namespace acc
