#pragma once

#include <vector>

namespace acc
{
/// The mean of the samples; 0 without samples (callers that must tell "none" apart check size).
double meanOf(const std::vector<double>& samples);

/// sqrt(mean) of squared errors: the RMSE from the squares; 0 without samples.
double rootMeanOf(const std::vector<double>& squared_errors);

/// The q-quantile (q clamped to [0, 1]) with linear interpolation between order statistics; 0
/// without samples.
double interpolatedQuantile(std::vector<double> values, double q);

/// The standard normal z with P(|Z| > z) = tail: 1.96 for 0.05; a one-sided 95 % limit is
/// twoSidedNormalQuantile(0.10) = 1.645 (Boost.Math). NaN unless tail is in (0, 1).
double twoSidedNormalQuantile(double tail);

/// Student's t with P(T > t) = upper_tail at `degrees_of_freedom` (Boost.Math): 1.895 for 0.05 at
/// 7, towards 1.645 as they grow. NaN unless upper_tail is in (0, 1) and the degrees are above 0.
double studentTUpperQuantile(double upper_tail, double degrees_of_freedom);

}  // namespace acc
