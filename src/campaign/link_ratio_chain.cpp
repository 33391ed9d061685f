#include "acc_identification/campaign/link_ratio_chain.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "acc_identification/campaign/campaign_inputs.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One measured link: a car's dip and the dip of the car directly ahead, in one perturbation.
struct LinkObservation
{
  std::string name, setting;
  std::size_t run = 0, perturbation = 0;
  double follower_dip_mps = 0.0, leader_dip_mps = 0.0;
};

bool drivenByHand(const PerturbationCheck& perturbation, int position)
{
  const auto& hand = perturbation.driven_by_hand;
  return std::find(hand.begin(), hand.end(), position) != hand.end();
}

/// Every link of every perturbation where both dips are measured, the leader's above the floor,
/// and neither car was driven by hand.
std::vector<LinkObservation> measuredLinks(const std::vector<PlatoonCheck>& platoons, double min_leader_dip_mps)
{
  std::vector<LinkObservation> links;
  for (std::size_t r = 0; r < platoons.size(); ++r)
  {
    const PlatoonCheck& check = platoons[r];
    for (std::size_t q = 0; q < check.perturbations.size(); ++q)
    {
      const PerturbationCheck& perturbation = check.perturbations[q];
      const auto& rows = perturbation.positions;
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        const double follower = rows[i].measured.dip_mps, leader = rows[i - 1].measured.dip_mps;
        if (!(std::isfinite(follower) && leader > min_leader_dip_mps) ||
            drivenByHand(perturbation, rows[i].position) || drivenByHand(perturbation, rows[i - 1].position))
          continue;
        links.push_back({rows[i].name, settingOfCar(check.car_settings, check.setting, rows[i].name), r, q, follower,
                         leader});
      }
    }
  }
  return links;
}

/// The car's summed dips over the summed dips ahead of it, over the links `use` accepts; NaN when
/// there is none.
template <typename Use>
double ratioOfSums(const std::vector<LinkObservation>& links, const std::string& name, const std::string& setting,
                   Use use)
{
  double follower = 0.0, leader = 0.0;
  for (const LinkObservation& link : links)
  {
    if (link.name == name && link.setting == setting && use(link))
    {
      follower += link.follower_dip_mps;
      leader += link.leader_dip_mps;
    }
  }
  return leader > 0.0 ? follower / leader : kNaN;
}

/// The car's link ratio for perturbation q of run r: from its other runs, else from its other
/// perturbations of this run.
double linkRatioFor(const std::vector<LinkObservation>& links, const std::string& name, const std::string& setting,
                    std::size_t r, std::size_t q)
{
  const double other_runs = ratioOfSums(links, name, setting, [r](const LinkObservation& l) { return l.run != r; });
  if (std::isfinite(other_runs))
    return other_runs;
  return ratioOfSums(links, name, setting, [r, q](const LinkObservation& l) { return l.run == r && l.perturbation != q; });
}
}  // namespace

void addLinkRatioChains(std::vector<PlatoonCheck>& platoons, double min_leader_dip_mps)
{
  const std::vector<LinkObservation> links = measuredLinks(platoons, min_leader_dip_mps);
  for (std::size_t r = 0; r < platoons.size(); ++r)
  {
    PlatoonCheck& check = platoons[r];
    for (std::size_t q = 0; q < check.perturbations.size(); ++q)
    {
      auto& rows = check.perturbations[q].positions;
      std::vector<double> ratio(rows.size(), kNaN);
      for (std::size_t i = 1; i < rows.size(); ++i)
        ratio[i] = linkRatioFor(links, rows[i].name, settingOfCar(check.car_settings, check.setting, rows[i].name), r, q);
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        DipComparison& row = rows[i];
        const DipComparison& ahead = rows[i - 1];
        // As the base chain: driven by the prediction ahead, or by the real car ahead where that
        // chain restarts (and where the car ahead had no ratio).
        const bool restart = row.chain_driven_by == ahead.position || !std::isfinite(ahead.link_ratio_chain_dip_mps);
        const double driver = restart ? ahead.measured.dip_mps : ahead.link_ratio_chain_dip_mps;
        row.link_ratio_chain_dip_mps = std::isfinite(row.chain.dip_mps) ? driver * ratio[i] : kNaN;
      }
    }
  }
}

}  // namespace acc
