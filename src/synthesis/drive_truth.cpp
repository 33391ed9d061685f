#include "acc_identification/synthesis/drive_truth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "acc_identification/diagnosis/augmented_simulation.h"

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
}  // namespace

DriveTruth simulateDriveTruth(const std::vector<double>& lead_speed_mps, double step_s, const AccParameters& parameters,
                              const EffectSettings& effects, double start_distance_m)
{
  if (lead_speed_mps.size() < 2)
    throw std::invalid_argument("the lead profile needs at least two samples");
  if (!(step_s > 0.0))
    throw std::invalid_argument("the time step must be positive");
  const std::size_t n = lead_speed_mps.size();
  DriveTruth truth;
  CarFollowingRun& run = truth.run;
  run.name = "synthetic";
  run.time_s.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    run.time_s[k] = static_cast<double>(k) * step_s;
  run.leader_speed_mps = recordedLeaderSpeed(lead_speed_mps, step_s, effects.sensor_time_offset_s);

  // Start in equilibrium behind the lead's initial speed; the simulator takes the recorded gap,
  // which is the true one less the distance the leader covers during the clock offset.
  const double v0 = lead_speed_mps.front();
  const double true_gap0 = parameters.eta_m + parameters.tau_e_s * v0 + effects.time_gap_speed_slope_s2_per_m * v0 * v0;
  run.space_gap_m.assign(n, true_gap0 - effects.sensor_time_offset_s * v0);
  run.follower_speed_mps.assign(n, v0);

  const SimulatedFollower follower = simulateAugmentedFollower(parameters, effects, run);
  run.space_gap_m = follower.space_gap_m;
  run.follower_speed_mps = follower.speed_mps;
  truth.diverged = follower.diverged;

  truth.follower_front_bumper_m.resize(n);
  truth.leader_rear_bumper_m.resize(n);
  double position_m = start_distance_m;
  for (std::size_t k = 0; k < n; ++k)
  {
    truth.follower_front_bumper_m[k] = position_m;
    truth.leader_rear_bumper_m[k] = position_m + run.space_gap_m[k];
    position_m += step_s * run.follower_speed_mps[k];  // the simulator's own Euler step
  }
  return truth;
}

}  // namespace acc
