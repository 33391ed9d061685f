#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
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

/// The same for the model with unmodelled effects switched on (diagnosis/augmented models).
FitQuality evaluateFit(const AccParameters& p, const EffectSettings& effects, const std::vector<CarFollowingRun>& runs);

/// Pools the squared errors of several fits (each weighted by its samples).
FitQuality poolFits(const std::vector<FitQuality>& fits);

/// Standard errors of (k1, k2, tau_e, eta) at the optimum by the Gauss-Newton sandwich
///   cov = (J^T J)^-1 M (J^T J)^-1,   M = sum over blocks b of g_b g_b^T,  g_b = sum_{k in b} J_k r_k
/// with J the exact Jacobian of the simulated speeds (forward sensitivities) and r the residuals.
/// M is the batch-means estimate of the scores' long-run covariance: it stays honest when the
/// residuals are correlated in time, which they are even on ideal data (leader-speed noise is
/// integrated by the simulation into slow speed errors) and much more on real data (model error
/// that lasts tens of seconds). With white residuals it reduces to the textbook s^2 (J^T J)^-1.
/// Blocks do not straddle segments; their length is five residual correlation times (from the
/// lag-1 autocorrelation), at least min_block_s, at most an eighth of the data so that M has
/// enough blocks to be estimated.
/// The residuals do not hold every error of the estimate: each run's simulation starts from its
/// one measured gap s(0), and the simulated speeds depend on s(0) and eta only through s - eta, so
/// an error e in s(0) moves eta by e exactly (one run; with several, by the run's share of eta's
/// information) and leaves the speeds' fit as good. With gap noise sigma that is sigma of eta
/// whatever the drive's length, which the residuals never show (synthetic drives with 0.4 m of gap
/// noise: eta off by 0.39 m RMS at 60, 120 and 300 s, the sandwich's error 0.07 to 0.02 m). So
/// the covariance adds sum over runs i of sigma_i^2 d_i d_i^T, d_i = (J^T J)^-1 J_i^T J_i,eta the
/// estimate's move per metre of run i's start gap, sigma_i = gapSampleNoiseM(run i) (start_gap_covariance.h).
struct ParameterUncertainty
{
  AccParameters standard_error;       ///< NaN when J^T J is singular
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Constant(std::numeric_limits<double>::quiet_NaN());
  double residual_lag1_autocorrelation = 0.0;
  double block_length_s = 0.0;        ///< of the batch means
  std::size_t blocks = 0;
  /// The gap's sample-to-sample measurement noise the start-gap term uses, RMS over the runs [m]
  /// (NaN when no run gives one: then the term is left out).
  double start_gap_noise_m = std::numeric_limits<double>::quiet_NaN();
  /// eta's standard error from the start gaps alone [m] (its share of standard_error.eta_m).
  double eta_start_gap_error_m = 0.0;
  /// Smallest over largest eigenvalue of J^T J with unit-scaled columns: near 0 when some
  /// combination of parameters leaves the simulated speed unchanged (no excitation).
  double reciprocal_condition = 0.0;
};

ParameterUncertainty estimateUncertainty(const AccParameters& p, const std::vector<CarFollowingRun>& runs,
                                         double min_block_s = 10.0);

}  // namespace acc
