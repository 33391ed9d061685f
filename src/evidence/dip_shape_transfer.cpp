#include "acc_identification/evidence/dip_shape_transfer.h"

#include <cmath>

namespace acc
{
namespace
{
using Measure = double (*)(const DipShape&);

double brakingOf(const DipShape& shape) { return shape.braking_mps2; }
double recoveryOf(const DipShape& shape) { return shape.recovery_mps2; }
double widthOf(const DipShape& shape) { return shape.width_s; }

bool scored(const DipShapeObservation& o, Measure measure)
{
  return std::isfinite(measure(o.judged)) && std::isfinite(measure(o.measured)) && std::isfinite(measure(o.leader));
}

/// The judged rate over the leader's, summed by cluster.
ClusteredRatio rateRatio(const std::vector<DipShapeObservation>& observations, Measure rate, std::size_t replicates,
                         std::uint64_t seed)
{
  ClusterSums sums;
  for (const DipShapeObservation& o : observations)
  {
    if (scored(o, rate) && rate(o.leader) > 0.0)
      sums.add(o.cluster, rate(o.judged), rate(o.leader));
  }
  return clusteredRatioOfSums(sums.clusters(), replicates, seed);
}
}  // namespace

DipShapeTransfer dipShapeTransfer(const std::vector<DipShapeObservation>& observations, std::size_t replicates,
                                  std::uint64_t seed)
{
  DipShapeTransfer out;
  out.braking = rateRatio(observations, brakingOf, replicates, seed);
  out.recovery = rateRatio(observations, recoveryOf, replicates, seed);
  std::vector<double> widenings;
  for (const DipShapeObservation& o : observations)
  {
    if (scored(o, widthOf))
      widenings.push_back(o.judged.width_s - o.leader.width_s);
  }
  out.widenings = widenings.size();
  out.median_widening_s = finiteMedian(widenings);
  return out;
}

}  // namespace acc
