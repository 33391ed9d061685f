// calibrate: fits one ACC model across runs (CSV or bags), as Gunter et al. do for each
// following setting (Section IV), and reports the fit, the parameters and string stability.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/stability_test.h"
#include "acc_identification/command_line.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/ros/run_bag_reader.h"


namespace
{
const char* kUsage =
    "usage: calibrate [options] RUN...\n"
    "  RUN: a canonical CSV (time_s,space_gap_m,follower_speed_mps,leader_speed_mps), an OpenACC\n"
    "       two-vehicle CSV, or a bag with acc_identification/RelativeState messages.\n"
    "  --split none|half  half: train on the first half of each run, test on the second (paper)\n"
    "  --starts N         starting points of the multistart search (default 100)\n"
    "  --json FILE        write parameters, standard errors, stability, objective, per-run RMSEs\n"
    "  --grid N           also search a dense grid of N nodes per axis (k1 0-0.5, k2 0-1.5, tau_e 0-3)\n"
    "                     and check that the multistart optimum is the global one\n"
    "  --topic NAME       RelativeState topic in bags (default relative_state)\n"
    "  --max-gap S        split runs at holes longer than S seconds (default 0.5)\n"
    "  --alpha A          level of the string-stability test (default 0.05)\n"
    "  --seed N           seed of the test's bootstrap (default: the library's fixed seed)\n"
    "  --no-stability-test  skip the string-stability test on held-out halves\n"
    "  --quiet            no progress display\n";

struct LoadedRun
{
  acc::CarFollowingRun run;
  std::string path;
};

std::vector<LoadedRun> loadRuns(const std::vector<std::string>& paths, const std::string& topic, double max_gap_s)
{
  std::vector<LoadedRun> loaded;
  for (const std::string& path : paths)
  {
    for (auto& run : acc::readRunArgument(path, topic, max_gap_s, std::cerr))
    {
      loaded.push_back({std::move(run), path});
    }
  }
  return loaded;
}

/// Progress on stderr: a live counter on a terminal, a line per tenth otherwise.
void showProgress(std::size_t done, std::size_t total)
{
  static const bool terminal = isatty(STDERR_FILENO) != 0;
  if (terminal)
  {
    std::fprintf(stderr, "\rcalibrating: start %zu/%zu", done, total);
    if (done == total)
      std::fprintf(stderr, "\n");
  }
  else if (total >= 10 && done % (total / 10) == 0)
  {
    std::fprintf(stderr, "calibrating: start %zu/%zu\n", done, total);
  }
}
}  // namespace

int main(int argc, char** argv)
{
  acc::CommandLine cli({"split", "starts", "json", "grid", "topic", "max-gap", "alpha", "seed"},
                       {"quiet", "help", "no-stability-test"});
  if (!cli.parse(argc, argv) || cli.has("help") || cli.positional().empty())
  {
    std::cerr << (cli.error().empty() ? "" : "error: " + cli.error() + "\n") << kUsage;
    return cli.has("help") ? 0 : 2;
  }
  const std::string split = cli.value("split").value_or("none");
  const auto starts = cli.number("starts");
  const auto grid_nodes = cli.number("grid");
  const auto max_gap = cli.number("max-gap");
  const auto alpha = cli.number("alpha");
  const auto seed = cli.number("seed");
  if (!cli.error().empty() || (split != "none" && split != "half") || (starts && *starts < 0) ||
      (grid_nodes && *grid_nodes < 2) || (max_gap && *max_gap <= 0) || (alpha && !(*alpha > 0 && *alpha < 1)) ||
      (seed && *seed < 0))
  {
    std::cerr << "error: "
              << (cli.error().empty() ? "bad --split, --starts, --grid, --max-gap, --alpha or --seed" : cli.error())
              << "\n"
              << kUsage;
    return 2;
  }
  std::vector<LoadedRun> loaded;
  try
  {
    loaded = loadRuns(cli.positional(), cli.value("topic").value_or("relative_state"), max_gap.value_or(0.5));
  }
  catch (const std::exception& error)
  {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }

  std::vector<acc::CarFollowingRun> training, testing;
  for (const LoadedRun& item : loaded)
  {
    if (split == "half")
    {
      auto [train, test] = acc::splitRunInHalf(item.run);
      if (train.size() < 2 || test.size() < 2)
      {
        std::cerr << "error: run '" << item.run.name << "' has " << item.run.size() << " samples, too few to split\n";
        return 1;
      }
      training.push_back(std::move(train));
      testing.push_back(std::move(test));
    }
    else
    {
      training.push_back(item.run);
    }
  }

  acc::CalibrationReport report;
  acc::IdentificationOptions options;
  options.multistart.starts = starts ? static_cast<std::size_t>(*starts) : 100;
  if (!cli.has("quiet"))
  {
    options.multistart.progress = showProgress;
  }
  // The same identification as the identifier node's (excitation check, fit, standard errors,
  // identifiability), so that batch and live agree on what a window says.
  const acc::Identification identification = acc::identifyAcc(training, options);
  if (!identification.solved || identification.calibration.diverged)
  {
    std::cerr << "error: no fit: " << identification.note << "\n";
    return 1;
  }
  report.calibration = identification.calibration;
  report.training_samples = identification.samples;
  report.uncertainty = identification.uncertainty;
  report.stability = identification.stability;
  report.identifiability_note = identification.note;
  try
  {
    const acc::CalibrationObjective objective(training, options.bounds);
    if (grid_nodes)
    {
      const auto n = static_cast<std::size_t>(*grid_nodes);
      if (!cli.has("quiet"))
        std::cerr << "grid check: " << n * n * n << " nodes...\n";
      report.grid = acc::gridSearch(objective, options.multistart.start_box_lower, options.multistart.start_box_upper,
                                    {n, n, n});
      acc::MultistartOptions polish = options.multistart;
      polish.starts = 0;
      polish.progress = nullptr;
      report.grid_polished = acc::calibrateMultistart(objective, polish, {report.grid->best});
    }
  }
  catch (const std::invalid_argument& error)
  {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
  const acc::AccParameters& p = report.calibration.parameters;
  report.quantities = acc::assessQuantities(p, report.uncertainty, training);
  if (!cli.has("no-stability-test"))
  {
    std::vector<acc::CarFollowingRun> runs;
    for (const LoadedRun& item : loaded)
      runs.push_back(item.run);
    acc::StabilityTestOptions test_options;
    test_options.alpha = alpha.value_or(test_options.alpha);
    if (seed)
      test_options.seed = static_cast<std::uint64_t>(*seed);
    test_options.multistart.starts = options.multistart.starts;
    test_options.warm_starts = {p};
    if (!cli.has("quiet"))
      std::cerr << "string-stability test on held-out halves...\n";
    report.stability_test = acc::testStringStability(runs, test_options);
  }
  std::vector<acc::FitQuality> train_fits, test_fits;
  for (std::size_t i = 0; i < loaded.size(); ++i)
  {
    acc::RunScore score{loaded[i].run.name, loaded[i].path, acc::evaluateFit(p, {training[i]}), std::nullopt};
    train_fits.push_back(score.train);
    if (!testing.empty())
    {
      score.test = acc::evaluateFit(p, {testing[i]});
      test_fits.push_back(*score.test);
    }
    report.runs.push_back(score);
  }
  report.summary_train = acc::poolFits(train_fits);
  if (!test_fits.empty())
  {
    report.summary_test = acc::poolFits(test_fits);
  }
  acc::printReport(report, std::cout);
  if (const auto json_path = cli.value("json"))
  {
    std::ofstream file(*json_path);
    file << acc::reportToJson(report).dump(2) << "\n";
    if (!file)
    {
      std::cerr << "error: cannot write " << *json_path << "\n";
      return 1;
    }
  }
  return report.calibration.diverged ? 1 : 0;
}
