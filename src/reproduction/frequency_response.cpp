#include "acc_identification/reproduction/frequency_response.h"

#include <cmath>
#include <complex>
#include <limits>
#include <stdexcept>

#include "acc_identification/model/string_stability.h"

namespace acc
{
std::vector<double> logSpacedFrequencies(double min_rad_s, double max_rad_s, std::size_t count)
{
  if (count < 2 || !(min_rad_s > 0.0) || !(min_rad_s < max_rad_s) || !std::isfinite(max_rad_s))
  {
    throw std::invalid_argument("frequencies need 0 < min < max and at least 2 points");
  }
  std::vector<double> frequencies(count);
  const double low = std::log10(min_rad_s);
  const double high = std::log10(max_rad_s);
  for (std::size_t i = 0; i < count; ++i)
  {
    frequencies[i] = std::pow(10.0, low + (high - low) * static_cast<double>(i) / static_cast<double>(count - 1));
  }
  return frequencies;
}

double eulerTransferGain(const AccParameters& p, double frequency_rad_s, double time_step_s)
{
  const double h = time_step_s;
  const std::complex<double> z_minus_1 = std::polar(1.0, frequency_rad_s * h) - 1.0;
  const std::complex<double> numerator = h * p.k2_per_s * z_minus_1 + h * h * p.k1_per_s2;
  const std::complex<double> denominator = z_minus_1 * z_minus_1 +
                                           h * (p.k2_per_s + p.k1_per_s2 * p.tau_e_s) * z_minus_1 +
                                           h * h * p.k1_per_s2;
  // At w = 0 both vanish when k1 = 0; the limit is then k2 h / (k2 h) = 1 as for the model.
  if (std::abs(denominator) == 0.0)
  {
    return std::abs(numerator) == 0.0 ? 1.0 : std::numeric_limits<double>::infinity();
  }
  return std::abs(numerator / denominator);
}

bool eulerRecursionStable(const AccParameters& p, double time_step_s)
{
  const double b = p.k2_per_s + p.k1_per_s2 * p.tau_e_s;
  const std::complex<double> root_of_discriminant = std::sqrt(std::complex<double>(b * b - 4.0 * p.k1_per_s2, 0.0));
  for (const std::complex<double> r : {0.5 * (-b + root_of_discriminant), 0.5 * (-b - root_of_discriminant)})
  {
    if (std::abs(1.0 + time_step_s * r) >= 1.0)
      return false;
  }
  return true;
}

EulerPeak eulerPeak(const AccParameters& p, double time_step_s)
{
  EulerPeak peak{-std::numeric_limits<double>::infinity(), 0.0};
  for (const double w : logSpacedFrequencies(1e-4, M_PI / time_step_s, 4000))
  {
    const double gain_db = 20.0 * std::log10(eulerTransferGain(p, w, time_step_s));
    if (gain_db > peak.gain_db)
      peak = {gain_db, w};
  }
  return peak;
}

std::vector<BodeSample> bodeMagnitude(const AccParameters& p, const std::vector<double>& frequencies_rad_s,
                                      double time_step_s)
{
  std::vector<BodeSample> samples;
  samples.reserve(frequencies_rad_s.size());
  for (double w : frequencies_rad_s)
  {
    samples.push_back({w, transferGainDb(p, w), 20.0 * std::log10(eulerTransferGain(p, w, time_step_s))});
  }
  return samples;
}

}  // namespace acc
