#include "acc_identification/sumo/sumo_acc_law.h"

#include <cmath>
#include <limits>

namespace acc
{
std::string toString(SumoAccMode mode)
{
  switch (mode)
  {
    case SumoAccMode::speed_control:
      return "speed_control";
    case SumoAccMode::gap_control:
      return "gap_control";
    case SumoAccMode::gap_closing:
      return "gap_closing";
    case SumoAccMode::collision_avoidance:
      return "collision_avoidance";
  }
  return "unknown";
}

double sumoAccGapMargin(double speed_mps)
{
  // MSCFModel_ACC::accelGapControl of SUMO 1.15, branch for branch (the ramp is continuous at 15
  // m/s and jumps by 0.06 m at 10.8 m/s).
  if (speed_mps < 10.8)
    return 2.0;
  if (speed_mps <= 15.0)
    return 75.0 / speed_mps - 5.0;
  return 0.0;
}

namespace
{
SumoAccCommand gapControlCommand(const SumoAccGains& gains, double tau_s, const SumoAccState& state)
{
  SumoAccCommand command;
  const double speed_error_mps = state.speed_mps - state.desired_speed_mps;
  const double closing_speed_mps = state.leader_speed_mps - state.speed_mps;
  command.spacing_error_m =
      state.gap2pred_m - tau_s * state.speed_mps - state.length_m - sumoAccGapMargin(state.speed_mps);
  double gain_speed = 0.0, gain_space = 0.0;
  if (std::abs(command.spacing_error_m) < kSumoAccGapModeSpacingM && std::abs(speed_error_mps) < kSumoAccGapModeSpeedMps)
  {
    command.mode = SumoAccMode::gap_control;
    gain_speed = gains.gap_control_gain_speed_per_s;
    gain_space = gains.gap_control_gain_space_per_s2;
  }
  else if (command.spacing_error_m < 0.0)
  {
    command.mode = SumoAccMode::collision_avoidance;
    gain_speed = gains.collision_avoidance_gain_speed_per_s;
    gain_space = gains.collision_avoidance_gain_space_per_s2;
  }
  else
  {
    command.mode = SumoAccMode::gap_closing;
    gain_speed = gains.gap_closing_gain_speed_per_s;
    gain_space = gains.gap_closing_gain_space_per_s2;
  }
  command.acceleration_mps2 = gain_speed * closing_speed_mps + gain_space * command.spacing_error_m;
  return command;
}

SumoAccCommand speedControlCommand(const SumoAccGains& gains, const SumoAccState& state)
{
  SumoAccCommand command;
  command.mode = SumoAccMode::speed_control;
  command.spacing_error_m = std::numeric_limits<double>::quiet_NaN();
  command.acceleration_mps2 = gains.speed_control_gain_per_s * (state.speed_mps - state.desired_speed_mps);
  return command;
}
}  // namespace

SumoAccCommand sumoAccCommand(const SumoAccGains& gains, double tau_s, const SumoAccState& state)
{
  if (state.gap2pred_m > kSumoAccSpeedControlGapM)
    return speedControlCommand(gains, state);
  if (state.gap2pred_m < kSumoAccGapControlGapM)
    return gapControlCommand(gains, tau_s, state);
  // Between the two thresholds SUMO keeps the law of the step before (hysteresis).
  return state.previous_mode == SumoAccMode::speed_control ? speedControlCommand(gains, state)
                                                           : gapControlCommand(gains, tau_s, state);
}

}  // namespace acc
