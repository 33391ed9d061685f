#include "acc_identification/evidence/wild_cluster_bootstrap.h"

#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "acc_identification/model/portable_uniform.h"

namespace acc
{
namespace
{
/// Webb's six-point weights: mean 0, variance 1, and 6^G sign-and-size patterns where Rademacher's
/// two points give only 2^G (32 with five clusters, too coarse for a p-value near 0.01).
const std::array<double, 6> kWebbWeights = {-std::sqrt(1.5), -1.0, -std::sqrt(0.5), std::sqrt(0.5), 1.0, std::sqrt(1.5)};

/// The pooled mean of the sums over its CR1 standard error; +-infinity where the clusters agree
/// exactly (no spread), NaN for a mean of 0 without spread.
double clusterT(const std::vector<double>& sums, const std::vector<std::size_t>& sizes, double entries)
{
  double total = 0.0;
  for (double s : sums)
    total += s;
  const double mean = total / entries;
  double squares = 0.0;
  for (std::size_t g = 0; g < sums.size(); ++g)
  {
    const double residual = sums[g] - static_cast<double>(sizes[g]) * mean;
    squares += residual * residual;
  }
  const double clusters = static_cast<double>(sums.size());
  const double standard_error = std::sqrt(squares * clusters / (clusters - 1.0)) / entries;
  if (standard_error > 0.0)
    return mean / standard_error;
  if (mean == 0.0)
    return std::numeric_limits<double>::quiet_NaN();
  return mean > 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
}
}  // namespace

double wildClusterBootstrapP(const std::vector<double>& cluster_sums, const std::vector<std::size_t>& cluster_sizes,
                             std::size_t replicates, std::uint64_t seed)
{
  if (cluster_sums.size() < 2 || cluster_sums.size() != cluster_sizes.size() || replicates == 0)
    return 1.0;
  double entries = 0.0;
  for (std::size_t n : cluster_sizes)
    entries += static_cast<double>(n);
  const double observed = clusterT(cluster_sums, cluster_sizes, entries);
  if (!(entries > 0.0) || std::isnan(observed))
    return 1.0;
  std::mt19937_64 engine(seed);
  std::vector<double> weighted(cluster_sums.size());
  std::size_t at_least = 0;
  for (std::size_t b = 0; b < replicates; ++b)
  {
    // The null imposed: under "mean 0" each cluster's residual is its whole sum.
    for (std::size_t g = 0; g < cluster_sums.size(); ++g)
      weighted[g] = kWebbWeights[static_cast<std::size_t>(uniformBelow(engine, kWebbWeights.size()))] * cluster_sums[g];
    if (clusterT(weighted, cluster_sizes, entries) >= observed)
      ++at_least;
  }
  return static_cast<double>(1 + at_least) / static_cast<double>(replicates + 1);
}

}  // namespace acc
