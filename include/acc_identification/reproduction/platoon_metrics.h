#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "acc_identification/model/platoon_simulation.h"

namespace acc
{
/// How large the disturbance is at one vehicle of a simulated platoon.
struct VehicleDisturbance
{
  double minimum_speed_mps = 0.0;
  double maximum_speed_mps = 0.0;
  double peak_to_peak_mps = 0.0;       ///< maximum minus minimum speed
  double drop_below_reference_mps = 0.0;  ///< reference minus minimum speed (>= 0)
  double rise_above_reference_mps = 0.0;  ///< maximum speed minus reference (>= 0)
};

/// Disturbance of every vehicle (index 0 is the lead) over samples [from_sample, end), measured
/// against reference_speed_mps (the cruise speed the platoon starts from).
std::vector<VehicleDisturbance> vehicleDisturbances(const PlatoonTrajectory& platoon,
                                                    double reference_speed_mps, std::size_t from_sample = 0);

/// Where a disturbance stops decaying along the platoon, read from one magnitude per vehicle
/// (index 0 the lead, then followers 1..N).
struct GrowthOnset
{
  bool decays_at_first = false;  ///< follower 1 carries less than the lead
  std::size_t smallest_at = 0;   ///< follower with the smallest magnitude (argmin over 1..N)
  /// smallest_at when some later follower carries more, i.e. the disturbance grows again behind
  /// it; nullopt when the smallest is the last follower (still decaying at the platoon's end).
  std::optional<std::size_t> growth_starts_at;
  /// First follower carrying more than the lead (the initial disturbance is amplified there).
  std::optional<std::size_t> exceeds_lead_at;
};

/// Throws std::invalid_argument when there are fewer than two magnitudes (lead and one follower).
GrowthOnset findGrowthOnset(const std::vector<double>& magnitude_per_vehicle);

/// Amplitude of the sinusoid of known frequency in signal[from, to), by linear least squares on
/// a sin(w t) + b cos(w t) + c (t = index * time_step_s): sqrt(a^2 + b^2). Exact for a pure
/// sinusoid whatever the window's phase, unlike half the peak-to-peak of the samples. Throws
/// std::invalid_argument when the window has fewer than 3 samples or lies outside the signal.
double fittedSinusoidAmplitude(const std::vector<double>& signal, double time_step_s, double frequency_rad_s,
                               std::size_t from, std::size_t to);

/// First follower whose speed goes below min_speed_mps, where the linear model stops describing
/// a real car (it would drive backwards); nullopt when none does.
std::optional<std::size_t> firstVehicleBelowSpeed(const PlatoonTrajectory& platoon, double min_speed_mps);

}  // namespace acc
