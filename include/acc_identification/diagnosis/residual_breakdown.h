#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
/// Driving regimes, judged per sample from the recorded data (accelerations by central
/// differences over about one second). The first that applies wins, so they partition the data.
enum class DrivingRegime
{
  gap_opening_follower_accelerating,  ///< leader faster than the follower and follower speeding up
  leader_braking,                     ///< leader acceleration below -threshold
  leader_accelerating,                ///< leader acceleration above +threshold
  steady_following,                   ///< everything else: the leader holds its speed
};

std::string regimeName(DrivingRegime regime);

struct BreakdownOptions
{
  double leader_acceleration_threshold_mps2 = 0.3;
  double gap_opening_speed_mps = 0.5;             ///< leader minus follower speed
  double follower_acceleration_threshold_mps2 = 0.1;
  double acceleration_window_s = 1.0;             ///< central-difference span
  double speed_band_width_mps = 5.0;
  double segment_length_s = 10.0;                 ///< worst-segment windows
  std::size_t worst_segments = 8;
  /// Upper edges of the frequency bands of the residual spectrum [Hz]; the last band ends at Nyquist.
  std::vector<double> frequency_band_edges_hz = {0.01, 0.03, 0.1, 0.3, 1.0};
};

/// The squared errors of one group of samples, before (base model) and after (augmented model).
struct ResidualGroup
{
  std::string name;
  std::size_t samples = 0;
  double share_of_time = 0.0;
  double rmse_speed_before_mps = 0.0;
  double rmse_gap_before_m = 0.0;
  double share_of_squared_speed_error = 0.0;  ///< of the base model's total over all groups
  double share_of_squared_gap_error = 0.0;
  double rmse_speed_after_mps = 0.0;
  double rmse_gap_after_m = 0.0;
};

struct FrequencyBand
{
  std::string name;
  double lower_hz = 0.0;
  double upper_hz = 0.0;
  double share_of_speed_residual_power_before = 0.0;  ///< of the base model's residual power
  double share_of_speed_residual_power_after = 0.0;   ///< of the base model's power too (comparable)
};

struct WorstSegment
{
  std::string run;
  double start_s = 0.0;
  double end_s = 0.0;
  double share_of_squared_speed_error = 0.0;  ///< of the base model's total held-out error
  double rmse_speed_before_mps = 0.0;
  double rmse_speed_after_mps = 0.0;
  double rmse_gap_before_m = 0.0;
  std::string main_regime;  ///< the regime of most of its samples
};

/// One bin of a periodogram of the speed residual, for plotting.
struct SpectrumPoint
{
  std::string run;
  double frequency_hz = 0.0;
  double power_before = 0.0;  ///< |DFT|^2 / n of the residual [(m/s)^2]
  double power_after = 0.0;
};

struct ResidualBreakdown
{
  std::vector<ResidualGroup> regimes;
  std::vector<ResidualGroup> speed_bands;
  std::vector<FrequencyBand> frequency_bands;
  std::vector<WorstSegment> segments;
  std::vector<SpectrumPoint> spectrum;
};

/// Per-sample regime of a run.
std::vector<DrivingRegime> classifyRegimes(const CarFollowingRun& run, const BreakdownOptions& options);

/// Where the held-out residual lies. runs[i] is scored against before[i] (base model) and after[i]
/// (augmented model; pass `before` again when there is none). Samples past a divergence are
/// skipped. The spectrum takes each run's median step as its sampling interval.
ResidualBreakdown breakDownResiduals(const std::vector<CarFollowingRun>& runs,
                                     const std::vector<SimulatedFollower>& before,
                                     const std::vector<SimulatedFollower>& after, const BreakdownOptions& options);

}  // namespace acc
