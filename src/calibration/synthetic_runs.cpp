#include "acc_identification/calibration/synthetic_runs.h"

#include <cmath>
#include <random>

#include "acc_identification/model/follower_simulation.h"

namespace acc
{
CarFollowingRun synthesizeRun(const AccParameters& truth, double duration_s, double time_step_s,
                              double cruise_speed_mps, std::uint32_t seed, const MeasurementNoise& noise)
{
  constexpr double kPi = 3.14159265358979323846;
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * kPi);
  const double periods_s[3] = {90.0, 45.0, 25.0};
  const double amplitudes_mps[3] = {3.0, 1.5, 0.8};
  double phases[3];
  for (double& p : phases)
  {
    p = phase(random);
  }
  const std::size_t n = static_cast<std::size_t>(std::floor(duration_s / time_step_s)) + 1;
  CarFollowingRun run;
  run.name = "synthetic-" + std::to_string(seed);
  for (std::size_t k = 0; k < n; ++k)
  {
    const double t = static_cast<double>(k) * time_step_s;
    double u = cruise_speed_mps;
    for (int i = 0; i < 3; ++i)
    {
      u += amplitudes_mps[i] * std::sin(2.0 * kPi * t / periods_s[i] + phases[i]);
    }
    // A braking event every 150 s: down 5 m/s at 2 m/s^2, hold 10 s, back at 1 m/s^2.
    const double into_event = std::fmod(t, 150.0) - 100.0;
    if (into_event > 0.0)
    {
      const double down = std::min(5.0, 2.0 * into_event);
      const double up = std::max(0.0, 1.0 * (into_event - 12.5));
      u -= std::max(0.0, down - up);
    }
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(u);
  }
  run.follower_speed_mps.assign(n, 0.0);
  run.space_gap_m.assign(n, 0.0);
  run.follower_speed_mps[0] = run.leader_speed_mps[0];
  run.space_gap_m[0] = truth.eta_m + truth.tau_e_s * run.leader_speed_mps[0];
  const SimulatedFollower truth_sim = simulateFollower(truth, run);
  std::normal_distribution<double> speed_error(0.0, noise.speed_std_mps), gap_error(0.0, noise.gap_std_m);
  for (std::size_t k = 0; k < n; ++k)
  {
    run.follower_speed_mps[k] = truth_sim.speed_mps[k] + speed_error(random);
    run.space_gap_m[k] = truth_sim.space_gap_m[k] + gap_error(random);
    run.leader_speed_mps[k] += speed_error(random);
  }
  return run;
}

}  // namespace acc
