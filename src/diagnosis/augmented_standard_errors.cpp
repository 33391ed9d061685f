#include "acc_identification/diagnosis/augmented_standard_errors.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "acc_identification/model/batch_means.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/start_gap_covariance.h"

namespace acc
{
namespace
{
constexpr double kMinBlockS = 10.0;

/// The block length rule of speedResidualBlockLengthS, on the segments' times.
double blockLengthS(const std::vector<std::vector<double>>& times, const Eigen::VectorXd& residuals)
{
  return batchMeansBlockLength(times, residuals, kMinBlockS).block_length_s;
}

std::vector<double> simulatedSpeeds(const std::vector<double>& x, const AugmentedParameterBox& box,
                                    const std::vector<CarFollowingRun>& segments)
{
  std::vector<double> speeds;
  const EffectSettings settings = box.settingsOf(x);
  for (const CarFollowingRun& run : segments)
  {
    const SimulatedFollower sim = simulateFollower(AugmentedParameterBox::baseOf(x), settings, run);
    speeds.insert(speeds.end(), sim.speed_mps.begin(), sim.speed_mps.end());
  }
  return speeds;
}

/// Each segment's sample times, for the batch means (whose blocks do not straddle segments).
std::vector<std::vector<double>> segmentTimes(const std::vector<CarFollowingRun>& segments)
{
  std::vector<std::vector<double>> times;
  for (const CarFollowingRun& run : segments)
    times.push_back(run.time_s);
  return times;
}

/// Measured less simulated follower speed, segment after segment.
Eigen::VectorXd speedResiduals(const std::vector<double>& x, const AugmentedParameterBox& box,
                               const std::vector<CarFollowingRun>& segments)
{
  std::vector<double> measured;
  for (const CarFollowingRun& run : segments)
    measured.insert(measured.end(), run.follower_speed_mps.begin(), run.follower_speed_mps.end());
  const std::vector<double> fitted = simulatedSpeeds(x, box, segments);
  Eigen::VectorXd residuals(static_cast<Eigen::Index>(measured.size()));
  for (std::size_t i = 0; i < measured.size(); ++i)
    residuals(static_cast<Eigen::Index>(i)) = measured[i] - fitted[i];
  return residuals;
}

/// The simulated speeds' central differences in each parameter: 1e-4 of its range, one-sided at a bound.
Eigen::MatrixXd speedJacobian(const std::vector<double>& x, const AugmentedParameterBox& box,
                              const std::vector<CarFollowingRun>& segments, Eigen::Index samples)
{
  Eigen::MatrixXd jacobian(samples, static_cast<Eigen::Index>(x.size()));
  for (std::size_t j = 0; j < x.size(); ++j)
  {
    const double step = 1e-4 * (box.upper[j] - box.lower[j]);
    std::vector<double> plus = x, minus = x;
    plus[j] = std::min(x[j] + step, box.upper[j]);
    minus[j] = std::max(x[j] - step, box.lower[j]);
    const std::vector<double> up = simulatedSpeeds(plus, box, segments);
    const std::vector<double> down = simulatedSpeeds(minus, box, segments);
    for (Eigen::Index i = 0; i < samples; ++i)
      jacobian(i, static_cast<Eigen::Index>(j)) =
          (up[static_cast<std::size_t>(i)] - down[static_cast<std::size_t>(i)]) / (plus[j] - minus[j]);
  }
  return jacobian;
}

/// The columns that move the speeds: one that does not (a limit never reached) is not determined.
std::vector<Eigen::Index> movingColumns(const Eigen::MatrixXd& jacobian)
{
  std::vector<Eigen::Index> moving;
  const double floor = 1e-9 * std::sqrt(static_cast<double>(jacobian.rows()));
  for (Eigen::Index j = 0; j < jacobian.cols(); ++j)
    if (jacobian.col(j).norm() > floor)
      moving.push_back(j);
  return moving;
}

/// What each segment's measured start gap puts on the estimate (start_gap_covariance.h): J_i^T g_i
/// with g_i the simulated speeds' central difference in the segment's start gap, since an effect
/// (a braking ratio of the gap, a sensor offset) may use the gap otherwise than through s - eta.
std::vector<StartGapScore> startGapScores(const std::vector<double>& x, const AugmentedParameterBox& box,
                                          const std::vector<CarFollowingRun>& segments, const Eigen::MatrixXd& jacobian)
{
  constexpr double kStartGapStepM = 0.01;
  const AccParameters base = AugmentedParameterBox::baseOf(x);
  const EffectSettings settings = box.settingsOf(x);
  std::vector<StartGapScore> scores;
  Eigen::Index first_row = 0;
  for (const CarFollowingRun& run : segments)
  {
    const Eigen::Index rows = static_cast<Eigen::Index>(run.size());
    CarFollowingRun farther = run, nearer = run;
    farther.space_gap_m[0] += kStartGapStepM;
    nearer.space_gap_m[0] -= kStartGapStepM;
    const std::vector<double> up = simulateFollower(base, settings, farther).speed_mps;
    const std::vector<double> down = simulateFollower(base, settings, nearer).speed_mps;
    Eigen::VectorXd per_metre(rows);
    for (Eigen::Index k = 0; k < rows; ++k)
      per_metre(k) = (up[static_cast<std::size_t>(k)] - down[static_cast<std::size_t>(k)]) / (2.0 * kStartGapStepM);
    scores.push_back({gapSampleNoiseM(run), jacobian.middleRows(first_row, rows).transpose() * per_metre});
    first_row += rows;
  }
  return scores;
}
}  // namespace

std::vector<double> augmentedStandardErrors(const std::vector<double>& x, const AugmentedParameterBox& box,
                                            const std::vector<CarFollowingRun>& segments)
{
  std::vector<double> errors(x.size(), std::numeric_limits<double>::quiet_NaN());
  const Eigen::VectorXd residuals = speedResiduals(x, box, segments);
  const Eigen::Index n = residuals.size();
  if (n <= static_cast<Eigen::Index>(x.size()))
    return errors;
  const Eigen::MatrixXd jacobian = speedJacobian(x, box, segments, n);
  const std::vector<Eigen::Index> moving = movingColumns(jacobian);
  const Eigen::MatrixXd reduced = jacobian(Eigen::all, moving);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(reduced.transpose() * reduced);
  std::size_t blocks = 0;
  const std::vector<std::vector<double>> times = segmentTimes(segments);
  const Eigen::MatrixXd scores_covariance =
      batchMeansScoreCovariance(times, reduced, residuals, blockLengthS(times, residuals), &blocks);
  if (!lu.isInvertible() || blocks < 4)
    return errors;
  const Eigen::MatrixXd bread = lu.inverse();
  // n / (n - p): the usual small-sample correction, as calibrate's sandwich (fit_statistics.h).
  const double correction = static_cast<double>(n) / static_cast<double>(n - reduced.cols());
  const Eigen::MatrixXd covariance = correction * bread * scores_covariance * bread +
                                     startGapCovariance(bread, startGapScores(x, box, segments, reduced));
  for (std::size_t a = 0; a < moving.size(); ++a)
  {
    const double variance = covariance(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(a));
    if (variance >= 0.0)
      errors[static_cast<std::size_t>(moving[a])] = std::sqrt(variance);
  }
  return errors;
}

double speedResidualBlockLengthS(const std::vector<CarFollowingRun>& segments, const std::vector<double>& residuals)
{
  const Eigen::VectorXd residual_vector =
      Eigen::Map<const Eigen::VectorXd>(residuals.data(), static_cast<Eigen::Index>(residuals.size()));
  return blockLengthS(segmentTimes(segments), residual_vector);
}

}  // namespace acc
