#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "acc_identification/evidence/clustered_ratio.h"
#include "acc_identification/evidence/perturbation.h"

namespace acc
{
// How much of its leader's dip shape (dipShape) a follower passes on: the sum of its peak braking
// and recovery rates over the sum of its leader's, and how much wider its dip is at half depth
// than its leader's (the time it comes back later than it went down, behind its leader). A car
// that passes its leader's rates on unchanged (ratio 1) and adds no width keeps a braking's shape;
// one that cuts the rates and widens the dip smooths it. The same measure serves a pair's
// perturbations (calibrate) and the cars of a platoon and their models (campaign).

/// One follower in one perturbation: the shape judged (the car's measured one, or a model's
/// prediction of it), the car's measured shape (what is known of the car decides what is scored),
/// and its leader's measured shape. `cluster` groups observations that share an input (every car
/// of one perturbation of a platoon).
struct DipShapeObservation
{
  std::size_t cluster = 0;
  DipShape judged;
  DipShape measured;
  DipShape leader;
};

struct DipShapeTransfer
{
  ClusteredRatio braking;
  ClusteredRatio recovery;
  /// Median over the observations of the judged width at half depth minus the leader's [s].
  double median_widening_s = std::numeric_limits<double>::quiet_NaN();
  std::size_t widenings = 0;
};

/// Each measure over the observations where the leader's and the car's measured value and the
/// judged one are known (a leader's rate must be positive); the ratios' intervals weigh whole
/// clusters (clusteredRatioOfSums: every weight pattern up to seven clusters, else `replicates`
/// drawn from `seed`).
DipShapeTransfer dipShapeTransfer(const std::vector<DipShapeObservation>& observations, std::size_t replicates,
                                  std::uint64_t seed);

}  // namespace acc
