#pragma once

#include <vector>

#include <Eigen/Core>

namespace acc
{
/// What the measured start gaps put on a speed fit's estimate. The simulated follower starts at
/// each segment's first measured gap, and that sample's error stays in the simulated gap all along,
/// so it moves the fit by bread * J_i^T g_i per metre: J_i the segment's rows of the speed Jacobian,
/// g_i the simulated speeds' sensitivity to its start gap, bread = (J^T J)^-1. The covariance is
/// sum_i sigma_i^2 d_i d_i^T, d_i = bread * J_i^T g_i, sigma_i the segment's gap sample noise
/// (gapSampleNoiseM). One term for the calibration (fit_statistics.h, where g_i = -J_i,eta) and the
/// diagnosis (augmented_calibration.h, where g_i comes by central difference, since an effect may
/// use the gap otherwise than through s - eta).
struct StartGapScore
{
  double noise_m = 0.0;   ///< sigma_i; a segment whose noise is not finite is left out
  Eigen::VectorXd score;  ///< J_i^T g_i, one entry per fitted parameter
};

/// The covariance above. rms_noise_m (optional): the RMS of the finite sigma_i, NaN without any.
Eigen::MatrixXd startGapCovariance(const Eigen::MatrixXd& bread, const std::vector<StartGapScore>& scores,
                                   double* rms_noise_m = nullptr);

}  // namespace acc
