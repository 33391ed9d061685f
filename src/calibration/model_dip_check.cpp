#include "acc_identification/calibration/model_dip_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
double median(std::vector<double> values)
{
  if (values.empty())
    return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// The model's follower speed over the run, NaN from where the simulation diverged.
std::vector<double> modelSpeed(const AccParameters& p, const CarFollowingRun& run)
{
  SimulatedFollower simulated = simulateFollower(p, run);
  if (simulated.diverged)
  {
    for (std::size_t i = simulated.diverged_at_index; i < simulated.speed_mps.size(); ++i)
      simulated.speed_mps[i] = std::numeric_limits<double>::quiet_NaN();
  }
  return simulated.speed_mps;
}
}  // namespace

ModelDipCheck checkModelDips(const AccParameters& p, const std::vector<CarFollowingRun>& runs,
                             const PairDipEvidence& evidence, const PerturbationCriteria& criteria, double min_dip_mps)
{
  ModelDipCheck check;
  std::vector<double> errors;
  double model_sum = 0.0, leader_sum = 0.0;
  for (const CarFollowingRun& run : runs)
  {
    const std::vector<Perturbation> perturbations = findPerturbations(run.time_s, run.leader_speed_mps, criteria);
    if (perturbations.empty() || run.size() < 2)
      continue;
    const std::vector<double> speed = modelSpeed(p, run);
    for (const Perturbation& perturbation : perturbations)
    {
      const std::size_t index = check.model_dips_mps.size();
      const double model_dip = dipDepthMps(run.time_s, speed, perturbation, criteria);
      check.model_dips_mps.push_back(model_dip);
      if (index >= evidence.dips.size())
        continue;  // evidence of other runs or criteria: nothing to compare with
      const PairDip& measured = evidence.dips[index];
      if (std::isfinite(model_dip) && std::isfinite(measured.follower_dip_mps) &&
          measured.follower_dip_mps >= min_dip_mps && std::isfinite(measured.leader_dip_mps))
      {
        errors.push_back(std::fabs(model_dip - measured.follower_dip_mps) / measured.follower_dip_mps);
        model_sum += model_dip;
        leader_sum += measured.leader_dip_mps;
      }
    }
  }
  check.scored = errors.size();
  check.median_abs_dip_error = median(errors);
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
