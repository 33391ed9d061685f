#pragma once

#include <cstddef>
#include <vector>

#include "acc_identification/sumo/sumo_acc_law.h"
#include "acc_identification/sumo/sumo_vtype.h"

namespace acc
{
/// What SUMO 1.15 does with one ACC car in a replay, step by step, in the package: SUMO's ACC law
/// (sumo_acc_law.h), its speed bounds (accel, emergencyDecel, the desired speed) and its Euler
/// step (the position moves by the NEW speed, the package's recursion by the old one). What it
/// leaves out is SUMO's own safe-speed override; a replay counts the steps where SUMO departs from
/// this, so that every difference between SUMO and the identified model is assigned a cause.
struct SumoAccTrace
{
  std::vector<double> speed_mps;
  std::vector<double> space_gap_m;       ///< bumper to bumper
  std::vector<SumoAccMode> mode;         ///< the law's mode at each step (the last sample repeats)
  std::vector<bool> speed_bound_active;  ///< accel, emergencyDecel or the desired speed cut the law's speed
};

/// The car of vtype behind a leader with the given speeds (uniform step), started at gap s0 and
/// speed v0; lane_speed_limit_mps as in the replay's road.
SumoAccTrace simulateSumoAcc(const SumoAccVType& vtype, const std::vector<double>& leader_speed_mps, double step_s,
                             double initial_gap_m, double initial_speed_mps, double lane_speed_limit_mps);

/// The step of SUMO's ACC from (gap, v) behind a leader at u: the speed after SUMO's bounds, and
/// the law's mode; used by simulateSumoAcc and to classify SUMO's own steps in a replay.
struct SumoAccStep
{
  double next_speed_mps = 0.0;
  SumoAccMode mode = SumoAccMode::speed_control;
  bool speed_bound_active = false;
};
SumoAccStep sumoAccStep(const SumoAccVType& vtype, double gap_m, double speed_mps, double leader_speed_mps,
                        SumoAccMode previous_mode, double step_s, double lane_speed_limit_mps);

/// How many simulation steps of step_s one action step of the vType spans (1 without an
/// actionStepLength): SUMO decides at the first step and every that many after. Like SUMO, in
/// whole milliseconds and rounded down where the action step is not a multiple of the step.
std::size_t sumoActionEvery(const SumoAccVType& vtype, double step_s);

/// A step between two action steps: SUMO keeps the acceleration it decided (speed not below 0).
SumoAccStep heldStep(double speed_mps, double held_acceleration_mps2, SumoAccMode mode, double step_s);

}  // namespace acc
