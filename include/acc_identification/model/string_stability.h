#pragma once

#include <optional>
#include <string>

#include "acc_identification/model/acc_parameters.h"

namespace acc
{
/// What the linear analysis of Section II-B says about a platoon of identical ACC vehicles.
struct StringStabilityReport
{
  /// Wilson & Ward's lambda2 = f_s / f_v^3 (f_v^2 / 2 - f_dv f_v - f_s); stable when < 0.
  /// +infinity when k1 > 0 and tau_e = 0 (f_v = 0: every low frequency grows); 0 when k1 = 0.
  double lambda2 = 0.0;
  /// |Gamma(j w)| <= 1 for every w >= 0 (the paper's sufficient condition, eq. 10). It agrees
  /// with lambda2 < 0 except on the boundary lambda2 = 0, where |Gamma| <= 1 still holds.
  bool string_stable = true;
  /// Disturbances with frequency in [0, w_c) grow along the platoon; 0 when none do [rad/s].
  double amplified_band_upper_rad_s = 0.0;
  /// max over w of 20 log10 |Gamma(j w)|; 0 dB (at w = 0) for a stable model [dB].
  double peak_gain_db = 0.0;
  double peak_frequency_rad_s = 0.0;
};

/// The string-stability margin of the model, m = k1 tau_e^2 + 2 k2 tau_e - 2: a platoon of
/// identical followers is string stable iff m >= 0 (|Gamma(j w)| <= 1 for every w, lambda2 < 0
/// off the boundary). eta plays no part.
double stabilityMargin(const AccParameters& p);

/// lambda2 of Wilson & Ward (paper eq. 11).
double lambda2(const AccParameters& p);

/// |Gamma(j w)| of the speed-to-speed transfer function (paper eq. 9), as a ratio.
double transferGain(const AccParameters& p, double frequency_rad_s);

/// 20 log10 |Gamma(j w)| [dB].
double transferGainDb(const AccParameters& p, double frequency_rad_s);

/// Upper end w_c of the amplified band: w_c^2 = -k1 m (m = stabilityMargin) when m < 0, else 0
/// (closed form: |Gamma|^2 > 1 exactly below it). A margin within the rounding of its own terms
/// is the boundary m = 0, string stable: (0.1, 0.95, 1 s) was called unstable by 8e-18.
double amplifiedBandUpperRadS(const AccParameters& p);

/// Frequency of the largest |Gamma| in closed form: setting d|Gamma|^2/d(w^2) = 0 gives
///   k2^2 x^2 + 2 k1^2 x - k1^2 w_c^2 = 0,  x = w^2.
/// 0 when the band is empty (the peak is |Gamma(0)| = 1).
double peakFrequencyRadS(const AccParameters& p);

StringStabilityReport analyzeStringStability(const AccParameters& p);

/// report.string_stable where lambda2 says anything; nullopt where lambda2 is NaN (parameters not
/// determined): a "false" there would read as "unstable". Every output writes this one (JSON null).
std::optional<bool> knownStringStability(const StringStabilityReport& report);

/// What held-out data say of string stability (calibration/string_stability_verdict.h for the paper's
/// model, diagnosis/augmented_stability_verdict.h for an augmented one).
enum class StabilityVerdict
{
  Stable,
  Unstable,
  Undecided
};

/// "stable", "unstable", "undecided".
std::string toString(StabilityVerdict verdict);

/// "STABLE", "UNSTABLE", "UNDECIDED": the verdict as the reports print it.
std::string verdictInCapitals(StabilityVerdict verdict);

}  // namespace acc
