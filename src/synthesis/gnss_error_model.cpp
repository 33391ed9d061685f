#include "acc_identification/synthesis/gnss_error_model.h"

#include <cmath>

namespace acc
{
GnssErrorModel::GnssErrorModel(const GnssErrorSettings& settings, std::uint64_t seed)
  : settings_(settings), normal_(seed)
{
}

double GnssErrorModel::markovStep(double previous, double sigma, double step_s)
{
  const double correlation_time_s = settings_.position_correlation_time_s;
  // T <= 0 means no correlation: white position noise.
  const double phi = correlation_time_s > 0.0 ? std::exp(-step_s / correlation_time_s) : 0.0;
  return phi * previous + sigma * std::sqrt(1.0 - phi * phi) * normal_.standardNormal();
}

GnssEpochError GnssErrorModel::next(double step_s)
{
  if (!started_)
  {
    // The stationary distribution, so that the first epoch is as wrong as any other.
    current_.east_m = settings_.horizontal_sigma_m * normal_.standardNormal();
    current_.north_m = settings_.horizontal_sigma_m * normal_.standardNormal();
    current_.up_m = settings_.vertical_sigma_m * normal_.standardNormal();
    started_ = true;
  }
  else
  {
    current_.east_m = markovStep(current_.east_m, settings_.horizontal_sigma_m, step_s);
    current_.north_m = markovStep(current_.north_m, settings_.horizontal_sigma_m, step_s);
    current_.up_m = markovStep(current_.up_m, settings_.vertical_sigma_m, step_s);
  }
  current_.along_track_speed_mps = settings_.speed_sigma_mps * normal_.standardNormal();
  current_.cross_track_speed_mps = settings_.speed_sigma_mps * normal_.standardNormal();
  return current_;
}

}  // namespace acc
