#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace acc
{
/// The median of observations that come in clusters sharing an input (every car of one
/// perturbation of a platoon), with an interval that weighs whole clusters and holds its coverage
/// with a handful of them (wildClusterMedianInterval): what a score over a handful of
/// perturbations is sure of.
struct ClusteredMedian
{
  std::size_t clusters = 0;
  std::size_t observations = 0;
  double median = std::numeric_limits<double>::quiet_NaN();
  /// The ends of the interval (observed values); NaN with fewer than two clusters that hold a
  /// finite value.
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  double confidence = 0.95;
  std::size_t replicates = 0;  ///< weight patterns drawn beyond seven clusters
};

/// The median of every finite value of every cluster, and its interval (wildClusterMedianInterval:
/// every weight pattern with up to seven clusters, else `replicates` drawn from `seed`). Clusters
/// without a finite value count in `clusters` and take no part in the interval. Throws
/// std::invalid_argument for a confidence outside (0, 1).
ClusteredMedian clusteredMedian(const std::vector<std::vector<double>>& clusters, std::size_t replicates,
                                std::uint64_t seed, double confidence = 0.95);

}  // namespace acc
