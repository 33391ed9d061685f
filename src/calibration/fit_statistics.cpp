#include "acc_identification/calibration/fit_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "acc_identification/follower_simulation.h"

namespace acc_identification
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Accumulates J^T J, the residual sum of squares and the lag-1 products of one run, by an Euler
/// pass carrying (s, v) and their sensitivities to (k1, k2, tau_e, eta).
struct JacobianSums
{
  Eigen::Matrix4d jtj = Eigen::Matrix4d::Zero();
  double ssr = 0.0;
  double lag1 = 0.0;
  std::size_t samples = 0;
  bool diverged = false;
};

void accumulateJacobian(const AccParameters& p, const CarFollowingRun& run, JacobianSums& sums)
{
  const double k1 = p.k1_per_s2, k2 = p.k2_per_s, tau = p.tau_e_s, eta = p.eta_m;
  double s = run.space_gap_m[0], v = run.follower_speed_mps[0];
  Eigen::Vector4d ds = Eigen::Vector4d::Zero(), dv = Eigen::Vector4d::Zero();
  double previous_residual = 0.0;  // the first sample's residual is 0 by construction
  sums.samples += run.size();
  for (std::size_t k = 0; k + 1 < run.size(); ++k)
  {
    const double h = run.time_s[k + 1] - run.time_s[k];
    const double relative = run.leader_speed_mps[k] - v;
    const double spacing = s - eta - tau * v;
    const Eigen::Vector4d explicit_partials(spacing, relative, -k1 * v, -k1);
    const Eigen::Vector4d df = k1 * (ds - tau * dv) - k2 * dv + explicit_partials;
    ds -= h * dv;
    dv += h * df;
    s += h * relative;
    v += h * (k1 * spacing + k2 * relative);
    if (!(std::abs(v) < kDivergenceBound && std::abs(s) < kDivergenceBound))
    {
      sums.diverged = true;
      return;
    }
    const double residual = run.follower_speed_mps[k + 1] - v;
    sums.jtj += dv * dv.transpose();
    sums.ssr += residual * residual;
    sums.lag1 += residual * previous_residual;
    previous_residual = residual;
  }
}
}  // namespace

FitQuality evaluateFit(const AccParameters& p, const std::vector<CarFollowingRun>& runs)
{
  double speed_sq = 0.0, gap_sq = 0.0;
  FitQuality fit;
  for (const CarFollowingRun& run : runs)
  {
    const SimulatedFollower sim = simulateFollower(p, run);
    fit.diverged = fit.diverged || sim.diverged;
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      speed_sq += std::pow(run.follower_speed_mps[k] - sim.speed_mps[k], 2);
      gap_sq += std::pow(run.space_gap_m[k] - sim.space_gap_m[k], 2);
    }
    fit.samples += run.size();
  }
  if (fit.samples > 0)
  {
    fit.rmse_speed_mps = std::sqrt(speed_sq / static_cast<double>(fit.samples));
    fit.rmse_gap_m = std::sqrt(gap_sq / static_cast<double>(fit.samples));
  }
  return fit;
}

FitQuality poolFits(const std::vector<FitQuality>& fits)
{
  FitQuality pooled;
  double speed_sq = 0.0, gap_sq = 0.0;
  for (const FitQuality& fit : fits)
  {
    pooled.samples += fit.samples;
    pooled.diverged = pooled.diverged || fit.diverged;
    speed_sq += fit.rmse_speed_mps * fit.rmse_speed_mps * static_cast<double>(fit.samples);
    gap_sq += fit.rmse_gap_m * fit.rmse_gap_m * static_cast<double>(fit.samples);
  }
  if (pooled.samples > 0)
  {
    pooled.rmse_speed_mps = std::sqrt(speed_sq / static_cast<double>(pooled.samples));
    pooled.rmse_gap_m = std::sqrt(gap_sq / static_cast<double>(pooled.samples));
  }
  return pooled;
}

ParameterUncertainty estimateUncertainty(const AccParameters& p, const std::vector<CarFollowingRun>& runs)
{
  ParameterUncertainty result;
  result.standard_error = AccParameters{kNaN, kNaN, kNaN, kNaN};
  JacobianSums sums;
  for (const CarFollowingRun& run : runs)
  {
    accumulateJacobian(p, run, sums);
    if (sums.diverged)
    {
      return result;
    }
  }
  if (sums.samples <= 4 || sums.ssr <= 0.0)
  {
    return result;
  }
  const double rho = std::clamp(sums.lag1 / sums.ssr, 0.0, 0.995);
  result.residual_lag1_autocorrelation = sums.lag1 / sums.ssr;
  result.variance_inflation = (1.0 + rho) / (1.0 - rho);
  const Eigen::Vector4d diagonal = sums.jtj.diagonal();
  if ((diagonal.array() <= 0.0).any())
  {
    return result;  // a parameter with no effect at all (e.g. eta when k1 = 0)
  }
  const Eigen::Vector4d unit = diagonal.cwiseSqrt().cwiseInverse();
  const Eigen::Matrix4d scaled = unit.asDiagonal() * sums.jtj * unit.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(scaled);
  const Eigen::Vector4d values = eigen.eigenvalues();  // ascending
  result.reciprocal_condition = values(3) > 0.0 ? std::max(0.0, values(0)) / values(3) : 0.0;
  if (result.reciprocal_condition < 1e-14)
  {
    return result;
  }
  const double sigma_sq = sums.ssr / static_cast<double>(sums.samples - 4) * result.variance_inflation;
  const Eigen::Matrix4d scaled_inverse =
      eigen.eigenvectors() * values.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
  result.covariance = sigma_sq * unit.asDiagonal() * scaled_inverse * unit.asDiagonal();
  const Eigen::Vector4d se = result.covariance.diagonal().cwiseSqrt();
  result.standard_error = AccParameters{se(0), se(1), se(2), se(3)};
  return result;
}

}  // namespace acc_identification
