#pragma once

#include <cstdint>

#include "acc_identification/model/normal_source.h"

namespace acc
{
/// GNSS errors of one receiver, sized after Section V-A of Gunter et al.: two u-blox receivers
/// 0.94 m apart on one car measured their distance 0.43 m too long on average and differed in
/// speed by 0.06 m/s on average (mean absolute difference).
struct GnssErrorSettings
{
  /// Stationary 1-sigma of the position error per horizontal axis and receiver [m]. The error of
  /// an antenna-to-antenna distance is then the difference of two such errors, sigma
  /// sqrt(2) * 0.30 = 0.42 m, the size the paper measured.
  double horizontal_sigma_m = 0.30;
  double vertical_sigma_m = 0.60;  ///< altitude error, 1-sigma [m] (GNSS vertical is about 2x worse)
  /// Correlation time of the first-order Gauss-Markov position error [s]: receiver position errors
  /// (multipath, atmosphere, orbits) wander slowly rather than jump from epoch to epoch.
  double position_correlation_time_s = 20.0;
  /// White noise on each receiver's Doppler speed and on its cross-track velocity [m/s]. 0.053
  /// makes the mean absolute difference of two receivers 2 sigma / sqrt(pi) = 0.06 m/s.
  double speed_sigma_mps = 0.053;
};

/// One epoch's errors of one receiver.
struct GnssEpochError
{
  double east_m = 0.0;
  double north_m = 0.0;
  double up_m = 0.0;
  double along_track_speed_mps = 0.0;  ///< added to the speed over ground
  double cross_track_speed_mps = 0.0;  ///< turns the course by atan(cross / speed)
};

/// The error sequence of one receiver: first-order Gauss-Markov position errors (exact
/// discretisation x[k+1] = phi x[k] + sigma sqrt(1 - phi^2) w, phi = exp(-h / T), started from
/// the stationary distribution, so every epoch has exactly the asked sigma) plus white speed noise.
class GnssErrorModel
{
public:
  GnssErrorModel(const GnssErrorSettings& settings, std::uint64_t seed);

  /// The errors of the next epoch, step_s after the previous one (ignored for the first epoch).
  GnssEpochError next(double step_s);

private:
  double markovStep(double previous, double sigma, double step_s);

  GnssErrorSettings settings_;
  NormalSource normal_;
  bool started_ = false;
  GnssEpochError current_;
};

}  // namespace acc
