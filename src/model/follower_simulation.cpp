#include "acc_identification/model/follower_simulation.h"

#include <cmath>

#include "acc_identification/model/acc_model.h"

namespace acc
{
namespace
{
bool isRunaway(double speed_mps, double space_gap_m)
{
  // Written so that NaN counts as runaway too.
  return !(std::abs(speed_mps) < kDivergenceBound && std::abs(space_gap_m) < kDivergenceBound);
}
}  // namespace

SimulatedFollower simulateFollower(const AccParameters& p, const CarFollowingRun& run)
{
  const std::size_t n = run.size();
  SimulatedFollower sim;
  sim.speed_mps.resize(n);
  sim.space_gap_m.resize(n);
  if (n == 0)
  {
    return sim;
  }
  double speed = run.follower_speed_mps[0];
  double gap = run.space_gap_m[0];
  sim.speed_mps[0] = speed;
  sim.space_gap_m[0] = gap;
  for (std::size_t k = 0; k + 1 < n; ++k)
  {
    const double step_s = run.time_s[k + 1] - run.time_s[k];
    const double relative_speed = run.leader_speed_mps[k] - speed;
    const double next_speed = speed + step_s * accelerationMps2(p, gap, speed, relative_speed);
    const double next_gap = gap + step_s * relative_speed;
    if (isRunaway(next_speed, next_gap))
    {
      sim.diverged = true;
      sim.diverged_at_index = k + 1;
      for (std::size_t rest = k + 1; rest < n; ++rest)
      {
        sim.speed_mps[rest] = speed;
        sim.space_gap_m[rest] = gap;
      }
      return sim;
    }
    speed = next_speed;
    gap = next_gap;
    sim.speed_mps[k + 1] = speed;
    sim.space_gap_m[k + 1] = gap;
  }
  return sim;
}

}  // namespace acc
