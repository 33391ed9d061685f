#pragma once

#include <cstddef>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// What the two cars really did, sampled at the receivers' epochs, before any GNSS error.
struct DriveTruth
{
  /// The canonical run the receivers would record without error: time from 0, bumper-to-bumper
  /// gap, follower speed, leader speed. With sensor_time_offset the leader columns are the
  /// offset ones (what the leader's receiver tags with its clock), as the diagnosis defines it.
  CarFollowingRun run;
  std::vector<double> follower_front_bumper_m;  ///< distance along the road
  std::vector<double> leader_rear_bumper_m;     ///< = follower_front_bumper_m + run.space_gap_m
  bool diverged = false;                        ///< the follower's simulation blew up
};

/// Explicit-Euler steps of the drive's truth per receiver epoch.
constexpr std::size_t kDriveTruthSubsteps = 10;

/// The follower driven by the lead speed (sampled every step_s from t = 0, linearly interpolated
/// between samples) through the ACC model with the given effects (model/follower_simulation.h):
/// explicit Euler at step_s / kDriveTruthSubsteps, sampled at the receivers' epochs every step_s.
/// Finer than the 10 Hz Euler the paper calibrates with, on purpose: a calibration of the truth
/// must not fit the very recursion that made it (an "inverse crime"), so it recovers the
/// parameters within their standard errors, not exactly. The follower starts at the lead's
/// initial speed at the equilibrium gap eta + tau_e v (+ c v^2 with speed_dependent_time_gap),
/// its front bumper at start_distance_m along the road; positions advance by the fine Euler
/// step of the speed (the same integration as the gap).
/// Throws std::invalid_argument on fewer than two samples or a step that is not positive.
DriveTruth simulateDriveTruth(const std::vector<double>& lead_speed_mps, double step_s, const AccParameters& parameters,
                              const EffectSettings& effects, double start_distance_m);

}  // namespace acc
