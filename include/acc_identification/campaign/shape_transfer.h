#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "acc_identification/campaign/platoon_check.h"
#include "acc_identification/campaign/platoon_diagnosis.h"
#include "acc_identification/evidence/clustered_ratio.h"

namespace acc
{
// How much of the car ahead's dip shape a car passes on (dipShape): the sum of the car's peak
// braking and recovery rates over the sum of its leader's measured ones, and how much wider its
// dip is at half depth than its leader's (the time it comes back later than it went down, behind
// its leader). Without a model for the cars, and for the pair-level models driven by the same
// real leaders, so all answer the same input. A platoon that passes its leaders' rates on
// unchanged (ratio 1) and adds no width keeps a braking's shape from car to car; one that cuts
// the rates and widens the dip smooths it. A model that smooths what the cars keep damps what
// they do not, and that compounds along a chain.

/// One kind of speed's (the cars' or a model's) shape against the car ahead's measured one.
struct ShapePassedOn
{
  ClusteredRatio braking;
  ClusteredRatio recovery;
  /// Median over the car-perturbations of the dip's width at half depth minus the car ahead's [s].
  double median_widening_s = std::numeric_limits<double>::quiet_NaN();
  std::size_t widenings = 0;
};

/// Over the car-perturbations a filter accepts: the cars', the base model's and the diagnosed
/// model's (pair level) shape against the measured one of the car ahead. The ratios' intervals
/// resample perturbations (every car of one perturbation together: they share its input).
struct ShapeTransferSummary
{
  ShapePassedOn cars;
  ShapePassedOn pair_base;
  ShapePassedOn pair_diagnosed;  ///< NaN without diagnosed models
};

/// Scored: positions 2 on with a measured dip above min_dip_mps whose own and leader's measured
/// rate (or width) is known; a model's ratio or median takes the rows where its own is known too
/// (`observations` and `widenings` say how many).
ShapeTransferSummary summarizeShapeTransfer(const std::vector<PlatoonCheck>& platoons, const DipRowFilter& include,
                                            std::size_t replicates, std::uint64_t seed,
                                            double min_dip_mps = kScoredMinDipMps);

}  // namespace acc
