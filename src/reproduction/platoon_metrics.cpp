#include "acc_identification/reproduction/platoon_metrics.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace acc
{
std::vector<VehicleDisturbance> vehicleDisturbances(const PlatoonTrajectory& platoon,
                                                    double reference_speed_mps, std::size_t from_sample)
{
  std::vector<VehicleDisturbance> result;
  result.reserve(platoon.vehicleCount());
  for (const std::vector<double>& speed : platoon.speed_mps)
  {
    VehicleDisturbance d;
    if (from_sample < speed.size())
    {
      const auto [low, high] = std::minmax_element(speed.begin() + static_cast<std::ptrdiff_t>(from_sample), speed.end());
      d.minimum_speed_mps = *low;
      d.maximum_speed_mps = *high;
      d.peak_to_peak_mps = *high - *low;
      d.drop_below_reference_mps = std::max(0.0, reference_speed_mps - *low);
      d.rise_above_reference_mps = std::max(0.0, *high - reference_speed_mps);
    }
    result.push_back(d);
  }
  return result;
}

GrowthOnset findGrowthOnset(const std::vector<double>& magnitude_per_vehicle)
{
  const std::vector<double>& m = magnitude_per_vehicle;
  if (m.size() < 2)
  {
    throw std::invalid_argument("growth onset needs the lead's and at least one follower's magnitude");
  }
  GrowthOnset onset;
  onset.decays_at_first = m[1] < m[0];
  onset.smallest_at = static_cast<std::size_t>(std::min_element(m.begin() + 1, m.end()) - m.begin());
  const bool grows_behind = std::any_of(m.begin() + static_cast<std::ptrdiff_t>(onset.smallest_at) + 1, m.end(),
                                        [&](double later) { return later > m[onset.smallest_at]; });
  if (grows_behind)
  {
    onset.growth_starts_at = onset.smallest_at;
  }
  for (std::size_t i = 1; i < m.size(); ++i)
  {
    if (m[i] > m[0])
    {
      onset.exceeds_lead_at = i;
      break;
    }
  }
  return onset;
}

double fittedSinusoidAmplitude(const std::vector<double>& signal, double time_step_s, double frequency_rad_s,
                               std::size_t from, std::size_t to)
{
  if (to > signal.size() || from >= to || to - from < 3)
  {
    throw std::invalid_argument("sinusoid fit needs a window of at least 3 samples inside the signal");
  }
  const auto rows = static_cast<Eigen::Index>(to - from);
  Eigen::MatrixXd design(rows, 3);
  Eigen::VectorXd observed(rows);
  for (Eigen::Index r = 0; r < rows; ++r)
  {
    const double t = static_cast<double>(from + static_cast<std::size_t>(r)) * time_step_s;
    design(r, 0) = std::sin(frequency_rad_s * t);
    design(r, 1) = std::cos(frequency_rad_s * t);
    design(r, 2) = 1.0;
    observed(r) = signal[from + static_cast<std::size_t>(r)];
  }
  const Eigen::Vector3d coefficients = design.colPivHouseholderQr().solve(observed);
  return std::hypot(coefficients(0), coefficients(1));
}

std::optional<std::size_t> firstVehicleBelowSpeed(const PlatoonTrajectory& platoon, double min_speed_mps)
{
  for (std::size_t i = 1; i < platoon.vehicleCount(); ++i)
  {
    const auto& speed = platoon.speed_mps[i];
    if (std::any_of(speed.begin(), speed.end(), [&](double v) { return v < min_speed_mps; }))
    {
      return i;
    }
  }
  return std::nullopt;
}

}  // namespace acc
