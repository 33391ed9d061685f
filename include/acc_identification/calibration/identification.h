#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/calibration/quantity_identifiability.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
/// When data can separate k1, k2, tau_e and eta. At steady following the data pin only
/// eta + tau_e v: a fit then returns noise, and the identifier says so instead.
struct IdentifiabilityCriteria
{
  double min_duration_s = 30.0;          ///< summed over segments
  std::size_t min_samples = 100;
  /// Standard deviation of the follower's speed over the window: below it, no speed changes to
  /// learn the dynamics from (GNSS noise alone is about 0.06 m/s).
  double min_speed_std_mps = 0.5;
  /// After the fit: what the data determine, quantity by quantity (assessQuantities). The window
  /// is identifiable when k1, k2, tau_e and eta all are: one definition for calibrate, the
  /// identifier node and every report.
  QuantityCriteria quantities;
};

/// Why the segments lack the excitation to start a fit, or "" when they have it.
std::string describeInsufficientExcitation(const std::vector<CarFollowingRun>& segments,
                                           const IdentifiabilityCriteria& criteria);

/// Why k1, k2, tau_e or eta is not determined (each reason, "; " between them), or "" when all
/// four are.
std::string describeUndeterminedParameters(const IdentifiableQuantities& quantities);

struct IdentificationOptions
{
  ParameterBounds bounds;
  MultistartOptions multistart;
  IdentifiabilityCriteria criteria;
};

/// Everything one calibration of a set of segments gives.
struct Identification
{
  bool solved = false;         ///< false when skipped for lack of excitation (then only note is set)
  bool identifiable = false;   ///< k1, k2, tau_e and eta all determined (see quantities)
  std::string note;            ///< why not identifiable; empty when identifiable
  std::size_t samples = 0;
  std::size_t segments = 0;
  MultistartResult calibration;
  FitQuality fit;
  ParameterUncertainty uncertainty;
  StringStabilityReport stability;
  /// What the data determine, quantity by quantity (set when solved and not diverged).
  std::optional<IdentifiableQuantities> quantities;
};

/// Checks excitation, calibrates (multistart, warm starts first), then scores the fit, its
/// standard errors, identifiability and string stability. Never throws on data problems: a
/// segment that cannot be simulated is reported in note and the result is not solved.
Identification identifyAcc(const std::vector<CarFollowingRun>& segments, const IdentificationOptions& options,
                           const std::vector<AccParameters>& warm_starts = {});

}  // namespace acc
