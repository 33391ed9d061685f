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
  double train_speed_rmse_mps = 0.0;
  double test_speed_rmse_mps = 0.0;
  double train_gap_rmse_m = 0.0;
  double test_gap_rmse_m = 0.0;
  bool diverged = false;           ///< the simulation blew up; errors only cover samples before it
};

/// RMS errors of sim against run on [0, split) and [split, end). Throws std::invalid_argument
/// when the sizes differ or train_fraction is not in (0, 1).
TrainTestErrors trainTestErrors(const CarFollowingRun& run, const SimulatedFollower& sim, double train_fraction);

/// Samples of steady following, where the gap should sit on the equilibrium line eta + tau_e v
/// (Fig. 5): |leader - follower speed| <= max_relative_speed_mps and the follower's acceleration
/// (central difference) within max_acceleration_mps2.
std::vector<std::size_t> steadyFollowingSamples(const CarFollowingRun& run, double max_relative_speed_mps,
                                                double max_acceleration_mps2);

/// Least-squares line gap = intercept + slope * speed through the chosen samples.
struct GapSpeedLine
{
  double intercept_m = 0.0;  ///< the data's jam distance (eta)
  double slope_s = 0.0;      ///< the data's effective time gap (tau_e)
  double rms_residual_m = 0.0;
  std::size_t samples = 0;
};

/// Throws std::invalid_argument with fewer than two samples or no spread of speed.
GapSpeedLine fitGapSpeedLine(const CarFollowingRun& run, const std::vector<std::size_t>& samples);

/// RMS distance [m] of the chosen samples' gaps from the line eta + tau_e v of p.
double rmsFromEquilibriumLine(const AccParameters& p, const CarFollowingRun& run,
                              const std::vector<std::size_t>& samples);

}  // namespace acc
