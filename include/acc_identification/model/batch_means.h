#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace acc
{
/// The batch-means estimate of the covariance M of the score sum_k J_k r_k of a least-squares fit
/// whose residuals r_k are correlated in time (GNSS errors and model errors are, over seconds):
/// the sandwich (J^T J)^-1 M (J^T J)^-1 with M from independent blocks is honest where the plain
/// Gauss-Newton covariance is too small (1.5x on simulated data). One estimator for the
/// calibration (fit_statistics.h) and the diagnosis (augmented_calibration.h).
///
/// The data are segments (runs, or pieces of runs between holes); blocks never straddle them.
/// Rows and residuals are concatenated in segment order: segment_times[i] holds the sample times
/// of segment i, and rows/residuals have one entry per sample of all segments together.

/// How long the blocks are: five correlation times of AR(1) residuals (-h / ln rho, rho the lag-1
/// autocorrelation of the residuals within segments, h the mean step), at least min_block_s, at
/// most an eighth of the data's duration.
struct BatchLength
{
  double block_length_s = 0.0;
  double residual_lag1_autocorrelation = 0.0;
};

BatchLength batchMeansBlockLength(const std::vector<std::vector<double>>& segment_times,
                                  const Eigen::VectorXd& residuals, double min_block_s);

/// M = sum over blocks of (sum_k in block J_k r_k)(...)^T: each segment is cut into consecutive
/// blocks of block_length_s (its last block may be shorter). blocks: how many blocks there were.
Eigen::MatrixXd batchMeansScoreCovariance(const std::vector<std::vector<double>>& segment_times,
                                          const Eigen::MatrixXd& rows, const Eigen::VectorXd& residuals,
                                          double block_length_s, std::size_t* blocks);

}  // namespace acc
