#include "acc_identification/campaign/shape_transfer.h"

#include <cmath>
#include <functional>
#include <map>

namespace acc
{
namespace
{
/// One quantity of a row's shape: the measured one, or a pair-level model's.
using ShapeOf = std::function<const DipShape&(const DipComparison&)>;
using Measure = double (*)(const DipShape&);

double brakingOf(const DipShape& shape) { return shape.braking_mps2; }
double recoveryOf(const DipShape& shape) { return shape.recovery_mps2; }
double widthOf(const DipShape& shape) { return shape.width_s; }

/// Calls visit(cluster index, row, car ahead) for every scored row whose measured `measure` and
/// its leader's are known, one cluster per perturbation.
template <typename Visit>
void forScoredRows(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include, double min_dip_mps,
                   Measure measure, const Visit& visit)
{
  std::size_t cluster = 0;
  for (const PlatoonCheck& check : platoons)
  {
    for (const PerturbationCheck& perturbation : check.perturbations)
    {
      const auto& rows = perturbation.positions;
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        if (rows[i].measured_dip_mps > min_dip_mps && std::isfinite(measure(rows[i].measured_shape)) &&
            std::isfinite(measure(rows[i - 1].measured_shape)) && (!include || include(check, rows[i])))
          visit(cluster, rows[i], rows[i - 1]);
      }
      ++cluster;
    }
  }
}

/// The rate ratio of `shape_of` to the car ahead's measured rate, clusters by perturbation.
ClusteredRatio rateRatio(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include, double min_dip_mps,
                         Measure rate, const ShapeOf& shape_of, std::size_t replicates, std::uint64_t seed)
{
  std::map<std::size_t, RatioCluster> clusters;
  forScoredRows(platoons, include, min_dip_mps, rate,
                [&](std::size_t cluster, const DipComparison& row, const DipComparison& ahead) {
                  const double value = rate(shape_of(row)), leader = rate(ahead.measured_shape);
                  if (!std::isfinite(value) || !(leader > 0.0))
                    return;
                  RatioCluster& c = clusters.try_emplace(cluster, RatioCluster{0.0, 0.0, 0}).first->second;
                  c.numerator += value;
                  c.denominator += leader;
                  ++c.n;
                });
  std::vector<RatioCluster> list;
  for (const auto& entry : clusters)
    list.push_back(entry.second);
  return clusteredRatioOfSums(list, replicates, seed);
}

ShapePassedOn passedOn(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include, double min_dip_mps,
                       const ShapeOf& shape_of, std::size_t replicates, std::uint64_t seed)
{
  ShapePassedOn out;
  out.braking = rateRatio(platoons, include, min_dip_mps, brakingOf, shape_of, replicates, seed);
  out.recovery = rateRatio(platoons, include, min_dip_mps, recoveryOf, shape_of, replicates, seed);
  std::vector<double> widenings;
  forScoredRows(platoons, include, min_dip_mps, widthOf,
                [&](std::size_t, const DipComparison& row, const DipComparison& ahead) {
                  const double width = shape_of(row).width_s;
                  if (std::isfinite(width))
                    widenings.push_back(width - ahead.measured_shape.width_s);
                });
  out.widenings = widenings.size();
  out.median_widening_s = finiteMedian(widenings);
  return out;
}
}  // namespace

ShapeTransferSummary summarizeShapeTransfer(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include,
                                            std::size_t replicates, std::uint64_t seed, double min_dip_mps)
{
  ShapeTransferSummary out;
  out.cars = passedOn(platoons, include, min_dip_mps, [](const DipComparison& r) -> const DipShape& { return r.measured_shape; },
                      replicates, seed);
  out.pair_base = passedOn(platoons, include, min_dip_mps,
                           [](const DipComparison& r) -> const DipShape& { return r.pair_predicted_shape; }, replicates,
                           seed);
  out.pair_diagnosed =
      passedOn(platoons, include, min_dip_mps,
               [](const DipComparison& r) -> const DipShape& { return r.pair_predicted_shape_diagnosed; }, replicates,
               seed);
  return out;
}

}  // namespace acc
