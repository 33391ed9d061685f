#include "acc_identification/validation/suite_runs.h"
#include "acc_identification/io/output_files.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "acc_identification/io/run_csv.h"
#include "acc_identification/model/json_number.h"
#include "acc_identification/validation/combined_effect_suite.h"

namespace acc
{
const std::vector<std::string>& suiteNames()
{
  static const std::vector<std::string> names{"small", "large", "semi-real", "combined"};
  return names;
}

std::vector<SemiRealSet> bundledSemiRealSets(const std::string& casale_dir, const std::string& toyota_dir)
{
  auto read = [](const std::string& name, const std::string& dir, const std::vector<std::string>& files,
                 const OpenAccPairSelector& selector) {
    SemiRealSet set{name, {}};
    for (const std::string& file : files)
      for (CarFollowingRun& run : readRuns(dir + "/" + file, RunPlausibilityBounds{}, selector))
        set.runs.push_back(std::move(run));
    return set;
  };
  return {read("casale_parts3-6", casale_dir, {"part3.csv", "part4.csv", "part5.csv", "part6.csv"},
               OpenAccPairSelector::first()),
          read("zalazone_toyota_rav4", toyota_dir,
               {"dynamic_part5.csv", "dynamic_part6.csv", "dynamic_part12.csv", "dynamic_part14.csv"},
               OpenAccPairSelector::byFollower("TOYOTA_RAV4"))};
}

namespace
{
nlohmann::json semiRealJson(const SemiRealOutcome& o)
{
  return {{"set", o.set_name},
          {"injected", effectName(o.input.injected)},
          {"injected_value", o.input.magnitude},
          {"dominant_effect", effectName(o.dominant)},
          {"selected_effects", effectNames(o.chain)},
          {"selected", o.selected},
          {"fitted_magnitude", jsonNumber(o.fitted_magnitude)},
          {"baseline_magnitude", o.baseline_magnitude},
          {"recovered_magnitude", jsonNumber(o.recoveredMagnitude())},
          {"single_fit_magnitude", jsonNumber(o.single_fit_magnitude)},
          {"baseline_single_fit_magnitude", jsonNumber(o.baseline_single_fit_magnitude)},
          {"single_fit_shift", jsonNumber(o.singleFitShift())},
          {"expected_magnitude", jsonNumber(o.expected_magnitude)},
          {"baseline_estimate", o.baseline_estimate},
          {"baseline_standard_error", jsonNumber(o.baseline_standard_error)},
          {"standard_error_at_expected_size", o.standard_error_at_expected_size},
          {"detection_z", o.detection_z},
          {"detectable", o.detectable()},
          {"found_magnitude", jsonNumber(o.foundMagnitude())},
          {"misattributed", o.misattributed()},
          {"base_test_rmse_speed", o.base_test_rmse_speed_mps},
          {"passed", o.passed()},
          {"seconds", o.seconds}};
}

/// Real runs with a known effect injected: each set's untouched diagnosis, then every injection.
SuiteReport runSemiRealSuite(const std::vector<SemiRealSet>& sets, const DiagnosisOptions& options,
                             std::FILE* progress)
{
  std::vector<SemiRealOutcome> outcomes;
  nlohmann::json cases = nlohmann::json::array();
  for (const SemiRealSet& set : sets)
  {
    const auto start = std::chrono::steady_clock::now();
    const DiagnosisResult baseline = diagnoseSemiReal(set.runs, options);
    std::vector<SemiRealCase> grid = semiRealCaseGrid();
    grid.insert(grid.begin(), SemiRealCase{});
    for (const SemiRealCase& c : grid)
    {
      SemiRealOutcome o = runSemiRealCase(set, c, baseline, options);
      if (c.injected == EffectKind::none)
        o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(progress, "%s: injected %s %.2f -> %s, recovered %.4g (%.1f s)\n", set.name.c_str(),
                   effectName(c.injected).c_str(), c.magnitude, effectName(o.dominant).c_str(),
                   o.recoveredMagnitude(), o.seconds);
      cases.push_back(semiRealJson(o));
      outcomes.push_back(o);
    }
  }
  return {formatSemiRealTables(outcomes), {{"cases", cases}}};
}

/// Every pair of effects withheld at once: does the forward selection's chain name both?
SuiteReport runCombinedSuite(const DiagnosisOptions& options, std::FILE* progress)
{
  const std::vector<WithheldCase> grid = combinedCaseGrid();
  std::vector<CombinedOutcome> outcomes;
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    const CombinedOutcome o = runCombinedCase(grid[i], options);
    nlohmann::json withheld = nlohmann::json::array();
    for (std::size_t k = 0; k < o.withheld.size(); ++k)
      withheld.push_back({{"effect", effectName(o.withheld[k].first)},
                          {"value", o.withheld[k].second},
                          {"fitted", jsonNumber(o.fitted[k])}});
    std::fprintf(progress, "[%zu/%zu] withheld %s + %s -> chain of %zu, %zu named (%.1f s)\n", i + 1, grid.size(),
                 effectName(o.withheld[0].first).c_str(), effectName(o.withheld[1].first).c_str(), o.chain.size(),
                 o.named(), o.seconds);
    cases.push_back({{"withheld", withheld},
                     {"chain", effectNames(o.chain)},
                     {"seed", o.input.seed},
                     {"base_test_rmse_speed", o.base_test_rmse_speed_mps},
                     {"chain_test_rmse_speed", o.final_test_rmse_speed_mps},
                     {"seconds", o.seconds}});
    outcomes.push_back(o);
  }
  return {formatCombinedTables(outcomes), {{"cases", cases}}};
}

/// The grid of a size; the effects the run adds with --effect beyond the default list are hidden too.
std::vector<WithheldCase> withheldGrid(const std::string& size, const std::vector<EffectKind>& candidates)
{
  const std::vector<EffectKind> exploratory = exploratoryCandidates(candidates);
  if (size == "small")
    return withheldCaseGrid(1, {SyntheticLeadProfile::steps, SyntheticLeadProfile::dip}, {1.0}, 1, exploratory);
  return withheldCaseGrid(3, {SyntheticLeadProfile::steps, SyntheticLeadProfile::oscillation, SyntheticLeadProfile::dip},
                          {0.5, 1.5}, 1, exploratory);
}

nlohmann::json withheldJson(const WithheldOutcome& o)
{
  return {{"truth", effectName(o.input.truth)},
          {"truth_values", o.input.truth_values},
          {"profile", leadProfileName(o.input.profile)},
          {"speed_noise_std_mps", o.input.speed_noise_std_mps},
          {"seed", o.input.seed},
          {"dominant_effect", effectName(o.dominant)},
          {"plausible_effects", effectNames(o.plausible)},
          {"determined_effects", effectNames(o.determined)},
          {"recovered_magnitude", jsonNumber(o.recovered_magnitude)},
          {"recovered_standard_error", jsonNumber(o.recovered_standard_error)},
          {"base_test_rmse_speed", o.base_test_rmse_speed_mps},
          {"effect_test_rmse_speed", o.effect_test_rmse_speed_mps}};
}

/// Synthetic runs with one effect withheld: the confusion matrix and the magnitudes recovered.
SuiteReport runWithheldSuite(const std::string& size, const DiagnosisOptions& options, std::FILE* progress)
{
  const std::vector<WithheldCase> grid = withheldGrid(size, options.candidates);
  std::vector<WithheldOutcome> outcomes;
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    const WithheldOutcome o = runWithheldCase(grid[i], options);
    std::fprintf(progress, "[%zu/%zu] truth %s %s (%s, noise x%.2g) -> %s, magnitude %.4g\n", i + 1, grid.size(),
                 effectName(o.input.truth).c_str(),
                 o.input.truth_values.empty() ? "" : std::to_string(o.input.truth_values.front()).c_str(),
                 leadProfileName(o.input.profile).c_str(), o.input.speed_noise_std_mps / 0.06,
                 effectName(o.dominant).c_str(), o.recovered_magnitude);
    cases.push_back(withheldJson(o));
    outcomes.push_back(o);
  }
  const ConfusionMatrix matrix = confusionMatrix(outcomes);
  return {formatConfusionMatrix(matrix) + "\n" + formatMagnitudeRecovery(outcomes) + "\n" +
              formatDeterminedTable(determinedTable(outcomes)),
          {{"cases", cases}}};
}
}  // namespace

SuiteReport runSuite(const std::string& name, const DiagnosisOptions& options,
                     const std::vector<SemiRealSet>& semi_real_sets, std::FILE* progress)
{
  if (name == "semi-real")
    return runSemiRealSuite(semi_real_sets, options, progress);
  if (name == "combined")
    return runCombinedSuite(options, progress);
  if (name == "small" || name == "large")
    return runWithheldSuite(name, options, progress);
  throw std::invalid_argument("--withheld-suite takes small, large, semi-real or combined, not '" + name + "'");
}

int runSuiteCommand(const std::string& name, const DiagnosisOptions& options, const std::string& casale_dir,
                    const std::string& toyota_dir, const std::string& json_path, std::ostream& out,
                    std::ostream& errors)
{
  try
  {
    const std::vector<SemiRealSet> sets =
        name == "semi-real" ? bundledSemiRealSets(casale_dir, toyota_dir) : std::vector<SemiRealSet>{};
    const SuiteReport report = runSuite(name, options, sets, stderr);
    out << report.tables;
    return !json_path.empty() && !writeJsonFile(report.json, json_path, errors) ? 1 : 0;
  }
  catch (const std::exception& e)
  {
    errors << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace acc
