#include "acc_identification/calibration/fit_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The Euler pass carrying (s, v) and their sensitivities to (k1, k2, tau_e, eta): per sample the
/// residual and the Jacobian row (as d v_simulated / d theta; the sign does not matter below).
struct JacobianRows
{
  std::vector<double> time_s;
  std::vector<double> residual;
  std::vector<Eigen::Vector4d> row;
  bool diverged = false;
};

JacobianRows jacobianRows(const AccParameters& p, const CarFollowingRun& run)
{
  const double k1 = p.k1_per_s2, k2 = p.k2_per_s, tau = p.tau_e_s, eta = p.eta_m;
  JacobianRows rows;
  double s = run.space_gap_m[0], v = run.follower_speed_mps[0];
  Eigen::Vector4d ds = Eigen::Vector4d::Zero(), dv = Eigen::Vector4d::Zero();
  rows.time_s.push_back(run.time_s[0]);
  rows.residual.push_back(0.0);  // the first sample is the measured start
  rows.row.push_back(dv);
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
      rows.diverged = true;
      return rows;
    }
    rows.time_s.push_back(run.time_s[k + 1]);
    rows.residual.push_back(run.follower_speed_mps[k + 1] - v);
    rows.row.push_back(dv);
  }
  return rows;
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

ParameterUncertainty estimateUncertainty(const AccParameters& p, const std::vector<CarFollowingRun>& runs,
                                         double min_block_s)
{
  ParameterUncertainty result;
  result.standard_error = AccParameters{kNaN, kNaN, kNaN, kNaN};
  std::vector<JacobianRows> all;
  Eigen::Matrix4d jtj = Eigen::Matrix4d::Zero();
  double ssr = 0.0, lag1 = 0.0, duration_s = 0.0;
  std::size_t samples = 0;
  for (const CarFollowingRun& run : runs)
  {
    all.push_back(jacobianRows(p, run));
    const JacobianRows& rows = all.back();
    if (rows.diverged)
    {
      return result;
    }
    for (std::size_t k = 0; k < rows.residual.size(); ++k)
    {
      jtj += rows.row[k] * rows.row[k].transpose();
      ssr += rows.residual[k] * rows.residual[k];
      lag1 += k > 0 ? rows.residual[k] * rows.residual[k - 1] : 0.0;
    }
    samples += run.size();
    duration_s += run.durationS();
  }
  if (samples <= 4 || ssr <= 0.0 || duration_s <= 0.0)
  {
    return result;
  }
  result.residual_lag1_autocorrelation = lag1 / ssr;
  // Correlation time of AR(1) residuals, -h / ln(rho); blocks of five of them.
  const double rho = std::clamp(result.residual_lag1_autocorrelation, 1e-6, 0.9999);
  const double mean_step_s = duration_s / static_cast<double>(samples - runs.size());
  const double correlation_time_s = -mean_step_s / std::log(rho);
  result.block_length_s = std::min(std::max(min_block_s, 5.0 * correlation_time_s), duration_s / 8.0);
  Eigen::Matrix4d meat = Eigen::Matrix4d::Zero();
  for (const JacobianRows& rows : all)
  {
    Eigen::Vector4d score = Eigen::Vector4d::Zero();
    double block_start_s = rows.time_s.front();
    for (std::size_t k = 0; k < rows.residual.size(); ++k)
    {
      if (rows.time_s[k] - block_start_s >= result.block_length_s)
      {
        meat += score * score.transpose();
        ++result.blocks;
        score.setZero();
        block_start_s = rows.time_s[k];
      }
      score += rows.row[k] * rows.residual[k];
    }
    meat += score * score.transpose();
    ++result.blocks;
  }
  const Eigen::Vector4d diagonal = jtj.diagonal();
  if ((diagonal.array() <= 0.0).any())
  {
    return result;  // a parameter with no effect at all (e.g. eta when k1 = 0)
  }
  const Eigen::Vector4d unit = diagonal.cwiseSqrt().cwiseInverse();
  const Eigen::Matrix4d scaled = unit.asDiagonal() * jtj * unit.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(scaled);
  const Eigen::Vector4d values = eigen.eigenvalues();  // ascending
  result.reciprocal_condition = values(3) > 0.0 ? std::max(0.0, values(0)) / values(3) : 0.0;
  if (result.reciprocal_condition < 1e-14 || result.blocks < 4)
  {
    return result;
  }
  const Eigen::Matrix4d bread =
      unit.asDiagonal() * eigen.eigenvectors() * values.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose() *
      unit.asDiagonal();
  // n / (n - 4): the usual small-sample correction for four fitted parameters.
  const double correction = static_cast<double>(samples) / static_cast<double>(samples - 4);
  result.covariance = correction * bread * meat * bread;
  const Eigen::Vector4d se = result.covariance.diagonal().cwiseSqrt();
  result.standard_error = AccParameters{se(0), se(1), se(2), se(3)};
  return result;
}

}  // namespace acc
