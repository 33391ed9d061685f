#include "acc_identification/campaign/shape_transfer.h"

namespace acc
{
namespace
{
/// The shape a prediction (or the measurement) gives a row.
using ShapeOf = const DipShape& (*)(const DipComparison&);

const DipShape& measuredShape(const DipComparison& row) { return row.measured.shape; }
const DipShape& pairBaseShape(const DipComparison& row) { return row.pair.shape; }
const DipShape& pairDiagnosedShape(const DipComparison& row) { return row.pair_diagnosed.shape; }

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
          transferOf(platoons, include, min_dip_mps, pairDiagnosedShape, replicates, seed)};
}

}  // namespace acc
