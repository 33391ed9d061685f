#pragma once

#include <vector>

#include "acc_identification/campaign/campaign.h"
#include "acc_identification/sumo/sumo_vtype.h"

namespace acc
{
/// The campaign's cars as SUMO vTypes (docs/SUMO.md): one per fitted (vehicle, setting) group,
/// "<VEHICLE>_<setting>", its base model with the group's own acceleration limits; and, where the
/// platoon diagnosis gave the group a model, "<VEHICLE>_<setting>_diagnosed": that model when SUMO
/// can carry its every effect (exactly, or as the reaction delay, approximately), else the effects
/// it carries refitted on the group's runs without the others (a caveat on both vTypes names what
/// is lost). Exporting the diagnosed fit stripped of an effect would be neither model.
std::vector<SumoExport> campaignSumoExports(const CampaignInputs& inputs, const CampaignResult& result);

}  // namespace acc
