#pragma once

#include <nlohmann/json.hpp>

#include "acc_identification/evidence/clustered_ratio.h"
#include "acc_identification/evidence/dip_shape_transfer.h"
#include "acc_identification/evidence/empirical_response.h"
#include "acc_identification/evidence/pair_dip_evidence.h"

namespace acc
{
/// {perturbations, skipped, ratio_of_means, median_ratio, lower, upper, confidence, verdict
/// ("amplifies" | "attenuates" | "undecided" | "insufficient"), reason}; NaN as null.
nlohmann::json toJson(const DipRatioEstimate& estimate);

/// {ratio, lower, upper, confidence, clusters, observations}; NaN as null.
nlohmann::json toJson(const ClusteredRatio& ratio);

/// {braking: toJson(ratio), recovery: toJson(ratio), median_widening_s, widenings}; NaN as null.
nlohmann::json toJson(const DipShapeTransfer& transfer);

/// {dips: [{run, onset_s, leader_dip_mps, follower_dip_mps, leader_/follower_peak_braking_mps2,
/// _peak_recovery_mps2, _dip_width_s}], dip_ratio: toJson(ratio), shape_passed_on: toJson(shape)}.
nlohmann::json toJson(const PairDipEvidence& evidence);

}  // namespace acc
