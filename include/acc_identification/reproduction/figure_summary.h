#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "acc_identification/model/paper_settings.h"
#include "acc_identification/reproduction/platoon_responses.h"

namespace acc
{
/// A parameter set as the figures' summaries give it: its name, source, the four parameters and
/// its string-stability analysis (lambda2 "inf" when infinite, verdict, amplified band, peak).
nlohmann::json settingSummaryJson(const NamedSetting& setting);

/// A platoon's response to a lead disturbance: per vehicle, and where growth starts by each measure.
nlohmann::json disturbanceJson(const DisturbanceResponse& response);

/// "decays first, smallest at follower 3, grows behind it, exceeds the lead's from follower 9".
std::string onsetText(const GrowthOnset& onset);

}  // namespace acc
