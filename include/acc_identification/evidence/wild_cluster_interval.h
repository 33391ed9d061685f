#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "acc_identification/evidence/clustered_ratio.h"

namespace acc
{
/// Confidence intervals over a handful of clusters, by inverting the wild cluster bootstrap-t
/// (wild_cluster_bootstrap.h): the interval holds every value the equal-tailed test does not
/// reject, each tail at (1 - confidence) / 2. A percentile bootstrap that resamples five clusters
/// whole covers too seldom (a median 82 %, a share 80.5 % of the time for a nominal 95 %, where
/// these intervals cover 92.5 % and 92.5 %: test_wild_cluster_interval, which also measures the
/// ratio's), for the reason its
/// p-values said too much
/// (docs/PLATOON_DIAGNOSIS.md, "Why the wild cluster bootstrap-t"). With up to seven clusters
/// every weight pattern is visited, so the interval does not depend on the seed; beyond,
/// `replicates` patterns are drawn from `seed`.
///
/// Each returns NaN bounds with fewer than two clusters that hold an observation, and throws
/// std::invalid_argument for a confidence outside (0, 1).

/// The median of every finite value of every cluster: the observed values m at which neither "at
/// most half the values lie at or below m" nor "at most half lie at or above m" is rejected (the
/// cluster-robust form of the sign test's interval), walking out from the median to the first
/// value rejected on each side. Its ends are observed values.
std::pair<double, double> wildClusterMedianInterval(const std::vector<std::vector<double>>& clusters,
                                                    double confidence, std::size_t replicates, std::uint64_t seed);

/// A ratio of sums, the summed numerators over the summed (positive) denominators: the ratios r
/// at which "numerators - r denominators has mean 0" is not rejected, Fieller's way of bounding a
/// ratio with the test above, each end found by bisection to 1e-4 of the ratio. When the numerators
/// are amounts and every one is at least 0 (dips, braking rates) so is the ratio, and the lower end
/// is searched down to 0 only; differences (a model's dip less the car's) may be of either sign
/// whatever the data show, and their lower end is searched to -inf. An end is infinite where the data do not bound it: far from the estimate the
/// test is that of the denominators alone, and when their sum is not shown positive at the tail
/// (two clusters never are at 95 %: their smallest p is 3/36), no ratio that far out is rejected.
/// NaN bounds also when every cluster shows the same ratio: without spread between the clusters
/// the test would call every other ratio certainly false. Throws std::invalid_argument for a
/// denominator that is not positive or a numerator that is not finite.
std::pair<double, double> wildClusterRatioInterval(const std::vector<RatioCluster>& clusters, double confidence,
                                                   std::size_t replicates, std::uint64_t seed,
                                                   RatioNumerators numerators = RatioNumerators::amounts);

/// A share, the summed successes (numerators) over the summed trials (denominators, each cluster's
/// n its trials): wildClusterRatioInterval within [0, 1] (each end 0 or 1 where that is not
/// rejected). Clusters without a trial take no part. NaN bounds when every cluster shows the same
/// share (all links right, say). Throws std::invalid_argument for a cluster whose successes are
/// not within [0, trials].
std::pair<double, double> wildClusterShareInterval(const std::vector<RatioCluster>& clusters, double confidence,
                                                   std::size_t replicates, std::uint64_t seed);

}  // namespace acc
