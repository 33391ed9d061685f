#include "acc_identification/model/sample_statistics.h"

#include <cmath>

namespace acc
{
double meanOf(const std::vector<double>& samples)
{
  double sum = 0.0;
  for (double value : samples)
    sum += value;
  return samples.empty() ? 0.0 : sum / static_cast<double>(samples.size());
}

double rootMeanOf(const std::vector<double>& squared_errors)
{
  return std::sqrt(meanOf(squared_errors));
}

}  // namespace acc
