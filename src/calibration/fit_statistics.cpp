#include "acc_identification/calibration/fit_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/model/batch_means.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/start_gap_covariance.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// What each run's measured start gap puts on the estimate (start_gap_covariance.h): a start-gap
/// error acts as -eta, so J_i^T g_i = -J_i^T J_i,eta (the sign drops out of the covariance).
std::vector<StartGapScore> startGapScores(const std::vector<SensitivityRows>& rows,
                                          const std::vector<CarFollowingRun>& runs)
{
  std::vector<StartGapScore> scores;
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    Eigen::Vector4d score = Eigen::Vector4d::Zero();
    for (const Eigen::Vector4d& row : rows[i].row)
      score += row * row(3);
    scores.push_back({gapSampleNoiseM(runs[i]), score});
  }
  return scores;
}

}  // namespace

FitQuality evaluateFit(const AccParameters& p, const std::vector<CarFollowingRun>& runs)
{
  return evaluateFit(p, EffectSettings{}, runs);
}

FitQuality evaluateFit(const AccParameters& p, const EffectSettings& effects, const std::vector<CarFollowingRun>& runs)
{
  double speed_sq = 0.0, gap_sq = 0.0;
  FitQuality fit;
  for (const CarFollowingRun& run : runs)
  {
    const SimulatedFollower sim = simulateFollower(p, effects, run);
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
  std::vector<SensitivityRows> all;
  std::size_t samples = 0;
  for (const CarFollowingRun& run : runs)
  {
    all.push_back(sensitivityRows(p, run));
    if (all.back().diverged)
    {
      return result;
    }
    samples += all.back().residual.size();
  }
  // Every run's rows and residuals in one matrix and vector, as the batch means take them.
  Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(samples), 4);
  Eigen::VectorXd residuals(static_cast<Eigen::Index>(samples));
  std::vector<std::vector<double>> times;
  Eigen::Index row = 0;
  for (const SensitivityRows& rows : all)
  {
    for (std::size_t k = 0; k < rows.residual.size(); ++k, ++row)
    {
      jacobian.row(row) = rows.row[k].transpose();
      residuals(row) = rows.residual[k];
    }
    times.push_back(rows.time_s);
  }
  if (samples <= 4 || residuals.squaredNorm() <= 0.0)
  {
    return result;
  }
  const BatchLength length = batchMeansBlockLength(times, residuals, min_block_s);
  result.residual_lag1_autocorrelation = length.residual_lag1_autocorrelation;
  result.block_length_s = length.block_length_s;
  const Eigen::Matrix4d jtj = jacobian.transpose() * jacobian;
  const Eigen::Matrix4d meat = batchMeansScoreCovariance(times, jacobian, residuals, result.block_length_s, &result.blocks);
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
  const Eigen::Matrix4d start_gaps = startGapCovariance(bread, startGapScores(all, runs), &result.start_gap_noise_m);
  result.eta_start_gap_error_m = std::sqrt(std::max(0.0, start_gaps(3, 3)));
  result.covariance = correction * bread * meat * bread + start_gaps;
  const Eigen::Vector4d se = result.covariance.diagonal().cwiseSqrt();
  result.standard_error = AccParameters{se(0), se(1), se(2), se(3)};
  return result;
}

}  // namespace acc
