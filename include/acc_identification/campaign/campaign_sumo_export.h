#pragma once

#include <vector>

#include "acc_identification/campaign/campaign.h"
#include "acc_identification/sumo/sumo_vtype.h"

namespace acc
{
/// The campaign's cars as SUMO vTypes (docs/SUMO.md): one per fitted (vehicle, setting) group,
/// "<VEHICLE>_<setting>", its base model with the group's own acceleration limits; and, where the
/// platoon diagnosis gave the group a model whose every effect SUMO can carry (exactly, or as the
/// reaction delay, approximately), that model too as "<VEHICLE>_<setting>_diagnosed". A diagnosed
/// effect SUMO lacks is a caveat on the base vType instead: exporting a fit without one of its
/// effects would be neither model.
std::vector<SumoExport> campaignSumoExports(const CampaignInputs& inputs, const CampaignResult& result);

}  // namespace acc
