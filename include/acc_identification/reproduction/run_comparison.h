#pragma once

#include <cstddef>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
/// Errors of a simulated follower against a measured run, split into the paper's training part
/// (the first train_fraction of the samples) and the held-out rest (Figs. 3 and 4).
struct TrainTestErrors
{
  std::size_t split_index = 0;     ///< first sample of the test part
  double split_time_s = 0.0;
  std::size_t train_samples = 0;   ///< the samples each part's RMSEs are over (a divergence cuts them)
  std::size_t test_samples = 0;
  double train_speed_rmse_mps = 0.0;  ///< NaN for a part without a sample: not a perfect fit
  double test_speed_rmse_mps = 0.0;
  double train_gap_rmse_m = 0.0;
  double test_gap_rmse_m = 0.0;
  bool diverged = false;           ///< the simulation blew up; errors only cover samples before it
};

/// RMS errors of sim against run on [0, split) and [split, end), NaN where a part has no sample.
/// Throws std::invalid_argument when the sizes differ or train_fraction is not in (0, 1).
TrainTestErrors trainTestErrors(const CarFollowingRun& run, const SimulatedFollower& sim, double train_fraction);

}  // namespace acc
