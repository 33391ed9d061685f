#include "acc_identification/model/batch_means.h"

#include <algorithm>
#include <cmath>

namespace acc
{
BatchLength batchMeansBlockLength(const std::vector<std::vector<double>>& segment_times,
                                  const Eigen::VectorXd& residuals, double min_block_s)
{
  double ssr = 0.0, lag1 = 0.0, duration_s = 0.0;
  Eigen::Index row = 0;
  for (const std::vector<double>& times : segment_times)
  {
    for (std::size_t k = 0; k < times.size(); ++k, ++row)
    {
      ssr += residuals(row) * residuals(row);
      lag1 += k > 0 ? residuals(row) * residuals(row - 1) : 0.0;
    }
    duration_s += times.empty() ? 0.0 : times.back() - times.front();
  }
  BatchLength out;
  const auto samples = static_cast<double>(residuals.size());
  const auto steps = samples - static_cast<double>(segment_times.size());
  if (ssr <= 0.0 || steps <= 0.0 || duration_s <= 0.0)
  {
    out.block_length_s = min_block_s;
    return out;
  }
  out.residual_lag1_autocorrelation = lag1 / ssr;
  const double rho = std::clamp(out.residual_lag1_autocorrelation, 1e-6, 0.9999);
  const double correlation_time_s = -(duration_s / steps) / std::log(rho);
  out.block_length_s = std::min(std::max(min_block_s, 5.0 * correlation_time_s), duration_s / 8.0);
  return out;
}

Eigen::MatrixXd batchMeansScoreCovariance(const std::vector<std::vector<double>>& segment_times,
                                          const Eigen::MatrixXd& rows, const Eigen::VectorXd& residuals,
                                          double block_length_s, std::size_t* blocks)
{
  const Eigen::Index q = rows.cols();
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(q, q);
  *blocks = 0;
  Eigen::Index row = 0;
  for (const std::vector<double>& times : segment_times)
  {
    if (times.empty())
    {
      continue;
    }
    Eigen::VectorXd score = Eigen::VectorXd::Zero(q);
    double block_start_s = times.front();
    for (std::size_t k = 0; k < times.size(); ++k, ++row)
    {
      if (times[k] - block_start_s >= block_length_s)
      {
        meat += score * score.transpose();
        ++*blocks;
        score.setZero();
        block_start_s = times[k];
      }
      score += rows.row(row).transpose() * residuals(row);
    }
    meat += score * score.transpose();
    ++*blocks;
  }
  return meat;
}

}  // namespace acc
