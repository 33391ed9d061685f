#include "acc_identification/model/sample_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

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

double interpolatedQuantile(std::vector<double> values, double q)
{
  if (values.empty())
    return 0.0;
  const double position = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(position));
  const std::size_t hi = std::min(values.size() - 1, lo + 1);
  std::nth_element(values.begin(), values.begin() + static_cast<long>(lo), values.end());
  const double a = values[lo];
  std::nth_element(values.begin(), values.begin() + static_cast<long>(hi), values.end());
  const double b = values[hi];
  return a + (position - static_cast<double>(lo)) * (b - a);
}

double twoSidedNormalQuantile(double tail)
{
  if (!(tail > 0.0 && tail < 1.0))
    return std::numeric_limits<double>::quiet_NaN();
  return boost::math::quantile(boost::math::complement(boost::math::normal(), 0.5 * tail));
}

double studentTUpperQuantile(double upper_tail, double degrees_of_freedom)
{
  if (!(upper_tail > 0.0 && upper_tail < 1.0 && degrees_of_freedom > 0.0 && std::isfinite(degrees_of_freedom)))
    return std::numeric_limits<double>::quiet_NaN();
  const boost::math::students_t distribution(degrees_of_freedom);
  return boost::math::quantile(boost::math::complement(distribution, upper_tail));
}

}  // namespace acc
