#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

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
  /// The leader's speed noise, an input of the simulation (errors in variables), where it differs
  /// from the follower's (speed_std_mps, the output's); unset: the same.
  std::optional<double> leader_speed_std_mps{};
};

/// Explicit-Euler steps of the truth per data step in synthesizeRun.
constexpr std::size_t kTruthSubsteps = 10;

/// A car-following run made from known parameters (tests, benchmarks, verdict_study): a leader that
/// oscillates (three sinusoids of 25-90 s period, random phases) around cruise_speed_mps and
/// brakes hard now and then; a follower simulated from equilibrium by the ACC model at a step
/// kTruthSubsteps times finer than time_step_s and sampled every time_step_s (not by the
/// calibration's own Euler recursion at the data step, which would make recovery exact by
/// construction: an "inverse crime"); then noise on all three measured columns. Deterministic
/// for a given seed on every platform (acc::NormalSource).
CarFollowingRun synthesizeRun(const AccParameters& truth, double duration_s, double time_step_s,
                              double cruise_speed_mps, std::uint32_t seed, const MeasurementNoise& noise = {});

/// A truth with string-stability margin m for studies and tests: k1 = 0.1 /s^2, k2 = 0.5 /s,
/// eta = 6 m and the tau_e that gives m (projectOntoMargin), for m from -2 to 5.5 (tau_e from 0 to
/// its bound 5 s); beyond, tau_e = 1.5 s and the k2 that gives m, up to 7.225 (k2 at its bound
/// 3 /s). Throws std::invalid_argument outside truthMarginRange().
AccParameters truthWithMargin(double margin);

/// The margins truthWithMargin reaches: -2 to 7.225 with the calibration's bounds.
std::array<double, 2> truthMarginRange();

/// The benchmarks' reference data (docs/PERFORMANCE.md): nine synthesizeRun drives of 480 s at
/// 10 Hz (4,320 s, 43,209 samples, the scale of the paper's calibration data), seeds 1 to 9,
/// cruising at 14, 16, ..., 30 m/s, followed by `truth`.
std::vector<CarFollowingRun> paperScaleRuns(const AccParameters& truth);

}  // namespace acc
