// calibrate: fits one ACC model across runs (CSV or bags), as Gunter et al. do for each
// following setting (Section IV), and reports the fit, the parameters and string stability.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/calibration/stability_test.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/ros/run_bag_reader.h"
#include "acc_identification/sumo/sumo_vtype.h"


namespace
{
struct LoadedRun
{
  acc::CarFollowingRun run;
  std::string path;
};

/// The runs as read, whole (what the test splits itself, and the dips are found in).
std::vector<acc::CarFollowingRun> runsOf(const std::vector<LoadedRun>& loaded)
{
  std::vector<acc::CarFollowingRun> runs;
  for (const LoadedRun& item : loaded)
    runs.push_back(item.run);
  return runs;
}

/// The OpenACC pair(s) read from one RUN argument, for the output.
struct PairsRead
{
  std::string path;
  std::vector<std::string> pairs;
};

std::vector<LoadedRun> loadRuns(const std::vector<std::string>& paths, const std::string& topic, double max_gap_s,
                                const acc::OpenAccPairSelector& selector, std::vector<PairsRead>& pairs_read)
{
  std::vector<LoadedRun> loaded;
  for (const std::string& path : paths)
  {
    acc::RunArgument argument = acc::readRunArgument(path, topic, max_gap_s, std::cerr, selector);
    if (!argument.pairs.empty())
    {
      pairs_read.push_back({path, argument.pairs});
    }
    for (auto& run : argument.runs)
    {
      loaded.push_back({std::move(run), path});
    }
  }
  return loaded;
}

/// "OpenACC pairs read: part3.csv: Hyundai behind Rexton, positions 2/1", one line per file.
void printPairsRead(const std::vector<PairsRead>& pairs_read, std::ostream& out)
{
  for (const PairsRead& file : pairs_read)
  {
    out << "OpenACC pair" << (file.pairs.size() > 1 ? "s" : "") << " read: " << file.path << ": ";
    for (std::size_t i = 0; i < file.pairs.size(); ++i)
    {
      out << (i > 0 ? "; " : "") << file.pairs[i];
    }
    out << "\n";
  }
}

/// One drive for the sequential verdict: the consecutive runs of one RUN argument (pieces between
/// holes), while each starts after the one before ends (another pair of an OpenACC file starts
/// its own drive).
struct Drive
{
  std::string path;
  std::vector<acc::CarFollowingRun> runs;
};

std::vector<Drive> groupIntoDrives(const std::vector<LoadedRun>& loaded)
{
  std::vector<Drive> drives;
  for (const LoadedRun& item : loaded)
  {
    const bool continues = !drives.empty() && drives.back().path == item.path && !item.run.time_s.empty() &&
                           !drives.back().runs.back().time_s.empty() &&
                           item.run.time_s.front() > drives.back().runs.back().time_s.back();
    if (!continues)
    {
      drives.push_back({item.path, {}});
    }
    drives.back().runs.push_back(item.run);
  }
  return drives;
}

/// The looks the identifier node would make on each drive, printed and as JSON.
nlohmann::json replayVerdicts(const std::vector<Drive>& drives, double every_s, double alpha, std::ostream& out)
{
  acc::SequentialVerdictOptions options;
  options.alpha = alpha;
  options.look_period_s = every_s;
  nlohmann::json all = nlohmann::json::array();
  for (const Drive& drive : drives)
  {
    const std::vector<acc::SequentialLook> looks = acc::replaySequentialVerdict(drive.runs, options);
    out << "\nSequential verdict (anytime-valid: what the identifier node publishes over the drive; a look every "
        << every_s << " s of data time): " << drive.path << " (" << drive.runs.front().name << ", "
        << drive.runs.size() << " segment(s))\n";
    acc::printVerdictSequence(looks, out);
    nlohmann::json entry{{"path", drive.path}, {"drive", drive.runs.front().name}, {"look_period_s", every_s}};
    entry["verdict_sequence"] = nlohmann::json::array();
    for (const acc::SequentialLook& look : looks)
    {
      entry["verdict_sequence"].push_back(acc::toSequenceEntryJson(look));
    }
    if (!looks.empty())
    {
      out << "  sequential verdict: " << acc::toString(looks.back().verdict) << ", p = " << looks.back().p_value
          << ": " << looks.back().reason << "\n";
      entry["sequential_verdict"] = acc::toJson(looks.back());
    }
    all.push_back(entry);
  }
  return all;
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

/// Exit status for valid data that cannot be fitted (steady speed, too short): the JSON is written
/// (fitted: false, the reason, what the data do decide), but there are no parameters to use, so a
/// script must not take the run for a fit (docs/TOOLS.md).
constexpr int kExitValidDataNoFit = 3;

/// Valid data without a fit: says so, writes the JSON anyway, exits kExitValidDataNoFit (1 if the
/// JSON cannot be written).
int reportUnfitted(const std::vector<LoadedRun>& loaded, const std::string& reason, double steady_speed_spread_mps,
                   const std::vector<PairsRead>& pairs_read, const std::string& json_path)
{
  const acc::UnfittedDataSummary summary = acc::summarizeUnfittedData(runsOf(loaded), reason, steady_speed_spread_mps);
  printPairsRead(pairs_read, std::cout);
  acc::printUnfitted(summary, std::cout);
  std::cerr << "no fit: " << reason << " (exit status " << kExitValidDataNoFit << ")\n";
  if (!json_path.empty())
  {
    auto json = acc::unfittedToJson(summary);
    for (const PairsRead& file : pairs_read)
      json["openacc_pairs"].push_back({{"path", file.path}, {"pairs", file.pairs}});
    std::ofstream file(json_path);
    file << json.dump(2) << "\n";
    if (!file)
    {
      std::cerr << "error: cannot write " << json_path << "\n";
      return 1;
    }
  }
  return kExitValidDataNoFit;
}

/// The fitted model as a SUMO vType (docs/SUMO.md), with the model's adequacy as a caveat when it
/// does not describe the data.
bool writeSumoVType(const std::string& path, const std::string& id, const acc::CalibrationReport& report,
                    const std::vector<acc::CarFollowingRun>& runs, bool from_openacc)
{
  acc::SumoExport exported = acc::exportToSumo(acc::sumoId(id), report.calibration.parameters, {}, {},
                                               acc::observedAccelerationLimits(runs));
  if (report.model_adequacy && report.model_adequacy->assessed && !report.model_adequacy->adequate)
    exported.caveats.push_back("the model is " + acc::describeAdequacy(*report.model_adequacy) +
                               " for the data it was fitted on: see `diagnose` before simulating with it");
  try
  {
    acc::writeSumoAdditional({exported}, path, from_openacc ? acc::kSumoOpenAccProvenance : "");
  }
  catch (const std::exception& error)
  {
    std::cerr << "error: " << error.what() << "\n";
    return false;
  }
  std::cerr << "SUMO vType '" << exported.vtype.id << "' written to " << path << "\n";
  return true;
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Fits one ACC model (Gunter et al.) across runs, as the paper does for each following setting, and "
               "reports the fit, the parameters with standard errors, what the data determine, and whether the "
               "ACC is string stable, decided on held-out halves."};
  std::vector<std::string> paths;
  std::string split = "none", topic = "relative_state";
  std::string json_path;
  int starts = 100;
  std::size_t grid_nodes = 0;
  double max_gap_s = 0.5, alpha = 0.05;
  std::uint64_t seed = 0;
  bool quiet = false, no_stability_test = false, all_pairs = false;
  double verdict_every_s = 0.0;
  std::string follower, sumo_vtype_path, sumo_id;
  app.add_option("RUN", paths,
                 "a canonical CSV (time_s,space_gap_m,follower_speed_mps,leader_speed_mps), an OpenACC CSV, or a "
                 "bag of acc_identification/RelativeState")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--split", split, "half: train on the first half of each run, test on the second (the paper)")
      ->check(CLI::IsMember({"none", "half"}))
      ->capture_default_str();
  app.add_option("--starts", starts, "starting points of the multistart search")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  app.add_option("--json", json_path, "write parameters, standard errors, stability, the stability test, per-run RMSEs");
  app.add_option("--grid", grid_nodes,
                 "also search a dense grid of N nodes per axis (k1 0-0.5, k2 0-1.5, tau_e 0-3) and check that the "
                 "multistart optimum is the global one")
      ->check(CLI::Range(std::size_t{2}, std::size_t{1000}));
  app.add_option("--topic", topic, "RelativeState topic in bags")->capture_default_str();
  app.add_option("--max-gap", max_gap_s, "split runs at holes longer than this [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--alpha", alpha, "level of the string-stability test")
      ->check(CLI::Range(1e-9, 1.0 - 1e-9))
      ->capture_default_str();
  auto* seed_option = app.add_option("--seed", seed, "seed of the test's bootstrap (default: the library's fixed seed)");
  app.add_option("--verdict-every", verdict_every_s,
                 "also replay each drive look by look every SECONDS of data time and report the sequential "
                 "(anytime-valid) verdicts the identifier node would publish, by the node's own code")
      ->check(CLI::PositiveNumber);
  app.add_option("--sumo-vtype", sumo_vtype_path,
                 "also write the fitted model as a SUMO vType (carFollowModel ACC) into this additional file");
  app.add_option("--sumo-id", sumo_id, "the vType's id (default: the first run's name)");
  app.add_flag("--no-stability-test", no_stability_test, "skip the string-stability test on held-out halves");
  app.add_flag("--quiet", quiet, "no progress display");
  auto* follower_option =
      app.add_option("--follower", follower,
                     "OpenACC files: the follower of the pair to read, by its Vehicle_order name (e.g. BMW_I3, any "
                     "case) or position (e.g. 3); its leader is the car directly ahead (default: the first pair, "
                     "said on stderr)");
  auto* all_pairs_option =
      app.add_flag("--all-pairs", all_pairs,
                   "OpenACC files: read every leader-follower pair; ONE model is fitted across all their runs, as "
                   "across several RUN files (one model per car: fit each --follower separately)");
  follower_option->excludes(all_pairs_option);
  CLI11_PARSE(app, argc, argv);

  std::vector<LoadedRun> loaded;
  std::vector<PairsRead> pairs_read;
  try
  {
    loaded = loadRuns(paths, topic, max_gap_s, acc::pairSelectorFromOptions(follower, all_pairs), pairs_read);
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
        return reportUnfitted(loaded,
                              "run '" + item.run.name + "' has " + std::to_string(item.run.size()) +
                                  " samples, too few to split in halves",
                              acc::IdentifiabilityCriteria{}.min_speed_std_mps, pairs_read, json_path);
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
  options.multistart.starts = static_cast<std::size_t>(starts);
  if (!quiet)
  {
    options.multistart.progress = showProgress;
  }
  // The same identification as the identifier node's (excitation check, fit, standard errors,
  // identifiability), so that batch and live agree on what a window says.
  const acc::Identification identification = acc::identifyAcc(training, options);
  if (!identification.solved || identification.calibration.diverged)
  {
    return reportUnfitted(loaded, identification.note.empty() ? "the fit diverged" : identification.note,
                          options.criteria.min_speed_std_mps, pairs_read, json_path);
  }
  report.calibration = identification.calibration;
  report.training_samples = identification.samples;
  report.uncertainty = identification.uncertainty;
  report.stability = identification.stability;
  report.identifiability_note = identification.note;
  try
  {
    const acc::CalibrationObjective objective(training, options.bounds);
    if (grid_nodes > 0)
    {
      const std::size_t n = grid_nodes;
      if (!quiet)
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
  report.quantities = identification.quantities;
  if (!no_stability_test)
  {
    acc::StabilityTestOptions test_options;
    test_options.alpha = alpha;
    if (seed_option->count() > 0)
      test_options.seed = seed;
    test_options.multistart.starts = options.multistart.starts;
    test_options.warm_starts = {p};
    if (!quiet)
      std::cerr << "string-stability test on held-out halves...\n";
    report.stability_test = acc::testStringStability(runsOf(loaded), test_options);
  }
  // Before the verdict is read: does the model describe the data at all? With --split half on both
  // halves: the test's verdict is judged on the held-out ones (on Casale part6 the first half fits
  // to 1.8 m of gap, the second misses by 8.1 m).
  std::vector<acc::CarFollowingRun> judged = training;
  judged.insert(judged.end(), testing.begin(), testing.end());
  report.model_adequacy = acc::assessModelAdequacy(p, judged, {}, report.uncertainty.standard_error);
  report.model_adequacy_data = testing.empty() ? "the runs it was fitted on"
                                               : "every run's training and held-out halves, each from its own start";
  // The second line of evidence: what each run's own dips say (whole runs, no model), and the
  // fitted model's dips beside them (the dip check of the adequacy).
  const std::vector<acc::CarFollowingRun> whole_runs = runsOf(loaded);
  report.dip_evidence = acc::pairDipEvidence(whole_runs);
  report.model_dips = acc::checkModelDips(p, whole_runs, *report.dip_evidence);
  acc::addDipCheck(*report.model_adequacy, report.model_dips->scored, report.model_dips->median_abs_dip_error);
  if (report.stability_test)
    report.verdict_contradiction = acc::verdictContradiction(acc::toString(report.stability_test->verdict),
                                                             *report.dip_evidence);
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
  printPairsRead(pairs_read, std::cout);
  acc::printReport(report, std::cout);
  nlohmann::json sequential_verdicts;
  if (verdict_every_s > 0.0)
  {
    if (!quiet)
      std::cerr << "sequential verdict: replaying the drives look by look...\n";
    sequential_verdicts = replayVerdicts(groupIntoDrives(loaded), verdict_every_s, alpha, std::cout);
  }
  if (!sumo_vtype_path.empty() &&
      !writeSumoVType(sumo_vtype_path, sumo_id.empty() ? loaded.front().run.name : sumo_id, report, whole_runs,
                      !pairs_read.empty()))
    return 1;
  if (!json_path.empty())
  {
    auto json = acc::reportToJson(report);
    for (const PairsRead& file : pairs_read)
    {
      json["openacc_pairs"].push_back({{"path", file.path}, {"pairs", file.pairs}});
    }
    if (!sequential_verdicts.is_null())
    {
      json["sequential_verdicts"] = sequential_verdicts;
    }
    std::ofstream file(json_path);
    file << json.dump(2) << "\n";
    if (!file)
    {
      std::cerr << "error: cannot write " << json_path << "\n";
      return 1;
    }
  }
  return report.calibration.diverged ? 1 : 0;
}
