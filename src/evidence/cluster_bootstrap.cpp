#include "acc_identification/evidence/cluster_bootstrap.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "acc_identification/model/portable_uniform.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
std::pair<double, double> clusterBootstrapInterval(std::size_t clusters, std::size_t replicates, std::uint64_t seed,
                                                   double confidence,
                                                   const std::function<double(const std::vector<std::size_t>&)>& statistic)
{
  if (!(confidence > 0.0 && confidence < 1.0))
    throw std::invalid_argument("cluster bootstrap: the confidence must lie in (0, 1)");
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (clusters < 2 || replicates == 0)
    return {kNaN, kNaN};
  std::mt19937_64 engine(seed);
  std::vector<std::size_t> picks(clusters);
  std::vector<double> values;
  values.reserve(replicates);
  for (std::size_t r = 0; r < replicates; ++r)
  {
    for (std::size_t& pick : picks)
      pick = static_cast<std::size_t>(uniformBelow(engine, clusters));
    const double value = statistic(picks);
    if (std::isfinite(value))
      values.push_back(value);
  }
  if (values.empty())
    return {kNaN, kNaN};
  return {interpolatedQuantile(values, 0.5 * (1.0 - confidence)), interpolatedQuantile(values, 0.5 * (1.0 + confidence))};
}

}  // namespace acc
