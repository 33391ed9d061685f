#include "acc_identification/campaign/shape_transfer.h"

#include <cmath>

#include "acc_identification/evidence/empirical_response.h"

namespace acc
{
namespace
{
/// What a prediction (or the measurement) gives a row: its dip and the dip's shape.
using MeasuresOf = const DipMeasures& (*)(const DipComparison&);

const DipMeasures& measured(const DipComparison& row) { return row.measured; }
const DipMeasures& pairBase(const DipComparison& row) { return row.pair; }
const DipMeasures& pairDiagnosed(const DipComparison& row) { return row.pair_diagnosed; }

/// Calls visit(cluster, rows, i) for every scored row: positions 2 on with a measured dip above
/// min_dip_mps that `include` accepts; cluster numbers the perturbations in order (every car of
/// one shares its input).
template <typename Visit>
void forEachScoredRow(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include, double min_dip_mps,
                      Visit visit)
{
  std::size_t cluster = 0;
  for (const PlatoonCheck& check : platoons)
  {
    for (const PerturbationCheck& perturbation : check.perturbations)
    {
      const auto& rows = perturbation.positions;
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        if (rows[i].measured.dip_mps > min_dip_mps && (!include || include(check, rows[i])))
          visit(cluster, rows, i);
      }
      ++cluster;
    }
  }
}

/// What a row adds to its perturbation's numerator (NaN where the judged dip is unknown), and
/// what kind of number that is.
struct DipTerm
{
  double (*value)(const DipComparison& row, MeasuresOf judged);
  RatioNumerators numerators;
};

double judgedDip(const DipComparison& row, MeasuresOf judged) { return judged(row).dip_mps; }
double judgedLessMeasured(const DipComparison& row, MeasuresOf judged)
{
  return judged(row).dip_mps - row.measured.dip_mps;
}

constexpr DipTerm kJudgedDip{judgedDip, RatioNumerators::amounts};
constexpr DipTerm kJudgedLessMeasured{judgedLessMeasured, RatioNumerators::differences};

/// The rows' terms over the measured dips of the cars ahead, summed by perturbation, over the
/// scored rows behind a car ahead that dipped more than kMinLeaderDipMps (a ratio to a dip the
/// GNSS noise could make is noise, as in linkDipRatio).
ClusteredRatio dipRatioOf(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include, double min_dip_mps,
                          MeasuresOf judged, DipTerm term, std::size_t replicates, std::uint64_t seed)
{
  ClusterSums by_perturbation;
  forEachScoredRow(platoons, include, min_dip_mps, [&](std::size_t cluster, const auto& rows, std::size_t i) {
    const double ahead = rows[i - 1].measured.dip_mps, value = term.value(rows[i], judged);
    if (ahead > kMinLeaderDipMps && std::isfinite(value))
      by_perturbation.add(cluster, value, ahead);
  });
  return clusteredRatioOfSums(by_perturbation.clusters(), replicates, seed, 0.95, term.numerators);
}

DipShapeTransfer transferOf(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include, double min_dip_mps,
                            MeasuresOf judged, std::size_t replicates, std::uint64_t seed)
{
  std::vector<DipShapeObservation> observations;
  forEachScoredRow(platoons, include, min_dip_mps, [&](std::size_t cluster, const auto& rows, std::size_t i) {
    observations.push_back({cluster, judged(rows[i]).shape, rows[i].measured.shape, rows[i - 1].measured.shape});
  });
  return dipShapeTransfer(observations, replicates, seed);
}
}  // namespace

ShapeTransferSummary summarizeShapeTransfer(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include,
                                            std::size_t replicates, std::uint64_t seed, double min_dip_mps)
{
  return {transferOf(platoons, include, min_dip_mps, measured, replicates, seed),
          transferOf(platoons, include, min_dip_mps, pairBase, replicates, seed),
          transferOf(platoons, include, min_dip_mps, pairDiagnosed, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, measured, kJudgedDip, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, pairBase, kJudgedDip, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, pairDiagnosed, kJudgedDip, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, pairBase, kJudgedLessMeasured, replicates, seed),
          dipRatioOf(platoons, include, min_dip_mps, pairDiagnosed, kJudgedLessMeasured, replicates, seed)};
}

}  // namespace acc
