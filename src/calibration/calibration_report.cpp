#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/model/acc_parameters_json.h"
#include "acc_identification/model/json_number.h"

#include "acc_identification/evidence/evidence_json.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "acc_identification/model/number_text.h"
#include "acc_identification/model/pooled_moments.h"

namespace acc
{
namespace
{
nlohmann::json fitJson(const FitQuality& fit)
{
  return {{"samples", fit.samples},
          {"rmse_speed_mps", jsonNumber(fit.rmse_speed_mps)},
          {"rmse_gap_m", jsonNumber(fit.rmse_gap_m)},
          {"diverged", fit.diverged}};
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string equilibriumGapNote(const UnfittedDataSummary& summary)
{
  char text[256];
  if (std::isfinite(summary.equilibrium_gap_m))
    std::snprintf(text, sizeof text,
                  "steady following: the equilibrium gap eta + tau_e v at %.2f m/s is %.2f m (the mean gap), though "
                  "not eta and tau_e apart",
                  summary.follower_speed_mean_mps, summary.equilibrium_gap_m);
  else
    std::snprintf(text, sizeof text,
                  "no equilibrium gap: the follower speed spread %.3f m/s is not steady (below %.3f m/s)",
                  summary.follower_speed_spread_mps, summary.steady_speed_spread_mps);
  return text;
}

/// The point estimate's lambda2, labelled as such: beside a stability test it is not the verdict.
std::string pointEstimateStabilityLine(const StringStabilityReport& s, bool tested)
{
  char line[400];
  const std::optional<bool> stable = knownStringStability(s);
  if (!stable)
    return "  lambda2 of the point estimate: not determined (NaN)\n";
  std::snprintf(line, sizeof line,
                "  lambda2 of the point estimate = %.4g (point estimate string %s%s); amplified band [0, %.4f) rad/s, "
                "peak %.3f dB at %.4f rad/s\n",
                s.lambda2, *stable ? "stable" : "unstable", tested ? "; the verdict is the test's, below" : "",
                s.amplified_band_upper_rad_s, s.peak_gain_db, s.peak_frequency_rad_s);
  return line;
}

/// "model adequacy: NOT ADEQUATE (...) -> ..." said before the verdict it qualifies.
std::string adequacyLine(const ModelAdequacy& adequacy, const std::string& data, bool tested)
{
  std::string line = "Model adequacy" + (data.empty() ? "" : " (on " + data + ")") + ": " + describeAdequacy(adequacy);
  if (adequacy.assessed && !adequacy.adequate)
    line += tested ? "\n  -> the verdict below compares two versions of a model that misses these data; run "
                     "`diagnose` on them for a model that does not (and its verdict)"
                   : "\n  -> the model misses these data; run `diagnose` on them";
  return line + "\n";
}

std::string fitCells(const std::optional<FitQuality>& fit)
{
  if (!fit)
  {
    return "       -          -         -";
  }
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "%8zu %10.3f %9.2f%s", fit->samples, fit->rmse_speed_mps, fit->rmse_gap_m,
                fit->diverged ? " (diverged)" : "");
  return buffer;
}
/// "  shape: the car passes on 0.81 [0.70, 0.93] of its leader's peak braking, ..."; nothing
/// without a scored perturbation.
void printDipShapeLine(const DipShapeTransfer& shape, std::ostream& out)
{
  if (shape.braking.observations == 0 && shape.recovery.observations == 0 && shape.widenings == 0)
    return;
  auto ratio = [](const ClusteredRatio& r) {
    return r.observations == 0 ? std::string("none (no rate scored)") : ratioWithIntervalText(r);
  };
  const std::string widening = shape.widenings == 0
                                   ? "no dip's width at half depth is known"
                                   : printfText("its dips %+.1f s wider at half depth (median of %zu)",
                                                shape.median_widening_s, shape.widenings);
  out << "  shape (no model): the car passes on " << ratio(shape.braking) << " of its leader's peak braking and "
      << ratio(shape.recovery) << " of its peak recovery (slopes over "
      << printfText("%g", PerturbationCriteria{}.acceleration_span_s)
      << " s, 95 % interval over perturbations); " << widening << "\n";
}

/// "Dips of the leader's perturbations (the data's own, no model): N perturbation(s); ...".
void printDipRatioLine(const PairDipEvidence& evidence, std::ostream& out)
{
  out << "Dips of the leader's perturbations (the data's own, no model): " << evidence.dips.size()
      << " perturbation(s); " << evidence.ratio.reason << "\n";
  // What that says in words: for the inputs the drive had, not for every frequency.
  if (evidence.ratio.amplifies == DipAmplification::Amplifies)
    out << "  the car amplified its leader's dips beyond their interval: string unstable for these inputs, "
           "whatever the model says\n";
  else if (evidence.ratio.amplifies == DipAmplification::Attenuates)
    out << "  the car damped its leader's dips beyond their interval: these inputs did not grow (a stable answer "
           "for them only)\n";
  printDipShapeLine(evidence.shape, out);
}

nlohmann::json dipEvidenceJson(const CalibrationReport& report)
{
  nlohmann::json json = toJson(*report.dip_evidence);
  if (report.model_dips)
  {
    for (std::size_t i = 0; i < json["dips"].size() && i < report.model_dips->model_dips_mps.size(); ++i)
      json["dips"][i]["model_dip_mps"] = jsonNumber(report.model_dips->model_dips_mps[i]);
    json["model"] = {{"scored", report.model_dips->scored},
                     {"median_abs_dip_error", jsonNumber(report.model_dips->median_abs_dip_error)},
                     {"ratio_of_means", jsonNumber(report.model_dips->model_ratio_of_means)}};
  }
  json["verdict_contradiction"] =
      report.verdict_contradiction.empty() ? nlohmann::json() : nlohmann::json(report.verdict_contradiction);
  return json;
}

void printDipEvidence(const CalibrationReport& report, std::ostream& out)
{
  const DipRatioEstimate& r = report.dip_evidence->ratio;
  out << "\n";
  printDipRatioLine(*report.dip_evidence, out);
  if (report.model_dips && report.model_dips->scored > 0)
  {
    char line[256];
    std::snprintf(line, sizeof line,
                  "  the fitted model's dips: ratio %.2f against the data's %.2f, median |error| %.0f %% over %zu\n",
                  report.model_dips->model_ratio_of_means, r.ratio_of_means,
                  100.0 * report.model_dips->median_abs_dip_error, report.model_dips->scored);
    out << line;
  }
  if (!report.verdict_contradiction.empty())
    out << "  CONTRADICTION: " << report.verdict_contradiction << "\n";
}

/// "  at a bound of the fit, so +- is no interval there; one-sided 95 %: tau_e in [0, 1.267] s\n"
/// for the parameters held at a bound; "" when none is.
std::string boundIntervalsLine(const std::optional<IdentifiableQuantities>& quantities)
{
  std::string cells;
  for (const char* name : {"k1", "k2", "tau_e", "eta"})
  {
    const QuantityEstimate* q = quantities ? quantities->find(name) : nullptr;
    if (q == nullptr || !q->hasBoundInterval())
      continue;
    const auto [low, high] = q->boundInterval();
    cells += printfText("%s%s in [%.4g, %.4g] %s", cells.empty() ? "" : ", ", name, low, high, q->unit.c_str());
  }
  return cells.empty() ? "" : "  at a bound of the fit, so +- is no interval there; one-sided 95 %: " + cells + "\n";
}
}  // namespace

nlohmann::json reportToJson(const CalibrationReport& report)
{
  const MultistartResult& c = report.calibration;
  nlohmann::json json;
  json["parameters"] = parametersJson(c.parameters);
  json["standard_errors"] = parametersJson(report.uncertainty.standard_error);
  json["standard_errors_method"] =
      "Gauss-Newton sandwich at the optimum, score covariance by batch means over blocks of block_length_s";
  json["block_length_s"] = jsonNumber(report.uncertainty.block_length_s);
  json["blocks"] = report.uncertainty.blocks;
  json["residual_lag1_autocorrelation"] = jsonNumber(report.uncertainty.residual_lag1_autocorrelation);
  json["reciprocal_condition"] = jsonNumber(report.uncertainty.reciprocal_condition);
  json["identifiable"] = report.identifiability_note.empty();
  json["identifiability_note"] = report.identifiability_note;
  json["fitted"] = true;
  const std::optional<bool> stable = knownStringStability(report.stability);
  json["stability"] = {{"lambda2", jsonNumberOrInfinity(report.stability.lambda2)},
                       {"lambda2_of", "the point estimate (parameters above); the verdict is stability_test's"},
                       {"string_stable", stable ? nlohmann::json(*stable) : nlohmann::json()},
                       {"amplified_band_upper_rad_s", jsonNumber(report.stability.amplified_band_upper_rad_s)},
                       {"peak_gain_db", jsonNumberOrInfinity(report.stability.peak_gain_db)},
                       {"peak_frequency_rad_s", jsonNumber(report.stability.peak_frequency_rad_s)}};
  json["objective"] = {{"status", c.status},
                       {"rmse_speed_mps", jsonNumber(c.rmse_speed_mps)},
                       {"samples", report.training_samples},
                       {"starts", c.starts},
                       {"local_solves", c.local_solves},
                       {"clustered_starts", c.clustered_starts},
                       {"joined_starts", c.joined_starts},
                       {"divergent_starts", c.divergent_starts},
                       {"local_minima", c.local_minima},
                       {"evaluations", c.evaluations},
                       {"solve_time_s", c.solve_time_s},
                       {"diverged", c.diverged}};
  json["runs"] = nlohmann::json::array();
  for (const RunScore& run : report.runs)
  {
    json["runs"].push_back({{"name", run.name},
                            {"path", run.path},
                            {"train", fitJson(run.train)},
                            {"test", run.test ? fitJson(*run.test) : nlohmann::json()}});
  }
  json["summary"] = {{"train", fitJson(report.summary_train)},
                     {"test", report.summary_test ? fitJson(*report.summary_test) : nlohmann::json()}};
  if (report.grid)
  {
    json["grid_check"] = {{"nodes", report.grid->nodes},
                          {"diverged_nodes", report.grid->diverged_nodes},
                          {"best_node", parametersJson(report.grid->best)},
                          {"best_node_rmse_speed_mps", jsonNumber(report.grid->best_rmse_speed_mps)},
                          {"spacing", report.grid->spacing}};
    if (report.grid_polished)
    {
      json["grid_check"]["polished"] = parametersJson(report.grid_polished->parameters);
      json["grid_check"]["polished_rmse_speed_mps"] = jsonNumber(report.grid_polished->rmse_speed_mps);
    }
  }
  if (report.quantities)
  {
    json["identifiable_quantities"] = toJson(*report.quantities);
  }
  if (report.refit_bootstrap)
    json["refit_bootstrap"] = toJson(*report.refit_bootstrap);
  if (report.stability_test)
  {
    json["stability_test"] = toJson(*report.stability_test);
  }
  if (report.model_adequacy)
  {
    json["model_adequacy"] = toJson(*report.model_adequacy);
    json["model_adequacy"]["data"] = report.model_adequacy_data;
  }
  if (report.dip_evidence)
    json["dip_evidence"] = dipEvidenceJson(report);
  if (report.euler_step_bias)
    json["euler_step_bias"] = toJson(*report.euler_step_bias);
  return json;
}


void printReport(const CalibrationReport& report, std::ostream& out)
{
  char line[512];
  out << "Fit (Gunter et al. Table I): speed and space-gap RMSE, each run simulated from its measured start\n";
  // As wide as the longest run name (a platoon pair's name is long): a cut name can be ambiguous.
  int name_width = 28;
  for (const RunScore& run : report.runs)
  {
    name_width = std::max(name_width, static_cast<int>(std::min<std::size_t>(run.name.size(), 200)));
  }
  std::snprintf(line, sizeof line, "%-*s %8s %10s %9s   %8s %10s %9s\n", name_width, "run", "train n", "speed m/s",
                "gap m", "test n", "speed m/s", "gap m");
  out << line;
  for (const RunScore& run : report.runs)
  {
    std::snprintf(line, sizeof line, "%-*s %s   %s\n", name_width, run.name.substr(0, 200).c_str(),
                  fitCells(run.train).c_str(), fitCells(run.test).c_str());
    out << line;
  }
  std::snprintf(line, sizeof line, "%-*s %s   %s\n", name_width, "summary", fitCells(report.summary_train).c_str(),
                fitCells(report.summary_test).c_str());
  out << line << "\n";

  const MultistartResult& c = report.calibration;
  const AccParameters& p = c.parameters;
  const AccParameters& se = report.uncertainty.standard_error;
  out << "Parameters (Gunter et al. Table II), +- standard error:\n";
  std::snprintf(line, sizeof line,
                "  k1 = %.4f +- %.4f 1/s^2   k2 = %.4f +- %.4f 1/s   tau_e = %.4f +- %.4f s   eta = %.3f +- %.3f m\n",
                p.k1_per_s2, se.k1_per_s2, p.k2_per_s, se.k2_per_s, p.tau_e_s, se.tau_e_s, p.eta_m, se.eta_m);
  out << line << boundIntervalsLine(report.quantities);
  std::snprintf(line, sizeof line,
                "  (sandwich errors over %zu blocks of %.1f s; residual lag-1 autocorrelation %.4f; reciprocal condition %.3g)\n",
                report.uncertainty.blocks, report.uncertainty.block_length_s,
                report.uncertainty.residual_lag1_autocorrelation, report.uncertainty.reciprocal_condition);
  out << line;
  out << pointEstimateStabilityLine(report.stability, report.stability_test.has_value());
  out << "  identifiable: " << (report.identifiability_note.empty() ? "yes" : "no (" + report.identifiability_note + ")")
      << "\n";
  std::snprintf(line, sizeof line,
                "Search: %zu starts, %zu local solves (%zu left to a better start nearby), %zu local minima, %zu divergent "
                "starts pulled back, %zu evaluations, %.3f s, status %s\n",
                c.starts, c.local_solves, c.clustered_starts, c.local_minima, c.divergent_starts, c.evaluations,
                c.solve_time_s, c.status.c_str());
  out << line;
  if (report.grid)
  {
    const GridSearchResult& g = *report.grid;
    std::snprintf(line, sizeof line,
                  "Grid check: %zu nodes (step %.4f, %.4f, %.4f); best node k1 %.4f k2 %.4f tau_e %.4f eta %.3f, "
                  "speed RMSE %.6f vs multistart %.6f m/s\n",
                  g.nodes, g.spacing[0], g.spacing[1], g.spacing[2], g.best.k1_per_s2, g.best.k2_per_s, g.best.tau_e_s,
                  g.best.eta_m, g.best_rmse_speed_mps, c.rmse_speed_mps);
    out << line;
    if (report.grid_polished)
    {
      const AccParameters& q = report.grid_polished->parameters;
      std::snprintf(line, sizeof line,
                    "  local solve from the best node: k1 %.4f k2 %.4f tau_e %.4f eta %.3f, speed RMSE %.6f m/s -> %s\n",
                    q.k1_per_s2, q.k2_per_s, q.tau_e_s, q.eta_m, report.grid_polished->rmse_speed_mps,
                    report.grid_polished->rmse_speed_mps >= c.rmse_speed_mps * (1.0 - 1e-9) &&
                            g.best_rmse_speed_mps >= c.rmse_speed_mps * (1.0 - 1e-9)
                        ? "agrees: no better basin on the grid"
                        : "DISAGREES: the grid found a better basin");
      out << line;
    }
  }
  if (report.quantities)
  {
    out << "\n";
    printQuantities(*report.quantities, out);
  }
  if (report.refit_bootstrap)
  {
    out << "\n";
    printRefitBootstrap(*report.refit_bootstrap, out);
  }
  if (report.euler_step_bias)
    out << "\n" << describeEulerStepBias(*report.euler_step_bias);
  if (report.model_adequacy)
  {
    out << "\n" << adequacyLine(*report.model_adequacy, report.model_adequacy_data, report.stability_test.has_value());
  }
  if (report.dip_evidence)
  {
    printDipEvidence(report, out);
  }
  if (report.stability_test)
  {
    out << "\n";
    printStabilityTest(*report.stability_test, out);
  }
}

UnfittedDataSummary summarizeUnfittedData(const std::vector<CarFollowingRun>& runs, const std::string& reason,
                                          double steady_speed_spread_mps)
{
  UnfittedDataSummary out;
  out.reason = reason;
  out.runs = runs.size();
  out.steady_speed_spread_mps = steady_speed_spread_mps;
  out.duration_s = totalDurationS(runs);
  const PooledMoments speed = pooledMoments(runs, &CarFollowingRun::follower_speed_mps);
  const PooledMoments gap = pooledMoments(runs, &CarFollowingRun::space_gap_m);
  out.samples = speed.samples;
  out.follower_speed_mean_mps = speed.mean;
  out.follower_speed_spread_mps = speed.standard_deviation;
  out.gap_mean_m = gap.mean;
  out.gap_spread_m = gap.standard_deviation;
  out.equilibrium_gap_m = out.follower_speed_spread_mps < steady_speed_spread_mps ? out.gap_mean_m : kNaN;
  out.dip_evidence = pairDipEvidence(runs);
  return out;
}

nlohmann::json unfittedToJson(const UnfittedDataSummary& summary)
{
  nlohmann::json json;
  json["fitted"] = false;
  json["reason"] = summary.reason;
  json["data"] = {{"runs", summary.runs},
                  {"samples", summary.samples},
                  {"duration_s", jsonNumber(summary.duration_s)},
                  {"follower_speed_mean_mps", jsonNumber(summary.follower_speed_mean_mps)},
                  {"follower_speed_spread_mps", jsonNumber(summary.follower_speed_spread_mps)},
                  {"gap_mean_m", jsonNumber(summary.gap_mean_m)},
                  {"gap_spread_m", jsonNumber(summary.gap_spread_m)},
                  {"equilibrium_gap_m", jsonNumber(summary.equilibrium_gap_m)},
                  {"equilibrium_gap_note", equilibriumGapNote(summary)}};
  json["parameters"] = nullptr;
  json["stability"] = nullptr;
  json["model_adequacy"] = nullptr;
  if (summary.dip_evidence)
    json["dip_evidence"] = toJson(*summary.dip_evidence);
  return json;
}

void printUnfitted(const UnfittedDataSummary& summary, std::ostream& out)
{
  char line[512];
  out << "No fit: " << summary.reason << "\n";
  std::snprintf(line, sizeof line,
                "What the data say: %zu run(s), %zu samples over %.1f s; follower speed %.2f m/s mean, %.3f m/s "
                "spread; gap %.2f m mean, %.2f m spread\n",
                summary.runs, summary.samples, summary.duration_s, summary.follower_speed_mean_mps,
                summary.follower_speed_spread_mps, summary.gap_mean_m, summary.gap_spread_m);
  out << line << "  " << equilibriumGapNote(summary) << "\n";
  if (summary.dip_evidence)
    printDipRatioLine(*summary.dip_evidence, out);
  out << "No parameters, no lambda2 and no model's string-stability verdict: these data do not decide them.\n";
}

}  // namespace acc
