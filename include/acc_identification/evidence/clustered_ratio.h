#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
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

/// Observations summed into their clusters by a cluster id (e.g. the perturbation's index): the
/// one way the callers build the clusters of a ratio of sums.
class ClusterSums
{
public:
  void add(std::size_t cluster, double numerator, double denominator);
  /// The clusters in the order of their ids.
  std::vector<RatioCluster> clusters() const;

private:
  std::map<std::size_t, RatioCluster> by_id_;
};

/// What a ratio's numerators are: amounts (dips, rates), whose ratio is at least 0 where every
/// numerator is, or differences (a model's dip less the car's), of either sign by construction.
enum class RatioNumerators
{
  amounts,
  differences
};

/// Sum of numerators over sum of denominators, with an interval that weighs whole clusters
/// (observations that share an input are not independent) and holds its coverage with a handful of
/// them (wildClusterRatioInterval).
struct ClusteredRatio
{
  std::size_t clusters = 0;
  std::size_t observations = 0;
  double ratio = std::numeric_limits<double>::quiet_NaN();
  /// The ends of the interval: infinite where the clusters do not bound the ratio (two never do
  /// at 95 %), NaN with fewer than two clusters or when every cluster shows the same ratio.
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  double confidence = 0.95;
  std::size_t replicates = 0;  ///< weight patterns drawn beyond seven clusters
};

/// The ratio and its interval (wildClusterRatioInterval: every weight pattern with up to seven
/// clusters, else `replicates` drawn from `seed`, bit for bit the same with every standard
/// library). Every denominator must be positive (a rate or a dip of the car ahead); throws
/// std::invalid_argument otherwise, or for a confidence outside (0, 1).
ClusteredRatio clusteredRatioOfSums(const std::vector<RatioCluster>& clusters, std::size_t replicates,
                                    std::uint64_t seed, double confidence = 0.95,
                                    RatioNumerators numerators = RatioNumerators::amounts);

/// "0.88 [0.78, 0.98]": the ratio with its interval ("inf" for an end the clusters do not bound),
/// the ratio alone where it has no interval, "NaN" for a ratio not available. The one way the
/// reports write a ClusteredRatio.
std::string ratioWithIntervalText(const ClusteredRatio& ratio);
/// The same for a ratio and interval held elsewhere (a link's DipRatioEstimate).
std::string ratioWithIntervalText(double ratio, double lower, double upper);

}  // namespace acc
