#include "acc_identification/model/start_gap_covariance.h"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace acc
{
Eigen::MatrixXd startGapCovariance(const Eigen::MatrixXd& bread, const std::vector<StartGapScore>& scores,
                                   double* rms_noise_m)
{
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(bread.rows(), bread.rows());
  double noise_sq = 0.0;
  std::size_t noisy = 0;
  for (const StartGapScore& segment : scores)
  {
    if (!std::isfinite(segment.noise_m))
      continue;
    const Eigen::VectorXd move = bread * segment.score;
    covariance += segment.noise_m * segment.noise_m * move * move.transpose();
    noise_sq += segment.noise_m * segment.noise_m;
    ++noisy;
  }
  if (rms_noise_m != nullptr)
    *rms_noise_m = noisy > 0 ? std::sqrt(noise_sq / static_cast<double>(noisy)) : std::numeric_limits<double>::quiet_NaN();
  return covariance;
}

}  // namespace acc
