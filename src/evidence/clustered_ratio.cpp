#include "acc_identification/evidence/clustered_ratio.h"

#include <cmath>
#include <stdexcept>
#include <tuple>

#include "acc_identification/evidence/cluster_bootstrap.h"

namespace acc
{
ClusteredRatio clusteredRatioOfSums(const std::vector<RatioCluster>& clusters, std::size_t replicates,
                                    std::uint64_t seed, double confidence)
{
  ClusteredRatio out;
  out.clusters = clusters.size();
  out.confidence = confidence;
  out.replicates = replicates;
  double top = 0.0, bottom = 0.0;
  for (const RatioCluster& c : clusters)
  {
    if (!(c.denominator > 0.0) || !std::isfinite(c.numerator))
      throw std::invalid_argument("clustered ratio: every cluster needs a finite numerator and a positive denominator");
    top += c.numerator;
    bottom += c.denominator;
    out.observations += c.n;
  }
  // Every denominator is positive, so every resample's is.
  const auto ratio_of = [&clusters](const std::vector<std::size_t>& picks) {
    double picked_top = 0.0, picked_bottom = 0.0;
    for (std::size_t pick : picks)
    {
      picked_top += clusters[pick].numerator;
      picked_bottom += clusters[pick].denominator;
    }
    return picked_top / picked_bottom;
  };
  std::tie(out.lower, out.upper) = clusterBootstrapInterval(clusters.size(), replicates, seed, confidence, ratio_of);
  if (!clusters.empty())
    out.ratio = top / bottom;
  return out;
}

}  // namespace acc
