#pragma once

#include <cstddef>
#include <vector>

#include "acc_identification/model/acc_parameters.h"

namespace acc
{
/// Every vehicle's speed and gap in a simulated platoon. Vehicle 0 is the lead vehicle (its gap
/// is NaN: nobody is ahead); vehicle i >= 1 is the i-th ACC follower.
struct PlatoonTrajectory
{
  double time_step_s = 0.0;
  std::vector<std::vector<double>> speed_mps;    ///< [vehicle][sample]
  std::vector<std::vector<double>> space_gap_m;  ///< [vehicle][sample]

  std::size_t vehicleCount() const { return speed_mps.size(); }
  std::size_t sampleCount() const { return speed_mps.empty() ? 0 : speed_mps.front().size(); }
};

/// Simulates follower_count identical ACC vehicles behind a lead vehicle whose speed is given at
/// a uniform time step (explicit Euler at that step, as the calibration). Every follower starts
/// at equilibrium with the lead's initial speed: v = u[0], s = eta + tau_e u[0].
PlatoonTrajectory simulatePlatoon(const AccParameters& p, const std::vector<double>& lead_speed_mps,
                                  double time_step_s, std::size_t follower_count);

/// A lead-speed profile that holds cruise_speed_mps, steps down by step_mps at step_down_at_s,
/// and steps back up at step_up_at_s (the paper's Fig. 2 experiment). Samples at time_step_s.
std::vector<double> stepDownUpLeadProfile(double cruise_speed_mps, double step_mps,
                                          double step_down_at_s, double step_up_at_s,
                                          double duration_s, double time_step_s);

/// Minimum over samples of each vehicle's speed (index 0 is the lead).
std::vector<double> minimumSpeedPerVehicle(const PlatoonTrajectory& platoon);

}  // namespace acc
