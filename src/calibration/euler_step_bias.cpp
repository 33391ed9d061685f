#include "acc_identification/calibration/euler_step_bias.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/calibration/margin_constrained_fit.h"
#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/model/acc_parameters_json.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/json_number.h"
#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// The fit's response to the run's leader under the continuous law (Euler on the refined run),
/// at the run's own times: the data a noise-free car obeying the fit would have recorded.
bool continuousResponse(const AccParameters& fit, const CarFollowingRun& run, std::size_t substeps,
                        CarFollowingRun& response)
{
  const SimulatedFollower fine = simulateFollower(fit, refineRun(run, substeps));
  if (fine.diverged)
    return false;
  response = run;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    response.follower_speed_mps[k] = fine.speed_mps[k * substeps];
    response.space_gap_m[k] = fine.space_gap_m[k * substeps];
  }
  return true;
}

AccParameters difference(const AccParameters& a, const AccParameters& b)
{
  return {a.k1_per_s2 - b.k1_per_s2, a.k2_per_s - b.k2_per_s, a.tau_e_s - b.tau_e_s, a.eta_m - b.eta_m};
}

/// p within the bounds: a correction that would carry a parameter held at its bound beyond it
/// (k2 = 0 corrected to -0.02) leaves it at the bound.
AccParameters withinBounds(const AccParameters& p, const ParameterBounds& b)
{
  return {std::clamp(p.k1_per_s2, b.lower.k1_per_s2, b.upper.k1_per_s2),
          std::clamp(p.k2_per_s, b.lower.k2_per_s, b.upper.k2_per_s),
          std::clamp(p.tau_e_s, b.lower.tau_e_s, b.upper.tau_e_s), std::clamp(p.eta_m, b.lower.eta_m, b.upper.eta_m)};
}

/// "k1 -26 % (4.1 standard errors)" for each bias above half its standard error (the fit's
/// quantities'), "; "-separated.
std::string materialBiases(const EulerStepBias& check, const std::optional<IdentifiableQuantities>& quantities)
{
  const char* names[5] = {"k1", "k2", "tau_e", "eta", "margin"};
  const char* quantity_names[5] = {"k1", "k2", "tau_e", "eta", "stability_margin"};
  const double bias[5] = {check.bias.k1_per_s2, check.bias.k2_per_s, check.bias.tau_e_s, check.bias.eta_m,
                          check.margin_bias};
  const double value[5] = {check.fit.k1_per_s2, check.fit.k2_per_s, check.fit.tau_e_s, check.fit.eta_m,
                           stabilityMargin(check.fit)};
  std::string out;
  for (int i = 0; i < 5; ++i)
  {
    const QuantityEstimate* q = quantities ? quantities->find(quantity_names[i]) : nullptr;
    const double error = q != nullptr ? q->standard_error : EulerStepBias::kNaN;
    // An error that is NaN (singular covariance, no quantities) or 0 is nothing to compare with.
    if (!(error > 0.0) || !(std::abs(bias[i]) > 0.5 * error))
      continue;
    const std::string size = i < 4 && std::abs(value[i]) > 0.0 ? printfText("%+.1f %%", 100.0 * bias[i] / value[i])
                                                                : printfText("%+.3g", bias[i]);
    out += printfText("%s%s %s (%.1f standard errors)", out.empty() ? "" : "; ", names[i], size.c_str(),
                      std::abs(bias[i]) / error);
  }
  return out;
}
}  // namespace

CarFollowingRun refineRun(const CarFollowingRun& run, std::size_t substeps)
{
  CarFollowingRun fine;
  fine.name = run.name;
  const auto add = [&fine](double t, double gap, double follower, double leader) {
    fine.time_s.push_back(t);
    fine.space_gap_m.push_back(gap);
    fine.follower_speed_mps.push_back(follower);
    fine.leader_speed_mps.push_back(leader);
  };
  for (std::size_t k = 0; k + 1 < run.size(); ++k)
  {
    for (std::size_t j = 0; j < substeps; ++j)
    {
      const double w = static_cast<double>(j) / static_cast<double>(substeps);
      const auto at = [&](const std::vector<double>& c) { return c[k] + w * (c[k + 1] - c[k]); };
      add(at(run.time_s), at(run.space_gap_m), at(run.follower_speed_mps), at(run.leader_speed_mps));
    }
  }
  if (run.size() > 0)
    add(run.time_s.back(), run.space_gap_m.back(), run.follower_speed_mps.back(), run.leader_speed_mps.back());
  return fine;
}

EulerStepBias estimateEulerStepBias(const Identification& fitted, const std::vector<CarFollowingRun>& runs,
                                    const IdentificationOptions& options, std::size_t substeps)
{
  const AccParameters& fit = fitted.calibration.parameters;
  EulerStepBias check;
  check.fit = fit;
  check.substeps = std::max<std::size_t>(2, substeps);
  check.median_step_s = medianStepS(runs);
  std::vector<CarFollowingRun> responses(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i)
  {
    if (!continuousResponse(fit, runs[i], check.substeps, responses[i]))
    {
      check.reason = "the fit's continuous-law response to run '" + runs[i].name + "' diverges";
      return check;
    }
  }
  // The calibration identifyAcc runs, without its excitation gate: the data passed it, and the
  // model's own response is smoother than what the car did (a steady drive can fall below it).
  MultistartOptions multistart = options.multistart;
  multistart.progress = nullptr;
  MultistartResult refit;
  try
  {
    refit = calibrateMultistart(CalibrationObjective(responses, options.bounds), multistart, {fit});
  }
  catch (const std::invalid_argument& error)
  {
    check.reason = std::string("the continuous-law response cannot be calibrated: ") + error.what();
    return check;
  }
  if (refit.diverged)
  {
    check.reason = "every start of the refit diverged";
    return check;
  }
  check.assessed = true;
  check.refit = refit.parameters;
  check.bias = difference(check.refit, fit);
  check.corrected = withinBounds(difference(fit, check.bias), options.bounds);
  check.margin_bias = stabilityMargin(check.refit) - stabilityMargin(fit);
  check.corrected_margin = stabilityMargin(check.corrected);
  check.material_because = materialBiases(check, fitted.quantities);
  check.material = !check.material_because.empty();
  return check;
}

nlohmann::json toJson(const EulerStepBias& check)
{
  return {{"assessed", check.assessed},
          {"reason", check.reason},
          {"median_step_s", jsonNumber(check.median_step_s)},
          {"substeps", check.substeps},
          {"refit", check.assessed ? parametersJson(check.refit) : nlohmann::json()},
          {"bias", check.assessed ? parametersJson(check.bias) : nlohmann::json()},
          {"corrected", check.assessed ? parametersJson(check.corrected) : nlohmann::json()},
          {"margin_bias", jsonNumber(check.margin_bias)},
          {"corrected_margin", jsonNumber(check.corrected_margin)},
          {"material", check.material},
          {"material_because", check.material_because}};
}

std::string describeEulerStepBias(const EulerStepBias& check)
{
  std::ostringstream out;
  out << printfText("Euler step (the paper's calibration simulates at the data's own step, median %.3g s): ",
                    check.median_step_s);
  if (!check.assessed)
  {
    out << "not assessed: " << check.reason << "\n";
    return out.str();
  }
  const AccParameters& b = check.bias;
  out << printfText("the fit's own response under the continuous law (%zu substeps), refitted, moves k1 %+.3g, "
                    "k2 %+.3g, tau_e %+.3g, eta %+.3g, margin %+.3g: ",
                    check.substeps, b.k1_per_s2, b.k2_per_s, b.tau_e_s, b.eta_m, check.margin_bias);
  if (!check.material)
  {
    out << "under half of every standard error, immaterial\n";
    return out.str();
  }
  out << "MATERIAL: " << check.material_because << "\n  " << correctedFitText(check)
      << "; a higher recording rate shrinks the bias in proportion to the step\n";
  return out.str();
}

std::string correctedFitText(const EulerStepBias& check)
{
  const AccParameters& c = check.corrected;
  return printfText("corrected (fit - bias): k1 %.4f k2 %.4f tau_e %.4f eta %.3f margin %+.3f", c.k1_per_s2,
                    c.k2_per_s, c.tau_e_s, c.eta_m, check.corrected_margin);
}

}  // namespace acc
