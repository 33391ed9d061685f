#include "acc_identification/calibration/calibrate_runs.h"

#include "acc_identification/calibration/fit_traces.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/calibration/string_stability_verdict.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/io/repeated_recording.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/plain_text.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace acc
{
std::vector<CarFollowingRun> runsOf(const std::vector<CalibrationInput>& inputs)
{
  std::vector<CarFollowingRun> runs;
  for (const CalibrationInput& item : inputs)
    runs.push_back(item.run);
  return runs;
}

std::string describeRepeatedInput(const std::vector<CalibrationInput>& inputs,
                                  const std::vector<std::size_t>& input_of)
{
  std::vector<std::string> path_of_run;
  for (const CalibrationInput& item : inputs)
    path_of_run.push_back(item.path);
  return describeRepeatedRun(runsOf(inputs), input_of, path_of_run);
}

namespace
{
/// What each RUN argument gave (inputs_read) and, for OpenACC files, the pairs (openacc_pairs).
void addInputsRead(const std::vector<InputAccount>& inputs_read, nlohmann::json& json)
{
  if (inputs_read.empty())
    return;
  json["inputs_read"] = inputAccountsJson(inputs_read);
  const nlohmann::json pairs = openAccPairsJson(inputs_read);
  if (!pairs.empty())
    json["openacc_pairs"] = pairs;
}

/// One drive for the sequential verdict: the consecutive runs of one RUN argument (pieces between
/// holes), while each starts after the one before ends (another pair of an OpenACC file starts
/// its own drive).
struct Drive
{
  std::string path;
  std::vector<CarFollowingRun> runs;
};

std::vector<Drive> groupIntoDrives(const std::vector<CalibrationInput>& inputs)
{
  std::vector<Drive> drives;
  for (const CalibrationInput& item : inputs)
  {
    const bool continues = !drives.empty() && drives.back().path == item.path && !item.run.time_s.empty() &&
                           !drives.back().runs.back().time_s.empty() &&
                           item.run.time_s.front() > drives.back().runs.back().time_s.back();
    if (!continues)
      drives.push_back({item.path, {}});
    drives.back().runs.push_back(item.run);
  }
  return drives;
}

/// The looks the identifier node would make on each drive, printed and as JSON.
nlohmann::json replayVerdicts(const std::vector<Drive>& drives, double every_s, double alpha, std::ostream& out)
{
  SequentialVerdictOptions options;
  options.alpha = alpha;
  options.look_period_s = every_s;
  nlohmann::json all = nlohmann::json::array();
  for (const Drive& drive : drives)
  {
    const std::vector<SequentialLook> looks = replaySequentialVerdict(drive.runs, options);
    out << "\nSequential verdict (anytime-valid: what the identifier node publishes over the drive; a look every "
        << every_s << " s of data time): " << drive.path << " (" << drive.runs.front().name << ", "
        << drive.runs.size() << " segment(s))\n";
    printVerdictSequence(looks, out);
    nlohmann::json entry{{"path", drive.path}, {"drive", drive.runs.front().name}, {"look_period_s", every_s}};
    entry["verdict_sequence"] = nlohmann::json::array();
    for (const SequentialLook& look : looks)
      entry["verdict_sequence"].push_back(toSequenceEntryJson(look));
    if (!looks.empty())
    {
      out << "  sequential verdict: " << toString(looks.back().verdict) << ", p = " << looks.back().p_value << ": "
          << looks.back().reason << "\n";
      entry["sequential_verdict"] = toJson(looks.back());
    }
    all.push_back(entry);
  }
  return all;
}

/// --verdict-every: the looks the identifier node would make on each drive, with a line on log.
void addSequentialVerdicts(const std::vector<CalibrationInput>& inputs, const CalibrateSettings& settings,
                           CalibrateOutcome& outcome, std::ostream& out, std::ostream& log)
{
  if (!(settings.verdict_every_s > 0.0))
    return;
  if (!settings.quiet)
    log << "sequential verdict: replaying the drives look by look...\n";
  outcome.json["sequential_verdicts"] =
      replayVerdicts(groupIntoDrives(inputs), settings.verdict_every_s, settings.alpha, out);
}

/// Valid data without a fit: says so and makes the JSON anyway, with what the data do decide (the
/// dips' own evidence; with --verdict-every, the verdicts the node would publish on them, as it
/// runs on data that a batch fit refuses).
CalibrateOutcome unfitted(const std::vector<CalibrationInput>& inputs, const std::string& reason,
                          double steady_speed_spread_mps, const std::vector<InputAccount>& inputs_read,
                          const CalibrateSettings& settings, std::ostream& out, std::ostream& log)
{
  const UnfittedDataSummary summary = summarizeUnfittedData(runsOf(inputs), reason, steady_speed_spread_mps);
  printOpenAccPairs(inputs_read, out);
  printUnfitted(summary, out);
  CalibrateOutcome outcome;
  outcome.exit_status = kExitValidDataNoFit;
  outcome.json = unfittedToJson(summary);
  addInputsRead(inputs_read, outcome.json);
  addSequentialVerdicts(inputs, settings, outcome, out, log);
  log << "no fit: " << reason << " (exit status " << kExitValidDataNoFit << ")\n";
  return outcome;
}

/// Throws std::invalid_argument, before any work, when the grid check would simulate more than
/// kMaxGridSampleSteps samples (nodes^3 simulations of the training data, about 4 ns a sample on
/// one core: 2e11 is some 15 minutes). --grid 1000 on a 45-minute drive would run for days.
void refuseGridBeyondReach(std::size_t nodes, const std::vector<CarFollowingRun>& training)
{
  constexpr double kMaxGridSampleSteps = 2e11;
  double samples = 0.0;
  for (const CarFollowingRun& run : training)
    samples += static_cast<double>(run.size());
  const double steps = std::pow(static_cast<double>(nodes), 3.0) * samples;
  if (nodes == 0 || steps <= kMaxGridSampleSteps)
    return;
  const auto most = static_cast<std::size_t>(std::floor(std::cbrt(kMaxGridSampleSteps / std::max(samples, 1.0))));
  throw std::invalid_argument(printfText("--grid %zu on %.0f training samples would simulate %.3g samples (%zu^3 "
                                         "simulations of the data); at most %.0e: give --grid %zu or less",
                                         nodes, samples, steps, nodes, kMaxGridSampleSteps, most));
}

/// The grid check of the multistart optimum (--grid N).
void checkOnGrid(const std::vector<CarFollowingRun>& training, const IdentificationOptions& options,
                 const CalibrateSettings& settings, CalibrationReport& report, std::ostream& log)
{
  const CalibrationObjective objective(training, options.bounds);
  const std::size_t n = settings.grid_nodes;
  if (!settings.quiet)
    log << "grid check: " << n * n * n << " nodes...\n";
  report.grid =
      gridSearch(objective, options.multistart.start_box_lower, options.multistart.start_box_upper, {n, n, n});
  MultistartOptions polish = options.multistart;
  polish.starts = 0;
  polish.progress = nullptr;
  report.grid_polished = calibrateMultistart(objective, polish, {report.grid->best});
}

/// Does the model describe the data at all, and what the runs' own dips say beside it.
void judgeModel(const std::vector<CarFollowingRun>& training, const std::vector<CarFollowingRun>& testing,
                const std::vector<CarFollowingRun>& whole_runs, CalibrationReport& report)
{
  const AccParameters& p = report.calibration.parameters;
  // With --split half on both halves: the test's verdict is judged on the held-out ones (on
  // Casale part6 the first half fits to 1.8 m of gap, the second misses by 8.1 m).
  std::vector<CarFollowingRun> judged = training;
  judged.insert(judged.end(), testing.begin(), testing.end());
  report.model_adequacy = assessModelAdequacy(p, judged, {}, report.uncertainty.standard_error);
  report.model_adequacy_data = testing.empty() ? "the runs it was fitted on"
                                               : "every run's training and held-out halves, each from its own start";
  // The second line of evidence: what each run's own dips say (no model), and the fitted model's
  // dips beside them (the dip check of the adequacy).
  report.dip_evidence = pairDipEvidence(whole_runs);
  report.model_dips = checkModelDips(p, whole_runs, *report.dip_evidence);
  addDipCheck(*report.model_adequacy, report.model_dips->scored, report.model_dips->median_abs_dip_error);
  if (report.stability_test)
    report.verdict_contradiction = verdictContradiction(toString(report.stability_test->verdict), *report.dip_evidence);
}

/// The refitting bootstrap of the fit, on short data (CalibrateSettings).
void bootstrapShortData(const std::vector<CarFollowingRun>& training, const CalibrateSettings& settings,
                        CalibrationReport& report, std::ostream& log)
{
  const double duration_s = totalDurationS(training);
  if (settings.bootstrap_replicates == 0 || !(duration_s < settings.bootstrap_below_s))
    return;
  RefitBootstrapOptions options;
  options.replicates = settings.bootstrap_replicates;
  if (settings.seed)
    options.seed = *settings.seed;
  if (!settings.quiet)
    log << "refitting bootstrap: " << options.replicates << " replicates of " << duration_s << " s of data...\n";
  report.refit_bootstrap = bootstrapRefits(report.calibration.parameters, training, options);
}

void scoreRuns(const std::vector<CalibrationInput>& inputs, const std::vector<CarFollowingRun>& training,
               const std::vector<CarFollowingRun>& testing, CalibrationReport& report)
{
  const AccParameters& p = report.calibration.parameters;
  std::vector<FitQuality> train_fits, test_fits;
  for (std::size_t i = 0; i < inputs.size(); ++i)
  {
    RunScore score{inputs[i].run.name, inputs[i].path, evaluateFit(p, {training[i]}), std::nullopt};
    train_fits.push_back(score.train);
    if (!testing.empty())
    {
      score.test = evaluateFit(p, {testing[i]});
      test_fits.push_back(*score.test);
    }
    report.runs.push_back(score);
  }
  report.summary_train = poolFits(train_fits);
  if (!test_fits.empty())
    report.summary_test = poolFits(test_fits);
}

/// The runs the model is fitted on and, with --split half, judged on: each run halved. A piece
/// too short to halve (a few rows between two rows a pair cannot use) is left out and said, not a
/// reason to refuse the rest.
struct FittedRuns
{
  std::vector<CalibrationInput> used;
  std::vector<CarFollowingRun> training, testing;
  std::vector<std::string> left_out;  ///< why each piece left out is
};

FittedRuns fittedRuns(const std::vector<CalibrationInput>& inputs, bool split_half)
{
  FittedRuns runs;
  for (const CalibrationInput& item : inputs)
  {
    if (!split_half)
    {
      runs.used.push_back(item);
      runs.training.push_back(item.run);
      continue;
    }
    auto [train, test] = splitRunInHalf(item.run);
    if (train.size() < 2 || test.size() < 2)
    {
      runs.left_out.push_back("run '" + item.run.name + "' has " + std::to_string(item.run.size()) +
                              " samples, too few to split in halves");
      continue;
    }
    runs.used.push_back(item);
    runs.training.push_back(std::move(train));
    runs.testing.push_back(std::move(test));
  }
  return runs;
}
}  // namespace

CalibrateOutcome calibrateRuns(const std::vector<CalibrationInput>& given_inputs,
                               const std::vector<InputAccount>& inputs_read, const CalibrateSettings& settings,
                               std::ostream& out, std::ostream& log)
{
  // Part6 before part3 moved the stability test's p from 0.063 to 0.054-0.066 until the runs were
  // put in one order.
  const std::vector<CalibrationInput> all_inputs =
      inNaturalOrder(given_inputs, [](const CalibrationInput& input) -> const std::string& { return input.run.name; });
  FittedRuns fitted = fittedRuns(all_inputs, settings.split_half);
  for (const std::string& why : fitted.left_out)
    log << "note: " << why << ": left out of the fit and its scores\n";
  if (fitted.used.empty())
    return unfitted(all_inputs, fitted.left_out.empty() ? "no run" : fitted.left_out.front(),
                    IdentifiabilityCriteria{}.min_speed_std_mps, inputs_read, settings, out, log);
  const std::vector<CalibrationInput>& inputs = fitted.used;
  std::vector<CarFollowingRun>& training = fitted.training;
  std::vector<CarFollowingRun>& testing = fitted.testing;
  refuseGridBeyondReach(settings.grid_nodes, training);
  IdentificationOptions options;
  options.multistart.starts = settings.starts;
  options.multistart.progress = settings.progress;
  // The same identification as the identifier node's (excitation check, fit, standard errors,
  // identifiability), so that batch and live agree on what a window says.
  const Identification identification = identifyAcc(training, options);
  if (!identification.solved || identification.calibration.diverged)
    return unfitted(inputs, identification.note.empty() ? "the fit diverged" : identification.note,
                    options.criteria.min_speed_std_mps, inputs_read, settings, out, log);
  CalibrationReport report;
  report.calibration = identification.calibration;
  report.training_samples = identification.samples;
  report.uncertainty = identification.uncertainty;
  report.stability = identification.stability;
  report.identifiability_note = identification.note;
  report.quantities = identification.quantities;
  if (!settings.quiet)
    log << "Euler step check...\n";
  report.euler_step_bias = estimateEulerStepBias(identification, training, options);
  bootstrapShortData(training, settings, report, log);
  if (settings.grid_nodes > 0)
    checkOnGrid(training, options, settings, report, log);
  const std::vector<CarFollowingRun> whole_runs = runsOf(all_inputs);
  if (settings.stability_test)
  {
    StabilityTestOptions test_options;
    test_options.alpha = settings.alpha;
    if (settings.seed)
      test_options.seed = *settings.seed;
    test_options.multistart.starts = options.multistart.starts;
    test_options.warm_starts = {report.calibration.parameters};
    if (!settings.quiet)
      log << "string-stability test on held-out halves...\n";
    report.stability_test = testStringStability(whole_runs, test_options);
  }
  judgeModel(training, testing, whole_runs, report);
  scoreRuns(inputs, training, testing, report);
  printOpenAccPairs(inputs_read, out);
  printReport(report, out);
  CalibrateOutcome outcome;
  outcome.json = reportToJson(report);
  addInputsRead(inputs_read, outcome.json);
  const bool inadequate =
      report.model_adequacy && report.model_adequacy->assessed && !report.model_adequacy->adequate;
  if (inadequate && report.stability_test && settings.second_opinion)
  {
    if (!settings.quiet)
      log << "the model does not describe the data: diagnosing them for one that does...\n";
    const SecondOpinion opinion = settings.second_opinion(whole_runs);
    out << opinion.text;
    outcome.json["diagnosed_verdict"] = opinion.json;
  }
  if (!fitted.left_out.empty())
    outcome.json["runs_left_out"] = fitted.left_out;
  addSequentialVerdicts(all_inputs, settings, outcome, out, log);
  outcome.exit_status = report.calibration.diverged ? 1 : 0;
  outcome.report = std::move(report);
  outcome.training = std::move(training);
  outcome.testing = std::move(testing);
  for (const CalibrationInput& input : inputs)
    outcome.run_names.push_back(input.run.name);
  return outcome;
}

bool writeCalibrationReport(const std::string& dir, const CalibrateOutcome& outcome, const std::string& plot_script,
                            std::ostream& log)
{
  if (!writeJsonFile(outcome.json, dir + "/calibration.json", log))
    return false;
  try
  {
    if (outcome.report)
      writeFitTracesCsv(
          fitTraces(outcome.report->calibration.parameters, outcome.run_names, outcome.training, outcome.testing),
          dir + "/fit_traces.csv");
  }
  catch (const std::exception& error)
  {
    log << "error: " << error.what() << "\n";
    return false;
  }
  return drawReportFigures(plot_script, dir, "the JSON and traces", log);
}

}  // namespace acc
