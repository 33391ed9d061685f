#pragma once

#include <cstddef>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// Speed and gap of a simulated follower at the run's sample times.
struct SimulatedFollower
{
  std::vector<double> speed_mps;
  std::vector<double> space_gap_m;
  /// True when the recursion blew up (|v| or |s| beyond the divergence bound, or non-finite).
  /// From diverged_at_index on, the samples hold the last finite state and must not be scored.
  bool diverged = false;
  std::size_t diverged_at_index = 0;
};

/// Speed or gap magnitude beyond which a simulation is declared divergent. Far above anything a
/// road vehicle reaches, far below where doubles lose meaning.
constexpr double kDivergenceBound = 1.0e4;

/// Explicit-Euler simulation of one follower driven by the measured leader speed, exactly as
/// Section IV of the paper calibrates the model:
///   v[k+1] = v[k] + h_k f(s[k], v[k], u[k] - v[k])
///   s[k+1] = s[k] + h_k (u[k] - v[k]),   h_k = t[k+1] - t[k] (the data's own step)
/// started from the measured s(0) and v(0). The run must satisfy describeRunProblem() == "".
SimulatedFollower simulateFollower(const AccParameters& p, const CarFollowingRun& run);

}  // namespace acc
