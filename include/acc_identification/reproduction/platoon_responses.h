#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/platoon_simulation.h"
#include "acc_identification/reproduction/platoon_metrics.h"

namespace acc
{
/// The numbers behind the paper's Fig. 7: a platoon in steady oscillation behind a sinusoidal lead.
struct SinusoidResponse
{
  std::vector<double> amplitude_mps;  ///< fitted amplitude per vehicle, index 0 the lead
  double last_to_first_follower = 0.0;  ///< amplitude of follower N over follower 1
  double last_follower_to_lead = 0.0;   ///< amplitude of follower N over the lead
  double model_gain = 0.0;              ///< |Gamma(j w)| of the model
  double euler_gain = 0.0;              ///< |Gamma_h| of the Euler recursion the simulation runs
  /// |Gamma|^N and |Gamma_h|^N for the platoon's N followers: what the linear theory predicts
  /// for follower N over the lead, to compare with last_follower_to_lead.
  double model_gain_over_platoon = 0.0;
  double euler_gain_over_platoon = 0.0;
};

/// Fits each vehicle's amplitude at frequency_rad_s over samples [from_sample, end): choose a
/// window after the start-up transient has died out. Needs at least one follower.
SinusoidResponse measureSinusoidResponse(const PlatoonTrajectory& platoon, const AccParameters& p,
                                         double frequency_rad_s, std::size_t from_sample);

/// The numbers behind the paper's Fig. 8 (and Fig. 2): how a lead disturbance changes along
/// the platoon, measured against the cruise speed the platoon starts from.
struct DisturbanceResponse
{
  double reference_speed_mps = 0.0;
  std::vector<VehicleDisturbance> per_vehicle;  ///< index 0 the lead
  GrowthOnset by_peak_to_peak;  ///< onset read from the peak-to-peak speed
  GrowthOnset by_drop;          ///< onset read from the drop below the cruise speed
  /// First follower whose speed goes negative: from there on the linear model describes no car.
  std::optional<std::size_t> first_negative_speed_vehicle;
  /// The last follower ends within 1% of the lead's peak-to-peak of the lead's final speed:
  /// the record was long enough for the whole disturbance to pass the platoon.
  bool last_follower_settled = false;
};

/// Needs at least one follower.
DisturbanceResponse measureDisturbanceResponse(const PlatoonTrajectory& platoon);

/// The lead and its first `followers` followers (at most all of them): the short platoon of
/// Fig. 8, measured on the same simulation as the long one.
PlatoonTrajectory firstFollowers(const PlatoonTrajectory& platoon, std::size_t followers);

/// How far the last follower of Fig. 2 leaves the lead's speed range after a step down to
/// low_speed_mps and back up to the cruise speed: 0 when it stays within.
struct StepExcursion
{
  double undershoot_below_low_speed_mps = 0.0;
  double overshoot_above_cruise_mps = 0.0;
};

StepExcursion lastFollowerStepExcursion(const DisturbanceResponse& response, double low_speed_mps);

}  // namespace acc
