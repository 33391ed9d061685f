#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
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

/// The paper's Fig. 5 for one set of samples: the data's own gap-speed line through its steady
/// samples, and how far those samples lie from each parameter set's line eta + tau_e v.
struct EquilibriumRegression
{
  std::vector<std::size_t> steady;     ///< the steady samples (indices into the run)
  std::optional<GapSpeedLine> line;    ///< none when the steady samples cannot pin a line
  std::string no_line_reason;          ///< why there is no line
  std::vector<double> rms_from_line_m;  ///< per parameter set, in the order given
};

/// Fig. 5 for one run: its steady samples (steadyFollowingSamples), their line and distances.
EquilibriumRegression regressEquilibrium(const CarFollowingRun& run, const std::vector<AccParameters>& settings,
                                         double max_relative_speed_mps, double max_acceleration_mps2);

/// The steady samples of all runs together as one run (time = sample number): one run's speed
/// range is often too narrow to pin the line's slope, the pooled samples span the whole campaign.
CarFollowingRun pooledSteadySamples(const std::vector<CarFollowingRun>& runs, double max_relative_speed_mps,
                                    double max_acceleration_mps2);

/// Fig. 5 over the pooled steady samples of all runs (every pooled sample counts as steady:
/// they were chosen in their own runs, where the acceleration is defined).
EquilibriumRegression regressPooledEquilibrium(const std::vector<CarFollowingRun>& runs,
                                               const std::vector<AccParameters>& settings,
                                               double max_relative_speed_mps, double max_acceleration_mps2);

}  // namespace acc
