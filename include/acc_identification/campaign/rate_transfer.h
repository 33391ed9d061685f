#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "acc_identification/campaign/platoon_check.h"
#include "acc_identification/campaign/platoon_diagnosis.h"
#include "acc_identification/evidence/clustered_ratio.h"

namespace acc
{
// How much of the car ahead's braking and recovery a car passes on (dipShape): the sum of the
// car's peak rates over the sum of its leader's measured ones. Without a model for the cars, and
// for the pair-level models driven by the same real leaders, so the two answer the same input.
// A platoon that passes its leaders' rates on unchanged (ratio 1) keeps a braking's shape from
// car to car, one that cuts them smooths it; a model that cuts what the cars pass on damps what
// they do not, and that compounds along a chain.

/// One kind of speed's ratios: braking and recovery.
struct RatesPassedOn
{
  ClusteredRatio braking;
  ClusteredRatio recovery;
};

/// Over the car-perturbations a filter accepts: the cars', the base model's and the diagnosed
/// model's (pair level) ratios to the measured rates of the car ahead. The intervals resample
/// perturbations (every car of one perturbation together: they share its input).
struct RateTransferSummary
{
  RatesPassedOn cars;
  RatesPassedOn pair_base;
  RatesPassedOn pair_diagnosed;  ///< NaN without diagnosed models
};

/// Scored: positions 2 on with a measured dip above min_dip_mps whose own and leader's measured
/// rates are known; a model's ratio sums the rows where its rates are known too (its
/// `observations` say how many).
RateTransferSummary summarizeRateTransfer(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include,
                                          std::size_t replicates, std::uint64_t seed,
                                          double min_dip_mps = kScoredMinDipMps);

}  // namespace acc
