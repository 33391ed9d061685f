#include "acc_identification/evidence/clustered_median.h"

#include <cmath>
#include <tuple>

#include "acc_identification/evidence/cluster_bootstrap.h"
#include "acc_identification/evidence/perturbation.h"

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
  std::vector<double> pooled;
  const auto median_of = [&clusters, &pooled](const std::vector<std::size_t>& picks) {
    pooled.clear();
    for (std::size_t pick : picks)
      pooled.insert(pooled.end(), clusters[pick].begin(), clusters[pick].end());
    return finiteMedian(pooled);  // NaN for a resample without a value: left out
  };
  std::tie(out.lower, out.upper) = clusterBootstrapInterval(clusters.size(), replicates, seed, confidence, median_of);
  return out;
}

}  // namespace acc
