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

}  // namespace acc
