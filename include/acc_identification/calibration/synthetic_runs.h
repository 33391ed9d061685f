#pragma once

#include <cstdint>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// Measurement errors to add to a synthetic run. Defaults: the paper's GPS errors (Section V-A:
/// about 0.06 m/s on speed, 0.4 m on the space gap), white and Gaussian.
struct MeasurementNoise
{
  double speed_std_mps = 0.06;
  double gap_std_m = 0.4;
};

/// A car-following run made from known parameters, for tests and benchmarks: a leader that
/// oscillates (three sinusoids of 25-90 s period, random phases) around cruise_speed_mps and
/// brakes hard now and then; a follower simulated exactly by the calibration's Euler model from
/// equilibrium; then noise on all three measured columns. Deterministic for a given seed.
CarFollowingRun synthesizeRun(const AccParameters& truth, double duration_s, double time_step_s,
                              double cruise_speed_mps, std::uint32_t seed, const MeasurementNoise& noise = {});

}  // namespace acc
