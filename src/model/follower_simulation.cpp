#include "acc_identification/model/follower_simulation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "acc_identification/model/acc_model.h"

namespace acc
{
namespace
{
/// Linear interpolation of values(t) at t_query, held constant outside [t_0, t_end]. `cursor` is
/// a search hint for queries that move forward in time (every use here), keeping a pass O(n).
double interpolateForward(const std::vector<double>& time_s, const std::vector<double>& values,
                          std::size_t available, double t_query, std::size_t* cursor)
{
  if (t_query <= time_s[0])
  {
    return values[0];
  }
  if (t_query >= time_s[available - 1])
  {
    return values[available - 1];
  }
  std::size_t i = std::min(*cursor, available - 2);
  while (i > 0 && time_s[i] > t_query)
  {
    --i;
  }
  while (i + 2 < available && time_s[i + 1] <= t_query)
  {
    ++i;
  }
  *cursor = i;
  const double w = (t_query - time_s[i]) / (time_s[i + 1] - time_s[i]);
  return values[i] + w * (values[i + 1] - values[i]);
}

/// The leader speed the ACC really saw at each sample: recorded at t + delta (only made when
/// delta != 0: the paper's model reads the recorded speeds in place).
std::vector<double> shiftedLeaderSpeed(const CarFollowingRun& run, double offset_s)
{
  std::vector<double> shifted(run.size());
  std::size_t cursor = 0;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    shifted[k] = interpolateForward(run.time_s, run.leader_speed_mps, run.size(), run.time_s[k] + offset_s, &cursor);
  }
  return shifted;
}

/// The law with the spacing-policy and cruise options, then the actuator's limits.
double commandedAcceleration(const AccParameters& p, const EffectSettings& e, double gap, double speed,
                             double leader_speed, double leader_acceleration)
{
  double command = accelerationMps2(p, gap, speed, leader_speed - speed);
  if (e.leader_acceleration_gain != 0.0)
  {
    command += e.leader_acceleration_gain * leader_acceleration;
  }
  if (e.time_gap_speed_slope_s2_per_m != 0.0)
  {
    command -= p.k1_per_s2 * e.time_gap_speed_slope_s2_per_m * speed * speed;
  }
  if (std::isfinite(e.set_speed_mps))
  {
    command = std::min(command, e.cruise_gain_per_s * (e.set_speed_mps - speed));
  }
  return std::max(-e.max_deceleration_mps2, std::min(e.max_acceleration_mps2, command));
}
}  // namespace

SimulatedFollower simulateFollower(const AccParameters& p, const EffectSettings& e, const CarFollowingRun& run)
{
  const std::size_t n = run.size();
  SimulatedFollower sim;
  sim.speed_mps.resize(n);
  sim.space_gap_m.resize(n);
  if (n == 0)
  {
    return sim;
  }
  const double offset = e.sensor_time_offset_s;
  const std::vector<double> shifted = offset != 0.0 ? shiftedLeaderSpeed(run, offset) : std::vector<double>{};
  const std::vector<double>& leader = offset != 0.0 ? shifted : run.leader_speed_mps;
  // The commands so far, kept only when a reaction delay reads them back.
  const bool delayed = e.reaction_delay_s > 0.0;
  std::vector<double> commands(delayed ? n : 0, 0.0);
  std::size_t delay_cursor = 0;
  double speed = run.follower_speed_mps[0];
  double gap = run.space_gap_m[0] + offset * leader[0];
  double realised = 0.0;
  sim.speed_mps[0] = speed;
  sim.space_gap_m[0] = run.space_gap_m[0];
  for (std::size_t k = 0; k + 1 < n; ++k)
  {
    const double step_s = run.time_s[k + 1] - run.time_s[k];
    const double relative_speed = leader[k] - speed;
    const double leader_acceleration = e.leader_acceleration_gain != 0.0 && k > 0
                                           ? (leader[k] - leader[k - 1]) / (run.time_s[k] - run.time_s[k - 1])
                                           : 0.0;
    const double command = commandedAcceleration(p, e, gap, speed, leader[k], leader_acceleration);
    double applied = command;
    if (delayed)
    {
      commands[k] = command;
      applied = interpolateForward(run.time_s, commands, k + 1, run.time_s[k] - e.reaction_delay_s, &delay_cursor);
    }
    if (e.actuation_lag_s > 0.0 && k > 0)
    {
      realised += (1.0 - std::exp(-step_s / e.actuation_lag_s)) * (applied - realised);
    }
    else
    {
      realised = applied;  // no lag, or the first step: realised equals commanded at the start
    }
    const double next_speed = speed + step_s * realised;
    const double next_gap = gap + step_s * relative_speed;
    if (isRunaway(next_speed, next_gap))
    {
      sim.diverged = true;
      sim.diverged_at_index = k + 1;
      for (std::size_t rest = k + 1; rest < n; ++rest)
      {
        sim.speed_mps[rest] = speed;
        sim.space_gap_m[rest] = gap - offset * leader[rest];
      }
      return sim;
    }
    speed = next_speed;
    gap = next_gap;
    sim.speed_mps[k + 1] = speed;
    sim.space_gap_m[k + 1] = gap - offset * leader[k + 1];
  }
  return sim;
}

}  // namespace acc
