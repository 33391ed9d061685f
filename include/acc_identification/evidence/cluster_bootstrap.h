#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace acc
{
/// The package's one cluster bootstrap: the percentile interval of a statistic over `replicates`
/// resamples of `clusters` clusters drawn whole with replacement (observations that share an
/// input, such as every car of one perturbation, are not independent). The indices are drawn by
/// uniformBelow (model/portable_uniform.h) from std::mt19937_64(seed), so the same seed gives the
/// same interval bit for bit with every standard library. statistic(picks) is one resample's value
/// from the indices drawn; non-finite values are left out. Returns the (1 - confidence) / 2 and
/// (1 + confidence) / 2 quantiles (linear interpolation), NaN with fewer than two clusters, no
/// replicates or no finite value. Throws std::invalid_argument for a confidence outside (0, 1).
std::pair<double, double> clusterBootstrapInterval(std::size_t clusters, std::size_t replicates, std::uint64_t seed,
                                                   double confidence,
                                                   const std::function<double(const std::vector<std::size_t>&)>& statistic);

}  // namespace acc
