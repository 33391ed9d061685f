#include "acc_identification/reproduction/platoon_responses.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "acc_identification/reproduction/frequency_response.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
namespace
{
void requireFollowers(const PlatoonTrajectory& platoon)
{
  if (platoon.vehicleCount() < 2 || platoon.sampleCount() < 2)
  {
    throw std::invalid_argument("platoon response needs a lead, at least one follower and two samples");
  }
}

std::vector<double> magnitudes(const std::vector<VehicleDisturbance>& per_vehicle,
                               double VehicleDisturbance::*field)
{
  std::vector<double> m;
  m.reserve(per_vehicle.size());
  for (const VehicleDisturbance& d : per_vehicle)
  {
    m.push_back(d.*field);
  }
  return m;
}
}  // namespace

SinusoidResponse measureSinusoidResponse(const PlatoonTrajectory& platoon, const AccParameters& p,
                                         double frequency_rad_s, std::size_t from_sample)
{
  requireFollowers(platoon);
  SinusoidResponse response;
  for (const std::vector<double>& speed : platoon.speed_mps)
  {
    response.amplitude_mps.push_back(
        fittedSinusoidAmplitude(speed, platoon.time_step_s, frequency_rad_s, from_sample, speed.size()));
  }
  const std::vector<double>& a = response.amplitude_mps;
  response.last_to_first_follower = a.back() / a[1];
  response.last_follower_to_lead = a.back() / a[0];
  response.model_gain = transferGain(p, frequency_rad_s);
  response.euler_gain = eulerTransferGain(p, frequency_rad_s, platoon.time_step_s);
  const double followers = static_cast<double>(platoon.speed_mps.size() - 1);
  response.model_gain_over_platoon = std::pow(response.model_gain, followers);
  response.euler_gain_over_platoon = std::pow(response.euler_gain, followers);
  return response;
}

DisturbanceResponse measureDisturbanceResponse(const PlatoonTrajectory& platoon)
{
  requireFollowers(platoon);
  DisturbanceResponse response;
  response.reference_speed_mps = platoon.speed_mps[0].front();
  response.per_vehicle = vehicleDisturbances(platoon, response.reference_speed_mps);
  response.by_peak_to_peak = findGrowthOnset(magnitudes(response.per_vehicle, &VehicleDisturbance::peak_to_peak_mps));
  response.by_drop = findGrowthOnset(magnitudes(response.per_vehicle, &VehicleDisturbance::drop_below_reference_mps));
  response.first_negative_speed_vehicle = firstVehicleBelowSpeed(platoon, 0.0);
  const double lead_final = platoon.speed_mps[0].back();
  const double tolerance = 0.01 * response.per_vehicle[0].peak_to_peak_mps;
  response.last_follower_settled = std::abs(platoon.speed_mps.back().back() - lead_final) <= tolerance;
  return response;
}

PlatoonTrajectory firstFollowers(const PlatoonTrajectory& platoon, std::size_t followers)
{
  PlatoonTrajectory shorter = platoon;
  const std::size_t vehicles = std::min(followers + 1, platoon.speed_mps.size());
  shorter.speed_mps.resize(vehicles);
  shorter.space_gap_m.resize(vehicles);
  return shorter;
}

StepExcursion lastFollowerStepExcursion(const DisturbanceResponse& response, double low_speed_mps)
{
  const VehicleDisturbance& last = response.per_vehicle.back();
  StepExcursion excursion;
  excursion.undershoot_below_low_speed_mps = std::max(0.0, low_speed_mps - last.minimum_speed_mps);
  excursion.overshoot_above_cruise_mps = last.rise_above_reference_mps;
  return excursion;
}

}  // namespace acc
