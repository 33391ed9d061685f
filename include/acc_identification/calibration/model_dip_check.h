#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "acc_identification/evidence/pair_dip_evidence.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// The fitted model against the dips the data show (issue 23: a model fitted well on average can
/// be wrong where it matters; whole-run RMSE barely sees a 3-second braking). Each run is
/// simulated from its measured start with the real leader, as the fit is, and the model's dip in
/// every perturbation of pairDipEvidence() is set beside the follower's measured one.
struct ModelDipCheck
{
  /// One per evidence.dips entry, in its order: the model's follower dip [m/s] (NaN where the
  /// simulation diverged before the dip).
  std::vector<double> model_dips_mps;
  std::size_t scored = 0;  ///< perturbations with a measured follower dip of at least min_dip_mps
  /// Median over them of |model dip - measured dip| / measured dip (NaN when none).
  double median_abs_dip_error = std::numeric_limits<double>::quiet_NaN();
  /// sum of model dips / sum of leader dips over the scored perturbations: the model's answer to
  /// the question the data's dip_ratio answers (NaN when none).
  double model_ratio_of_means = std::numeric_limits<double>::quiet_NaN();
};

/// The check of p on `runs`, whose dips `evidence` holds (pairDipEvidence of the same runs and
/// criteria: its perturbations are taken as found there, each run simulated once). Dips below
/// min_dip_mps are within GNSS noise and driving jitter: not scored.
ModelDipCheck checkModelDips(const AccParameters& p, const std::vector<CarFollowingRun>& runs,
                             const PairDipEvidence& evidence, const PerturbationCriteria& criteria = {},
                             double min_dip_mps = 0.3);

/// When the model's verdict and the data's own dips disagree on the direction, the sentence that
/// says so (empty otherwise): a verdict "stable" from a model while the car amplified its
/// leader's dips beyond their interval is contradicted by the data for that input.
std::string verdictContradiction(const std::string& verdict, const PairDipEvidence& evidence);

}  // namespace acc
