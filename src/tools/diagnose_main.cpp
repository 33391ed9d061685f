// diagnose: where a calibrated ACC model misses the real car, which physical effect it lacks and
// what adding that effect buys (issue 6). Also runs the withheld-effect suite.
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <cctype>
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

#include <CLI/CLI.hpp>

#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/diagnosis/diagnosis_output.h"
#include "acc_identification/diagnosis/combined_effect_suite.h"
#include "acc_identification/diagnosis/withheld_effect_suite.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/io/installed_beside.h"
#include "acc_identification/ros/run_bag_reader.h"
#include "acc_identification/sumo/sumo_vtype.h"


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

/// The real data sets of the semi-real suite, read from the bundled data unpacked at build time:
/// Casale parts 3-6 (one set) and the ZalaZone Toyota RAV4 excerpt runs (another).
std::vector<acc::SemiRealSet> bundledSemiRealSets()
{
  auto read = [](const std::string& name, const std::string& dir, const std::vector<std::string>& files,
                 const acc::OpenAccPairSelector& selector) {
    acc::SemiRealSet set{name, {}};
    for (const std::string& file : files)
    {
      for (acc::CarFollowingRun& run : acc::readRuns(dir + "/" + file, acc::RunPlausibilityBounds{}, selector))
      {
        set.runs.push_back(std::move(run));
      }
    }
    return set;
  };
  return {read("casale_parts3-6", ACC_CASALE_DIR, {"part3.csv", "part4.csv", "part5.csv", "part6.csv"},
               acc::OpenAccPairSelector::first()),
          read("zalazone_toyota_rav4", ACC_ZALAZONE_TOYOTA_DIR,
               {"dynamic_part5.csv", "dynamic_part6.csv", "dynamic_part12.csv", "dynamic_part14.csv"},
               acc::OpenAccPairSelector::byFollower("TOYOTA_RAV4"))};
}

/// The names of effects, in order (a forward-selection chain).
nlohmann::json effectNamesJson(const std::vector<acc::EffectKind>& effects)
{
  nlohmann::json names = nlohmann::json::array();
  for (acc::EffectKind kind : effects)
  {
    names.push_back(acc::effectName(kind));
  }
  return names;
}

nlohmann::json semiRealJson(const acc::SemiRealOutcome& o)
{
  auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  return {{"set", o.set_name},
          {"injected", acc::effectName(o.input.injected)},
          {"injected_value", o.input.magnitude},
          {"dominant_effect", acc::effectName(o.dominant)},
          {"selected_effects", effectNamesJson(o.chain)},
          {"selected", o.selected},
          {"fitted_magnitude", number(o.fitted_magnitude)},
          {"baseline_magnitude", o.baseline_magnitude},
          {"recovered_magnitude", number(o.recoveredMagnitude())},
          {"single_fit_magnitude", number(o.single_fit_magnitude)},
          {"baseline_single_fit_magnitude", number(o.baseline_single_fit_magnitude)},
          {"single_fit_shift", number(o.singleFitShift())},
          {"expected_magnitude", number(o.expected_magnitude)},
          {"baseline_estimate", o.baseline_estimate},
          {"baseline_standard_error", number(o.baseline_standard_error)},
          {"detection_z", o.detection_z},
          {"detectable", o.detectable()},
          {"found_magnitude", number(o.foundMagnitude())},
          {"misattributed", o.misattributed()},
          {"base_test_rmse_speed", o.base_test_rmse_speed_mps},
          {"passed", o.passed()},
          {"seconds", o.seconds}};
}

/// Real runs with a known effect injected: each set's untouched diagnosis, then every injection.
int runSemiRealSuite(const acc::DiagnosisOptions& options, const std::optional<std::string>& json_path)
{
  std::vector<acc::SemiRealSet> sets;
  try
  {
    sets = bundledSemiRealSets();
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  std::vector<acc::SemiRealOutcome> outcomes;
  nlohmann::json cases = nlohmann::json::array();
  for (const acc::SemiRealSet& set : sets)
  {
    const auto start = std::chrono::steady_clock::now();
    const acc::DiagnosisResult baseline = acc::diagnoseSemiReal(set.runs, options);
    std::vector<acc::SemiRealCase> grid = acc::semiRealCaseGrid();
    grid.insert(grid.begin(), acc::SemiRealCase{});
    for (const acc::SemiRealCase& c : grid)
    {
      acc::SemiRealOutcome o = acc::runSemiRealCase(set, c, baseline, options);
      if (c.injected == acc::EffectKind::none)
      {
        o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
      std::fprintf(stderr, "%s: injected %s %.2f -> %s, recovered %.4g (%.1f s)\n", set.name.c_str(),
                   acc::effectName(c.injected).c_str(), c.magnitude, acc::effectName(o.dominant).c_str(),
                   o.recoveredMagnitude(), o.seconds);
      cases.push_back(semiRealJson(o));
      outcomes.push_back(o);
    }
  }
  std::cout << acc::formatSemiRealTables(outcomes);
  return json_path && !writeJson({{"cases", cases}}, *json_path) ? 1 : 0;
}

/// Every pair of effects withheld at once: does the forward selection's chain name both?
int runCombinedSuite(const acc::DiagnosisOptions& options, const std::optional<std::string>& json_path)
{
  const std::vector<acc::WithheldCase> grid = acc::combinedCaseGrid();
  std::vector<acc::CombinedOutcome> outcomes;
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    const acc::CombinedOutcome o = acc::runCombinedCase(grid[i], options);
    nlohmann::json withheld = nlohmann::json::array();
    for (std::size_t k = 0; k < o.withheld.size(); ++k)
    {
      withheld.push_back({{"effect", acc::effectName(o.withheld[k].first)},
                          {"value", o.withheld[k].second},
                          {"fitted", std::isfinite(o.fitted[k]) ? nlohmann::json(o.fitted[k]) : nlohmann::json(nullptr)}});
    }
    std::fprintf(stderr, "[%zu/%zu] withheld %s + %s -> chain of %zu, %zu named (%.1f s)\n", i + 1, grid.size(),
                 acc::effectName(o.withheld[0].first).c_str(), acc::effectName(o.withheld[1].first).c_str(),
                 o.chain.size(), o.named(), o.seconds);
    cases.push_back({{"withheld", withheld},
                     {"chain", effectNamesJson(o.chain)},
                     {"seed", o.input.seed},
                     {"base_test_rmse_speed", o.base_test_rmse_speed_mps},
                     {"chain_test_rmse_speed", o.final_test_rmse_speed_mps},
                     {"seconds", o.seconds}});
    outcomes.push_back(o);
  }
  std::cout << acc::formatCombinedTables(outcomes);
  return json_path && !writeJson({{"cases", cases}}, *json_path) ? 1 : 0;
}

int runSuite(const std::string& size, const acc::DiagnosisOptions& options, const std::optional<std::string>& json_path)
{
  if (size == "semi-real")
  {
    return runSemiRealSuite(options, json_path);
  }
  if (size == "combined")
  {
    return runCombinedSuite(options, json_path);
  }
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
    std::cerr << "error: --withheld-suite takes small, large, semi-real or combined\n";
    return 2;
  }
  std::vector<acc::WithheldOutcome> outcomes;
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    const acc::WithheldOutcome o = acc::runWithheldCase(grid[i], options);
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
                     {"plausible_effects", effectNamesJson(o.plausible)},
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

/// "string UNSTABLE (p (H0: stable) = 0.002; p (H0: unstable) = 0.97)": p-values named by the
/// hypothesis they test.
std::string testVerdictText(const acc::AugmentedStabilityTestResult& test)
{
  char text[200];
  std::string verdict = acc::toString(test.verdict);
  for (char& c : verdict)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  std::snprintf(text, sizeof text, "%s%s (p (H0: stable) = %.3g; p (H0: unstable) = %.3g)",
                test.verdict == acc::StabilityVerdict::Undecided ? "" : "string ", verdict.c_str(),
                test.p_value_stable_rejected, test.p_value_unstable_rejected);
  return text;
}

/// Each model's adequacy, then THE verdict: the final model's test where the diagnosis found a
/// better model, the base model's otherwise, and why.
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

void printVerdict(const acc::DiagnosisResult& r)
{
  const acc::DiagnosisVerdict verdict = acc::statedVerdict(r);
  std::printf("model adequacy, base model: %s\n", acc::describeAdequacy(r.baseline_adequacy).c_str());
  if (!r.selected_effects.empty())
    std::printf("model adequacy, %s: %s\n", verdict.model.c_str(), acc::describeAdequacy(r.final_adequacy).c_str());
  std::printf("verdict (string-stability test of the %s): %s\n  why this model: %s\n", verdict.model.c_str(),
              verdict.test ? testVerdictText(*verdict.test).c_str() : "not tested", verdict.why.c_str());
}

/// The forward selection's chain: one line per step with its held-out RMSE, gain and verdict,
/// then the parameters of that step's model with their standard errors.
void printChain(const acc::DiagnosisResult& r)
{
  std::printf("effects in combination (forward selection): %s\n",
              r.selected_effects.empty() ? "none" : "");
  for (std::size_t i = 0; i < r.selected_effects.size(); ++i)
  {
    const acc::ForwardSelectionStep& step = r.selected_effects[i];
    const acc::ModelDiagnosis& m = step.model;
    std::printf("  %zu. + %-26s test_v %.4f m/s, test_gap %.3f m, MSE -%.1f%% of the previous model's (lower bound %.4g m^2/s^2), %s",
                i + 1, acc::effectName(step.added).c_str(), m.test_rmse_speed_mps, m.test_rmse_gap_m,
                100.0 * m.improvement.relative, m.improvement.lower_bound,
                m.stability.string_stable ? "point estimate stable" : "point estimate unstable");
    if (step.stability_test)
    {
      std::printf(", test: %s", testVerdictText(*step.stability_test).c_str());
    }
    // A diverged fit has no standard errors: print nan rather than fail.
    auto se = [&m](std::size_t i) { return i < m.fit.standard_errors.size() ? m.fit.standard_errors[i] : NAN; };
    std::printf("\n     k1 %.4g +- %.2g, k2 %.4g +- %.2g, tau_e %.4g +- %.2g, eta %.4g +- %.2g", m.fit.base.k1_per_s2, se(0),
                m.fit.base.k2_per_s, se(1), m.fit.base.tau_e_s, se(2), m.fit.base.eta_m, se(3));
    const std::vector<std::string> names = acc::effectParameterNames(acc::effectsOf(m.fit));
    for (std::size_t j = 0; j < names.size() && j < m.fit.effect_values.size(); ++j)
    {
      std::printf(", %s %.4g +- %.2g", names[j].c_str(), m.fit.effect_values[j],
                  se(acc::AugmentedParameterBox::kBaseDimension + j));
    }
    std::printf("\n");
  }
  std::printf("  stopped: %s\n", r.forward_stop_reason.c_str());
}

void printSummary(const acc::DiagnosisResult& r)
{
  std::printf("%-26s %10s %10s %10s %9s %11s  %s\n", "model", "train_v", "test_v", "test_gap", "improve", "significant",
              "point estimate's stability (not a verdict)");
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
  // What the training data pin down, named by the held-out rule or not (determined_effects.h).
  std::printf("determined by the training data (size away from none, Bonferroni):%s\n", r.determined.empty() ? " none" : "");
  for (const acc::DeterminedEffect& e : r.determined)
  {
    std::printf("  %s\n", acc::describeDeterminedEffect(e).c_str());
  }
  if (r.stability_test)
  {
    const acc::AugmentedStabilityTestResult& t = *r.stability_test;
    std::printf("string-stability test of the %s model on the held-out parts: %s\n  why: %s\n",
                acc::effectName(t.effect).c_str(), testVerdictText(t).c_str(), t.reason.c_str());
  }
  printChain(r);
  printVerdict(r);
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
      ->check(CLI::IsMember({"small", "large", "semi-real", "combined"}));
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
    return runSuite(suite, options, json_path.empty() ? std::nullopt : std::optional<std::string>(json_path));
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
  printSummary(result);
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
