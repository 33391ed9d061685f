// diagnose: where a calibrated ACC model misses the real car, which physical effect it lacks and
// what adding that effect buys (issue 6). Also runs the withheld-effect suite.
#include <cstdio>
#include <cstdlib>
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


/// Everything the command line says.
struct DiagnoseRequest
{
  acc::DiagnosisOptions options;
  std::vector<std::string> paths, effects;
  std::string topic = "relative_state", json_path, report_dir, suite, follower, sumo_vtype_path, sumo_id;
  std::string plot_script = acc::installedBeside("plot_diagnosis.py");
  double max_gap_s = 0.5;
  std::uint32_t seed = acc::DiagnosisOptions{}.selection.seed;
  bool no_plots = false, all_pairs = false, no_forward_selection = false;
};

void addDiagnosisOptions(CLI::App& app, DiagnoseRequest& r)
{
  app.add_option("--train-fraction", r.options.train_fraction, "share of each run used for fitting")
      ->check(CLI::Range(0.05, 0.95))
      ->capture_default_str();
  app.add_option("--effect", r.effects, "candidate effect (repeatable; default all six)");
  app.add_option("--block-length-s", r.options.selection.block_length_s, "bootstrap block length [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--resamples", r.options.selection.resamples, "bootstrap resamples")
      ->check(CLI::Range(std::size_t{100}, std::size_t{1000000}))
      ->capture_default_str();
  app.add_option("--alpha", r.options.selection.alpha, "level of the selection rule")
      ->check(CLI::Range(1e-9, 0.5))
      ->capture_default_str();
  app.add_option("--min-relative-improvement", r.options.selection.min_relative_improvement,
                 "smallest held-out MSE reduction worth naming")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--seed", r.seed, "bootstrap seed")->capture_default_str();
  app.add_flag("--no-forward-selection", r.no_forward_selection,
               "name the dominant effect only; do not try effects in combination");
  app.add_option("--max-chain-length", r.options.max_chain_length, "most effects the forward selection adds")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  app.add_option("--threads", r.options.threads,
                 "threads for the independent effect fits (0: every core); the result does not depend on it")
      ->capture_default_str();
  app.add_option("--withheld-suite", r.suite,
                 "synthetic runs with a hidden effect (small, large), or the bundled real runs with an offset or "
                 "lag injected (semi-real), or every pair of effects withheld at once (combined); prints the "
                 "confusion matrix")
      ->check(CLI::IsMember(acc::suiteNames()));
}

void addInputOutputOptions(CLI::App& app, DiagnoseRequest& r)
{
  app.add_option("RUN", r.paths, "canonical run CSV, OpenACC CSV, or a bag of acc_identification/RelativeState")
      ->check(CLI::ExistingFile);
  app.add_option("--topic", r.topic, "RelativeState topic in bags")->capture_default_str();
  app.add_option("--max-gap", r.max_gap_s, "split runs at holes longer than this [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--json", r.json_path, "write the diagnosis as JSON");
  app.add_option("--sumo-vtype", r.sumo_vtype_path,
                 "also write the final model as a SUMO vType (carFollowModel ACC; its effects where SUMO has them)");
  app.add_option("--sumo-id", r.sumo_id, "the vType's id (default: the first run's name)");
  app.add_option("--report", r.report_dir, "write tables, diagnosis.json, PNG figures and report.md into DIR");
  app.add_option("--plot-script", r.plot_script, "figure script")->capture_default_str();
  app.add_flag("--no-plots", r.no_plots, "write the tables and JSON of --report but draw nothing");
  auto* follower_option =
      app.add_option("--follower", r.follower,
                     "OpenACC files: the follower of the pair to read, by its Vehicle_order name (e.g. BMW_I3, any "
                     "case) or position (e.g. 3); its leader is the car directly ahead (default: the first pair, "
                     "said on stderr)");
  auto* all_pairs_option = app.add_flag("--all-pairs", r.all_pairs,
                                        "OpenACC files: read every leader-follower pair; all their runs are "
                                        "diagnosed together, as the runs of several RUN files");
  follower_option->excludes(all_pairs_option);
}

/// tables, diagnosis.json and (unless --no-plots) the figures and report.md in the report folder.
bool writeReport(const DiagnoseRequest& r, const acc::DiagnosisResult& result, const nlohmann::json& json)
{
  try
  {
    acc::writeDiagnosisTables(result, r.report_dir);
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return false;
  }
  if (!writeJson(json, r.report_dir + "/diagnosis.json"))
    return false;
  if (r.no_plots)
    return true;
  if (!std::filesystem::exists(r.plot_script))
  {
    std::cerr << "error: no figure script at " << r.plot_script << " (--plot-script, or --no-plots); tables and "
              << "JSON are in " << r.report_dir << "\n";
    return false;
  }
  const std::string command = "/usr/bin/python3 '" + r.plot_script + "' '" + r.report_dir + "'";
  if (std::system(command.c_str()) != 0)
  {
    std::cerr << "error: the report figures failed (" << command << "); tables and JSON are in " << r.report_dir
              << "\n";
    return false;
  }
  std::cerr << "report: " << r.report_dir << "/report.md\n";
  return true;
}

/// The runs of the RUN arguments diagnosed: the summary, then the files asked for.
int diagnoseFiles(const DiagnoseRequest& r)
{
  std::vector<acc::CarFollowingRun> runs;
  acc::DiagnosisResult result;
  nlohmann::json pairs_read = nlohmann::json::array();
  try
  {
    const acc::RunArguments read = acc::readRunArguments(r.paths, r.topic, r.max_gap_s, std::cerr,
                                                         acc::pairSelectorFromOptions(r.follower, r.all_pairs));
    for (const acc::PairsRead& file : read.pairs_read)
    {
      for (const std::string& pair : file.pairs)
        std::cout << "OpenACC pair read: " << file.path << ": " << pair << "\n";
      pairs_read.push_back({{"path", file.path}, {"pairs", file.pairs}});
    }
    for (const acc::CalibrationInput& input : read.runs)
      runs.push_back(input.run);
    result = acc::diagnoseRuns(runs, r.options);
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  for (const std::string& note : result.notes)
    std::cerr << "note: " << note << "\n";
  std::cerr << result.notes.size() << " run(s) or part(s) not used\n";
  acc::printDiagnosisSummary(result, stdout);
  if (!r.sumo_vtype_path.empty() &&
      !writeSumoVType(r.sumo_vtype_path, r.sumo_id.empty() ? runs.front().name : r.sumo_id, result, runs,
                      !pairs_read.empty()))
    return 1;
  nlohmann::json json = acc::diagnosisToJson(result);
  json["inputs"] = r.paths;
  json["openacc_pairs"] = pairs_read;
  if (!r.json_path.empty() && !writeJson(json, r.json_path))
    return 1;
  return !r.report_dir.empty() && !writeReport(r, result, json) ? 1 : 0;
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Where a calibrated ACC model misses the real car, which physical effect it lacks, and what adding "
               "that effect buys. Each run is fitted on its first part and scored on the rest. With "
               "--withheld-suite: synthetic runs with a hidden effect, and the confusion matrix."};
  DiagnoseRequest request;
  addInputOutputOptions(app, request);
  addDiagnosisOptions(app, request);
  CLI11_PARSE(app, argc, argv);
  request.options.selection.seed = request.seed;
  request.options.forward_selection = !request.no_forward_selection;
  if (!applyEffects(request.effects, &request.options))
    return 2;
  if (!request.suite.empty())
    return runValidationSuite(request.suite, request.options, request.json_path);
  if (request.paths.empty())
  {
    std::cerr << "error: no run given (see --help)\n";
    return 2;
  }
  // The report's folder before the work: a diagnosis should not end in "cannot create" after it.
  std::error_code made;
  if (!request.report_dir.empty() && !std::filesystem::create_directories(request.report_dir, made) && made)
  {
    std::cerr << "error: cannot create " << request.report_dir << ": " << made.message() << "\n";
    return 1;
  }
  return diagnoseFiles(request);
}
