#include "acc_identification/campaign/shape_transfer.h"

#include <cmath>

#include "acc_identification/evidence/empirical_response.h"

namespace acc
{
namespace
{
/// The shape a prediction (or the measurement) gives a row.
using ShapeOf = const DipShape& (*)(const DipComparison&);

const DipShape& measuredShape(const DipComparison& row) { return row.measured.shape; }
const DipShape& pairBaseShape(const DipComparison& row) { return row.pair.shape; }
const DipShape& pairDiagnosedShape(const DipComparison& row) { return row.pair_diagnosed.shape; }

/// The dip a prediction (or the measurement) gives a row.
using DipOf = const DipMeasures& (*)(const DipComparison&);

const DipMeasures& measuredDip(const DipComparison& row) { return row.measured; }
const DipMeasures& pairBaseDip(const DipComparison& row) { return row.pair; }
const DipMeasures& pairDiagnosedDip(const DipComparison& row) { return row.pair_diagnosed; }

/// The dips a row adds to its perturbation's numerator: the judged one, or the judged one less the
/// car's (NaN where the judged one is unknown).
using DipTerm = double (*)(const DipComparison&, DipOf);

double judgedDip(const DipComparison& row, DipOf judged) { return judged(row).dip_mps; }
double judgedLessMeasured(const DipComparison& row, DipOf judged) { return judged(row).dip_mps - row.measured.dip_mps; }

/// The rows' terms over the measured dips of the cars ahead, summed by perturbation, over the rows
/// with a measured dip above min_dip_mps behind a car ahead that dipped more than kMinLeaderDipMps
/// (a ratio to a dip the GNSS noise could make is noise, as in linkDipRatio).
ClusteredRatio dipRatioOf(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include, double min_dip_mps,
                          DipOf judged, DipTerm term, std::size_t replicates, std::uint64_t seed)
{
  std::vector<RatioCluster> clusters;
  for (const PlatoonCheck& check : platoons)
  {
    for (const PerturbationCheck& perturbation : check.perturbations)
    {
      const auto& rows = perturbation.positions;
      RatioCluster cluster{0.0, 0.0, 0};
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        const double ahead = rows[i - 1].measured.dip_mps, value = term(rows[i], judged);
        if (rows[i].measured.dip_mps > min_dip_mps && ahead > kMinLeaderDipMps && std::isfinite(value) &&
            (!include || include(check, rows[i])))
        {
          cluster.numerator += value;
          cluster.denominator += ahead;
          ++cluster.n;
        }
      }
      if (cluster.n > 0)
        clusters.push_back(cluster);
    }
  }
  return clusteredRatioOfSums(clusters, replicates, seed, 0.95,
                              term == judgedDip ? RatioNumerators::amounts : RatioNumerators::differences);
}

DipShapeTransfer transferOf(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include, double min_dip_mps,
                            ShapeOf judged, std::size_t replicates, std::uint64_t seed)
{
  std::vector<DipShapeObservation> observations;
  std::size_t cluster = 0;
  for (const PlatoonCheck& check : platoons)
  {
    for (const PerturbationCheck& perturbation : check.perturbations)
    {
      const auto& rows = perturbation.positions;
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        if (rows[i].measured.dip_mps > min_dip_mps && (!include || include(check, rows[i])))
          observations.push_back({cluster, judged(rows[i]), rows[i].measured.shape, rows[i - 1].measured.shape});
      }
      ++cluster;
    }
  }
  return dipShapeTransfer(observations, replicates, seed);
}
}  // namespace

ShapeTransferSummary summarizeShapeTransfer(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include,
                                            std::size_t replicates, std::uint64_t seed, double min_dip_mps)
{
  return {transferOf(platoons, include, min_dip_mps, measuredShape, replicates, seed),
          transferOf(platoons, include, min_dip_mps, pairBaseShape, replicates, seed),
          transferOf(platoons, include, min_dip_mps, pairDiagnosedShape, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, measuredDip, judgedDip, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, pairBaseDip, judgedDip, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, pairDiagnosedDip, judgedDip, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, pairBaseDip, judgedLessMeasured, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, pairDiagnosedDip, judgedLessMeasured, replicates, seed)};
}

}  // namespace acc
