#pragma once

#include <cstddef>
#include <vector>

#include "acc_identification/model/acc_parameters.h"

namespace acc
{
/// One point of the paper's Fig. 6: the speed-to-speed gain at one frequency.
struct BodeSample
{
  double frequency_rad_s = 0.0;
  double gain_db = 0.0;        ///< continuous model, 20 log10 |Gamma(j w)|
  double euler_gain_db = 0.0;  ///< the explicit-Euler recursion the simulations run (see below)
};

/// count frequencies spaced evenly in log10 between min and max (inclusive; count >= 2,
/// 0 < min < max). Throws std::invalid_argument otherwise.
std::vector<double> logSpacedFrequencies(double min_rad_s, double max_rad_s, std::size_t count);

/// |Gamma_h(e^{j w h})| of the explicit-Euler platoon recursion at step h. Eliminating the gap
/// from v[k+1] = v[k] + h f(s[k], v[k], u[k] - v[k]), s[k+1] = s[k] + h (u[k] - v[k]) gives
///   Gamma_h(z) = (h k2 (z - 1) + h^2 k1) / ((z - 1)^2 + h (k2 + k1 tau_e)(z - 1) + h^2 k1),
/// which tends to Gamma(j w) as h -> 0. A simulated platoon in steady oscillation follows it.
double eulerTransferGain(const AccParameters& p, double frequency_rad_s, double time_step_s);

/// Whether one car's explicit-Euler recursion at step h is stable behind a steady leader: both
/// roots z = 1 + h r of its characteristic polynomial (r the roots of r^2 + (k2 + k1 tau_e) r + k1)
/// lie inside the unit circle. A stable recursion can still pass oscillations on amplified
/// (eulerPeak) where the continuous law does not.
bool eulerRecursionStable(const AccParameters& p, double time_step_s);

/// The peak of |Gamma_h| over its frequencies up to Nyquist, pi / h: the most a platoon simulated
/// at step h passes on from car to car.
struct EulerPeak
{
  double gain_db = 0.0;
  double frequency_rad_s = 0.0;
};
EulerPeak eulerPeak(const AccParameters& p, double time_step_s);

/// Bode magnitude of both the model and its Euler recursion at the given frequencies.
std::vector<BodeSample> bodeMagnitude(const AccParameters& p, const std::vector<double>& frequencies_rad_s,
                                      double time_step_s);

}  // namespace acc
