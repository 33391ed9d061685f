#include "acc_identification/reproduction/measured_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/io/csv_fields.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/reproduction/equilibrium_regression.h"
#include "acc_identification/reproduction/figure_csv.h"
#include "acc_identification/reproduction/figure_summary.h"
#include "acc_identification/reproduction/run_comparison.h"

namespace acc
{
using nlohmann::json;

namespace
{
/// Every run of every --run file (a file may give several pieces: rejected rows and ACC-off rows
/// split a run). The reader lists each rejected row on stderr.
std::vector<acc::CarFollowingRun> readRunsOrThrow(const FigureOptions& options)
{
  std::vector<acc::CarFollowingRun> runs;
  for (const std::string& path : options.texts("run"))
  {
    try
    {
      for (acc::CarFollowingRun& run : acc::readRuns(path))
      {
        runs.push_back(std::move(run));
      }
    }
    catch (const acc::RunReadError& error)
    {
      throw FigureUsageError(error.what());
    }
  }
  if (runs.empty())
  {
    throw FigureUsageError("this figure needs --run RUN.csv");
  }
  return runs;
}

std::vector<acc::AccParameters> parametersOf(const std::vector<acc::NamedSetting>& settings)
{
  std::vector<acc::AccParameters> parameters;
  for (const auto& setting : settings)
  {
    parameters.push_back(setting.parameters);
  }
  return parameters;
}

/// The line's JSON and its printed line (indent and wording as given), or why there is none.
void reportLine(const acc::EquilibriumRegression& regression, json& entry, const char* indent, const char* label,
                std::FILE* out)
{
  if (!regression.line)
  {
    std::fprintf(out, "%sno line fitted: %s\n", indent, regression.no_line_reason.c_str());
    return;
  }
  const acc::GapSpeedLine& line = *regression.line;
  entry["fit"] = {{"eta_m", line.intercept_m}, {"tau_e_s", line.slope_s}, {"rms_residual_m", line.rms_residual_m}};
  std::fprintf(out, "%s%s: gap = %.3f m + %.4f s * v (rms %.3f m)\n", indent, label, line.intercept_m, line.slope_s,
              line.rms_residual_m);
}

json pooledEquilibrium(const std::vector<acc::CarFollowingRun>& runs, const std::vector<acc::NamedSetting>& settings,
                       double max_dv, double max_accel, std::FILE* out)
{
  const auto pooled = acc::regressPooledEquilibrium(runs, parametersOf(settings), max_dv, max_accel);
  json entry = {{"steady_samples", pooled.steady.size()}};
  std::fprintf(out, "  all runs pooled: %zu steady samples\n", pooled.steady.size());
  reportLine(pooled, entry, "    ", "least-squares line", out);
  for (std::size_t i = 0; i < settings.size(); ++i)
  {
    entry["rms_from_line_m"][settings[i].name] = pooled.rms_from_line_m[i];
    std::fprintf(out, "    %-14s rms distance of steady samples from eta + tau_e v: %.3f m\n", settings[i].name.c_str(),
                pooled.rms_from_line_m[i]);
  }
  return entry;
}

/// An RMSE as the timeseries figure prints it: "none" for a part without a sample (NaN).
std::string rmseText(double rmse) { return std::isnan(rmse) ? "none" : printfText("%.3f", rmse); }

}  // namespace

json equilibriumFigure(const FigureRequest& request)
{
  const FigureOptions& options = request.options;
  const auto runs = readRunsOrThrow(options);
  const auto settings = resolveSettings(options, {"min", "max"});
  const double max_dv = options.positive("max-relative-speed", 0.5);
  const double max_accel = options.positive("max-acceleration", 0.1);
  CsvWriter csv(request.csv_path, "run,time_s,follower_speed_mps,space_gap_m,steady");
  json summary = {{"figure", "equilibrium"}, {"max_relative_speed_mps", max_dv}, {"max_acceleration_mps2", max_accel}};
  std::fprintf(request.streams.numbers,
               "space gap against speed (paper Fig. 5); steady: |dv| <= %g m/s and |a| <= %g m/s^2\n", max_dv,
               max_accel);
  for (const auto& run : runs)
  {
    const auto regression = acc::regressEquilibrium(run, parametersOf(settings), max_dv, max_accel);
    std::vector<bool> is_steady(run.size(), false);
    for (std::size_t k : regression.steady)
    {
      is_steady[k] = true;
    }
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      csv.row() << csvQuoted(run.name) << ',' << run.time_s[k] << ',' << run.follower_speed_mps[k] << ','
                << run.space_gap_m[k] << ',' << (is_steady[k] ? 1 : 0) << '\n';
    }
    const auto [slowest, fastest] = std::minmax_element(run.follower_speed_mps.begin(), run.follower_speed_mps.end());
    json entry = {{"run", run.name}, {"samples", run.size()}, {"steady_samples", regression.steady.size()},
                  {"speed_range_mps", {*slowest, *fastest}}};
    std::fprintf(request.streams.numbers, "  %s: %zu samples, %zu steady, speeds %.1f to %.1f m/s\n", run.name.c_str(),
                 run.size(), regression.steady.size(), *slowest, *fastest);
    reportLine(regression, entry, "    ", "least-squares line through steady samples", request.streams.numbers);
    for (std::size_t i = 0; i < settings.size(); ++i)
    {
      entry["rms_from_line_m"][settings[i].name] = regression.rms_from_line_m[i];
      std::fprintf(request.streams.numbers,
                   "    %-14s eta + tau_e v = %.3f + %.4f v: rms distance of steady samples %.3f m\n",
                   settings[i].name.c_str(), settings[i].parameters.eta_m, settings[i].parameters.tau_e_s,
                   regression.rms_from_line_m[i]);
    }
    summary["runs"].push_back(entry);
  }
  summary["pooled"] = pooledEquilibrium(runs, settings, max_dv, max_accel, request.streams.numbers);
  for (const auto& setting : settings)
  {
    summary["settings"].push_back({{"parameters", settingSummaryJson(setting)}});
  }
  csv.close();
  return summary;
}

json timeseriesFigure(const FigureRequest& request)
{
  const FigureOptions& options = request.options;
  const auto runs = readRunsOrThrow(options);
  if (options.texts("run").size() != 1)
  {
    throw FigureUsageError("timeseries takes one --run");
  }
  // A file split into pieces (rejected or ACC-off rows): plot the longest piece, and say so.
  const auto longest = std::max_element(runs.begin(), runs.end(), [](const auto& a, const auto& b) {
    return a.durationS() < b.durationS();
  });
  if (runs.size() > 1)
  {
    std::fprintf(request.streams.notes, "note: the run file gave %zu pieces; using the longest, %s (%.1f s)\n",
                 runs.size(), longest->name.c_str(), longest->durationS());
  }
  const acc::CarFollowingRun& run = *longest;
  const std::string problem = acc::describeRunProblem(run);
  if (!problem.empty())
  {
    throw FigureUsageError(run.name + ": " + problem);
  }
  const auto settings = resolveSettings(options, {"min"});
  const double fraction = options.number("train-fraction", 0.5);
  CsvWriter csv(request.csv_path, "setting,time_s,leader_speed_mps,measured_speed_mps,simulated_speed_mps,"
                          "measured_gap_m,simulated_gap_m,part");
  json summary = {{"figure", "timeseries"}, {"run", run.name}, {"train_fraction", fraction}};
  std::fprintf(request.streams.numbers, "measured against simulated follower (paper Figs. 3 and 4), run %s\n",
               run.name.c_str());
  for (const auto& setting : settings)
  {
    const auto sim = acc::simulateFollower(setting.parameters, run);
    acc::TrainTestErrors e;
    try
    {
      e = acc::trainTestErrors(run, sim, fraction);
    }
    catch (const std::invalid_argument& error)
    {
      throw FigureUsageError(error.what());
    }
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      csv.row() << setting.name << ',' << run.time_s[k] << ',' << run.leader_speed_mps[k] << ','
                << run.follower_speed_mps[k] << ',' << sim.speed_mps[k] << ',' << run.space_gap_m[k] << ','
                << sim.space_gap_m[k] << ',' << (k < e.split_index ? "train" : "test") << '\n';
    }
    summary["settings"].push_back({{"parameters", settingSummaryJson(setting)},
                                   {"split_time_s", e.split_time_s},
                                   {"train_samples", e.train_samples},
                                   {"test_samples", e.test_samples},
                                   {"train_speed_rmse_mps", e.train_speed_rmse_mps},
                                   {"test_speed_rmse_mps", e.test_speed_rmse_mps},
                                   {"train_gap_rmse_m", e.train_gap_rmse_m},
                                   {"test_gap_rmse_m", e.test_gap_rmse_m},
                                   {"diverged", e.diverged}});
    std::fprintf(request.streams.numbers,
                 "  %-14s speed RMSE train %s / test %s m/s, gap RMSE train %s / test %s m (split at %.1f s; %zu / "
                 "%zu samples)%s\n",
                 setting.name.c_str(), rmseText(e.train_speed_rmse_mps).c_str(),
                 rmseText(e.test_speed_rmse_mps).c_str(), rmseText(e.train_gap_rmse_m).c_str(),
                 rmseText(e.test_gap_rmse_m).c_str(), e.split_time_s, e.train_samples, e.test_samples,
                 e.diverged ? "  DIVERGED" : "");
  }
  csv.close();
  return summary;
}

}  // namespace acc
