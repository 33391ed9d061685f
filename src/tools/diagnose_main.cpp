// diagnose: where a calibrated ACC model misses the real car, which physical effect it lacks and
// what adding that effect buys (issue 6). Also runs the withheld-effect suite.
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/diagnosis/diagnosis_output.h"
#include "acc_identification/diagnosis/diagnosis_text.h"
#include "acc_identification/io/installed_beside.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/ros/run_input_options.h"
#include "acc_identification/tools/bootstrap_options.h"
#include "acc_identification/tools/number_checks.h"
#include "acc_identification/tools/option_rules.h"
#include "acc_identification/validation/suite_runs.h"

namespace
{
/// Everything the command line says.
struct DiagnoseRequest
{
  acc::DiagnosisOptions options;
  acc::RunInputOptions input;
  std::vector<std::string> effects;
  std::string json_path, report_dir, suite, sumo_vtype_path, sumo_id;
  std::vector<std::string> held_out;  ///< runs kept aside whole: the RUN files are then fitted whole
  std::string plot_script = acc::installedBeside("plot_diagnosis.py");
  std::uint32_t seed = acc::DiagnosisOptions{}.selection.seed;
  bool no_plots = false, no_forward_selection = false;
};

void addDiagnosisOptions(CLI::App& app, DiagnoseRequest& r)
{
  app.add_option("--train-fraction", r.options.train_fraction, "share of each run used for fitting")
      ->check(acc::trainFraction())
      ->capture_default_str();
  app.add_option("--held-out", r.held_out, "runs kept aside (read as RUN, same --follower): the RUNs are fitted whole "
                 "and these scored whole, not each run's first part and the rest")->check(CLI::ExistingFile);
  app.add_option("--effect", r.effects, "candidate effect (repeatable; replaces the default list: the six timing and spacing effects, "
                 "asymmetric_response and speed_dependent_gains; leader_acceleration_feedforward, "
                 "quadratic_closing_response and leader_braking_anticipation are tested only when named here)");
  app.add_option("--block-length-s", r.options.selection.block_length_s, "bootstrap block length [s]")
      ->check(acc::positiveNumber())->capture_default_str();
  app.add_option("--resamples", r.options.selection.resamples, "bootstrap resamples")
      ->check(acc::wholeNumberFrom(100.0, 1000000.0, "RESAMPLES"))->capture_default_str();
  app.add_option("--alpha", r.options.selection.alpha, "level of the selection rule")
      ->check(acc::openInterval(0.0, 0.5))->capture_default_str();
  app.add_option("--min-relative-improvement", r.options.selection.min_relative_improvement,
                 "smallest held-out MSE reduction worth naming")
      ->check(acc::nonNegativeNumber())
      ->capture_default_str();
  app.add_option("--seed", r.seed, "bootstrap seed")->check(acc::seed32())->capture_default_str();
  app.add_flag("--no-forward-selection", r.no_forward_selection,
               "name the dominant effect only; do not try effects in combination");
  app.add_option("--max-chain-length", r.options.max_chain_length, "most effects the forward selection adds")
      ->check(acc::wholeNumberFrom(1.0, 8.0, "EFFECTS"))->capture_default_str();
  // What calibrate makes; the library's default is none (its suites and second opinion do without).
  r.options.bootstrap_replicates = acc::RefitBootstrapOptions{}.replicates;
  acc::addRefitBootstrapOptions(app, r.options.bootstrap_replicates, r.options.bootstrap_below_s, "the final model");
  app.add_option("--threads", r.options.threads,
                 "threads for the independent effect fits (0: every core); the result does not depend on it")
      ->check(acc::nonNegativeWholeNumber())->capture_default_str();
  app.add_option("--withheld-suite", r.suite,
                 "synthetic runs with a hidden effect (small, large), or the bundled real runs with an offset or "
                 "lag injected (semi-real), or every pair of effects withheld at once (combined); prints the "
                 "confusion matrix")
      ->check(CLI::IsMember(acc::suiteNames()));
}

void addInputOutputOptions(CLI::App& app, DiagnoseRequest& r)
{
  r.input.declare(app, "all their runs are diagnosed together, as the runs of several RUN files", false);
  app.add_option("--json", r.json_path, "write the diagnosis as JSON");
  app.add_option("--sumo-vtype", r.sumo_vtype_path,
                 "also write the final model as a SUMO vType (carFollowModel ACC; its effects where SUMO has them)");
  app.add_option("--sumo-id", r.sumo_id, "the vType's id (default: the first run's name)");
  app.add_option("--report", r.report_dir, "write tables, diagnosis.json, PNG figures and report.md into DIR");
  app.add_option("--plot-script", r.plot_script, "figure script")->capture_default_str();
  app.add_flag("--no-plots", r.no_plots, "write the tables and JSON of --report but draw nothing");
}

/// The runs of the RUN arguments diagnosed: the summary, then the files asked for.
int diagnoseFiles(const DiagnoseRequest& r)
{
  std::vector<acc::CarFollowingRun> runs;
  acc::DiagnosisResult result;
  std::vector<acc::InputAccount> inputs_read;
  try
  {
    const auto [read, held_out] = r.input.readWithHeldOut(r.held_out, std::cerr);
    inputs_read = read.inputs_read;  // the held-out files are read too
    inputs_read.insert(inputs_read.end(), held_out.inputs_read.begin(), held_out.inputs_read.end());
    acc::printOpenAccPairs(inputs_read, std::cout);
    runs = acc::runsOf(read.runs);
    result = r.held_out.empty() ? acc::diagnoseRuns(runs, r.options)
                                : acc::diagnoseHeldOutRuns(runs, acc::runsOf(held_out.runs), r.options);
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  acc::writeUnusedRunNotes(result, std::cerr);
  acc::printDiagnosisSummary(result, stdout);
  if (!r.sumo_vtype_path.empty() &&
      !acc::saveFinalModelVType(result, runs, r.sumo_vtype_path, r.sumo_id.empty() ? runs.front().name : r.sumo_id,
                                acc::anyOpenAcc(inputs_read), std::cerr))
    return 1;
  const nlohmann::json json = acc::diagnosisToJson(result, r.input.paths, r.held_out, inputs_read);
  if (!r.json_path.empty() && !acc::writeJsonFile(json, r.json_path, std::cerr))
    return 1;
  const bool report_failed = !r.report_dir.empty() &&
                             !acc::writeDiagnosisReport(result, json, r.report_dir, r.plot_script, r.no_plots, std::cerr);
  return report_failed ? 1 : 0;
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
  request.options.bootstrap.seed = request.seed;
  request.options.forward_selection = !request.no_forward_selection;
  std::string unknown;
  if (!request.effects.empty() && !acc::parseEffectNames(request.effects, &request.options.candidates, &unknown))
  {
    std::cerr << "error: unknown effect '" << unknown << "'\n";
    return 2;
  }
  if (!request.suite.empty())
  {
    request.options.bootstrap_replicates = 0;  // the suites judge which effect is named, not its size
    return acc::runSuiteCommand(request.suite, request.options, ACC_CASALE_DIR, ACC_ZALAZONE_TOYOTA_DIR,
                                request.json_path, std::cout, std::cerr);
  }
  if (request.input.paths.empty())
  {
    std::cerr << "error: no run given (see --help)"  // a list option takes every word up to the next option
              << (request.held_out.size() > 1 ? ": --held-out took every file after it; give the RUNs before it" : "")
              << "\n";
    return 2;
  }
  for (const std::vector<std::string>* inputs : {&request.input.paths, &request.held_out})
    if (!acc::outputsLeaveInputsAlone(*inputs, {request.json_path, request.sumo_vtype_path}, std::cerr))
      return 2;
  // The report's folder before the work: a diagnosis should not end in "cannot create" after it.
  if (!request.report_dir.empty() && !acc::makeOutputFolder(request.report_dir, std::cerr))
    return 1;
  return diagnoseFiles(request);
}
