#include "acc_identification/campaign/link_ratio_chain.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "acc_identification/campaign/campaign_inputs.h"
#include "acc_identification/campaign/link_evidence.h"
#include "acc_identification/evidence/empirical_response.h"

namespace acc
{
namespace
{
bool drivenByHand(const PerturbationCheck& perturbation, int position)
{
  const auto& hand = perturbation.driven_by_hand;
  return std::find(hand.begin(), hand.end(), position) != hand.end();
}

/// The car's link ratio (linkDipRatioOfMeans) over the links of its setting `use` takes, leaving
/// out links where it or the car ahead was driven by hand.
template <typename Use>
double linkRatioOver(const std::vector<PlatoonCheck>& platoons, const std::string& name, const std::string& setting,
                     double min_leader_dip_mps, Use use)
{
  std::vector<double> follower, leader;
  collectLinkDips(platoons, name, setting, &follower, &leader, [&](std::size_t r, std::size_t q, int position) {
    const PerturbationCheck& perturbation = platoons[r].perturbations[q];
    return use(r, q) && !drivenByHand(perturbation, position) && !drivenByHand(perturbation, position - 1);
  });
  return linkDipRatioOfMeans(follower, leader, min_leader_dip_mps);
}

/// The car's link ratio for perturbation q of run r: from its other runs, else from its other
/// perturbations of this run.
double linkRatioFor(const std::vector<PlatoonCheck>& platoons, const std::string& name, const std::string& setting,
                    std::size_t r, std::size_t q, double min_leader_dip_mps)
{
  const double other_runs =
      linkRatioOver(platoons, name, setting, min_leader_dip_mps, [r](std::size_t run, std::size_t) { return run != r; });
  if (std::isfinite(other_runs))
    return other_runs;
  return linkRatioOver(platoons, name, setting, min_leader_dip_mps,
                       [r, q](std::size_t run, std::size_t perturbation) { return run == r && perturbation != q; });
}
}  // namespace

void addLinkRatioChains(std::vector<PlatoonCheck>& platoons, double min_leader_dip_mps)
{
  for (std::size_t r = 0; r < platoons.size(); ++r)
  {
    PlatoonCheck& check = platoons[r];
    for (std::size_t q = 0; q < check.perturbations.size(); ++q)
    {
      auto& rows = check.perturbations[q].positions;
      std::vector<double> ratio(rows.size(), std::numeric_limits<double>::quiet_NaN());
      for (std::size_t i = 1; i < rows.size(); ++i)
        ratio[i] = linkRatioFor(platoons, rows[i].name, settingOfCar(check.car_settings, check.setting, rows[i].name),
                                r, q, min_leader_dip_mps);
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        DipComparison& row = rows[i];
        const DipComparison& ahead = rows[i - 1];
        // As the base chain: driven by the prediction ahead, or by the real car ahead where that
        // chain restarts (and where the car ahead had no ratio).
        const bool restart = row.chain_driven_by == ahead.position || !std::isfinite(ahead.link_ratio_chain_dip_mps);
        const double driver = restart ? ahead.measured.dip_mps : ahead.link_ratio_chain_dip_mps;
        row.link_ratio_chain_dip_mps =
            std::isfinite(row.chain.dip_mps) ? driver * ratio[i] : std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
}

}  // namespace acc
