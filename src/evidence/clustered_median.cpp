#include "acc_identification/evidence/clustered_median.h"

#include <cmath>
#include <tuple>

#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/evidence/wild_cluster_interval.h"

namespace acc
{
ClusteredMedian clusteredMedian(const std::vector<std::vector<double>>& clusters, std::size_t replicates,
                                std::uint64_t seed, double confidence)
{
  ClusteredMedian out;
  out.clusters = clusters.size();
  out.confidence = confidence;
  out.replicates = replicates;
  std::vector<double> all;
  for (const std::vector<double>& cluster : clusters)
  {
    for (double value : cluster)
    {
      if (std::isfinite(value))
        all.push_back(value);
    }
  }
  out.observations = all.size();
  out.median = finiteMedian(all);
  std::tie(out.lower, out.upper) = wildClusterMedianInterval(clusters, confidence, replicates, seed);
  return out;
}

}  // namespace acc
