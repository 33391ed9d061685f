// calibrate: fits one ACC model across runs (CSV or bags), as Gunter et al. do for each
// following setting (Section IV), and reports the fit, the parameters and string stability. The
// work is calibrateRuns (calibration/calibrate_runs.h), which the Python API calls too.
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/calibration/calibrate_runs.h"
#ifdef ACC_WITH_DIAGNOSIS
#include "acc_identification/diagnosis/calibration_second_opinion.h"
#endif
#include "acc_identification/io/installed_beside.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/ros/run_input_options.h"
#include "acc_identification/sumo/sumo_vtype.h"
#include "acc_identification/tools/bootstrap_options.h"
#include "acc_identification/tools/number_checks.h"
#include "acc_identification/tools/option_rules.h"

namespace
{
/// The fitted model as a SUMO vType (docs/SUMO.md), with the model's adequacy as a caveat when it
/// does not describe the data.
bool writeSumoVType(const std::string& path, const std::string& id, const acc::CalibrationReport& report,
                    const std::vector<acc::CalibrationInput>& inputs, bool from_openacc)
{
  const std::vector<acc::CarFollowingRun> runs = acc::runsOf(inputs);
  const bool misses = report.model_adequacy && report.model_adequacy->assessed && !report.model_adequacy->adequate;
  const std::string caveat = misses ? "the model is " + acc::describeAdequacy(*report.model_adequacy) +
                                          " for the data it was fitted on: see `diagnose` before simulating with it"
                                    : "";
  return acc::saveFittedModelVType(path, id, report.calibration.parameters, {}, {}, runs, caveat, from_openacc,
                                   std::cerr);
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Fits one ACC model (Gunter et al.) across runs, as the paper does for each following setting, and "
               "reports the fit, the parameters with standard errors, what the data determine, and whether the "
               "ACC is string stable, decided on held-out halves."};
  acc::RunInputOptions input;
  std::string split = "none", json_path, sumo_vtype_path, sumo_id, report_dir;
  int starts = 100;
  std::uint64_t seed = 0;
  bool no_stability_test = false, no_second_opinion = false;
  acc::CalibrateSettings settings;
  input.declare(app,
                "ONE model is fitted across all their runs, as across several RUN files (one model per car: fit "
                "each --follower separately)",
                true);
  app.add_option("--split", split, "half: train on the first half of each run, test on the second (the paper)")
      ->check(CLI::IsMember({"none", "half"}))
      ->capture_default_str();
  app.add_option("--starts", starts, "starting points of the multistart search")
      ->check(acc::multistartStarts())
      ->capture_default_str();
  app.add_option("--json", json_path, "write parameters, standard errors, stability, the stability test, per-run RMSEs");
  app.add_option("--grid", settings.grid_nodes,
                 "also search a dense grid of N nodes per axis (k1 0-0.5, k2 0-1.5, tau_e 0-3) and check that the "
                 "multistart optimum is the global one (N^3 simulations: at most 2e11 simulated samples in all)")
      ->check(acc::gridNodesPerAxis());
  app.add_option("--alpha", settings.alpha, "level of the string-stability test")
      ->check(acc::testLevel())
      ->capture_default_str();
  auto* seed_option =
      app.add_option("--seed", seed, "seed of the stability test's and the refitting bootstrap's draws (default: fixed seeds)")
          ->check(acc::nonNegativeWholeNumber());
  acc::addRefitBootstrapOptions(app, settings.bootstrap_replicates, settings.bootstrap_below_s, "the fit");
  app.add_option("--verdict-every", settings.verdict_every_s,
                 "also replay each drive look by look every SECONDS of data time and report the sequential "
                 "(anytime-valid) verdicts the identifier node would publish, by the node's own code (1 s or more: "
                 "each look refits the drive so far)")
      ->check(acc::verdictEverySeconds());
  app.add_option("--report", report_dir,
                 "write calibration.json, fit_traces.csv (each run measured and simulated), a figure per run and "
                 "report.md into DIR");
  app.add_option("--sumo-vtype", sumo_vtype_path,
                 "also write the fitted model as a SUMO vType (carFollowModel ACC) into this additional file");
  app.add_option("--sumo-id", sumo_id, "the vType's id (default: the first run's name)");
  app.add_flag("--no-stability-test", no_stability_test, "skip the string-stability test on held-out halves");
  app.add_flag("--no-second-opinion", no_second_opinion,
               "do not diagnose the runs when the model does not describe them (saves the diagnosis's time)");
  app.add_flag("--quiet", settings.quiet, "no progress display");
  CLI11_PARSE(app, argc, argv);
  if (!acc::outputsLeaveInputsAlone(input.paths, {json_path, sumo_vtype_path}, std::cerr))
    return 2;
  settings.split_half = split == "half";
  settings.starts = static_cast<std::size_t>(starts);
  settings.stability_test = !no_stability_test;
  if (seed_option->count() > 0)
    settings.seed = seed;
  if (!settings.quiet)
    settings.progress = [](std::size_t done, std::size_t total) { acc::showProgress("calibrating", done, total); };
#ifdef ACC_WITH_DIAGNOSIS
  if (!no_second_opinion)
    settings.second_opinion = acc::diagnosisSecondOpinion();
#endif
  if (!report_dir.empty() && !acc::makeOutputFolder(report_dir, std::cerr))
    return 1;

  try
  {
    const acc::RunArguments read = input.read(std::cerr);
    const std::vector<acc::CalibrationInput>& inputs = read.runs;
    const acc::CalibrateOutcome outcome = acc::calibrateRuns(inputs, read.inputs_read, settings, std::cout, std::cerr);
    if (outcome.report && !sumo_vtype_path.empty() &&
        !writeSumoVType(sumo_vtype_path, sumo_id.empty() ? inputs.front().run.name : sumo_id, *outcome.report,
                        inputs, acc::anyOpenAcc(read.inputs_read)))
      return 1;
    if (!json_path.empty() && !acc::writeJsonFile(outcome.json, json_path, std::cerr))
      return 1;
    if (!report_dir.empty() && !acc::writeCalibrationReport(report_dir, outcome,
                                                            acc::installedBeside("plot_calibration.py"), std::cerr))
      return 1;
    return outcome.exit_status;
  }
  catch (const std::exception& error)
  {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
}
