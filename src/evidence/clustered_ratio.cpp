#include "acc_identification/evidence/clustered_ratio.h"

#include <cmath>
#include <stdexcept>
#include <tuple>

#include "acc_identification/evidence/wild_cluster_interval.h"
#include "acc_identification/model/number_text.h"

namespace acc
{
void ClusterSums::add(std::size_t cluster, double numerator, double denominator)
{
  RatioCluster& c = by_id_.try_emplace(cluster, RatioCluster{0.0, 0.0, 0}).first->second;
  c.numerator += numerator;
  c.denominator += denominator;
  ++c.n;
}

std::vector<RatioCluster> ClusterSums::clusters() const
{
  std::vector<RatioCluster> list;
  for (const auto& entry : by_id_)
    list.push_back(entry.second);
  return list;
}

ClusteredRatio clusteredRatioOfSums(const std::vector<RatioCluster>& clusters, std::size_t replicates,
                                    std::uint64_t seed, double confidence, RatioNumerators numerators)
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
  std::tie(out.lower, out.upper) = wildClusterRatioInterval(clusters, confidence, replicates, seed, numerators);
  if (!clusters.empty())
    out.ratio = top / bottom;
  return out;
}

std::string ratioWithIntervalText(const ClusteredRatio& ratio)
{
  return ratioWithIntervalText(ratio.ratio, ratio.lower, ratio.upper);
}

std::string ratioWithIntervalText(double ratio, double lower, double upper)
{
  const std::string text = cellNumber("%.2f", ratio);
  if (std::isnan(lower))
    return text;
  return text + " [" + cellNumber("%.2f", lower) + ", " + cellNumber("%.2f", upper) + "]";
}

}  // namespace acc
