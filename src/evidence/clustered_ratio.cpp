#include "acc_identification/evidence/clustered_ratio.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include "acc_identification/model/portable_uniform.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
/// The ratio of sums of `replicates` resamples of the clusters with replacement.
std::vector<double> bootstrapRatios(const std::vector<RatioCluster>& clusters, std::size_t replicates,
                                    std::uint64_t seed)
{
  std::mt19937_64 engine(seed);
  const std::size_t n = clusters.size();
  std::vector<double> ratios(replicates);
  for (double& ratio : ratios)
  {
    double top = 0.0, bottom = 0.0;
    for (std::size_t j = 0; j < n; ++j)
    {
      const RatioCluster& pick = clusters[static_cast<std::size_t>(uniformBelow(engine, n))];
      top += pick.numerator;
      bottom += pick.denominator;
    }
    ratio = top / bottom;  // every denominator is positive: bottom > 0
  }
  return ratios;
}
}  // namespace

ClusteredRatio clusteredRatioOfSums(const std::vector<RatioCluster>& clusters, std::size_t replicates,
                                    std::uint64_t seed, double confidence)
{
  if (!(confidence > 0.0 && confidence < 1.0))
    throw std::invalid_argument("clustered ratio: the confidence must lie in (0, 1)");
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
  if (clusters.empty())
    return out;
  out.ratio = top / bottom;
  if (clusters.size() >= 2 && replicates > 0)
  {
    const std::vector<double> ratios = bootstrapRatios(clusters, replicates, seed);
    out.lower = interpolatedQuantile(ratios, 0.5 * (1.0 - confidence));
    out.upper = interpolatedQuantile(ratios, 0.5 * (1.0 + confidence));
  }
  return out;
}

}  // namespace acc
