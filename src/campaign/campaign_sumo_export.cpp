#include "acc_identification/campaign/campaign_sumo_export.h"

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>

#include "acc_identification/campaign/link_evidence.h"

namespace acc
{
namespace
{
bool sumoCarries(EffectKind kind)
{
  return kind == EffectKind::asymmetric_response || kind == EffectKind::acceleration_limits ||
         kind == EffectKind::set_speed_cruise || kind == EffectKind::reaction_delay;
}

/// The effects of a model that SUMO's ACC has no term for.
std::vector<EffectKind> lostInSumo(const std::vector<EffectKind>& effects)
{
  std::vector<EffectKind> lost;
  std::copy_if(effects.begin(), effects.end(), std::back_inserter(lost), [](EffectKind kind) { return !sumoCarries(kind); });
  return lost;
}

std::string effectList(const std::vector<EffectKind>& effects)
{
  std::string names;
  for (EffectKind kind : effects)
    names += (names.empty() ? "" : " + ") + effectName(kind);
  return names;
}
/// The diagnosed model's effects that SUMO carries, refitted on all the group's runs (warm from the
/// base fit) without the ones it lacks: a model of its own, where the diagnosed fit stripped of an
/// effect would be neither model. Nothing when no effect is carried or the fit runs away.
std::optional<SumoExport> carriedPartExport(const std::string& id, const CampaignGroup& group, const GroupResult& result,
                                            const LinkEvidence& link, const ObservedAccelerationLimits& limits)
{
  std::vector<EffectKind> carried;
  std::copy_if(link.diagnosed.effects.begin(), link.diagnosed.effects.end(), std::back_inserter(carried), sumoCarries);
  if (carried.empty())
    return std::nullopt;
  const AugmentedFit fit = fitOnAllRuns({carried, link.diagnosed.objective}, group, result);
  if (fit.diverged)
    return std::nullopt;
  SumoExport out = exportToSumo(id, fit.base, carried, fit.effect_values, limits);
  const std::vector<EffectKind> lost = lostInSumo(link.diagnosed.effects);
  out.caveats.push_back("the platoon diagnosis's model is " + effectList(link.diagnosed.effects) +
                        "; SUMO's ACC cannot carry " + effectList(lost) + ", so this is " + effectList(carried) +
                        " refitted on the car's runs without " + (lost.size() > 1 ? "them" : "it") +
                        ": in SUMO this car passes on less of a hard braking than the diagnosed model (docs/SUMO.md)");
  return out;
}
}  // namespace

std::vector<SumoExport> campaignSumoExports(const CampaignInputs& inputs, const CampaignResult& result)
{
  std::vector<SumoExport> exports;
  for (std::size_t g = 0; g < result.groups.size(); ++g)
  {
    const GroupResult& group = result.groups[g];
    if (!group.fitted())
      continue;
    const std::string id = sumoId(group.vehicle + "_" + group.setting);
    const ObservedAccelerationLimits limits = observedAccelerationLimits(inputs.groups[g].segments());
    SumoExport base = exportToSumo(id, group.identification.calibration.parameters, {}, {}, limits);
    if (group.model_adequacy.assessed && !group.model_adequacy.adequate)
      base.caveats.push_back("the base model is " + describeAdequacy(group.model_adequacy));
    const LinkEvidence* link = g < result.links.size() ? &result.links[g] : nullptr;
    const bool diagnosed = link != nullptr && link->diagnosed_available && !link->diagnosed.effects.empty();
    if (!diagnosed)
    {
      exports.push_back(base);
      continue;
    }
    const std::vector<EffectKind> lost = lostInSumo(link->diagnosed.effects);
    if (lost.empty())
    {
      exports.push_back(base);
      exports.push_back(exportToSumo(id + "_diagnosed", link->diagnosed_fit.base, link->diagnosed.effects,
                                     link->diagnosed_fit.effect_values, limits));
      continue;
    }
    base.caveats.push_back("the platoon diagnosis gives this car " + effectList(link->diagnosed.effects) +
                           ", of which SUMO's ACC cannot carry " + effectList(lost) +
                           ": in SUMO it passes on less of a hard braking than the real car "
                           "(docs/PLATOON_DIAGNOSIS.md)");
    exports.push_back(base);
    const std::optional<SumoExport> carried = carriedPartExport(id + "_diagnosed", inputs.groups[g], group, *link, limits);
    if (carried)
      exports.push_back(*carried);
  }
  return exports;
}

}  // namespace acc
