#pragma once
// Synthetic OpenACC platoon files for the campaign tests: a lead car's speed profile, each car
// simulated behind the car ahead with known parameters at a step ten times finer than the 0.1 s
// data, sampled at 0.1 s, with seeded GNSS-size noise (the
// paper's 0.06 m/s on speed and 0.4 m on the gap by default, as acc::MeasurementNoise), written as an OpenACC file.

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/normal_source.h"

namespace acc_test
{
struct SyntheticCar
{
  std::string name;
  acc::AccParameters truth;
  acc::EffectSettings effects{};  ///< unmodelled effects of the true car (default: none)
};

/// Speed that moves smoothly from `from` to `to` between t0 and t1 (cosine ramp).
inline double ramp(double t, double t0, double t1, double from, double to)
{
  if (t <= t0)
    return from;
  if (t >= t1)
    return to;
  return from + (to - from) * 0.5 * (1.0 - std::cos(M_PI * (t - t0) / (t1 - t0)));
}

/// 20 m/s cruise with a slow 0.4 m/s wave (excitation that is no perturbation), a dip to 14 m/s
/// at 60 s (the perturbation), a climb to 25 m/s at 170 s and back to 20 at 260 s (different
/// steady speeds: eta and tau_e apart), and a second dip to 15 m/s at 300 s.
inline double leadSpeedMps(double t)
{
  double v = 20.0 + 0.4 * std::sin(2.0 * M_PI * t / 40.0);
  v += ramp(t, 60.0, 66.0, 0.0, -6.0) + ramp(t, 80.0, 90.0, 0.0, 6.0);
  v += ramp(t, 170.0, 180.0, 0.0, 5.0) + ramp(t, 260.0, 270.0, 0.0, -5.0);
  v += ramp(t, 300.0, 305.0, 0.0, -5.0) + ramp(t, 320.0, 330.0, 0.0, 5.0);
  return v;
}

/// Writes the platoon (lead "LEAD" then `cars`) as an OpenACC file with Time, Speedk, IVSk.
inline void writeSyntheticPlatoon(const std::string& path, const std::string& setting,
                                  const std::vector<SyntheticCar>& cars, std::uint64_t seed,
                                  double duration_s = 400.0, double speed_noise_mps = 0.06, double gap_noise_m = 0.4)
{
  constexpr double kFineStepS = 0.01;
  constexpr int kEvery = 10;  // data at 0.1 s
  const std::size_t fine = static_cast<std::size_t>(duration_s / kFineStepS) + 1;
  acc::CarFollowingRun run;
  run.time_s.resize(fine);
  run.leader_speed_mps.resize(fine);
  for (std::size_t i = 0; i < fine; ++i)
  {
    run.time_s[i] = i * kFineStepS;
    run.leader_speed_mps[i] = leadSpeedMps(run.time_s[i]);
  }
  std::vector<std::vector<double>> speed{run.leader_speed_mps}, gap;
  for (const SyntheticCar& car : cars)
  {
    const double v0 = run.leader_speed_mps[0];
    run.follower_speed_mps.assign(fine, v0);
    run.space_gap_m.assign(fine, car.truth.eta_m + car.truth.tau_e_s * v0);  // at equilibrium
    const acc::SimulatedFollower sim = acc::simulateFollower(car.truth, car.effects, run);
    speed.push_back(sim.speed_mps);
    gap.push_back(sim.space_gap_m);
    run.leader_speed_mps = sim.speed_mps;
  }
  acc::NormalSource noise(seed);
  std::ofstream out(path);
  out << "Date,8,10,2019\nVehicle_order,LEAD,";
  for (const SyntheticCar& car : cars)
    out << car.name << ",";
  out << "\nNumber_of_vehicles," << cars.size() + 1 << "\nACC,1\nDistance_setting," << setting << "\nTime";
  for (std::size_t k = 1; k <= cars.size() + 1; ++k)
    out << ",Speed" << k;
  for (std::size_t k = 1; k <= cars.size(); ++k)
    out << ",IVS" << k;
  out << "\n";
  out.precision(10);
  for (std::size_t i = 0; i < fine; i += kEvery)
  {
    out << run.time_s[i];
    for (const auto& v : speed)
      out << "," << v[i] + speed_noise_mps * noise.standardNormal();
    for (const auto& s : gap)
      out << "," << s[i] + gap_noise_m * noise.standardNormal();
    out << "\n";
  }
}

}  // namespace acc_test
