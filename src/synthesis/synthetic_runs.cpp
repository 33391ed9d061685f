#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/angles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "acc_identification/calibration/margin_constrained_fit.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/normal_source.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
namespace
{

/// The leader's speed [m/s] at time t: three sinusoids around the cruise speed and a braking
/// event every 150 s (down 5 m/s at 2 m/s^2, hold 10 s, back at 1 m/s^2).
double leaderSpeedAt(double t, double cruise_speed_mps, const double (&phases)[3])
{
  const double periods_s[3] = {90.0, 45.0, 25.0};
  const double amplitudes_mps[3] = {3.0, 1.5, 0.8};
  double u = cruise_speed_mps;
  for (int i = 0; i < 3; ++i)
  {
    u += amplitudes_mps[i] * std::sin(2.0 * kPi * t / periods_s[i] + phases[i]);
  }
  const double into_event = std::fmod(t, 150.0) - 100.0;
  if (into_event > 0.0)
  {
    const double down = std::min(5.0, 2.0 * into_event);
    const double up = std::max(0.0, 1.0 * (into_event - 12.5));
    u -= std::max(0.0, down - up);
  }
  return u;
}

/// The true follower at samples_n data epochs every time_step_s: Euler at time_step_s /
/// kTruthSubsteps from equilibrium, kept every kTruthSubsteps-th step. Finer than the fit's Euler
/// at the data step, so that a recovery test does not fit the very recursion that made its data.
CarFollowingRun fineTruth(const AccParameters& truth, std::size_t samples_n, double time_step_s,
                          double cruise_speed_mps, const double (&phases)[3])
{
  const double fine_step_s = time_step_s / kTruthSubsteps;
  const std::size_t fine_n = (samples_n - 1) * kTruthSubsteps + 1;
  CarFollowingRun fine;
  for (std::size_t j = 0; j < fine_n; ++j)
  {
    const double t = static_cast<double>(j) * fine_step_s;
    fine.time_s.push_back(t);
    fine.leader_speed_mps.push_back(leaderSpeedAt(t, cruise_speed_mps, phases));
  }
  fine.follower_speed_mps.assign(fine_n, fine.leader_speed_mps[0]);
  fine.space_gap_m.assign(fine_n, truth.eta_m + truth.tau_e_s * fine.leader_speed_mps[0]);
  const SimulatedFollower sim = simulateFollower(truth, fine);
  CarFollowingRun sampled;
  for (std::size_t k = 0; k < samples_n; ++k)
  {
    const std::size_t j = k * kTruthSubsteps;
    sampled.time_s.push_back(static_cast<double>(k) * time_step_s);
    sampled.leader_speed_mps.push_back(fine.leader_speed_mps[j]);
    sampled.follower_speed_mps.push_back(sim.speed_mps[j]);
    sampled.space_gap_m.push_back(sim.space_gap_m[j]);
  }
  return sampled;
}
}  // namespace

CarFollowingRun synthesizeRun(const AccParameters& truth, double duration_s, double time_step_s,
                              double cruise_speed_mps, std::uint32_t seed, const MeasurementNoise& noise)
{
  NormalSource random(seed);
  double phases[3];
  for (double& p : phases)
  {
    p = 2.0 * kPi * random.uniformOpenClosed();
  }
  const std::size_t n = static_cast<std::size_t>(std::floor(duration_s / time_step_s)) + 1;
  CarFollowingRun run = fineTruth(truth, n, time_step_s, cruise_speed_mps, phases);
  run.name = "synthetic-" + std::to_string(seed);
  const double leader_speed_std_mps = noise.leader_speed_std_mps.value_or(noise.speed_std_mps);
  for (std::size_t k = 0; k < n; ++k)
  {
    run.follower_speed_mps[k] += noise.speed_std_mps * random.standardNormal();
    run.space_gap_m[k] += noise.gap_std_m * random.standardNormal();
    run.leader_speed_mps[k] += leader_speed_std_mps * random.standardNormal();
  }
  return run;
}

namespace
{
/// The truths' gains and eta; tau_e sets the margin.
constexpr AccParameters kTruthBase{0.1, 0.5, 1.5, 6.0};
}  // namespace

AccParameters truthWithMargin(double margin)
{
  const std::vector<AccParameters> on_margin = projectOntoMargin(kTruthBase, margin, ParameterBounds{});
  if (on_margin.empty())
  {
    const std::array<double, 2> range = truthMarginRange();
    throw std::invalid_argument("truthWithMargin: no k1 = 0.1, k2 = 0.5 model within the bounds has margin " +
                                std::to_string(margin) + " (they reach " + std::to_string(range[0]) + " to " +
                                std::to_string(range[1]) + ")");
  }
  return on_margin.front();
}

std::array<double, 2> truthMarginRange()
{
  // projectOntoMargin changes one parameter of the base truth within the bounds: tau_e, k2 or k1.
  // The margin grows with each, so each reaches its largest at its upper bound.
  const ParameterBounds bounds;
  AccParameters least = kTruthBase;
  least.tau_e_s = bounds.lower.tau_e_s;
  double largest = -std::numeric_limits<double>::infinity();
  for (double AccParameters::*changed : {&AccParameters::tau_e_s, &AccParameters::k2_per_s, &AccParameters::k1_per_s2})
  {
    AccParameters at_bound = kTruthBase;
    at_bound.*changed = bounds.upper.*changed;
    largest = std::max(largest, stabilityMargin(at_bound));
  }
  return {stabilityMargin(least), largest};
}

std::vector<CarFollowingRun> paperScaleRuns(const AccParameters& truth)
{
  std::vector<CarFollowingRun> runs;
  for (std::uint32_t seed = 1; seed <= 9; ++seed)
    runs.push_back(synthesizeRun(truth, 480.0, 0.1, 12.0 + 2.0 * seed, seed));
  return runs;
}

}  // namespace acc
