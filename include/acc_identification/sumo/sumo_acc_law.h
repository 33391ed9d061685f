#pragma once

#include <string>

namespace acc
{
/// SUMO's ACC car-following model (carFollowModel="ACC", MSCFModel_ACC) as SUMO 1.15, the version
/// Debian 12 ships, implements it; read from its source and checked against the sumo binary
/// (test_sumo: equilibrium gaps at 8, 12 and 20 m/s, and the replays of docs/SUMO.md). The law:
///   gap2pred = bumper-to-bumper gap - minGap          (what SUMO hands the model)
///   gap2pred > 120 m: speed control   a = speedControlGain (v - v_des)
///   gap2pred < 100 m: gap control, with the spacing error
///       e = gap2pred - tau v - length - d0(v),  d0 = 2 m (v < 10.8), 75/v - 5 (10.8 <= v <= 15), 0
///     |e| < 0.2 and |v - v_des| < 0.1: gap mode         a = gapControlGainSpeed (u - v) + gapControlGainSpace e
///     e < 0:                           collision avoid.  a = collisionAvoidanceGainSpeed (u - v) + ...GainSpace e
///     otherwise:                       gap closing      a = gapClosingControlGainSpeed (u - v) + ...GainSpace e
///   in between (100-120 m): the mode of the previous step
/// then v_next = max(0, v + a h), bounded by accel and (emergency) decel, and by vSafe +
/// collisionAvoidanceOverride when SUMO's own safe speed is lower (not modelled here: the replay
/// counts the steps where SUMO departs from this law instead).
/// v_des = min(lane speed limit, the vType's maxSpeed); length is the follower's own vehicle length
/// (SUMO 1.15 subtracts it; later releases no longer do).
struct SumoAccGains
{
  double speed_control_gain_per_s = -0.4;              ///< speedControlGain (SUMO's default)
  double gap_closing_gain_speed_per_s = 0.8;           ///< gapClosingControlGainSpeed
  double gap_closing_gain_space_per_s2 = 0.04;         ///< gapClosingControlGainSpace
  double gap_control_gain_speed_per_s = 0.07;          ///< gapControlGainSpeed
  double gap_control_gain_space_per_s2 = 0.23;         ///< gapControlGainSpace
  double collision_avoidance_gain_speed_per_s = 0.23;  ///< collisionAvoidanceGainSpeed
  double collision_avoidance_gain_space_per_s2 = 0.8;  ///< collisionAvoidanceGainSpace
  double collision_avoidance_override_mps = 2.0;       ///< collisionAvoidanceOverride
};

/// The gap above which SUMO's ACC controls speed, and below which it controls the gap [m of gap2pred].
constexpr double kSumoAccSpeedControlGapM = 120.0;
constexpr double kSumoAccGapControlGapM = 100.0;
/// Thresholds of SUMO's gap mode: |spacing error| and |v - v_des| below these.
constexpr double kSumoAccGapModeSpacingM = 0.2;
constexpr double kSumoAccGapModeSpeedMps = 0.1;

/// The mode SUMO's ACC applies in a step.
enum class SumoAccMode
{
  speed_control,
  gap_control,          ///< "gap mode": at the desired gap and the desired speed
  gap_closing,          ///< spacing error >= 0
  collision_avoidance,  ///< spacing error < 0
};

std::string toString(SumoAccMode mode);

/// Xiao et al.'s (2018) dynamic gap margin d0(v) as SUMO 1.15 adds it to the desired gap [m].
double sumoAccGapMargin(double speed_mps);

/// One step of SUMO's ACC law (before SUMO's speed bounds).
struct SumoAccCommand
{
  double acceleration_mps2 = 0.0;
  SumoAccMode mode = SumoAccMode::speed_control;
  double spacing_error_m = 0.0;  ///< e above (NaN in speed control)
};

/// The state the law reads: SUMO's gap2pred, the follower's own speed and length, the leader's
/// speed, the desired speed, and the mode of the previous step (for the 100-120 m band; SUMO
/// starts a vehicle in speed control).
struct SumoAccState
{
  double gap2pred_m = 0.0;
  double speed_mps = 0.0;
  double leader_speed_mps = 0.0;
  double desired_speed_mps = 0.0;
  double length_m = 0.0;
  SumoAccMode previous_mode = SumoAccMode::speed_control;
};

SumoAccCommand sumoAccCommand(const SumoAccGains& gains, double tau_s, const SumoAccState& state);

}  // namespace acc
