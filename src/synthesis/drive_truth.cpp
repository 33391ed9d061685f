#include "acc_identification/synthesis/drive_truth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
/// values (sampled every step_s from 0) at time t by linear interpolation, held outside.
double sampleAt(const std::vector<double>& values, double step_s, double t)
{
  const double position = t / step_s;
  if (position <= 0.0)
    return values.front();
  const std::size_t i = static_cast<std::size_t>(position);
  if (i + 1 >= values.size())
    return values.back();
  const double w = position - static_cast<double>(i);
  return values[i] + w * (values[i + 1] - values[i]);
}

/// What the leader's receiver tags with time t when its clock is offset_s ahead of the truth:
/// the truth at t - offset (the diagnosis's sensor_time_offset, recorded(t) = true(t - delta)).
std::vector<double> recordedLeaderSpeed(const std::vector<double>& lead_speed_mps, double step_s, double offset_s)
{
  if (offset_s == 0.0)
    return lead_speed_mps;
  std::vector<double> recorded(lead_speed_mps.size());
  for (std::size_t k = 0; k < recorded.size(); ++k)
    recorded[k] = sampleAt(lead_speed_mps, step_s, static_cast<double>(k) * step_s - offset_s);
  return recorded;
}

/// The fine run the truth is simulated on: kDriveTruthSubsteps steps per data step, the lead
/// linearly interpolated between its samples (the continuous lead the samples stand for), the
/// leader columns as its receiver records them, the follower in equilibrium at the start.
CarFollowingRun fineTruth(const std::vector<double>& lead_speed_mps, double step_s, const AccParameters& parameters,
                          const EffectSettings& effects)
{
  const double fine_step_s = step_s / static_cast<double>(kDriveTruthSubsteps);
  const std::size_t fine_n = (lead_speed_mps.size() - 1) * kDriveTruthSubsteps + 1;
  CarFollowingRun fine;
  std::vector<double> lead(fine_n);
  for (std::size_t j = 0; j < fine_n; ++j)
  {
    fine.time_s.push_back(static_cast<double>(j) * fine_step_s);
    // By index, not by time: at the epochs the lead is its own sample to the bit.
    const std::size_t i = j / kDriveTruthSubsteps, part = j % kDriveTruthSubsteps;
    const double w = static_cast<double>(part) / static_cast<double>(kDriveTruthSubsteps);
    lead[j] = part == 0 ? lead_speed_mps[i] : lead_speed_mps[i] + w * (lead_speed_mps[i + 1] - lead_speed_mps[i]);
  }
  fine.leader_speed_mps = recordedLeaderSpeed(lead, fine_step_s, effects.sensor_time_offset_s);
  // Start in equilibrium behind the lead's initial speed; the simulator takes the recorded gap,
  // which is the true one less the distance the leader covers during the clock offset.
  const double v0 = lead_speed_mps.front();
  const double true_gap0 = parameters.eta_m + parameters.tau_e_s * v0 + effects.time_gap_speed_slope_s2_per_m * v0 * v0;
  fine.space_gap_m.assign(fine_n, true_gap0 - effects.sensor_time_offset_s * v0);
  fine.follower_speed_mps.assign(fine_n, v0);
  return fine;
}
}  // namespace

DriveTruth simulateDriveTruth(const std::vector<double>& lead_speed_mps, double step_s, const AccParameters& parameters,
                              const EffectSettings& effects, double start_distance_m)
{
  if (lead_speed_mps.size() < 2)
    throw std::invalid_argument("the lead profile needs at least two samples");
  if (!(step_s > 0.0))
    throw std::invalid_argument("the time step must be positive");
  const std::size_t n = lead_speed_mps.size();
  const CarFollowingRun fine = fineTruth(lead_speed_mps, step_s, parameters, effects);
  const SimulatedFollower follower = simulateFollower(parameters, effects, fine);

  // The receivers' epochs: every kDriveTruthSubsteps-th fine sample.
  DriveTruth truth;
  CarFollowingRun& run = truth.run;
  run.name = "synthetic";
  truth.diverged = follower.diverged;
  truth.follower_front_bumper_m.resize(n);
  truth.leader_rear_bumper_m.resize(n);
  const double fine_step_s = step_s / static_cast<double>(kDriveTruthSubsteps);
  double position_m = start_distance_m;
  for (std::size_t j = 0; j < fine.size(); ++j)
  {
    if (j % kDriveTruthSubsteps == 0)
    {
      const std::size_t k = j / kDriveTruthSubsteps;
      run.time_s.push_back(static_cast<double>(k) * step_s);
      run.leader_speed_mps.push_back(fine.leader_speed_mps[j]);
      run.follower_speed_mps.push_back(follower.speed_mps[j]);
      run.space_gap_m.push_back(follower.space_gap_m[j]);
      truth.follower_front_bumper_m[k] = position_m;
      truth.leader_rear_bumper_m[k] = position_m + follower.space_gap_m[j];
    }
    position_m += fine_step_s * follower.speed_mps[j];  // the fine simulation's own Euler step
  }
  return truth;
}

}  // namespace acc
