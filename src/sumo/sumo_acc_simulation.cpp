#include "acc_identification/sumo/sumo_acc_simulation.h"

#include <algorithm>
#include <cmath>

namespace acc
{
SumoAccStep sumoAccStep(const SumoAccVType& vtype, double gap_m, double speed_mps, double leader_speed_mps,
                        SumoAccMode previous_mode, double step_s, double lane_speed_limit_mps)
{
  const double desired_speed_mps =
      std::isfinite(vtype.max_speed_mps) ? std::min(lane_speed_limit_mps, vtype.max_speed_mps) : lane_speed_limit_mps;
  SumoAccState state;
  state.gap2pred_m = gap_m - vtype.min_gap_m;
  state.speed_mps = speed_mps;
  state.leader_speed_mps = leader_speed_mps;
  state.desired_speed_mps = desired_speed_mps;
  state.length_m = vtype.length_m;
  state.previous_mode = previous_mode;
  const SumoAccCommand command = sumoAccCommand(vtype.gains, vtype.tau_s, state);
  const double wanted_mps = std::max(0.0, speed_mps + command.acceleration_mps2 * step_s);
  // MSCFModel::finalizeSpeed: never above v + accel h nor the desired speed, never below
  // v - emergencyDecel h (an ACC command may brake harder than decel, down to that).
  const double highest_mps = std::min(speed_mps + vtype.accel_mps2 * step_s, desired_speed_mps);
  const double lowest_mps = std::max(0.0, speed_mps - vtype.emergency_decel_mps2 * step_s);
  SumoAccStep step;
  step.next_speed_mps = std::clamp(wanted_mps, lowest_mps, std::max(lowest_mps, highest_mps));
  step.mode = command.mode;
  step.speed_bound_active = step.next_speed_mps != wanted_mps;
  return step;
}

std::size_t sumoActionEvery(const SumoAccVType& vtype, double step_s)
{
  if (!(vtype.action_step_length_s > step_s))
    return 1;
  // As SUMO: times in whole milliseconds, an action step not a multiple of the step rounded DOWN
  // to one (0.9 s at 0.2 s steps acts every 0.8 s; rounding to the nearest once made the replica
  // act every 1.0 s and blame the difference on SUMO's safe speed).
  const long long action_ms = std::llround(vtype.action_step_length_s * 1000.0);
  const long long step_ms = std::llround(step_s * 1000.0);
  return static_cast<std::size_t>(std::max(1LL, action_ms / std::max(1LL, step_ms)));
}

SumoAccStep heldStep(double speed_mps, double held_acceleration_mps2, SumoAccMode mode, double step_s)
{
  SumoAccStep step;
  step.next_speed_mps = std::max(0.0, speed_mps + held_acceleration_mps2 * step_s);
  step.mode = mode;
  return step;
}

SumoAccTrace simulateSumoAcc(const SumoAccVType& vtype, const std::vector<double>& leader_speed_mps, double step_s,
                             double initial_gap_m, double initial_speed_mps, double lane_speed_limit_mps)
{
  const std::size_t n = leader_speed_mps.size();
  SumoAccTrace trace;
  trace.speed_mps.resize(n);
  trace.space_gap_m.resize(n);
  trace.mode.resize(n, SumoAccMode::speed_control);
  trace.speed_bound_active.resize(n, false);
  if (n == 0)
    return trace;
  trace.speed_mps[0] = initial_speed_mps;
  trace.space_gap_m[0] = initial_gap_m;
  SumoAccMode mode = SumoAccMode::speed_control;  // SUMO starts every ACC in speed control
  const std::size_t every = sumoActionEvery(vtype, step_s);
  double held_acceleration_mps2 = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k)
  {
    SumoAccStep step;
    if (k % every == 0)
    {
      step = sumoAccStep(vtype, trace.space_gap_m[k], trace.speed_mps[k], leader_speed_mps[k], mode, step_s,
                         lane_speed_limit_mps);
      held_acceleration_mps2 = (step.next_speed_mps - trace.speed_mps[k]) / step_s;
    }
    else
    {
      step = heldStep(trace.speed_mps[k], held_acceleration_mps2, mode, step_s);
    }
    mode = step.mode;
    trace.mode[k] = step.mode;
    trace.speed_bound_active[k] = step.speed_bound_active;
    trace.speed_mps[k + 1] = step.next_speed_mps;
    // SUMO's Euler update moves both cars by their new speeds.
    trace.space_gap_m[k + 1] = trace.space_gap_m[k] + step_s * (leader_speed_mps[k + 1] - step.next_speed_mps);
  }
  trace.mode[n - 1] = trace.mode[n > 1 ? n - 2 : 0];
  return trace;
}

}  // namespace acc
