#pragma once

#include <cstddef>
#include <vector>

#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// One column (e.g. &CarFollowingRun::space_gap_m) over every sample of the runs, pooled around one
/// mean: the data's own spread, for the model-adequacy checks and for data without a fit.
struct PooledMoments
{
  std::size_t samples = 0;
  double mean = 0.0;                ///< NaN without samples
  double standard_deviation = 0.0;  ///< population form; NaN under two samples
};

PooledMoments pooledMoments(const std::vector<CarFollowingRun>& runs, std::vector<double> CarFollowingRun::*column);

}  // namespace acc
