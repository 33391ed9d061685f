#include "acc_identification/reproduction/lead_inputs.h"

#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace acc
{
namespace
{
std::size_t sampleCount(double duration_s, double time_step_s)
{
  if (!(time_step_s > 0.0) || !(duration_s > 0.0) || !std::isfinite(duration_s))
  {
    throw std::invalid_argument("time step and duration must be positive numbers of seconds");
  }
  return static_cast<std::size_t>(std::floor(duration_s / time_step_s + 1e-9)) + 1;
}
}  // namespace

std::vector<double> sinusoidLeadProfile(double cruise_speed_mps, double amplitude_mps, double frequency_rad_s,
                                        double lead_in_s, double duration_s, double time_step_s)
{
  std::vector<double> speed(sampleCount(duration_s, time_step_s), cruise_speed_mps);
  for (std::size_t k = 0; k < speed.size(); ++k)
  {
    const double t = static_cast<double>(k) * time_step_s;
    if (t > lead_in_s)
    {
      speed[k] += amplitude_mps * std::sin(frequency_rad_s * (t - lead_in_s));
    }
  }
  return speed;
}

std::vector<double> withFinalHold(std::vector<double> lead_speed_mps, double hold_s, double time_step_s)
{
  if (lead_speed_mps.empty() || !(hold_s > 0.0))
  {
    return lead_speed_mps;
  }
  const double last = lead_speed_mps.back();
  lead_speed_mps.resize(lead_speed_mps.size() + sampleCount(hold_s, time_step_s) - 1, last);
  return lead_speed_mps;
}

}  // namespace acc
