#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace acc
{
/// A numerator and a denominator summed over one cluster of observations that share an input:
/// every car of one perturbation of a platoon, or the one follower of a pair's perturbation.
struct RatioCluster
{
  double numerator = 0.0;
  double denominator = 0.0;
  std::size_t n = 1;  ///< observations summed
};

/// Sum of numerators over sum of denominators, with a percentile-bootstrap interval that resamples
/// whole clusters (observations that share an input are not independent).
struct ClusteredRatio
{
  std::size_t clusters = 0;
  std::size_t observations = 0;
  double ratio = std::numeric_limits<double>::quiet_NaN();
  /// The (1 - confidence) / 2 and (1 + confidence) / 2 quantiles of the replicates (linear
  /// interpolation); NaN with fewer than two clusters.
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  double confidence = 0.95;
  std::size_t replicates = 0;
};

/// The ratio and its interval: `replicates` resamples of the clusters with replacement
/// (clusterBootstrapInterval: the same seed gives the same interval bit for bit with every
/// standard library). Every denominator must be positive (a
/// rate or a dip of the car ahead); throws std::invalid_argument otherwise, or for a confidence
/// outside (0, 1).
ClusteredRatio clusteredRatioOfSums(const std::vector<RatioCluster>& clusters, std::size_t replicates,
                                    std::uint64_t seed, double confidence = 0.95);

}  // namespace acc
