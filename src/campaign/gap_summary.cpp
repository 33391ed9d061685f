#include "acc_identification/campaign/gap_summary.h"

namespace acc
{
namespace
{
/// A row's key, label, prediction and the car-perturbations it scores (all when `include` is empty).
struct GapRow
{
  const char* key;
  const char* label;
  DipPrediction which;
  DipRowFilter include;
};

const std::vector<GapRow>& gapRowsInOrder()
{
  static const std::vector<GapRow> kRows{
      {"chain_base", "platoon, base model", DipPrediction::chain_base, {}},
      {"chain_diagnosed", "platoon, diagnosed", DipPrediction::chain_diagnosed, {}},
      {"pair_base", "pair (real leader), base", DipPrediction::pair_base, {}},
      {"pair_diagnosed", "pair (real leader), diagnosed", DipPrediction::pair_diagnosed, {}},
      {"pair_diagnosed_first_follower", "  of which first followers", DipPrediction::pair_diagnosed, isFirstFollower},
      {"pair_diagnosed_further_back", "  of which cars further back", DipPrediction::pair_diagnosed, isFurtherBack},
      {"unchanged_dip", "no model: every car dips as the first", DipPrediction::unchanged_dip, {}},
      {"link_ratio_chain", "no model: each car's link ratio, other runs", DipPrediction::link_ratio_chain, {}}};
  return kRows;
}
}  // namespace

std::vector<GapSummary> summarizeGap(const std::vector<PlatoonCheck>& platoons)
{
  std::vector<GapSummary> out;
  for (const GapRow& row : gapRowsInOrder())
    out.push_back({row.key, row.label,
                   summarizeDipPredictions(platoons, row.which, kScoredMinDipMps, kScoredMinLinkChangeMps, row.include)});
  return out;
}

}  // namespace acc
