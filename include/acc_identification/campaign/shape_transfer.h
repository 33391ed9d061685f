#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "acc_identification/campaign/platoon_check.h"
#include "acc_identification/campaign/platoon_diagnosis.h"
#include "acc_identification/evidence/dip_shape_transfer.h"

namespace acc
{
/// How much of the car ahead's dip shape the cars of the platoons pass on (dipShapeTransfer), over
/// the car-perturbations a filter accepts: the cars', the base model's and the diagnosed model's
/// (pair level: driven by the same real leaders, so all three answer the same input), each
/// against the measured shape of the car ahead. The ratios' intervals weigh whole perturbations
/// (every car of one perturbation together: they share its input). A model that smooths what the
/// cars keep damps what they do not, and that compounds along a chain.
struct ShapeTransferSummary
{
  DipShapeTransfer cars;
  DipShapeTransfer pair_base;
  DipShapeTransfer pair_diagnosed;  ///< NaN without diagnosed models
  /// The dips themselves: the summed dips over the summed measured dips of the cars ahead (each
  /// above kMinLeaderDipMps), with the same interval. Under 1 the place damps a braking as it passes
  /// it on, over 1 it amplifies it: for the cars, what the platoons did without any model; for the
  /// models, what they predict driven by the same real leaders.
  ClusteredRatio dip_cars, dip_pair_base, dip_pair_diagnosed;
  /// The models against the cars, paired perturbation by perturbation: the summed model dip less
  /// the car's over the summed dips of the cars ahead (where the model predicted the car), with the
  /// same interval, of either sign. Below 0 the model passes on less of each dip than the car did.
  ClusteredRatio dip_pair_base_less_cars, dip_pair_diagnosed_less_cars;
};

/// Scored: positions 2 on with a measured dip above min_dip_mps (dipShapeTransfer says which
/// measures of each are known).
ShapeTransferSummary summarizeShapeTransfer(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include,
                                            std::size_t replicates, std::uint64_t seed,
                                            double min_dip_mps = kScoredMinDipMps);

}  // namespace acc
