#pragma once

#include <vector>

#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// Standard errors of an augmented fit's parameters x (k1, k2, tau_e, eta, effect values...; box:
/// their ranges) on its segments: the Gauss-Newton sandwich (J^T J)^-1 M (J^T J)^-1 with a
/// central-difference Jacobian J of the simulated speeds (1e-4 of each range, one-sided at a bound)
/// and M the batch-means covariance of the scores J_k r_k (blocks of speedResidualBlockLengthS,
/// within segments), times n / (n - p), plus what the segments' measured start gaps carry
/// (start_gap_covariance.h). As the calibration component's fit statistics (fit_statistics.h): for
/// the base model they are calibrate's. NaN for a parameter that does not move the speeds (a limit
/// never reached: the others are computed without it), and for all when there are no more samples
/// than parameters, J^T J is singular or there are fewer than four blocks.
std::vector<double> augmentedStandardErrors(const std::vector<double>& x, const AugmentedParameterBox& box,
                                            const std::vector<CarFollowingRun>& segments);

/// The batch-means block length [s] of a fit's speed residuals (measured less simulated speed,
/// segment after segment) as the fits' standard errors take it: five residual correlation times,
/// at least 10 s (batch_means.h). What the diagnosed model's bootstrap resamples its residuals in.
double speedResidualBlockLengthS(const std::vector<CarFollowingRun>& segments, const std::vector<double>& residuals);

}  // namespace acc
