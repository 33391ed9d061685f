#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace acc
{
/// One-sided test of "the mean per entry of clustered values is not positive" that holds its level
/// with few clusters: the wild cluster bootstrap-t with the null imposed and Webb's six-point
/// weights (Cameron, Gelbach and Miller, REStat 2008; Webb, Canadian Journal of Economics 2023;
/// MacKinnon and Webb's simulations keep its size near nominal from about five clusters on).
///
/// Cluster g holds cluster_sizes[g] entries whose values sum to cluster_sums[g] (for a model
/// comparison: the reference's summed loss minus the candidate's). The statistic is the pooled
/// mean sum / entries over its cluster-robust standard error (CR1); each replicate multiplies every
/// cluster's sum by one weight drawn from {-sqrt(3/2), -1, -sqrt(1/2), sqrt(1/2), 1, sqrt(3/2)} by
/// uniformBelow from std::mt19937_64(seed) (bit for bit the same with every standard library).
/// Returns (1 + replicates whose t is at least the observed t) / (replicates + 1); 1 with fewer than
/// two clusters, no replicates, sizes that do not match the sums, or a mean of exactly 0.
///
/// Why not the percentile cluster bootstrap: resampling five clusters whole, every replicate of five
/// improvements is an improvement, so it says p = 1 / (replicates + 1) where the chance that five
/// of five clusters improve under the null is 1 / 32 (docs/PLATOON_DIAGNOSIS.md).
double wildClusterBootstrapP(const std::vector<double>& cluster_sums, const std::vector<std::size_t>& cluster_sizes,
                             std::size_t replicates, std::uint64_t seed);

}  // namespace acc
