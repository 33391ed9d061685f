#include "acc_identification/campaign/rate_transfer.h"

#include <cmath>
#include <functional>

namespace acc
{
namespace
{
/// One rate of a row: the measured one, or a pair-level model's.
using RateOf = std::function<double(const DipComparison&)>;

/// The clusters (one per perturbation) of rate / leader's measured rate over the scored rows.
std::vector<RatioCluster> clustersOf(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include,
                                     double min_dip_mps, const RateOf& rate, const RateOf& leader_rate,
                                     const RateOf& measured_rate)
{
  std::vector<RatioCluster> clusters;
  for (const PlatoonCheck& check : platoons)
  {
    for (const PerturbationCheck& perturbation : check.perturbations)
    {
      RatioCluster cluster{0.0, 0.0, 0};
      const auto& rows = perturbation.positions;
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        const double leader = leader_rate(rows[i - 1]), value = rate(rows[i]);
        if (!(rows[i].measured_dip_mps > min_dip_mps) || !std::isfinite(measured_rate(rows[i])) ||
            !(leader > 0.0) || !std::isfinite(value) || (include && !include(check, rows[i])))
          continue;
        cluster.numerator += value;
        cluster.denominator += leader;
        ++cluster.n;
      }
      if (cluster.n > 0)
        clusters.push_back(cluster);
    }
  }
  return clusters;
}
}  // namespace

RateTransferSummary summarizeRateTransfer(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include,
                                          std::size_t replicates, std::uint64_t seed, double min_dip_mps)
{
  const RateOf braking = [](const DipComparison& r) { return r.measured_shape.braking_mps2; };
  const RateOf recovery = [](const DipComparison& r) { return r.measured_shape.recovery_mps2; };
  auto passedOn = [&](const RateOf& braking_of, const RateOf& recovery_of) {
    return RatesPassedOn{
        clusteredRatioOfSums(clustersOf(platoons, include, min_dip_mps, braking_of, braking, braking), replicates, seed),
        clusteredRatioOfSums(clustersOf(platoons, include, min_dip_mps, recovery_of, recovery, recovery), replicates,
                             seed)};
  };
  RateTransferSummary out;
  out.cars = passedOn(braking, recovery);
  out.pair_base = passedOn([](const DipComparison& r) { return r.pair_predicted_shape.braking_mps2; },
                           [](const DipComparison& r) { return r.pair_predicted_shape.recovery_mps2; });
  out.pair_diagnosed = passedOn([](const DipComparison& r) { return r.pair_predicted_shape_diagnosed.braking_mps2; },
                                [](const DipComparison& r) { return r.pair_predicted_shape_diagnosed.recovery_mps2; });
  return out;
}

}  // namespace acc
