#include "acc_identification/calibration/model_dip_check.h"

#include <cmath>
#include <cstdio>

#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
/// The model's follower speed over the run, NaN from where the simulation diverged.
std::vector<double> modelSpeed(const AccParameters& p, const CarFollowingRun& run)
{
  return scorable(simulateFollower(p, run)).speed_mps;
}
}  // namespace

ModelDipCheck checkModelDips(const AccParameters& p, const std::vector<CarFollowingRun>& runs,
                             const PairDipEvidence& evidence, const PerturbationCriteria& criteria, double min_dip_mps)
{
  ModelDipCheck check;
  std::vector<double> errors;
  double model_sum = 0.0, leader_sum = 0.0;
  std::vector<std::vector<double>> speeds(runs.size());  // each run simulated once, when it has a dip
  for (const PairDip& measured : evidence.dips)
  {
    if (measured.run_index >= runs.size())
    {
      check.model_dips_mps.push_back(std::numeric_limits<double>::quiet_NaN());  // not a run given here
      continue;
    }
    const CarFollowingRun& run = runs[measured.run_index];
    std::vector<double>& speed = speeds[measured.run_index];
    if (speed.empty())
      speed = modelSpeed(p, run);
    const double model_dip = dipDepthMps(run.time_s, speed, measured.perturbation, criteria);
    check.model_dips_mps.push_back(model_dip);
    if (std::isfinite(model_dip) && std::isfinite(measured.follower_dip_mps) &&
        measured.follower_dip_mps >= min_dip_mps && std::isfinite(measured.leader_dip_mps))
    {
      errors.push_back(std::fabs(model_dip - measured.follower_dip_mps) / measured.follower_dip_mps);
      model_sum += model_dip;
      leader_sum += measured.leader_dip_mps;
    }
  }
  check.scored = errors.size();
  check.median_abs_dip_error = finiteMedian(errors);
  if (leader_sum > 0.0)
    check.model_ratio_of_means = model_sum / leader_sum;
  return check;
}

std::string verdictContradiction(const std::string& verdict, const PairDipEvidence& evidence)
{
  const DipRatioEstimate& r = evidence.ratio;
  char line[320];
  if (verdict == "stable" && r.amplifies == DipAmplification::Amplifies)
  {
    std::snprintf(line, sizeof line,
                  "the verdict says stable, but the car amplified its leader's dips (ratio %.2f, %.0f %% interval "
                  "[%.2f, %.2f] over %zu perturbations): for that input the data show an amplification the "
                  "verdict's model does not",
                  r.ratio_of_means, 100.0 * r.confidence, r.lower, r.upper, r.count);
    return line;
  }
  return "";
}

}  // namespace acc
