#pragma once

// A run whose gap agrees with its speeds exactly, for the tests of the gap's kinematic checks.

#include <cmath>

#include "acc_identification/model/car_following_run.h"

namespace acc_test
{
/// What oscillatingRun draws: a leader oscillating about a speed, a follower doing the same late.
struct Oscillation
{
  double duration_s = 60.0;
  double mean_speed_mps = 10.0, amplitude_mps = 2.0, period_s = 20.0;
  double follower_delay_s = 1.5;
  double initial_gap_m = 20.0;
};

/// 10 Hz samples of the oscillation, named "synthetic", the gap the integral of the speed
/// difference (exact to the trapezoid rule).
inline acc::CarFollowingRun oscillatingRun(const Oscillation& o)
{
  acc::CarFollowingRun run;
  run.name = "synthetic";
  double gap_m = o.initial_gap_m;
  const int samples = static_cast<int>(std::lround(o.duration_s / 0.1));
  for (int k = 0; k <= samples; ++k)
  {
    const double t = 0.1 * k;
    const double leader = o.mean_speed_mps + o.amplitude_mps * std::sin(2.0 * M_PI * t / o.period_s);
    const double follower = o.mean_speed_mps + o.amplitude_mps * std::sin(2.0 * M_PI * (t - o.follower_delay_s) / o.period_s);
    if (k > 0)
      gap_m += 0.05 * (run.leader_speed_mps.back() - run.follower_speed_mps.back() + leader - follower);
    run.time_s.push_back(t);
    run.leader_speed_mps.push_back(leader);
    run.follower_speed_mps.push_back(follower);
    run.space_gap_m.push_back(gap_m);
  }
  return run;
}
}  // namespace acc_test
