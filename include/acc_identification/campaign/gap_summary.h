#pragma once

#include <string>
#include <vector>

#include "acc_identification/campaign/platoon_check.h"
#include "acc_identification/campaign/platoon_diagnosis.h"

namespace acc
{
/// One row of "how far the gap shrinks": one kind of prediction (or the part of one a filter
/// keeps) against what the cars did.
struct GapSummary
{
  std::string key;    ///< its name in the campaign's JSON (chain_base, ...)
  std::string label;  ///< its row in the text and the report
  DipPredictionSummary summary;
};

/// Every row, in the order the report prints them: the base and diagnosed platoons, the base and
/// diagnosed pairs, the diagnosed pairs split into first followers and cars further back, and the
/// two references without a model. Each summary carries the two target scores' intervals, which
/// cost far more than the scores, so a campaign computes them once (runCampaign) and every output
/// prints them.
std::vector<GapSummary> summarizeGap(const std::vector<PlatoonCheck>& platoons);

}  // namespace acc
