// diagnose: where a calibrated ACC model misses the real car, which physical effect it lacks and
// what adding that effect buys (issue 6). Also runs the withheld-effect suite.
#include <cerrno>
#include <cmath>
#include <optional>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <sys/stat.h>
#include <vector>

#include "acc_identification/command_line.h"
#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/diagnosis/diagnosis_output.h"
#include "acc_identification/diagnosis/withheld_effect_suite.h"
#include "acc_identification/ros/run_bag_reader.h"


namespace
{
const char* kUsage =
    "usage: diagnose [options] RUN... [--json FILE] [--report DIR]\n"
    "       diagnose --withheld-suite small|large [--json FILE]\n"
    "  RUN: canonical run CSV, OpenACC CSV, or a bag of acc_identification/RelativeState (as calibrate).\n"
    "       Each run is fitted on its first part and scored on the rest.\n"
    "  --topic NAME                RelativeState topic in bags (default relative_state)\n"
    "  --max-gap S                 split runs at holes longer than S seconds (default 0.5)\n"
    "  --json FILE                 write the diagnosis as JSON\n"
    "  --report DIR                write tables, diagnosis.json, PNG figures and report.md into DIR\n"
    "  --train-fraction F          share of each run used for fitting (default 0.5)\n"
    "  --effect NAME               candidate effect (repeatable; default all six)\n"
    "  --block-length-s S          bootstrap block length (default 10)\n"
    "  --resamples N               bootstrap resamples (default 2000)\n"
    "  --alpha A                   level of the selection rule (default 0.05)\n"
    "  --min-relative-improvement R  smallest held-out MSE reduction worth naming (default 0.02)\n"
    "  --seed N                    bootstrap seed (default 12345)\n"
    "  --plot-script PATH          figure script (default: the package's scripts/plot_diagnosis.py)\n"
    "  --no-plots                  write the tables and JSON of --report but draw nothing\n"
    "  --withheld-suite SIZE       synthetic runs with a hidden effect; prints the confusion matrix\n";

bool makeDirectory(const std::string& path)
{
  std::string partial;
  for (std::size_t i = 0; i <= path.size(); ++i)
  {
    if (i == path.size() || path[i] == '/')
    {
      if (!partial.empty() && mkdir(partial.c_str(), 0755) != 0 && errno != EEXIST)
      {
        return false;
      }
    }
    if (i < path.size())
    {
      partial += path[i];
    }
  }
  return true;
}

bool writeJson(const nlohmann::json& j, const std::string& path)
{
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out)
  {
    std::cerr << "error: cannot write " << path << "\n";
    return false;
  }
  return true;
}

bool applyOptions(acc::CommandLine& cli, acc::DiagnosisOptions* options)
{
  if (auto v = cli.number("train-fraction"))
  {
    options->train_fraction = *v;
  }
  if (auto v = cli.number("block-length-s"))
  {
    options->selection.block_length_s = *v;
  }
  if (auto v = cli.number("resamples"))
  {
    options->selection.resamples = static_cast<std::size_t>(*v);
  }
  if (auto v = cli.number("alpha"))
  {
    options->selection.alpha = *v;
  }
  if (auto v = cli.number("min-relative-improvement"))
  {
    options->selection.min_relative_improvement = *v;
  }
  if (auto v = cli.number("seed"))
  {
    options->selection.seed = static_cast<std::uint32_t>(*v);
  }
  if (!cli.error().empty())
  {
    std::cerr << "error: " << cli.error() << "\n";
    return false;
  }
  if (!(options->train_fraction > 0.05 && options->train_fraction < 0.95) || options->selection.resamples < 100 ||
      !(options->selection.block_length_s > 0.0) || !(options->selection.alpha > 0.0 && options->selection.alpha < 0.5))
  {
    std::cerr << "error: --train-fraction must be in (0.05, 0.95), --resamples >= 100, --block-length-s > 0, "
                 "--alpha in (0, 0.5)\n";
    return false;
  }
  if (cli.has("effect"))
  {
    options->candidates.clear();
    for (const std::string& name : cli.values("effect"))
    {
      acc::EffectKind kind;
      if (!acc::parseEffectName(name, &kind) || kind == acc::EffectKind::none)
      {
        std::cerr << "error: unknown effect '" << name << "'\n";
        return false;
      }
      options->candidates.push_back(kind);
    }
  }
  return true;
}

int runSuite(const std::string& size, const acc::DiagnosisOptions& options, const std::optional<std::string>& json_path)
{
  std::vector<acc::WithheldCase> grid;
  if (size == "small")
  {
    grid = acc::withheldCaseGrid(1, {acc::SyntheticLeadProfile::steps, acc::SyntheticLeadProfile::dip}, {1.0}, 1);
  }
  else if (size == "large")
  {
    grid = acc::withheldCaseGrid(3,
                                 {acc::SyntheticLeadProfile::steps, acc::SyntheticLeadProfile::oscillation,
                                  acc::SyntheticLeadProfile::dip},
                                 {0.5, 1.5}, 1);
  }
  else
  {
    std::cerr << "error: --withheld-suite takes small or large\n";
    return 2;
  }
  std::vector<acc::WithheldOutcome> outcomes;
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    const acc::WithheldOutcome o = acc::runWithheldCase(grid[i], options);
    std::vector<std::string> plausible;
    for (acc::EffectKind kind : o.plausible)
    {
      plausible.push_back(acc::effectName(kind));
    }
    std::fprintf(stderr, "[%zu/%zu] truth %s %s (%s, noise x%.2g) -> %s, magnitude %.4g\n", i + 1, grid.size(),
                 acc::effectName(o.input.truth).c_str(),
                 o.input.truth_values.empty() ? "" : std::to_string(o.input.truth_values.front()).c_str(),
                 acc::leadProfileName(o.input.profile).c_str(), o.input.speed_noise_std_mps / 0.06,
                 acc::effectName(o.dominant).c_str(), o.recovered_magnitude);
    cases.push_back({{"truth", acc::effectName(o.input.truth)},
                     {"truth_values", o.input.truth_values},
                     {"profile", acc::leadProfileName(o.input.profile)},
                     {"speed_noise_std_mps", o.input.speed_noise_std_mps},
                     {"seed", o.input.seed},
                     {"dominant_effect", acc::effectName(o.dominant)},
                     {"plausible_effects", plausible},
                     {"recovered_magnitude", std::isfinite(o.recovered_magnitude) ? nlohmann::json(o.recovered_magnitude)
                                                                                  : nlohmann::json(nullptr)},
                     {"recovered_standard_error", std::isfinite(o.recovered_standard_error)
                                                      ? nlohmann::json(o.recovered_standard_error)
                                                      : nlohmann::json(nullptr)},
                     {"base_test_rmse_speed", o.base_test_rmse_speed_mps},
                     {"effect_test_rmse_speed", o.effect_test_rmse_speed_mps}});
    outcomes.push_back(o);
  }
  const acc::ConfusionMatrix matrix = acc::confusionMatrix(outcomes);
  std::cout << acc::formatConfusionMatrix(matrix) << "\n" << acc::formatMagnitudeRecovery(outcomes);
  if (json_path && !writeJson({{"cases", cases}}, *json_path))
  {
    return 1;
  }
  return 0;
}

void printSummary(const acc::DiagnosisResult& r)
{
  std::printf("%-26s %10s %10s %10s %9s %11s  %s\n", "model", "train_v", "test_v", "test_gap", "improve", "significant",
              "stability");
  auto row = [](const acc::ModelDiagnosis& m, bool is_base) {
    std::printf("%-26s %10.4f %10.4f %10.3f %8.1f%% %11s  %s (peak %.3f dB)\n", acc::effectName(m.fit.effect).c_str(),
                m.train_rmse_speed_mps, m.test_rmse_speed_mps, m.test_rmse_gap_m, 100.0 * m.improvement.relative,
                is_base ? "-" : (m.significant ? "yes" : "no"), m.stability.string_stable ? "stable" : "UNSTABLE",
                m.stability.peak_gain_db);
  };
  row(r.baseline, true);
  for (const acc::ModelDiagnosis& m : r.effects)
  {
    row(m, false);
  }
  std::printf("dominant effect: %s; plausible:", acc::effectName(r.selection.dominant).c_str());
  for (acc::EffectKind kind : r.selection.plausible)
  {
    std::printf(" %s", acc::effectName(kind).c_str());
  }
  std::printf("%s\n", r.selection.plausible.empty() ? " (none)" : "");
}
}  // namespace

int main(int argc, char** argv)
{
  acc::CommandLine cli({"json", "report", "train-fraction", "effect", "block-length-s", "resamples", "alpha",
                        "min-relative-improvement", "seed", "plot-script", "withheld-suite", "topic", "max-gap"},
                       {"no-plots", "help"});
  if (!cli.parse(argc, argv) || cli.has("help"))
  {
    std::cerr << (cli.error().empty() ? "" : "error: " + cli.error() + "\n") << kUsage;
    return cli.has("help") ? 0 : 2;
  }
  acc::DiagnosisOptions options;
  if (!applyOptions(cli, &options))
  {
    std::cerr << kUsage;
    return 2;
  }
  if (cli.has("withheld-suite"))
  {
    return runSuite(*cli.value("withheld-suite"), options, cli.value("json"));
  }
  if (cli.positional().empty())
  {
    std::cerr << "error: no run given\n" << kUsage;
    return 2;
  }
  const std::string topic = cli.value("topic").value_or("relative_state");
  const auto max_gap_s = cli.number("max-gap");
  if (!cli.error().empty())
  {
    std::cerr << "error: " << cli.error() << "\n" << kUsage;
    return 2;
  }
  std::vector<acc::CarFollowingRun> runs;
  try
  {
    for (const std::string& path : cli.positional())
    {
      for (acc::CarFollowingRun& run : acc::readRunArgument(path, topic, max_gap_s.value_or(0.5), std::cerr))
      {
        runs.push_back(std::move(run));
      }
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  acc::DiagnosisResult result;
  try
  {
    result = acc::diagnoseRuns(runs, options);
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  for (const std::string& note : result.notes)
  {
    std::cerr << "note: " << note << "\n";
  }
  std::cerr << result.notes.size() << " run(s) or part(s) not used\n";
  printSummary(result);
  nlohmann::json json = acc::diagnosisToJson(result);
  json["inputs"] = cli.positional();
  if (const auto path = cli.value("json"); path && !writeJson(json, *path))
  {
    return 1;
  }
  if (const auto dir = cli.value("report"))
  {
    if (!makeDirectory(*dir))
    {
      std::cerr << "error: cannot create " << *dir << ": " << std::strerror(errno) << "\n";
      return 1;
    }
    try
    {
      acc::writeDiagnosisTables(result, *dir);
    }
    catch (const std::exception& e)
    {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    }
    if (!writeJson(json, *dir + "/diagnosis.json"))
    {
      return 1;
    }
    if (!cli.has("no-plots"))
    {
      const std::string script = cli.value("plot-script").value_or(ACC_PLOT_DIAGNOSIS_SCRIPT);
      const std::string command = "/usr/bin/python3 '" + script + "' '" + *dir + "'";
      if (std::system(command.c_str()) != 0)
      {
        std::cerr << "error: the report figures failed (" << command << "); tables and JSON are in " << *dir << "\n";
        return 1;
      }
      std::cerr << "report: " << *dir << "/report.md\n";
    }
  }
  return 0;
}
