#include "acc_identification/campaign/campaign_sumo_export.h"

#include <algorithm>

namespace acc
{
namespace
{
bool sumoCarriesEvery(const std::vector<EffectKind>& effects)
{
  return std::all_of(effects.begin(), effects.end(), [](EffectKind kind) {
    return kind == EffectKind::asymmetric_response || kind == EffectKind::acceleration_limits ||
           kind == EffectKind::set_speed_cruise || kind == EffectKind::reaction_delay;
  });
}

std::string effectList(const std::vector<EffectKind>& effects)
{
  std::string names;
  for (EffectKind kind : effects)
    names += (names.empty() ? "" : " + ") + effectName(kind);
  return names;
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
    if (diagnosed && !sumoCarriesEvery(link->diagnosed.effects))
      base.caveats.push_back("the platoon diagnosis gives this car " + effectList(link->diagnosed.effects) +
                             ", which SUMO's ACC cannot carry: in SUMO it passes on less of a hard braking than "
                             "the real car (docs/PLATOON_DIAGNOSIS.md)");
    exports.push_back(base);
    if (diagnosed && sumoCarriesEvery(link->diagnosed.effects))
      exports.push_back(exportToSumo(id + "_diagnosed", link->diagnosed_parameters, link->diagnosed.effects,
                                     link->diagnosed_effect_values, limits));
  }
  return exports;
}

}  // namespace acc
