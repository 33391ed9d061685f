#include "acc_identification/model/platoon_simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "acc_identification/model/acc_model.h"

namespace acc
{
PlatoonTrajectory simulatePlatoon(const AccParameters& p, const std::vector<double>& lead_speed_mps,
                                  double time_step_s, std::size_t follower_count)
{
  PlatoonTrajectory platoon;
  platoon.time_step_s = time_step_s;
  const std::size_t n = lead_speed_mps.size();
  platoon.speed_mps.assign(follower_count + 1, std::vector<double>(n));
  platoon.space_gap_m.assign(follower_count + 1, std::vector<double>(n));
  platoon.speed_mps[0] = lead_speed_mps;
  std::fill(platoon.space_gap_m[0].begin(), platoon.space_gap_m[0].end(),
            std::numeric_limits<double>::quiet_NaN());
  if (n == 0)
  {
    return platoon;
  }
  const double initial_speed = lead_speed_mps.front();
  for (std::size_t vehicle = 1; vehicle <= follower_count; ++vehicle)
  {
    const std::vector<double>& ahead = platoon.speed_mps[vehicle - 1];
    std::vector<double>& speed = platoon.speed_mps[vehicle];
    std::vector<double>& gap = platoon.space_gap_m[vehicle];
    speed[0] = initial_speed;
    gap[0] = equilibriumSpaceGapM(p, initial_speed);
    // Vehicle i depends only on vehicle i-1, so each follower is one pass over time.
    for (std::size_t k = 0; k + 1 < n; ++k)
    {
      const double relative_speed = ahead[k] - speed[k];
      speed[k + 1] = speed[k] + time_step_s * accelerationMps2(p, gap[k], speed[k], relative_speed);
      gap[k + 1] = gap[k] + time_step_s * relative_speed;
    }
  }
  return platoon;
}

std::vector<double> stepDownUpLeadProfile(double cruise_speed_mps, double step_mps,
                                          double step_down_at_s, double step_up_at_s,
                                          double duration_s, double time_step_s)
{
  const auto samples = static_cast<std::size_t>(std::floor(duration_s / time_step_s)) + 1;
  std::vector<double> speed(samples, cruise_speed_mps);
  for (std::size_t k = 0; k < samples; ++k)
  {
    const double t = static_cast<double>(k) * time_step_s;
    if (t >= step_down_at_s && t < step_up_at_s)
    {
      speed[k] = cruise_speed_mps - step_mps;
    }
  }
  return speed;
}

std::vector<double> minimumSpeedPerVehicle(const PlatoonTrajectory& platoon)
{
  std::vector<double> minimum;
  minimum.reserve(platoon.vehicleCount());
  for (const auto& speed : platoon.speed_mps)
  {
    minimum.push_back(speed.empty() ? std::numeric_limits<double>::quiet_NaN()
                                    : *std::min_element(speed.begin(), speed.end()));
  }
  return minimum;
}

}  // namespace acc
