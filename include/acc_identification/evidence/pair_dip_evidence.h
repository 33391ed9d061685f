#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "acc_identification/evidence/dip_shape_transfer.h"
#include "acc_identification/evidence/empirical_response.h"
#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// One perturbation of a pair run: its leader's dip and what the follower made of it.
struct PairDip
{
  std::string run;          ///< the run's name
  std::size_t run_index = 0;  ///< the run's index among the runs given
  Perturbation perturbation;  ///< where it lies in that run (sample indices)
  double onset_s = 0.0;     ///< time of the leader's onset (the run's clock)
  double leader_dip_mps = 0.0;
  double follower_dip_mps = 0.0;
  DipShape leader_shape;    ///< how steep and how wide each dip is (dipShape)
  DipShape follower_shape;
};

/// What the data of leader-follower runs say of string stability without any model: every
/// perturbation of each run's leader (findPerturbations on its leader speed), the two cars' dips
/// (dipDepthMps), and the ratio follower dip / leader dip over them with its bootstrap interval
/// (linkDipRatio). A follower whose ratio's interval lies above 1 amplified the dips it was given:
/// for that input the pair is string unstable, whatever a fitted model says; one whose interval
/// lies below 1 damped them. Nothing is said with fewer than two usable perturbations.
struct PairDipEvidence
{
  std::vector<PairDip> dips;    ///< every perturbation found, in run order
  DipRatioEstimate ratio;       ///< over the dips (skips counted in it)
  /// How much of its leader's dip shape the follower passes on (one cluster per perturbation): a
  /// car that cuts a steep braking or recovery, or comes back later than it went down, smooths it.
  DipShapeTransfer shape;
};

/// The dips of runs whose leader perturbs (pair runs: each run's leader is the car ahead), with
/// the ratio's interval from `replicates` bootstrap draws seeded with `seed`. Runs without a
/// perturbation add nothing. Never throws on data: NaN samples are skipped by the detector.
PairDipEvidence pairDipEvidence(const std::vector<CarFollowingRun>& runs, const PerturbationCriteria& criteria = {},
                                std::size_t replicates = 1999, std::uint64_t seed = 20240601);

}  // namespace acc
