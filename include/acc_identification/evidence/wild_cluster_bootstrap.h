#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace acc
{
/// One member of a family of tests: its values summed per cluster. Cluster c of the member is
/// cluster clusters[c] of the family (a numbering shared by every member, so that one replicate
/// weighs a cluster alike in all of them); sums[c] is the sum of its sizes[c] entries (for a model
/// comparison: the reference's summed loss minus the candidate's).
struct ClusteredDifferences
{
  std::vector<std::size_t> clusters;
  std::vector<double> sums;
  std::vector<std::size_t> sizes;
};

/// A member's test: its t statistic, its own p and its p within the family.
struct WildClusterTest
{
  double t = std::numeric_limits<double>::quiet_NaN();
  double p_value = 1.0;         ///< of this member alone
  double family_p_value = 1.0;  ///< single-step max-t: holds the family-wise level over the members
};

/// Families with at most this many weight patterns (6^G) are enumerated whole: 6^7, seven clusters.
constexpr std::size_t kMaxEnumeratedWeightPatterns = 279936;

/// 6^family_clusters when the patterns are enumerated, else 0 (they are drawn).
std::size_t enumerableWeightPatterns(std::size_t family_clusters);

/// One-sided tests of "the mean per entry is not positive" for every member of a family, which
/// hold their level with few clusters: the wild cluster bootstrap-t with the null imposed and
/// Webb's six-point weights (Cameron, Gelbach and Miller, REStat 2008; Webb, Canadian Journal of
/// Economics 2023; MacKinnon and Webb's simulations keep its size near nominal from about five
/// clusters on), with the family's level held by the joint max-t (Westfall and Young, 1993).
///
/// A member's t is its pooled mean (sum over entries) over its cluster-robust standard error
/// (CR1). A weight pattern gives one weight per family cluster from {-sqrt(3/2), -1, -sqrt(1/2),
/// sqrt(1/2), 1, sqrt(3/2)} and multiplies each member's cluster sums by them.
///
/// With G family clusters there are 6^G patterns. Up to kMaxEnumeratedWeightPatterns (G <= 7,
/// which is where the bootstrap matters most) every pattern is visited: p_value is the exact share
/// of patterns whose t reaches the member's (the all-ones pattern among them, and every t within a
/// relative 1e-9 of it: the patterns of equal positive weights give the member's own t, up to
/// rounding, so two clusters give at least 3 of 36 and name nothing at 0.05), and family_p_value
/// the share whose largest t over the members reaches it; neither depends on the seed, so a
/// decision near the level is never one of Monte-Carlo noise. With more clusters, `replicates`
/// patterns are drawn by uniformBelow from std::mt19937_64(seed) (bit for bit the same with every
/// standard library) and the shares are (1 + count) / (replicates + 1). `replicates` = 0 asks for
/// no test: every p is 1. Correlated members (models that answer the same brakings) share their
/// patterns, so the family costs far less than Bonferroni's division. A member with fewer than two
/// clusters, sizes that do not match its sums, cluster numbers not below family_clusters, or a mean
/// of exactly 0 with no spread gets p = 1 and takes no part in the maximum.
///
/// Why not a percentile cluster bootstrap: resampling five clusters whole, every replicate of five
/// improvements is an improvement, so it says p = 1 / (replicates + 1) where the chance that five
/// of five clusters improve under the null is 1 / 32 (docs/PLATOON_DIAGNOSIS.md).
std::vector<WildClusterTest> wildClusterMaxT(const std::vector<ClusteredDifferences>& family,
                                             std::size_t family_clusters, std::size_t replicates, std::uint64_t seed);

/// The family of one: clusters numbered 0..n-1.
WildClusterTest wildClusterTest(const std::vector<double>& cluster_sums, const std::vector<std::size_t>& cluster_sizes,
                                std::size_t replicates, std::uint64_t seed);

}  // namespace acc
