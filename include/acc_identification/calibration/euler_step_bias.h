#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/identification.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// The paper's calibration simulates the model by explicit Euler at the data's own step (Section
/// IV), so it identifies the parameters of that discrete-time map, not those of the continuous ACC
/// law dv/dt = k1 (s - eta - tau_e v) + k2 (v_lead - v). The difference grows with the step: on
/// synthetic drives whose truth is simulated ten times finer, k1 comes out 3 % low, k2 2 % high
/// and the margin 0.013 high at 10 Hz; 26 %, 13 % and 0.14 at 1 Hz (docs/RESULTS.md).
///
/// This check measures it for one fit on its own data: the fit's response to the measured leader
/// under the continuous law (Euler at a step `substeps` times finer, the leader's speed linear
/// between samples), sampled at the data's times and calibrated as the data were. Without noise
/// the refit differs from the fit only by what the Euler step adds: bias = refit - fit (a
/// parametric bootstrap of the discretisation), and fit - bias (within the bounds) is the
/// first-order corrected fit.
struct EulerStepBias
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  bool assessed = false;
  std::string reason;           ///< why not assessed; empty when assessed
  double median_step_s = kNaN;  ///< of the data
  std::size_t substeps = 0;
  AccParameters fit;            ///< the fit checked
  AccParameters refit;          ///< the calibration of the fit's own continuous-law response
  AccParameters bias;           ///< refit - fit, per parameter
  AccParameters corrected;      ///< fit - bias, within the fit's bounds (a parameter held at one stays)
  double margin_bias = kNaN;    ///< margin(refit) - margin(fit)
  double corrected_margin = kNaN;  ///< margin(corrected)
  /// Some bias (k1, k2, tau_e, eta or the margin) above half its standard error at the fit: the
  /// step moves the answer by a visible part of what the data pin.
  bool material = false;
  std::string material_because;  ///< which, "k1 -26 % (4.1 standard errors)"; empty when immaterial
};

/// The check above for identifyAcc's fit on `runs` (its parameters; its quantities' standard
/// errors, where it has them, say what is material), refitted with the same options (its bounds
/// and starts; the fit as a warm start; not its excitation gate, which the data passed). Not
/// assessed when the continuous-law response diverges or the refit fails (no data); the reason
/// says so.
EulerStepBias estimateEulerStepBias(const Identification& fitted, const std::vector<CarFollowingRun>& runs,
                                    const IdentificationOptions& options, std::size_t substeps = 10);

/// The run with every step cut into `substeps` equal steps: the leader's speed (and the other
/// columns) linear between the samples, the samples themselves kept at index k * substeps.
CarFollowingRun refineRun(const CarFollowingRun& run, std::size_t substeps);

/// {assessed, reason, median_step_s, substeps, refit, bias, corrected (parameters as the JSON's
/// "parameters"), margin_bias, corrected_margin, material, material_because}; NaN as null.
nlohmann::json toJson(const EulerStepBias& check);

/// The report's lines: what the step moves, and whether that matters against the standard errors.
std::string describeEulerStepBias(const EulerStepBias& check);

/// "corrected (fit - bias): k1 0.0741 k2 0.5669 tau_e 1.0239 eta 5.676 margin -0.761", as the
/// report and the campaign's notes say it.
std::string correctedFitText(const EulerStepBias& check);

}  // namespace acc
