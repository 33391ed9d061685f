#include "acc_identification/model/string_stability.h"
#include "acc_identification/model/plain_text.h"

#include <cmath>
#include <limits>

#include "acc_identification/model/acc_model.h"

namespace acc
{
double lambda2(const AccParameters& p)
{
  const AccelerationPartials d = accelerationPartials(p);
  if (d.f_s == 0.0)
  {
    return 0.0;  // no spacing feedback: Gamma = k2 / (j w + k2), never above 1
  }
  if (d.f_v == 0.0)
  {
    return std::numeric_limits<double>::infinity();  // tau_e = 0: the limit f_v -> 0- of lambda2
  }
  return d.f_s / (d.f_v * d.f_v * d.f_v) * (d.f_v * d.f_v / 2.0 - d.f_dv * d.f_v - d.f_s);
}

double transferGain(const AccParameters& p, double frequency_rad_s)
{
  const AccelerationPartials d = accelerationPartials(p);
  const double w2 = frequency_rad_s * frequency_rad_s;
  const double damping = d.f_dv - d.f_v;
  const double numerator = w2 * d.f_dv * d.f_dv + d.f_s * d.f_s;
  const double denominator = (d.f_s - w2) * (d.f_s - w2) + w2 * damping * damping;
  if (denominator == 0.0)
  {
    return numerator == 0.0 ? 1.0 : std::numeric_limits<double>::infinity();
  }
  return std::sqrt(numerator / denominator);
}

double transferGainDb(const AccParameters& p, double frequency_rad_s)
{
  return 20.0 * std::log10(transferGain(p, frequency_rad_s));
}

double stabilityMargin(const AccParameters& p)
{
  return p.k1_per_s2 * p.tau_e_s * p.tau_e_s + 2.0 * p.k2_per_s * p.tau_e_s - 2.0;
}

namespace
{
/// w_c^2 = -k1 m; 0 (no amplified band) when m >= 0 or m is within the rounding of its terms:
/// parameters on the boundary (k1 tau_e^2 + 2 k2 tau_e = 2 in decimal) land on either side of 0
/// by a few ulps, and the verdict must not depend on which.
double amplifiedBandUpperSquared(const AccParameters& p)
{
  const double margin = stabilityMargin(p);
  const double terms = std::abs(p.k1_per_s2 * p.tau_e_s * p.tau_e_s) + std::abs(2.0 * p.k2_per_s * p.tau_e_s) + 2.0;
  if (margin >= -8.0 * std::numeric_limits<double>::epsilon() * terms)
    return 0.0;
  return -p.k1_per_s2 * margin;
}
}  // namespace

double amplifiedBandUpperRadS(const AccParameters& p)
{
  const double upper_squared = amplifiedBandUpperSquared(p);
  return upper_squared > 0.0 ? std::sqrt(upper_squared) : 0.0;
}

double peakFrequencyRadS(const AccParameters& p)
{
  const double upper_squared = amplifiedBandUpperSquared(p);
  if (!(upper_squared > 0.0))
  {
    return 0.0;
  }
  const double k1 = p.k1_per_s2;
  const double k2 = p.k2_per_s;
  if (k2 == 0.0)
  {
    return std::sqrt(upper_squared / 2.0);  // the quadratic degenerates to 2 k1^2 x = k1^2 w_c^2
  }
  // Positive root of k2^2 x^2 + 2 k1^2 x - k1^2 w_c^2 = 0, written to avoid cancellation, and
  // divided through by k1 so that a tiny k1 (1e-300, whose square underflows) gives 0, not 0/0.
  const double x = k1 * upper_squared / (k1 + std::sqrt(k1 * k1 + k2 * k2 * upper_squared));
  return std::sqrt(x);
}

StringStabilityReport analyzeStringStability(const AccParameters& p)
{
  StringStabilityReport report;
  report.lambda2 = lambda2(p);
  report.amplified_band_upper_rad_s = amplifiedBandUpperRadS(p);
  report.string_stable = report.amplified_band_upper_rad_s == 0.0;
  report.peak_frequency_rad_s = peakFrequencyRadS(p);
  report.peak_gain_db = transferGainDb(p, report.peak_frequency_rad_s);
  if (p.k1_per_s2 > 0.0 && p.k2_per_s + p.k1_per_s2 * p.tau_e_s == 0.0)
  {
    // Undamped (k2 = tau_e = 0): |Gamma| = k1 / |k1 - w^2| is infinite at sqrt(k1), where the
    // rounded square of the root left a finite 313 dB.
    report.peak_frequency_rad_s = std::sqrt(p.k1_per_s2);
    report.peak_gain_db = std::numeric_limits<double>::infinity();
  }
  return report;
}

std::string toString(StabilityVerdict verdict)
{
  switch (verdict)
  {
    case StabilityVerdict::Stable: return "stable";
    case StabilityVerdict::Unstable: return "unstable";
    case StabilityVerdict::Undecided: return "undecided";
  }
  return "undecided";
}

std::string verdictInCapitals(StabilityVerdict verdict)
{
  return upperCase(toString(verdict));
}

std::optional<bool> knownStringStability(const StringStabilityReport& report)
{
  if (std::isnan(report.lambda2))
    return std::nullopt;
  return report.string_stable;
}

}  // namespace acc
