#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "acc_identification/acc_parameters.h"
#include "acc_identification/car_following_run.h"

namespace acc_identification
{
/// How well a parameter set reproduces runs, by the reference simulateFollower() from each run's
/// own measured start (the paper's Table I columns).
struct FitQuality
{
  std::size_t samples = 0;
  double rmse_speed_mps = 0.0;
  double rmse_gap_m = 0.0;
  bool diverged = false;  ///< some run's simulation diverged; the RMSEs are then meaningless
};

FitQuality evaluateFit(const AccParameters& p, const std::vector<CarFollowingRun>& runs);

/// Pools the squared errors of several fits (each weighted by its samples).
FitQuality poolFits(const std::vector<FitQuality>& fits);

/// Standard errors of (k1, k2, tau_e, eta) from the Gauss-Newton approximation at the optimum:
/// cov = s^2 (J^T J)^-1 with J the exact Jacobian of the simulated speeds (forward sensitivities)
/// and s^2 = SSR / (n - 4), multiplied by the long-run variance factor (1 + rho) / (1 - rho) of
/// AR(1) residuals with lag-1 autocorrelation rho. Real residuals are far from white (10 Hz
/// spline-interpolated GNSS, model error that lasts seconds); without the factor the errors
/// would be too small by up to an order of magnitude. The factor is the sandwich estimate
/// J^T Sigma J ~ s^2 (1 + rho) / (1 - rho) J^T J, valid because the sensitivities vary slowly
/// compared with the residuals' correlation time.
struct ParameterUncertainty
{
  AccParameters standard_error;       ///< NaN when J^T J is singular
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Constant(std::numeric_limits<double>::quiet_NaN());
  double residual_lag1_autocorrelation = 0.0;
  double variance_inflation = 1.0;    ///< (1 + rho) / (1 - rho), rho clipped to [0, 0.995]
  /// Smallest over largest eigenvalue of J^T J with unit-scaled columns: near 0 when some
  /// combination of parameters leaves the simulated speed unchanged (no excitation).
  double reciprocal_condition = 0.0;
};

ParameterUncertainty estimateUncertainty(const AccParameters& p, const std::vector<CarFollowingRun>& runs);

}  // namespace acc_identification
