#include "acc_identification/diagnosis/diagnosis_output.h"
#include "acc_identification/diagnosis/augmented_fit_json.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/sumo/sumo_vtype.h"
#include "acc_identification/model/json_number.h"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "acc_identification/io/csv_fields.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
nlohmann::json parametersJson(const AugmentedFit& fit)
{
  nlohmann::json p;
  p["k1_per_s2"] = jsonNumber(fit.base.k1_per_s2);
  p["k2_per_s"] = jsonNumber(fit.base.k2_per_s);
  p["tau_e_s"] = jsonNumber(fit.base.tau_e_s);
  p["eta_m"] = jsonNumber(fit.base.eta_m);
  const std::vector<std::string> names = effectParameterNames(effectsOf(fit));
  for (std::size_t i = 0; i < names.size() && i < fit.effect_values.size(); ++i)
  {
    p[names[i]] = jsonNumber(fit.effect_values[i]);
  }
  return p;
}

nlohmann::json standardErrorsJson(const AugmentedFit& fit)
{
  return standardErrorsJson(effectsOf(fit), fit.standard_errors);
}

nlohmann::json stabilityJson(const AugmentedStability& s)
{
  return {{"peak_gain_db", jsonNumberOrInfinity(s.peak_gain_db)},
          {"peak_frequency_rad_s", jsonNumber(s.peak_frequency_rad_s)},
          // Meaningless without a gain (parameters not finite): null rather than a "false" that reads unstable.
          {"string_stable", std::isfinite(s.peak_gain_db) ? nlohmann::json(s.string_stable) : nlohmann::json()},
          {"lambda2", jsonNumberOrInfinity(s.lambda2)},
          {"locally_stable", s.locally_stable},
          {"phase_margin_deg", jsonNumber(s.phase_margin_deg)},
          {"crossover_rad_s", jsonNumber(s.crossover_rad_s)},
          {"note", s.note}};
}

nlohmann::json improvementJson(const ImprovementEstimate& e)
{
  return {{"mean_mse_reduction", jsonNumber(e.mean)},
          {"relative", jsonNumber(e.relative)},
          {"lower_bound", jsonNumber(e.lower_bound)},
          {"upper_bound", jsonNumber(e.upper_bound)}};
}

nlohmann::json modelJson(const ModelDiagnosis& m)
{
  nlohmann::json j;
  j["name"] = effectName(m.fit.effect);
  j["parameters"] = parametersJson(m.fit);
  j["standard_errors"] = standardErrorsJson(m.fit);
  j["train_rmse_speed"] = jsonNumber(m.train_rmse_speed_mps);
  j["test_rmse_speed"] = jsonNumber(m.test_rmse_speed_mps);
  j["test_rmse_gap"] = jsonNumber(m.test_rmse_gap_m);
  j["test_diverged"] = m.test_diverged;
  j["fit_diverged"] = m.fit.diverged;
  j["evaluations"] = m.fit.evaluations;
  j["stability"] = stabilityJson(m.stability);
  return j;
}

/// One step of the forward selection: the model with every effect chosen up to it.
nlohmann::json chainStepJson(const ForwardSelectionStep& step)
{
  const AugmentedFit& fit = step.model.fit;
  const std::vector<std::string> effects = effectNames(effectsOf(fit));
  nlohmann::json effect_parameters = nlohmann::json::object();
  const std::vector<std::string> names = effectParameterNames(effectsOf(fit));
  for (std::size_t i = 0; i < names.size() && i < fit.effect_values.size(); ++i)
  {
    effect_parameters[names[i]] = jsonNumber(fit.effect_values[i]);
  }
  nlohmann::json test = nullptr;
  if (step.stability_test)
  {
    test = {{"verdict", toString(step.stability_test->verdict)},
            {"p_value", jsonNumber(step.stability_test->p_value)},
            {"reason", step.stability_test->reason}};
  }
  return {{"effect", effectName(step.added)},
          {"model_effects", effects},
          {"train_rmse_speed", jsonNumber(step.model.train_rmse_speed_mps)},
          {"test_rmse_speed", jsonNumber(step.model.test_rmse_speed_mps)},
          {"test_rmse_gap", jsonNumber(step.model.test_rmse_gap_m)},
          {"test_diverged", step.model.test_diverged},
          {"improvement", improvementJson(step.model.improvement)},
          {"parameters",
           {{"k1_per_s2", jsonNumber(fit.base.k1_per_s2)},
            {"k2_per_s", jsonNumber(fit.base.k2_per_s)},
            {"tau_e_s", jsonNumber(fit.base.tau_e_s)},
            {"eta_m", jsonNumber(fit.base.eta_m)}}},
          {"effect_parameters", effect_parameters},
          {"standard_errors", standardErrorsJson(fit)},
          {"added_effect_size", effectSizeJson(step.added_size)},
          {"stability", stabilityJson(step.model.stability)},
          {"stability_test", test}};
}

/// Every comparison of the forward selection, so that why the chain stopped can be read off.
nlohmann::json forwardSelectionJson(const DiagnosisResult& r)
{
  nlohmann::json rounds = nlohmann::json::array();
  for (std::size_t i = 0; i < r.forward_rounds.size(); ++i)
  {
    const SelectionResult& s = r.forward_rounds[i];
    nlohmann::json candidates = nlohmann::json::array();
    for (std::size_t k = 0; k < s.candidates.size(); ++k)
    {
      candidates.push_back({{"effect", effectName(s.candidates[k])},
                            {"improvement", improvementJson(s.versus_base[k])},
                            {"significant", static_cast<bool>(s.significant[k])}});
    }
    const std::vector<EffectKind> on_top_of =
        i < r.selected_effects.size() ? effectsOf(r.selected_effects[i].model.fit) : std::vector<EffectKind>{};
    candidates = {{"on_top_of", combinedEffectName(on_top_of)},
                  {"added", effectName(s.dominant)},
                  {"level", jsonNumber(s.level)},
                  {"candidates", candidates}};
    rounds.push_back(candidates);
  }
  return {{"stop_reason", r.forward_stop_reason}, {"rounds", rounds}};
}

nlohmann::json groupsJson(const std::vector<ResidualGroup>& groups)
{
  nlohmann::json list = nlohmann::json::array();
  for (const ResidualGroup& g : groups)
  {
    list.push_back({{"name", g.name},
                    {"samples", g.samples},
                    {"share_of_time", jsonNumber(g.share_of_time)},
                    {"rmse_speed_before", jsonNumber(g.rmse_speed_before_mps)},
                    {"rmse_gap_before", jsonNumber(g.rmse_gap_before_m)},
                    {"share_of_squared_speed_error", jsonNumber(g.share_of_squared_speed_error)},
                    {"share_of_squared_gap_error", jsonNumber(g.share_of_squared_gap_error)},
                    {"rmse_speed_after", jsonNumber(g.rmse_speed_after_mps)},
                    {"rmse_gap_after", jsonNumber(g.rmse_gap_after_m)}});
  }
  return list;
}

nlohmann::json whereJson(const ResidualBreakdown& where)
{
  nlohmann::json j;
  j["regimes"] = groupsJson(where.regimes);
  j["speed_bands"] = groupsJson(where.speed_bands);
  j["frequency_bands"] = nlohmann::json::array();
  for (const FrequencyBand& b : where.frequency_bands)
  {
    j["frequency_bands"].push_back({{"name", b.name},
                                    {"lower_hz", jsonNumber(b.lower_hz)},
                                    {"upper_hz", b.upper_hz > 0.0 ? jsonNumber(b.upper_hz) : nlohmann::json(nullptr)},
                                    {"share_of_squared_speed_error_before", jsonNumber(b.share_of_speed_residual_power_before)},
                                    {"share_of_squared_speed_error_after", jsonNumber(b.share_of_speed_residual_power_after)}});
  }
  j["segments"] = nlohmann::json::array();
  for (const WorstSegment& s : where.segments)
  {
    j["segments"].push_back({{"run", s.run},
                             {"start_s", jsonNumber(s.start_s)},
                             {"end_s", jsonNumber(s.end_s)},
                             {"share_of_squared_speed_error", jsonNumber(s.share_of_squared_speed_error)},
                             {"rmse_speed_before", jsonNumber(s.rmse_speed_before_mps)},
                             {"rmse_speed_after", jsonNumber(s.rmse_speed_after_mps)},
                             {"rmse_gap_before", jsonNumber(s.rmse_gap_before_m)},
                             {"main_regime", s.main_regime}});
  }
  return j;
}

std::ofstream openForWriting(const std::string& path)
{
  std::ofstream out(path);
  if (!out)
  {
    throw std::runtime_error("cannot write " + path);
  }
  out.precision(10);
  return out;
}
}  // namespace

nlohmann::json perturbationWindowsJson(const PerturbationWindowCriterion& c)
{
  nlohmann::json effects = nlohmann::json::array();
  for (const PerturbationWindowScore& e : c.effects)
  {
    effects.push_back({{"effect", effectName(e.effect)},
                       {"window_rmse_speed_mps", jsonNumber(e.window_rmse_speed_mps)},
                       {"relative_improvement", jsonNumber(e.versus_base.relative_improvement)},
                       {"p_value", c.reason.empty() ? jsonNumber(e.versus_base.p_value) : nlohmann::json(nullptr)},
                       {"family_p_value", c.reason.empty() ? jsonNumber(e.family_p_value) : nlohmann::json(nullptr)},
                       {"significant", e.significant}});
  }
  return {{"perturbations", c.perturbations},
          {"base_window_rmse_speed_mps", jsonNumber(c.base_window_rmse_speed_mps)},
          {"effects", effects},
          {"named", effectName(c.named)},
          {"rule", c.rule},
          {"reason", c.reason}};
}

nlohmann::json verdictJson(const DiagnosisResult& r)
{
  // One verdict, stated once: which model's test it is and why that model.
  const DiagnosisVerdict verdict = statedVerdict(r);
  return {{"model", verdict.model},
          {"verdict", verdict.test ? nlohmann::json(toString(verdict.test->verdict)) : nlohmann::json()},
          {"p_value_stable_rejected", verdict.test ? jsonNumber(verdict.test->p_value_stable_rejected) : nlohmann::json()},
          {"p_value_unstable_rejected",
           verdict.test ? jsonNumber(verdict.test->p_value_unstable_rejected) : nlohmann::json()},
          {"model_adequate", verdict.model_adequate},
          {"why", verdict.why}};
}

namespace
{
/// Each run's part fitted and part held out; with runs kept aside whole, each fitted run and each
/// held-out run on its own (a fitted run has no held-out part then, nor the other way round).
nlohmann::json runsJson(const DiagnosisResult& r)
{
  auto trainJson = [](const CarFollowingRun& run) {
    return nlohmann::json{{"train", run.name}, {"train_start_s", run.time_s.front()}, {"train_end_s", run.time_s.back()}};
  };
  auto testJson = [](const CarFollowingRun& run) {
    return nlohmann::json{{"test", run.name},
                          {"test_start_s", run.time_s.front()},
                          {"test_end_s", run.time_s.back()},
                          {"test_samples", run.size()}};
  };
  nlohmann::json runs = nlohmann::json::array();
  if (r.held_out_whole_runs)
  {
    for (const CarFollowingRun& run : r.train)
      runs.push_back(trainJson(run));
    for (const CarFollowingRun& run : r.test)
      runs.push_back(testJson(run));
    return runs;
  }
  for (std::size_t i = 0; i < r.train.size(); ++i)
  {
    nlohmann::json entry = trainJson(r.train[i]);
    entry.update(testJson(r.test[i]));
    runs.push_back(entry);
  }
  return runs;
}
}  // namespace

nlohmann::json diagnosisToJson(const DiagnosisResult& r)
{
  nlohmann::json j;
  j["held_out"] = r.held_out_whole_runs ? "whole runs kept aside" : "the later part of each run";
  j["dominant_effect"] = effectName(r.selection.dominant);
  j["plausible_effects"] = nlohmann::json::array();
  for (EffectKind kind : r.selection.plausible)
  {
    j["plausible_effects"].push_back(effectName(kind));
  }
  j["distinguishable_from_runner_up"] = r.selection.distinguishable;
  j["determined_effects"] = nlohmann::json::array();
  for (const DeterminedEffect& e : r.determined)
  {
    auto base = [](const AccParameters& p) {
      return nlohmann::json{{"k1_per_s2", jsonNumber(p.k1_per_s2)}, {"k2_per_s", jsonNumber(p.k2_per_s)},
                            {"tau_e_s", jsonNumber(p.tau_e_s)}, {"eta_m", jsonNumber(p.eta_m)}};
    };
    j["determined_effects"].push_back({{"effect", effectName(e.effect)},
                                       {"value", jsonNumber(e.value)},
                                       {"standard_error", jsonNumber(e.standard_error)},
                                       {"z", jsonNumber(e.z)},
                                       {"base_with_effect", base(e.base_with)},
                                       {"base_without_effect", base(e.base_without)}});
  }
  j["unmeasured_effects"] = nlohmann::json::array();
  for (const UnmeasuredEffect& e : r.unmeasured)
  {
    j["unmeasured_effects"].push_back({{"effect", effectName(e.effect)},
                                       {"held_value", jsonNumber(e.held_value)},
                                       {"standard_error", jsonNumber(e.standard_error)},
                                       {"z", jsonNumber(e.z)},
                                       {"would_be_determined", e.would_be_determined}});
  }
  j["selected_effects"] = nlohmann::json::array();
  for (const ForwardSelectionStep& step : r.selected_effects)
  {
    j["selected_effects"].push_back(chainStepJson(step));
  }
  j["forward_selection"] = forwardSelectionJson(r);
  j["perturbation_windows"] = perturbationWindowsJson(r.perturbation_windows);
  j["baseline"] = modelJson(r.baseline);
  {
    // The model the diagnosis ends with (the last of the forward-selection chain, or the base
    // model): what a user takes away, beside the baseline it is judged against.
    const ModelDiagnosis& final_model = finalModel(r);
    j["final_model"] = {{"effects", effectNames(effectsOf(final_model.fit))},
                        {"parameters", parametersJson(final_model.fit)},
                        {"standard_errors", standardErrorsJson(final_model.fit)},
                        {"test_rmse_speed", jsonNumber(final_model.test_rmse_speed_mps)},
                        {"test_rmse_gap", jsonNumber(final_model.test_rmse_gap_m)},
                        {"model_adequacy", toJson(r.final_adequacy)}};
    if (r.final_bootstrap)
      j["final_model"]["refit_bootstrap"] = toJson(*r.final_bootstrap);
  }
  j["baseline"]["model_adequacy"] = toJson(r.baseline_adequacy);
  j["verdict"] = verdictJson(r);
  j["effects"] = nlohmann::json::array();
  for (std::size_t k = 0; k < r.effects.size(); ++k)
  {
    nlohmann::json e = modelJson(r.effects[k]);
    e["significant"] = r.effects[k].significant;
    e["resolvable"] = r.effects[k].resolvable;
    e["improvement"] = improvementJson(r.effects[k].improvement);
    e["stability_verdict_changes"] = r.effects[k].stability_verdict_changes;
    e["how_it_enters"] = candidateEffect(r.effects[k].fit.effect).how_it_enters;
    j["effects"].push_back(e);
  }
  j["ranking"] = nlohmann::json::array();
  for (std::size_t index : r.selection.ranking)
  {
    j["ranking"].push_back(effectName(r.selection.candidates[index]));
  }
  j["selection"] = {{"rule", r.selection_rule},
                    {"block_length_samples", jsonNumber(r.selection.block_length_samples)},
                    {"level", jsonNumber(r.selection.level)},
                    {"has_runner_up", r.selection.has_runner_up},
                    {"best_versus_runner_up", improvementJson(r.selection.best_versus_runner_up)}};
  j["stability_test"] = r.stability_test ? toJson(*r.stability_test) : nlohmann::json(nullptr);
  j["where"] = whereJson(r.where);
  j["operating_speed_mps"] = jsonNumber(r.operating_speed_mps);
  j["sample_period_s"] = jsonNumber(r.sample_period_s);
  j["runs"] = runsJson(r);
  j["notes"] = r.notes;
  j["steady_training"] = r.steady_training.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.steady_training);
  return j;
}

nlohmann::json diagnosisToJson(const DiagnosisResult& result, const std::vector<std::string>& inputs,
                               const std::vector<std::string>& held_out_inputs,
                               const std::vector<InputAccount>& inputs_read)
{
  nlohmann::json json = diagnosisToJson(result);
  json["inputs"] = inputs;
  if (!held_out_inputs.empty())
    json["held_out_inputs"] = held_out_inputs;
  json["openacc_pairs"] = openAccPairsJson(inputs_read);
  json["inputs_read"] = inputAccountsJson(inputs_read);
  return json;
}

void writeDiagnosisTables(const DiagnosisResult& r, const std::string& dir)
{
  const ModelDiagnosis& after = dominantModel(r);
  {
    std::ofstream out = openForWriting(dir + "/residuals.csv");
    out << "run,time_s,regime,speed_mps,gap_m,base_speed_mps,base_gap_m,effect_speed_mps,effect_gap_m\n";
    for (std::size_t i = 0; i < r.test.size(); ++i)
    {
      const CarFollowingRun& run = r.test[i];
      const auto regimes = classifyRegimes(run, BreakdownOptions{});
      const SimulatedFollower& b = r.baseline.test_simulations[i];
      const SimulatedFollower& a = after.test_simulations[i];
      for (std::size_t k = 0; k < run.size(); ++k)
      {
        out << csvQuoted(run.name) << ',' << run.time_s[k] << ',' << regimeName(regimes[k]) << ','
            << run.follower_speed_mps[k] << ',' << run.space_gap_m[k] << ',' << b.speed_mps[k] << ','
            << b.space_gap_m[k] << ',' << a.speed_mps[k] << ',' << a.space_gap_m[k] << '\n';
      }
    }
  }
  {
    std::ofstream out = openForWriting(dir + "/train_fit.csv");
    out << "run,time_s,speed_mps,base_speed_mps,effect_speed_mps\n";
    for (const CarFollowingRun& run : r.train)
    {
      const SimulatedFollower b = simulateFollower(r.baseline.fit.base, r.baseline.fit.settings, run);
      const SimulatedFollower a = simulateFollower(after.fit.base, after.fit.settings, run);
      for (std::size_t k = 0; k < run.size(); ++k)
      {
        out << csvQuoted(run.name) << ',' << run.time_s[k] << ',' << run.follower_speed_mps[k] << ','
            << b.speed_mps[k] << ',' << a.speed_mps[k] << '\n';
      }
    }
  }
  {
    std::ofstream out = openForWriting(dir + "/spectrum.csv");
    out << "run,frequency_hz,power_before,power_after\n";
    for (const SpectrumPoint& p : r.where.spectrum)
    {
      out << csvQuoted(p.run) << ',' << p.frequency_hz << ',' << p.power_before << ',' << p.power_after << '\n';
    }
  }
  {
    std::ofstream out = openForWriting(dir + "/gain.csv");
    out << "frequency_rad_s,base_db";
    for (const ModelDiagnosis& m : r.effects)
    {
      out << ',' << effectName(m.fit.effect) << "_db";
    }
    out << '\n';
    for (int i = 0; i <= 400; ++i)
    {
      const double w = 1e-3 * std::pow(1e4, i / 400.0);
      out << w << ','
          << 20.0 * std::log10(augmentedTransferGain(r.baseline.fit.base, r.baseline.fit.settings, r.operating_speed_mps, w));
      for (const ModelDiagnosis& m : r.effects)
      {
        out << ',' << 20.0 * std::log10(augmentedTransferGain(m.fit.base, m.fit.settings, r.operating_speed_mps, w));
      }
      out << '\n';
    }
  }
}

bool writeDiagnosisReport(const DiagnosisResult& result, const nlohmann::json& json, const std::string& dir,
                          const std::string& plot_script, bool no_plots, std::ostream& log)
{
  try
  {
    writeDiagnosisTables(result, dir);
  }
  catch (const std::exception& e)
  {
    log << "error: " << e.what() << "\n";
    return false;
  }
  if (!writeJsonFile(json, dir + "/diagnosis.json", log))
    return false;
  return no_plots || drawReportFigures(plot_script, dir, "tables and JSON", log);
}

bool saveFinalModelVType(const DiagnosisResult& result, const std::vector<CarFollowingRun>& runs,
                         const std::string& path, const std::string& id, bool from_openacc, std::ostream& log)
{
  const AugmentedFit& fit = finalModel(result).fit;
  if (fit.diverged)
  {
    log << "error: --sumo-vtype: the final model has no fit to export\n";
    return false;
  }
  const bool misses = result.final_adequacy.assessed && !result.final_adequacy.adequate;
  return saveFittedModelVType(path, id, fit.base, fit.effects, fit.effect_values, runs,
                              misses ? "the final model is " + describeAdequacy(result.final_adequacy) : "",
                              from_openacc, log);
}

}  // namespace acc
