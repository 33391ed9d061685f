#include "acc_identification/calibration/calibration_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace acc
{
namespace
{
/// JSON has no NaN: a value that does not exist is null.
nlohmann::json number(double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); }

nlohmann::json parametersJson(const AccParameters& p)
{
  return {{"k1_per_s2", number(p.k1_per_s2)},
          {"k2_per_s", number(p.k2_per_s)},
          {"tau_e_s", number(p.tau_e_s)},
          {"eta_m", number(p.eta_m)}};
}

nlohmann::json fitJson(const FitQuality& fit)
{
  return {{"samples", fit.samples},
          {"rmse_speed_mps", number(fit.rmse_speed_mps)},
          {"rmse_gap_m", number(fit.rmse_gap_m)},
          {"diverged", fit.diverged}};
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
}  // namespace

std::pair<CarFollowingRun, CarFollowingRun> splitRunInHalf(const CarFollowingRun& run)
{
  const std::size_t half = run.size() / 2;
  auto slice = [&run](std::size_t from, std::size_t to, const std::string& suffix) {
    CarFollowingRun part;
    part.name = run.name + suffix;
    part.time_s.assign(run.time_s.begin() + from, run.time_s.begin() + to);
    part.space_gap_m.assign(run.space_gap_m.begin() + from, run.space_gap_m.begin() + to);
    part.follower_speed_mps.assign(run.follower_speed_mps.begin() + from, run.follower_speed_mps.begin() + to);
    part.leader_speed_mps.assign(run.leader_speed_mps.begin() + from, run.leader_speed_mps.begin() + to);
    return part;
  };
  return {slice(0, half, " (train)"), slice(half, run.size(), " (test)")};
}

nlohmann::json reportToJson(const CalibrationReport& report)
{
  const MultistartResult& c = report.calibration;
  nlohmann::json json;
  json["parameters"] = parametersJson(c.parameters);
  json["standard_errors"] = parametersJson(report.uncertainty.standard_error);
  json["standard_errors_method"] =
      "Gauss-Newton sandwich at the optimum, score covariance by batch means over blocks of block_length_s";
  json["block_length_s"] = number(report.uncertainty.block_length_s);
  json["blocks"] = report.uncertainty.blocks;
  json["residual_lag1_autocorrelation"] = number(report.uncertainty.residual_lag1_autocorrelation);
  json["reciprocal_condition"] = number(report.uncertainty.reciprocal_condition);
  json["identifiable"] = report.identifiability_note.empty();
  json["identifiability_note"] = report.identifiability_note;
  json["stability"] = {{"lambda2", number(report.stability.lambda2)},
                       {"string_stable", report.stability.string_stable},
                       {"amplified_band_upper_rad_s", number(report.stability.amplified_band_upper_rad_s)},
                       {"peak_gain_db", number(report.stability.peak_gain_db)},
                       {"peak_frequency_rad_s", number(report.stability.peak_frequency_rad_s)}};
  json["objective"] = {{"status", c.status},
                       {"rmse_speed_mps", number(c.rmse_speed_mps)},
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
                          {"best_node_rmse_speed_mps", number(report.grid->best_rmse_speed_mps)},
                          {"spacing", report.grid->spacing}};
    if (report.grid_polished)
    {
      json["grid_check"]["polished"] = parametersJson(report.grid_polished->parameters);
      json["grid_check"]["polished_rmse_speed_mps"] = number(report.grid_polished->rmse_speed_mps);
    }
  }
  if (report.quantities)
  {
    json["identifiable_quantities"] = toJson(*report.quantities);
  }
  if (report.stability_test)
  {
    json["stability_test"] = toJson(*report.stability_test);
  }
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
  out << line;
  std::snprintf(line, sizeof line,
                "  (sandwich errors over %zu blocks of %.1f s; residual lag-1 autocorrelation %.4f; reciprocal condition %.3g)\n",
                report.uncertainty.blocks, report.uncertainty.block_length_s,
                report.uncertainty.residual_lag1_autocorrelation, report.uncertainty.reciprocal_condition);
  out << line;
  const StringStabilityReport& s = report.stability;
  std::snprintf(line, sizeof line, "  lambda2 = %.4g -> %s; amplified band [0, %.4f) rad/s, peak %.3f dB at %.4f rad/s\n",
                s.lambda2, s.string_stable ? "string STABLE" : "string UNSTABLE", s.amplified_band_upper_rad_s,
                s.peak_gain_db, s.peak_frequency_rad_s);
  out << line;
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
  if (report.stability_test)
  {
    out << "\n";
    printStabilityTest(*report.stability_test, out);
  }
}

}  // namespace acc
