// diagnose: where a calibrated ACC model misses the real car, which physical effect it lacks and
// what adding that effect buys (issue 6). Also runs the withheld-effect suite.
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/diagnosis/diagnosis_output.h"
#include "acc_identification/diagnosis/diagnosis_text.h"
#include "acc_identification/io/installed_beside.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/ros/run_bag_reader.h"
#include "acc_identification/sumo/sumo_vtype.h"
#include "acc_identification/validation/suite_runs.h"


namespace
{
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

/// The candidate effects named on the command line (all six when none is).
bool applyEffects(const std::vector<std::string>& names, acc::DiagnosisOptions* options)
{
  if (names.empty())
  {
    return true;
  }
  options->candidates.clear();
  for (const std::string& name : names)
  {
    acc::EffectKind kind;
    if (!acc::parseEffectName(name, &kind) || kind == acc::EffectKind::none)
    {
      std::cerr << "error: unknown effect '" << name << "'\n";
      return false;
    }
    options->candidates.push_back(kind);
  }
  return true;
}

/// diagnose --withheld-suite NAME: the suite's tables on stdout, every case in --json.
int runValidationSuite(const std::string& name, const acc::DiagnosisOptions& options, const std::string& json_path)
{
  try
  {
    // The semi-real suite's real runs are the bundled ones, unpacked at build time.
    const std::vector<acc::SemiRealSet> sets =
        name == "semi-real" ? acc::bundledSemiRealSets(ACC_CASALE_DIR, ACC_ZALAZONE_TOYOTA_DIR)
                            : std::vector<acc::SemiRealSet>{};
    const acc::SuiteReport report = acc::runSuite(name, options, sets, stderr);
    std::cout << report.tables;
    return !json_path.empty() && !writeJson(report.json, json_path) ? 1 : 0;
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

/// The final model as a SUMO vType (docs/SUMO.md): its effects where SUMO has an equivalent, the
/// others named in the file, its adequacy as a caveat when it does not describe the data.
bool writeSumoVType(const std::string& path, const std::string& id, const acc::DiagnosisResult& result,
                    const std::vector<acc::CarFollowingRun>& runs, bool from_openacc)
{
  const acc::AugmentedFit& fit = acc::finalModel(result).fit;
  if (fit.diverged)
  {
    std::cerr << "error: --sumo-vtype: the final model has no fit to export\n";
    return false;
  }
  acc::SumoExport exported = acc::exportToSumo(acc::sumoId(id), fit.base, fit.effects, fit.effect_values,
                                               acc::observedAccelerationLimits(runs));
  if (result.final_adequacy.assessed && !result.final_adequacy.adequate)
    exported.caveats.push_back("the final model is " + acc::describeAdequacy(result.final_adequacy));
  return acc::saveSumoVTypes({exported}, path, from_openacc ? acc::kSumoOpenAccProvenance : "", std::cerr);
}

}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Where a calibrated ACC model misses the real car, which physical effect it lacks, and what adding "
               "that effect buys. Each run is fitted on its first part and scored on the rest. With "
               "--withheld-suite: synthetic runs with a hidden effect, and the confusion matrix."};
  acc::DiagnosisOptions options;
  std::vector<std::string> paths, effects;
  std::string topic = "relative_state", json_path, report_dir, plot_script = acc::installedBeside("plot_diagnosis.py"), suite;
  double max_gap_s = 0.5;
  std::uint32_t seed = options.selection.seed;
  bool no_plots = false, all_pairs = false;
  std::string follower;
  app.add_option("RUN", paths, "canonical run CSV, OpenACC CSV, or a bag of acc_identification/RelativeState")
      ->check(CLI::ExistingFile);
  app.add_option("--topic", topic, "RelativeState topic in bags")->capture_default_str();
  app.add_option("--max-gap", max_gap_s, "split runs at holes longer than this [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--json", json_path, "write the diagnosis as JSON");
  std::string sumo_vtype_path, sumo_id;
  app.add_option("--sumo-vtype", sumo_vtype_path,
                 "also write the final model as a SUMO vType (carFollowModel ACC; its effects where SUMO has them)");
  app.add_option("--sumo-id", sumo_id, "the vType's id (default: the first run's name)");
  app.add_option("--report", report_dir, "write tables, diagnosis.json, PNG figures and report.md into DIR");
  app.add_option("--train-fraction", options.train_fraction, "share of each run used for fitting")
      ->check(CLI::Range(0.05, 0.95))
      ->capture_default_str();
  app.add_option("--effect", effects, "candidate effect (repeatable; default all six)");
  app.add_option("--block-length-s", options.selection.block_length_s, "bootstrap block length [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--resamples", options.selection.resamples, "bootstrap resamples")
      ->check(CLI::Range(std::size_t{100}, std::size_t{1000000}))
      ->capture_default_str();
  app.add_option("--alpha", options.selection.alpha, "level of the selection rule")
      ->check(CLI::Range(1e-9, 0.5))
      ->capture_default_str();
  app.add_option("--min-relative-improvement", options.selection.min_relative_improvement,
                 "smallest held-out MSE reduction worth naming")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--seed", seed, "bootstrap seed")->capture_default_str();
  app.add_option("--plot-script", plot_script, "figure script")->capture_default_str();
  app.add_flag("--no-plots", no_plots, "write the tables and JSON of --report but draw nothing");
  bool no_forward_selection = false;
  app.add_flag("--no-forward-selection", no_forward_selection,
               "name the dominant effect only; do not try effects in combination");
  app.add_option("--max-chain-length", options.max_chain_length, "most effects the forward selection adds")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  app.add_option("--threads", options.threads,
                 "threads for the independent effect fits (0: every core); the result does not depend on it")
      ->capture_default_str();
  app.add_option("--withheld-suite", suite,
                 "synthetic runs with a hidden effect (small, large), or the bundled real runs with an offset or "
                 "lag injected (semi-real), or every pair of effects withheld at once (combined); prints the "
                 "confusion matrix")
      ->check(CLI::IsMember(acc::suiteNames()));
  auto* follower_option =
      app.add_option("--follower", follower,
                     "OpenACC files: the follower of the pair to read, by its Vehicle_order name (e.g. BMW_I3, any "
                     "case) or position (e.g. 3); its leader is the car directly ahead (default: the first pair, "
                     "said on stderr)");
  auto* all_pairs_option = app.add_flag("--all-pairs", all_pairs,
                                        "OpenACC files: read every leader-follower pair; all their runs are "
                                        "diagnosed together, as the runs of several RUN files");
  follower_option->excludes(all_pairs_option);
  CLI11_PARSE(app, argc, argv);
  options.selection.seed = seed;
  options.forward_selection = !no_forward_selection;
  if (!applyEffects(effects, &options))
  {
    return 2;
  }
  if (!suite.empty())
  {
    return runValidationSuite(suite, options, json_path);
  }
  if (paths.empty())
  {
    std::cerr << "error: no run given (see --help)\n";
    return 2;
  }
  // The report's folder before the work: a diagnosis should not end in "cannot create" after it.
  if (!report_dir.empty() && !makeDirectory(report_dir))
  {
    std::cerr << "error: cannot create " << report_dir << ": " << std::strerror(errno) << "\n";
    return 1;
  }
  std::vector<acc::CarFollowingRun> runs;
  nlohmann::json pairs_read = nlohmann::json::array();
  try
  {
    const acc::OpenAccPairSelector selector = acc::pairSelectorFromOptions(follower, all_pairs);
    for (const std::string& path : paths)
    {
      acc::RunArgument argument = acc::readRunArgument(path, topic, max_gap_s, std::cerr, selector);
      for (const std::string& pair : argument.pairs)
      {
        std::cout << "OpenACC pair read: " << path << ": " << pair << "\n";
      }
      if (!argument.pairs.empty())
      {
        pairs_read.push_back({{"path", path}, {"pairs", argument.pairs}});
      }
      for (acc::CarFollowingRun& run : argument.runs)
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
  acc::printDiagnosisSummary(result, stdout);
  if (!sumo_vtype_path.empty() &&
      !writeSumoVType(sumo_vtype_path, sumo_id.empty() ? runs.front().name : sumo_id, result, runs,
                      !pairs_read.empty()))
    return 1;
  nlohmann::json json = acc::diagnosisToJson(result);
  json["inputs"] = paths;
  json["openacc_pairs"] = pairs_read;
  if (!json_path.empty() && !writeJson(json, json_path))
  {
    return 1;
  }
  if (!report_dir.empty())
  {
    const std::string* dir = &report_dir;
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
    if (!no_plots)
    {
      if (!std::filesystem::exists(plot_script))
      {
        std::cerr << "error: no figure script at " << plot_script << " (--plot-script, or --no-plots); tables and "
                  << "JSON are in " << *dir << "\n";
        return 1;
      }
      const std::string command = "/usr/bin/python3 '" + plot_script + "' '" + *dir + "'";
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
