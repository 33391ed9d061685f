#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace acc
{
/// The median of observations that come in clusters sharing an input (every car of one
/// perturbation of a platoon), with a percentile-bootstrap interval that resamples whole
/// clusters: what a score over a handful of perturbations is sure of.
struct ClusteredMedian
{
  std::size_t clusters = 0;
  std::size_t observations = 0;
  double median = std::numeric_limits<double>::quiet_NaN();
  /// The (1 - confidence) / 2 and (1 + confidence) / 2 quantiles of the replicates' medians
  /// (linear interpolation); NaN with fewer than two clusters.
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  double confidence = 0.95;
  std::size_t replicates = 0;
};

/// The median of every finite value of every cluster, and its interval from `replicates`
/// resamples of the clusters (clusterBootstrapInterval, seeded). Empty clusters count as clusters
/// without values. Throws std::invalid_argument for a confidence outside (0, 1).
ClusteredMedian clusteredMedian(const std::vector<std::vector<double>>& clusters, std::size_t replicates,
                                std::uint64_t seed, double confidence = 0.95);

}  // namespace acc
