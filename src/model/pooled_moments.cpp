#include "acc_identification/model/pooled_moments.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace acc
{
PooledMoments pooledMoments(const std::vector<CarFollowingRun>& runs, std::vector<double> CarFollowingRun::*column)
{
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0, sum_sq = 0.0;
  PooledMoments out;
  for (const CarFollowingRun& run : runs)
  {
    for (double value : run.*column)
    {
      sum += value;
      sum_sq += value * value;
      ++out.samples;
    }
  }
  const double n = static_cast<double>(out.samples);
  out.mean = out.samples > 0 ? sum / n : kNaN;
  out.standard_deviation = out.samples >= 2 ? std::sqrt(std::max(0.0, sum_sq / n - out.mean * out.mean)) : kNaN;
  return out;
}

}  // namespace acc
