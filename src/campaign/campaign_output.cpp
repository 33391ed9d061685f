#include "acc_identification/campaign/campaign_output.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <map>
#include <optional>
#include <sstream>

#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/model/json_number.h"
#include "acc_identification/calibration/quantity_identifiability.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/diagnosis/augmented_fit_json.h"
#include "acc_identification/evidence/evidence_json.h"
#include "acc_identification/model/acc_parameters_json.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/plain_text.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
const char* const kOpenAccAttribution =
    "Data: JRC OpenACC database (Makridis, Mattas, Anesiadou, Ciuffo, \"OpenACC. An open database of "
    "car-following experiments to study the properties of commercial ACC systems\", Transportation Research "
    "Part C 125 (2021) 103047), (c) European Union, 1995-2025, licensed under CC BY 4.0 "
    "(https://creativecommons.org/licenses/by/4.0). The JRC does not endorse this package. Changes: an excerpt "
    "of the columns Time, Speedk and IVSk; each car's runs calibrated with the ACC model; platoons simulated "
    "with the calibrated models; dips, ratios and statistics derived.";

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* const kParameterNames[] = {"k1", "k2", "tau_e", "eta"};
const char* const kParameterKeys[] = {"k1_per_s2", "k2_per_s", "tau_e_s", "eta_m"};

/// The quantity's value and standard error where the data determine it, NaN otherwise.
std::pair<double, double> determined(const GroupResult& group, const std::string& name)
{
  if (!group.fitted() || !group.identification.quantities)
    return {kNaN, kNaN};
  const QuantityEstimate* q = group.identification.quantities->find(name);
  if (q == nullptr || !q->determined)
    return {kNaN, kNaN};
  return {q->value, q->standard_error};
}

/// "0.210+-0.016" where the data determine the quantity; "(0.171+-1.497)" where it was fitted and
/// they do not (the reason is among the notes): the fit's value is shown, not hidden, and not
/// mistaken for a result; "-2.00 to -1.37" for a quantity held at a bound of the fit (its
/// one-sided 95 % interval: +- would reach beyond the bound); "-" where nothing was fitted.
std::string valuePlusMinus(const GroupResult& group, const std::string& name, const char* pattern)
{
  if (!group.fitted() || !group.identification.quantities)
    return "-";
  const QuantityEstimate* q = group.identification.quantities->find(name);
  if (q == nullptr)
    return "-";
  const auto [low, high] = q->boundInterval();
  const std::string cell = q->hasBoundInterval()
                               ? cellNumber(pattern, low) + " to " + cellNumber(pattern, high)
                               : cellNumber(pattern, q->value) + "+-" + cellNumber(pattern, q->standard_error);
  return q->determined ? cell : "(" + cell + ")";
}

double parameterOf(const AccParameters& p, int i)
{
  const double values[] = {p.k1_per_s2, p.k2_per_s, p.tau_e_s, p.eta_m};
  return values[i];
}

nlohmann::json parametersJson(const GroupResult& group, bool only_determined, bool errors)
{
  nlohmann::json j;
  for (int i = 0; i < 4; ++i)
  {
    double value = kNaN;
    if (group.fitted())
    {
      value = parameterOf(errors ? group.identification.uncertainty.standard_error
                                 : group.identification.calibration.parameters, i);
    }
    if (only_determined && !std::isfinite(determined(group, kParameterNames[i]).first))
      value = kNaN;
    j[kParameterKeys[i]] = value;
  }
  return j;
}

nlohmann::json stabilityTestJson(const StabilityTestResult& test)
{
  return {{"verdict", toString(test.verdict)},
          {"p_value", test.p_value},
          {"p_value_hypothesis", test.tested ? nlohmann::json(pValueHypothesis(test)) : nlohmann::json()},
          {"p_value_stable_rejected", test.p_value_stable_rejected},
          {"p_value_unstable_rejected", test.p_value_unstable_rejected},
          {"alpha", test.alpha},
          {"tested", test.tested},
          {"margin_interval", {test.margin_low, test.margin_high}},
          {"margin_allowed_pieces", marginPiecesJson(test)},
          {"training_samples", test.training_samples},
          {"held_out_samples", test.held_out_samples},
          {"reason", test.reason}};
}

nlohmann::json vehicleJson(const CampaignInputs& inputs, std::size_t index, const GroupResult& group)
{
  nlohmann::json run_files = nlohmann::json::array();
  for (const CampaignRun& run : inputs.groups[index].runs)
    run_files.push_back({{"run", inputs.files[run.file_index].name}, {"pair", run.pair.label()}});
  const Identification& id = group.identification;
  const auto margin = determined(group, "stability_margin");
  const bool fitted = group.fitted();
  const bool dynamics = group.dynamicsDetermined();
  nlohmann::json j = {{"name", group.vehicle},
          {"setting", group.setting},
          {"runs", group.runs},
          {"run_files", run_files},
          {"samples", group.samples},
          {"parameters", parametersJson(group, true, false)},
          {"fitted_parameters", parametersJson(group, false, false)},
          {"standard_errors", parametersJson(group, false, true)},
          {"identifiable", fitted && id.identifiable},
          {"note", fitted ? id.note : group.reason},
          {"fit_rmse_speed_mps", fitted ? id.fit.rmse_speed_mps : kNaN},
          {"margin", {{"value", margin.first}, {"standard_error", margin.second}}},
          {"quantities", id.quantities ? toJson(*id.quantities) : nlohmann::json()},
          {"stability",
           {{"lambda2", jsonNumberOrInfinity(dynamics ? id.stability.lambda2 : kNaN)},
            {"string_stable", dynamics ? nlohmann::json(id.stability.string_stable) : nlohmann::json()},
            {"band_upper_rad_s", dynamics ? id.stability.amplified_band_upper_rad_s : kNaN},
            {"peak_gain_db", jsonNumberOrInfinity(dynamics ? id.stability.peak_gain_db : kNaN)}}},
          {"stability_test", stabilityTestJson(group.stability_test)},
          {"model_adequacy", toJson(group.model_adequacy)},
          {"euler_step_bias", group.euler_step_bias ? toJson(*group.euler_step_bias) : nlohmann::json()},
          {"fitted", fitted},
          // Valid data without a fit (steady speed, too short) still say what they decide, as calibrate's JSON.
          {"unfitted_data", fitted ? nlohmann::json() : unfittedToJson(summarizeUnfittedData(
                                                             inputs.groups[index].segments(), group.reason,
                                                             IdentifiabilityCriteria{}.min_speed_std_mps))["data"]},
          {"seed", group.seed}};
  if (group.refit_bootstrap)
    j["refit_bootstrap"] = toJson(*group.refit_bootstrap);
  return j;
}

/// A car's position, null for 0 (none).
nlohmann::json positionOrNull(int position) { return position > 0 ? nlohmann::json(position) : nlohmann::json(); }

/// {model name: dip} of the run's alternative models at one position.
nlohmann::json alternativeDipsJson(const DipComparison& row, const std::vector<std::string>& models)
{
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t a = 0; a < models.size() && a < row.chain_alternatives_dip_mps.size(); ++a)
    j[models[a]] = row.chain_alternatives_dip_mps[a];
  return j;
}

nlohmann::json positionsJson(const std::vector<DipComparison>& positions, const std::vector<std::string>& alternatives)
{
  nlohmann::json j = nlohmann::json::array();
  for (const DipComparison& row : positions)
  {
    j.push_back({{"position", row.position},
                 {"name", row.name},
                 {"measured_dip_mps", row.measured.dip_mps},
                 {"predicted_dip_mps", row.chain.dip_mps},
                 {"predicted_from_position", positionOrNull(row.chain_driven_by)},
                 {"predicted_from_position_diagnosed", positionOrNull(row.chain_diagnosed_driven_by)},
                 {"measured_amplification", row.measured_amplification},
                 {"predicted_amplification", row.chain_amplification},
                 {"predicted_dip_mps_diagnosed", row.chain_diagnosed.dip_mps},
                 {"predicted_amplification_diagnosed", row.chain_amplification_diagnosed},
                 {"predicted_dip_mps_alternatives", alternativeDipsJson(row, alternatives)},
                 {"pair_predicted_dip_mps", row.pair.dip_mps},
                 {"pair_predicted_dip_mps_diagnosed", row.pair_diagnosed.dip_mps},
                 {"predicted_dip_mps_link_ratios", row.link_ratio_chain_dip_mps},
                 {"measured_distance_lost_m", row.measured.distance_lost_m},
                 {"predicted_distance_lost_m", row.chain.distance_lost_m},
                 {"predicted_distance_lost_m_diagnosed", row.chain_diagnosed.distance_lost_m},
                 {"pair_predicted_distance_lost_m", row.pair.distance_lost_m},
                 {"pair_predicted_distance_lost_m_diagnosed", row.pair_diagnosed.distance_lost_m},
                 {"measured_peak_braking_mps2", row.measured.shape.braking_mps2},
                 {"measured_peak_recovery_mps2", row.measured.shape.recovery_mps2},
                 {"pair_predicted_peak_braking_mps2", row.pair.shape.braking_mps2},
                 {"pair_predicted_peak_recovery_mps2", row.pair.shape.recovery_mps2},
                 {"pair_predicted_peak_braking_mps2_diagnosed", row.pair_diagnosed.shape.braking_mps2},
                 {"pair_predicted_peak_recovery_mps2_diagnosed", row.pair_diagnosed.shape.recovery_mps2},
                 {"measured_dip_width_s", row.measured.shape.width_s},
                 {"predicted_dip_width_s", row.chain.shape.width_s},
                 {"predicted_dip_width_s_diagnosed", row.chain_diagnosed.shape.width_s},
                 {"pair_predicted_dip_width_s", row.pair.shape.width_s},
                 {"pair_predicted_dip_width_s_diagnosed", row.pair_diagnosed.shape.width_s}});
  }
  return j;
}

nlohmann::json disagreementsJson(const std::vector<PlatoonDisagreement>& list)
{
  nlohmann::json j = nlohmann::json::array();
  for (const PlatoonDisagreement& d : list)
    j.push_back({{"perturbation", d.perturbation}, {"position", d.position}, {"name", d.name}, {"what", d.what}});
  return j;
}

/// The effects of a model with their values and standard errors (effect parameters only).
nlohmann::json effectsJson(const PlatoonCarModel& model)
{
  nlohmann::json values = nlohmann::json::object(), errors = nlohmann::json::object();
  const std::vector<std::string> names = effectParameterNames(model.effects);
  for (std::size_t i = 0; i < names.size() && i < model.effect_values.size(); ++i)
  {
    values[names[i]] = model.effect_values[i];
    const std::size_t se = AugmentedParameterBox::kBaseDimension + i;
    errors[names[i]] = se < model.standard_errors.size() ? model.standard_errors[se] : kNaN;
  }
  return {{"effects", effectNames(model.effects)}, {"values", values}, {"standard_errors", errors}};
}

nlohmann::json candidateJson(const PlatoonCandidate& candidate)
{
  return {{"name", candidate.name()},
          {"effects", effectNames(candidate.effects)},
          {"objective", objectiveName(candidate.objective)}};
}

nlohmann::json comparisonJson(const EffectSetComparison& c)
{
  return {{"model", candidateJson(c.candidate)},
          {"against", candidateJson(c.against)},
          {"car_perturbations", c.car_perturbations},
          {"perturbations", c.perturbations},
          {"mean_loss", c.mean_loss},
          {"against_loss", c.against_loss},
          {"mean_window_mse_m2ps2", c.mean_window_mse},
          {"against_window_mse_m2ps2", c.against_window_mse},
          {"relative_improvement", c.relative_improvement},
          {"p_value", c.p_value},
          {"p_value_alone", c.p_value_alone},
          {"significant", c.significant}};
}

nlohmann::json selectionJson(const EffectSetSelection& selection)
{
  nlohmann::json comparisons = nlohmann::json::array(), rivals = nlohmann::json::array(),
                 alternatives = nlohmann::json::array();
  for (const EffectSetComparison& c : selection.comparisons)
    comparisons.push_back(comparisonJson(c));
  for (const EffectSetComparison& c : selection.rivals)
    rivals.push_back(comparisonJson(c));
  for (const EffectSetComparison& c : selection.alternatives)
    alternatives.push_back(comparisonJson(c));
  return {{"model", candidateJson(selection.model)},
          {"effects", effectNames(selection.model.effects)},
          {"objective", objectiveName(selection.model.objective)},
          {"excluded_run", selection.excluded_run},
          {"comparisons", comparisons},
          {"rivals", rivals},
          {"alternatives", alternatives}};
}

nlohmann::json summaryJson(const DipPredictionSummary& s)
{
  return {{"car_perturbations", s.car_perturbations},
          {"median_dip_error", s.median_dip_error},
          {"median_abs_dip_error", s.median_abs_dip_error},
          {"median_abs_dip_error_interval", {s.median_abs_dip_error_lower, s.median_abs_dip_error_upper}},
          {"share_within_30_percent", s.share_within_30_percent},
          {"links", s.links},
          {"share_links_growth_right", s.share_links_growth_right},
          {"share_links_growth_right_interval", {s.share_links_growth_right_lower, s.share_links_growth_right_upper}},
          {"median_distance_lost_error", s.median_distance_lost_error},
          {"distance_lost_scored", s.distance_lost_scored},
          {"median_dip_width_error", s.median_dip_width_error},
          {"dip_width_scored", s.dip_width_scored}};
}

nlohmann::json rangesJson(const std::vector<std::pair<double, double>>& ranges)
{
  nlohmann::json j = nlohmann::json::array();
  for (const auto& [low, high] : ranges)
    j.push_back({low, high});
  return j;
}

/// Each effect of the diagnosed model by name: how precisely the group's runs pin its size.
nlohmann::json effectSizesJson(const LinkEvidence& e)
{
  nlohmann::json sizes = nlohmann::json::object();
  const std::vector<EffectSize> effect_sizes = diagnosedEffectSizes(e);
  for (std::size_t i = 0; i < e.diagnosed.effects.size() && i < effect_sizes.size(); ++i)
    sizes[effectName(e.diagnosed.effects[i])] = effectSizeJson(effect_sizes[i]);
  return sizes;
}

/// Whether ten cars with the diagnosed model amplify the real perturbations: a ratio above 1, or a
/// chain that ran away, collided or drove backwards (it amplifies whatever its ratio says); null
/// when nothing tells.
nlohmann::json longPlatoonAmplifies(const LinkEvidence& e)
{
  if (e.long_platoon_ran_away_at_car > 0 || e.long_platoon_breaks_down_at_car > 0)
    return true;
  return std::isfinite(e.long_platoon_dip_ratio) ? nlohmann::json(e.long_platoon_dip_ratio > 1.0)
                                                 : nlohmann::json(nullptr);
}

nlohmann::json linkJson(const LinkEvidence& e)
{
  const EmpiricalResponse& r = e.response;
  nlohmann::json informative = nlohmann::json::array();
  for (bool flag : r.informative)
    informative.push_back(flag);
  nlohmann::json values = nlohmann::json::object();
  const std::vector<std::string> names = effectParameterNames(e.diagnosed.effects);
  for (std::size_t i = 0; i < names.size() && i < e.diagnosed_fit.effect_values.size(); ++i)
    values[names[i]] = e.diagnosed_fit.effect_values[i];
  nlohmann::json j = {{"vehicle", e.vehicle},
          {"setting", e.setting},
          {"dip_ratio", toJson(e.dip_ratio)},
          {"frequency_response",
           {{"segments_used", r.segments_used},
            {"samples_unused", r.samples_unused},
            {"frequency_rad_s", r.frequency_rad_s},
            {"gain", r.gain},
            {"gain_lower", r.gain_lower},
            {"gain_upper", r.gain_upper},
            {"coherence", r.coherence},
            {"informative", informative},
            {"model_gain_base", e.model_gain_base},
            {"model_gain_diagnosed", e.model_gain_diagnosed},
            {"base_departs_rad_s", rangesJson(e.base_departs_rad_s)},
            {"diagnosed_departs_rad_s", rangesJson(e.diagnosed_departs_rad_s)}}},
          {"operating_speed_mps", e.operating_speed_mps},
          {"diagnosed_model",
           {{"name", e.diagnosed.name()},
            {"available", e.diagnosed_available},
            {"parameters", parametersJson(e.diagnosed_fit.base)},
            {"effect_values", values},
            {"standard_errors", standardErrorsJson(e.diagnosed.effects, e.diagnosed_fit.standard_errors)},
            {"effect_sizes", effectSizesJson(e)},
            {"small_signal",
             e.diagnosed_available
                 ? nlohmann::json{{"peak_gain_db", e.diagnosed_small_signal.peak_gain_db},
                                  {"peak_frequency_rad_s", e.diagnosed_small_signal.peak_frequency_rad_s},
                                  {"string_stable", e.diagnosed_small_signal.string_stable},
                                  {"locally_stable", e.diagnosed_small_signal.locally_stable},
                                  {"phase_margin_deg", e.diagnosed_small_signal.phase_margin_deg},
                                  {"how", e.diagnosed_small_signal.note}}
                 : nlohmann::json(nullptr)},
            {"long_platoon",
             {{"cars", kLongPlatoonCars},
              {"perturbations", e.long_platoon_perturbations},
              {"median_last_to_first_dip_ratio", e.long_platoon_dip_ratio},
              {"amplifies", longPlatoonAmplifies(e)},
              {"unfinished_perturbations", e.long_platoon_unfinished},
              {"ran_away_at_car", e.long_platoon_ran_away_at_car > 0 ? nlohmann::json(e.long_platoon_ran_away_at_car)
                                                                      : nlohmann::json(nullptr)},
              {"breaks_down_at_car", e.long_platoon_breaks_down_at_car > 0
                                         ? nlohmann::json(e.long_platoon_breaks_down_at_car)
                                         : nlohmann::json(nullptr)},
              {"breakdown", e.long_platoon_breakdown}}}}},
          {"note", e.note}};
  if (e.diagnosed_bootstrap)
    j["diagnosed_model"]["refit_bootstrap"] = toJson(*e.diagnosed_bootstrap);
  return j;
}

const std::vector<std::string> kLinkHeader{"vehicle", "set", "dips", "dip ratio [CI]", "each dip", "data say", "model departs [rad/s]",
                                           "diagnosed departs", "diag peak [dB]", "10-car ratio"};

std::string rangesText(const std::vector<std::pair<double, double>>& ranges)
{
  if (ranges.empty())
    return "nowhere";
  std::string text;
  for (const auto& [low, high] : ranges)
    text += (text.empty() ? "" : " ") + cellNumber("%.2f", low) + "-" + cellNumber("%.2f", high);
  return text;
}

/// Where a model's |Gamma| leaves the empirical band: "too short" without an empirical response,
/// "no model" without the model (its gains are NaN, and no departure would read as "nowhere").
std::string departsCell(const LinkEvidence& e, bool model_available,
                        const std::vector<std::pair<double, double>>& departs_rad_s)
{
  if (!responseRead(e))
    return "too short";
  return model_available ? rangesText(departs_rad_s) : "no model";
}

/// The ten-car ratio, and where a simulation ran away or broke down, at which car (a NaN alone
/// would hide a runaway, a ratio alone a collision).
std::string longPlatoonText(const LinkEvidence& e)
{
  if (!e.diagnosed_available)
    return "no model";  // the note says why
  if (e.long_platoon_perturbations == 0 && e.long_platoon_ran_away_at_car == 0 &&
      e.long_platoon_breaks_down_at_car == 0 && e.long_platoon_unfinished == 0)
    return "no dip";  // no run's first car at this setting braked
  std::vector<std::string> said;
  if (e.long_platoon_ran_away_at_car > 0)
    said.push_back("ran away at car " + std::to_string(e.long_platoon_ran_away_at_car) + " in a run");
  if (e.long_platoon_breaks_down_at_car > 0 && e.long_platoon_breaks_down_at_car != e.long_platoon_ran_away_at_car)
    said.push_back("car " + std::to_string(e.long_platoon_breaks_down_at_car) +
                   (e.long_platoon_collides ? " collides" : " drives backwards"));
  if (e.long_platoon_unfinished > 0)
    said.push_back(std::to_string(e.long_platoon_unfinished) + " cut short");
  if (!std::isfinite(e.long_platoon_dip_ratio))
    return said.empty() ? "-" : join(said, ", ");
  const std::string ratio = cellNumber("%.2f", e.long_platoon_dip_ratio);
  return said.empty() ? ratio : ratio + " (" + join(said, ", ") + ")";
}

/// Where each car's ten-car chain broke down, one line each ("" when none did).
std::string longPlatoonBreakdownLines(const CampaignResult& result)
{
  std::string lines;
  for (const LinkEvidence& e : result.links)
  {
    if (e.long_platoon_breaks_down_at_car > 0)
      lines += "- Ten " + e.vehicle + " at " + e.setting + ": " + e.long_platoon_breakdown + ".\n";
  }
  return lines.empty() ? "" : "\nWhere a ten-car chain broke down:\n\n" + lines;
}

/// The link's dip ratio with its interval where there is one; "no dip" without a perturbation
/// (a link whose leader never braked in these runs has no ratio to print).
std::string dipRatioCell(const DipRatioEstimate& d)
{
  if (d.count == 0)
    return "no dip";
  return ratioWithIntervalText(d.ratio_of_means, d.lower, d.upper);
}

/// Each dip's own ratio, smallest to largest ("-" without a dip).
std::string eachDipCell(const DipRatioEstimate& d)
{
  if (d.count == 0)
    return "-";
  return d.count < 2 ? cellNumber("%.2f", d.smallest_ratio)
                     : cellNumber("%.2f", d.smallest_ratio) + "-" + cellNumber("%.2f", d.largest_ratio);
}

std::vector<std::vector<std::string>> linkRows(const CampaignResult& result)
{
  std::vector<std::vector<std::string>> rows;
  for (const LinkEvidence& e : result.links)
  {
    const DipRatioEstimate& d = e.dip_ratio;
    rows.push_back({e.vehicle, e.setting, std::to_string(d.count), dipRatioCell(d), eachDipCell(d),
                    toString(d.amplifies),
                    departsCell(e, e.base_available, e.base_departs_rad_s),
                    departsCell(e, e.diagnosed_available, e.diagnosed_departs_rad_s),
                    e.diagnosed_available ? cellNumber("%.2f", e.diagnosed_small_signal.peak_gain_db) : "no model",
                    longPlatoonText(e)});
  }
  return rows;
}

const std::vector<std::string> kDiagnosedModelHeader{"vehicle", "set", "diagnosed model",
                                                     "effect parameters +- SE, 95 % (bootstrap, short runs) (size: z from none)"};

/// "[low, high]" of a quantity's bootstrap-t 95 % interval, "" where the bootstrap gives none.
std::string bootstrapInterval(const BootstrapQuantity& q)
{
  if (!q.hasInterval())
    return "";
  return "[" + cellNumber("%.3g", q.interval_95_low) + ", " + cellNumber("%.3g", q.interval_95_high) + "]";
}

/// " 95 % [low, high]" of the named quantity where the bootstrap gives an interval ("" else).
std::string bootstrapIntervalText(const RefitBootstrap* bootstrap, const std::string& name)
{
  const BootstrapQuantity* q = bootstrap != nullptr ? bootstrap->find(name) : nullptr;
  const std::string interval = q != nullptr ? bootstrapInterval(*q) : "";
  return interval.empty() ? "" : " 95 % " + interval;
}

/// One effect's parameters in fit with their standard errors (its first at *parameter among the
/// fit's effect values, advanced past them) and bootstrap intervals where made, and whether the
/// runs pin its size.
std::string effectSizeText(const AugmentedFit& fit, EffectKind kind, const EffectSize& size, std::size_t* parameter,
                           const RefitBootstrap* bootstrap)
{
  std::string text;
  for (const EffectParameterSpec& spec : candidateEffect(kind).parameters)
  {
    const std::size_t i = (*parameter)++;
    const std::size_t se = AugmentedParameterBox::kBaseDimension + i;
    const double value = i < fit.effect_values.size() ? fit.effect_values[i] : kNaN;
    const double error = se < fit.standard_errors.size() ? fit.standard_errors[se] : kNaN;
    text += (text.empty() ? "" : ", ") + spec.name + " " + cellNumber("%.3g", value) + "+-" + cellNumber("%.2g", error) +
            bootstrapIntervalText(bootstrap, spec.name);
  }
  if (std::isfinite(size.z))
    text += " (z " + cellNumber("%.1f", size.z) + (size.determined ? ", determined" : ", not determined") +
            bootstrapVerdictText(size) + ")";
  return text;
}

/// Each diagnosed model's effects as fitted on all of its group's runs, with standard errors.
std::vector<std::vector<std::string>> diagnosedModelRows(const CampaignResult& result)
{
  std::vector<std::vector<std::string>> rows;
  for (const LinkEvidence& e : result.links)
  {
    std::string effects = e.diagnosed_available ? "" : "no fit";
    const std::vector<EffectSize> sizes = diagnosedEffectSizes(e);
    std::size_t parameter = 0;
    for (std::size_t k = 0; e.diagnosed_available && k < e.diagnosed.effects.size(); ++k)
      effects += (effects.empty() ? "" : "; ") + effectSizeText(e.diagnosed_fit, e.diagnosed.effects[k], sizes[k], &parameter,
                                                                 e.diagnosed_bootstrap ? &*e.diagnosed_bootstrap : nullptr);
    if (e.diagnosed_bootstrap && !e.diagnosed_bootstrap->note.empty())
      effects += "; no bootstrap: " + e.diagnosed_bootstrap->note;
    else if (e.diagnosed_bootstrap && !e.diagnosed_bootstrap->held_near_bound.empty())
      effects += "; 95 % approximate: " + e.diagnosed_bootstrap->held_near_bound;
    rows.push_back({e.vehicle, e.setting, e.diagnosed.name(), effects.empty() ? "-" : effects});
  }
  return rows;
}

/// A car's model, and its diagnosed model where it has one: as cars[] and own_chain_models give it.
nlohmann::json carModelJson(int position, const std::string& name, const PlatoonCarModel& model,
                            const PlatoonCarModel* diagnosed)
{
  nlohmann::json j{{"position", position},
                   {"name", name},
                   {"model_available", model.available},
                   {"model_source", model.source},
                   {"parameters", parametersJson(model.parameters)}};
  if (diagnosed != nullptr)
  {
    j["diagnosed_effects"] = effectsJson(*diagnosed);
    j["diagnosed_parameters"] = parametersJson(diagnosed->parameters);
    j["diagnosed_model_source"] = diagnosed->source;
  }
  return j;
}

/// The cars a perturbation's own chain predicted with other models than the check's cars show.
nlohmann::json ownChainModelsJson(const std::vector<PerturbationCarModels>& cars)
{
  nlohmann::json out = nlohmann::json::array();
  for (const PerturbationCarModels& car : cars)
  {
    const bool diagnosed = car.diagnosed.available || !car.diagnosed.source.empty();
    out.push_back(carModelJson(car.position, car.name, car.model, diagnosed ? &car.diagnosed : nullptr));
  }
  return out;
}

/// The diagnosed car matching a base car of the chain (same position), or nullptr.
const PlatoonCarPrediction* diagnosedCar(const PlatoonCheck& check, int position)
{
  for (const PlatoonCarPrediction& car : check.cars_diagnosed)
  {
    if (car.position == position)
      return &car;
  }
  return nullptr;
}

nlohmann::json platoonJson(const PlatoonCheck& check, const EffectSetSelection* selection)
{
  nlohmann::json perturbations = nlohmann::json::array(), cars = nlohmann::json::array(),
                 disagreements = nlohmann::json::array();
  for (const PerturbationCheck& p : check.perturbations)
  {
    perturbations.push_back({{"onset_s", p.perturbation.onset_s},
                             {"end_s", p.perturbation.end_s},
                             {"window_end_s", p.perturbation.window_end_s},
                             {"lead_median_mps", p.perturbation.lead_median_mps},
                             {"incomplete", p.perturbation.incomplete},
                             {"positions", positionsJson(p.positions, check.alternative_models)},
                             {"data_show_growth", p.data_show_growth},
                             {"driven_by_hand", p.driven_by_hand},
                             {"models_fitted_on_it", p.fitted_on_it},
                             {"own_chain_models", ownChainModelsJson(p.own_chain_models)},
                             {"disagreements", disagreementsJson(p.disagreements)}});
    for (const auto& d : disagreementsJson(p.disagreements))
      disagreements.push_back(d);
  }
  for (const PlatoonCarPrediction& car : check.cars)
  {
    const PlatoonCarPrediction* diagnosed = diagnosedCar(check, car.position);
    nlohmann::json j = carModelJson(car.position, car.name, car.model, diagnosed != nullptr ? &diagnosed->model : nullptr);
    j["predicted"] = car.predicted;
    j["rmse_speed_mps"] = car.predicted ? car.rmse_speed_mps : kNaN;
    j["note"] = car.note;
    if (diagnosed != nullptr)
      j["diagnosed_rmse_speed_mps"] = diagnosed->predicted ? diagnosed->rmse_speed_mps : kNaN;
    cars.push_back(std::move(j));
  }
  const bool any = !check.perturbations.empty();
  return {{"run", check.run},
          {"setting", check.setting},
          {"positions", any ? positionsJson(check.perturbations.front().positions, check.alternative_models)
                            : nlohmann::json::array()},
          {"data_show_growth", any && check.perturbations.front().data_show_growth},
          {"disagreements", disagreements},
          {"perturbations", perturbations},
          {"cars", cars},
          {"effect_selection", selection != nullptr ? selectionJson(*selection) : nlohmann::json(nullptr)},
          {"notes", check.notes}};
}

/// "yes", "NO" (the reasons are in the notes) or "not assessed".
std::string adequacyCell(const ModelAdequacy& adequacy)
{
  if (!adequacy.assessed)
    return "not assessed";
  return adequacy.adequate ? "yes" : "NO";
}

/// The verdict as the headline counts it (a test that did not run decided nothing: "not tested"),
/// and for an undecided one whose paired test rejected a side, why its small p decides nothing:
/// the held-out data still allow m = 0 (a user read "undecided 0.001 (H0 unstable)" as a
/// contradiction; the note under the table gives the allowed margins).
std::string verdictCell(const StabilityTestResult& test)
{
  if (!test.tested)
    return "not tested";
  const bool side_rejected = std::min(test.p_value_stable_rejected, test.p_value_unstable_rejected) <= test.alpha;
  if (test.verdict == StabilityVerdict::Undecided && side_rejected)
    return "undecided (m = 0 allowed)";
  return toString(test.verdict);
}

/// One table row per group, in the columns of printCampaignTables.
std::vector<std::string> groupCells(const GroupResult& g)
{
  const Identification& id = g.identification;
  return {g.vehicle,
          g.setting,
          std::to_string(g.runs),
          std::to_string(g.samples),
          valuePlusMinus(g, "k1", "%.3f"),
          valuePlusMinus(g, "k2", "%.3f"),
          valuePlusMinus(g, "tau_e", "%.2f"),
          valuePlusMinus(g, "eta", "%.1f"),
          valuePlusMinus(g, "stability_margin", "%.2f"),
          verdictCell(g.stability_test),
          // A test that did not run has no p-value (its default 1 would read as "no evidence").
          g.stability_test.tested
              ? cellNumber("%.3f", g.stability_test.p_value) + " (H0 " + pValueHypothesis(g.stability_test) + ")"
              : "- (not run)",
          adequacyCell(g.model_adequacy),
          // Of the fit's k1, k2 and tau_e: "-" unless the data determine all three.
          g.dynamicsDetermined() ? cellNumber("%.3f", id.stability.amplified_band_upper_rad_s) : "-",
          g.dynamicsDetermined() ? cellNumber("%.2f", id.stability.peak_gain_db) : "-"};
}

const std::vector<std::string> kGroupHeader{"vehicle", "set", "runs", "samples", "k1 [1/s2]", "k2 [1/s]", "tau_e [s]",
                                            "eta [m]", "margin", "verdict", "p (H0)", "model adequate",
                                            "band [rad/s]", "peak [dB]"};

/// A number's cell, "-" where there is none (NaN: no car ahead, no data, no model); an infinite
/// value stays "inf", which says something.
std::string cellOrDash(const char* pattern, double value)
{
  return std::isnan(value) ? "-" : cellNumber(pattern, value);
}

const std::vector<std::string> kPlatoonHeader{"run",      "dip",      "pos",       "car",      "meas dip",
                                              "pred dip", "diag dip", "meas amp",  "pred amp", "diag amp",
                                              "pair dip", "pair diag", "meas lost", "diag lost", "pair diag lost"};

std::vector<std::vector<std::string>> platoonRows(const CampaignResult& result)
{
  std::vector<std::vector<std::string>> rows;
  for (const PlatoonCheck& check : result.platoons)
  {
    for (std::size_t i = 0; i < check.perturbations.size(); ++i)
    {
      const std::vector<int>& in_sample = check.perturbations[i].fitted_on_it;
      for (const DipComparison& row : check.perturbations[i].positions)
      {
        const bool saw_dip = std::find(in_sample.begin(), in_sample.end(), row.position) != in_sample.end();
        rows.push_back({check.run + "/" + check.setting, std::to_string(i + 1), std::to_string(row.position),
                        row.name + (saw_dip ? " *" : ""),
                        cellOrDash("%.2f", row.measured.dip_mps), cellOrDash("%.2f", row.chain.dip_mps),
                        cellOrDash("%.2f", row.chain_diagnosed.dip_mps), cellOrDash("%.2f", row.measured_amplification),
                        cellOrDash("%.2f", row.chain_amplification),
                        cellOrDash("%.2f", row.chain_amplification_diagnosed), cellOrDash("%.2f", row.pair.dip_mps),
                        cellOrDash("%.2f", row.pair_diagnosed.dip_mps),
                        cellOrDash("%.1f", row.measured.distance_lost_m),
                        cellOrDash("%.1f", row.chain_diagnosed.distance_lost_m),
                        cellOrDash("%.1f", row.pair_diagnosed.distance_lost_m)});
      }
    }
  }
  return rows;
}

void printAligned(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                  std::ostream& out)
{
  std::vector<std::size_t> width(header.size());
  for (std::size_t c = 0; c < header.size(); ++c)
  {
    width[c] = header[c].size();
    for (const auto& row : rows)
      width[c] = std::max(width[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c)
    {
      out << cells[c] << std::string(width[c] - cells[c].size() + 2, ' ');
    }
    out << "\n";
  };
  line(header);
  for (const auto& row : rows)
    line(row);
}

void printMarkdownTable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                        std::ostream& out)
{
  // A '|' inside a cell ("median |error|") would split it: Markdown's escape keeps the columns.
  auto line = [&out](const std::vector<std::string>& cells) {
    out << "|";
    for (const std::string& cell : cells)
    {
      out << " ";
      for (char c : cell)
        out << (c == '|' ? "\\|" : std::string(1, c));
      out << " |";
    }
    out << "\n";
  };
  line(header);
  out << "|";
  for (std::size_t c = 0; c < header.size(); ++c)
    out << "---|";
  out << "\n";
  for (const auto& row : rows)
    line(row);
}

std::vector<std::vector<std::string>> groupRows(const CampaignResult& result)
{
  std::vector<std::vector<std::string>> rows;
  for (const GroupResult& g : result.groups)
    rows.push_back(groupCells(g));
  return rows;
}

/// "the Euler step at the data's rate (median 0.5 s) moves k1 -15.4 % (...); corrected (fit - bias): k1 ..."
std::string eulerStepNote(const EulerStepBias& check)
{
  return printfText("the Euler step at the data's rate (median %.3g s) moves %s; ", check.median_step_s,
                    check.material_because.c_str()) +
         correctedFitText(check);
}

/// A short group's refitting bootstrap in one line: each quantity's 95 % interval, or why none.
std::string bootstrapNote(const RefitBootstrap& bootstrap)
{
  if (!bootstrap.note.empty())
    return "no refitting bootstrap: " + bootstrap.note;
  std::string text = "short runs, refitting bootstrap (" + std::to_string(bootstrap.refitted) + " of " +
                     std::to_string(bootstrap.replicates) + " replicates refitted), 95 %:";
  for (const BootstrapQuantity& q : bootstrap.quantities)
  {
    const std::string interval = bootstrapInterval(q);
    text += " " + q.name + " " + (interval.empty() ? "none" : interval) + ";";
  }
  text.pop_back();
  return text + (bootstrap.held_near_bound.empty() ? "" : " (approximate: " + bootstrap.held_near_bound + ")");
}

std::vector<std::string> groupNotes(const CampaignResult& result)
{
  std::vector<std::string> notes;
  for (const GroupResult& g : result.groups)
  {
    const std::string name = g.vehicle + "/" + g.setting + ": ";
    if (!g.fitted())
      notes.push_back(name + g.reason + ": no parameters and no verdict (a verdict needs the data a fit needs)");
    else if (!g.identification.note.empty())
      notes.push_back(name + g.identification.note);
    if (g.model_adequacy.assessed && !g.model_adequacy.adequate)
      notes.push_back(name + "model " + describeAdequacy(g.model_adequacy) +
                      ": its verdict compares two versions of a model that misses these data");
    else if (!g.model_adequacy.assessed && g.stability_test.tested &&
             g.stability_test.verdict != StabilityVerdict::Undecided)
      notes.push_back(name + "model adequacy " +
                      (g.model_adequacy.reasons.empty() ? std::string("not assessed") : g.model_adequacy.reasons.front()) +
                      ": its verdict compares two models fitted on halves, and nothing checked that they describe "
                      "these data");
    if (g.fitted() && g.stability_test.verdict == StabilityVerdict::Undecided)
      notes.push_back(name + (g.stability_test.tested ? "undecided: " : "not tested: ") + g.stability_test.reason);
    if (g.euler_step_bias && g.euler_step_bias->material)
      notes.push_back(name + eulerStepNote(*g.euler_step_bias));
    if (g.refit_bootstrap)
      notes.push_back(name + bootstrapNote(*g.refit_bootstrap));
  }
  return notes;
}

const std::vector<std::string> kGapHeader{"prediction", "car-perturbations", "median dip error",
                                          "median |error| [95 % over perturbations]", "within 30 %", "links",
                                          "growth/decay right [95 %]",
                                          "median distance-lost error", "median dip-width error"};

/// A fraction as a percent cell; "-" where the prediction has none (a model-free row has no
/// distance lost of its own).
std::string percentCell(const char* pattern, double fraction)
{
  return cellOrDash(pattern, 100.0 * fraction);
}

/// "19 % [12-27]": a share in percent with its interval where it has one.
std::string percentWithInterval(double value, double lower, double upper)
{
  const std::string cell = percentCell("%.0f %%", value);
  return std::isfinite(lower) ? cell + " [" + cellNumber("%.0f", 100.0 * lower) + "-" + cellNumber("%.0f", 100.0 * upper) + "]"
                              : cell;
}

/// "How far the gap shrinks": each kind of prediction against what the cars did.
std::vector<std::vector<std::string>> gapRows(const CampaignResult& result)
{
  std::vector<std::vector<std::string>> rows;
  for (const GapSummary& row : result.gap)
  {
    const DipPredictionSummary& s = row.summary;
    rows.push_back({row.label, std::to_string(s.car_perturbations),
                    percentCell("%+.0f %%", s.median_dip_error),
                    percentWithInterval(s.median_abs_dip_error, s.median_abs_dip_error_lower, s.median_abs_dip_error_upper),
                    percentCell("%.0f %%", s.share_within_30_percent), std::to_string(s.links),
                    percentWithInterval(s.share_links_growth_right, s.share_links_growth_right_lower,
                                        s.share_links_growth_right_upper),
                    percentCell("%+.0f %%", s.median_distance_lost_error),
                    percentCell("%+.0f %%", s.median_dip_width_error)});
  }
  return rows;
}

nlohmann::json gapJson(const CampaignResult& result)
{
  nlohmann::json j = nlohmann::json::object();
  for (const GapSummary& row : result.gap)
    j[row.key] = summaryJson(row.summary);
  return j;
}

const std::vector<std::string> kShapeHeader{
    "car ahead",       "car-perturbations", "dip passed on: cars", "base model",     "diagnosed model",
    "braking passed on: cars", "base model",     "diagnosed model",
    "recovery passed on: cars", "base model", "diagnosed model",       "dip widened: cars", "base model",
    "diagnosed model"};

/// The two places of "how much of the car ahead's braking and recovery each car passes on".
std::vector<std::pair<const char*, const ShapeTransferSummary*>> shapePlaces(const CampaignResult& result)
{
  return {{"the real first car (first followers)", &result.shapes_first_followers},
          {"another ACC car (further back)", &result.shapes_further_back}};
}

/// The span the rates are slopes over, as the report states it ("2 s").
std::string rateSpanText() { return cellNumber("%g s", PerturbationCriteria{}.acceleration_span_s); }

std::string ratioCell(const ClusteredRatio& r, bool with_interval)
{
  return with_interval ? ratioWithIntervalText(r) : cellNumber("%.2f", r.ratio);
}

std::vector<std::vector<std::string>> shapeRows(const CampaignResult& result)
{
  std::vector<std::vector<std::string>> rows;
  for (const auto& [label, s] : shapePlaces(result))
  {
    rows.push_back({label, std::to_string(s->cars.recovery.observations), ratioCell(s->dip_cars, true),
                    ratioCell(s->dip_pair_base, false), ratioCell(s->dip_pair_diagnosed, false),
                    ratioCell(s->cars.braking, true),
                    ratioCell(s->pair_base.braking, false), ratioCell(s->pair_diagnosed.braking, false),
                    ratioCell(s->cars.recovery, true), ratioCell(s->pair_base.recovery, false),
                    ratioCell(s->pair_diagnosed.recovery, false), cellNumber("%+.1f s", s->cars.median_widening_s),
                    cellNumber("%+.1f s", s->pair_base.median_widening_s),
                    cellNumber("%+.1f s", s->pair_diagnosed.median_widening_s)});
  }
  return rows;
}

/// "Paired over perturbations, ...": how much less of each dip the models pass on than the cars,
/// in each place, with the interval.
std::string dipShortfallLine(const CampaignResult& result)
{
  std::string line = "Paired over perturbations, the models' dips less the cars' over the dips of the cars ahead "
                     "(95 % CI; below 0 a model passes on less of each dip than the car did):";
  const char* separator = " ";
  for (const auto& [label, s] : shapePlaces(result))
  {
    line += separator + std::string("behind ") + label + ", base " + ratioCell(s->dip_pair_base_less_cars, true) +
            ", diagnosed " + ratioCell(s->dip_pair_diagnosed_less_cars, true);
    separator = "; ";
  }
  return line + ".";
}

nlohmann::json shapesJson(const ShapeTransferSummary& s)
{
  return {{"cars", toJson(s.cars)},
          {"pair_base", toJson(s.pair_base)},
          {"pair_diagnosed", toJson(s.pair_diagnosed)},
          {"dip", {{"cars", toJson(s.dip_cars)}, {"pair_base", toJson(s.dip_pair_base)},
                   {"pair_diagnosed", toJson(s.dip_pair_diagnosed)},
                   {"pair_base_less_cars", toJson(s.dip_pair_base_less_cars)},
                   {"pair_diagnosed_less_cars", toJson(s.dip_pair_diagnosed_less_cars)}}}};
}

std::string comparisonLine(const EffectSetComparison& c)
{
  if (c.perturbations == 0)  // every loss NaN: say so, not "loss NaN vs NaN"
    return c.candidate.name() + " against " + c.against.name() +
           ": not compared, no car-perturbation both predict with a measured dip above " +
           printfText("%g m/s", kScoredMinDipMps);
  return c.candidate.name() + " against " + c.against.name() + ": loss " + cellNumber("%.3f", c.mean_loss) + " vs " +
         cellNumber("%.3f", c.against_loss) + " (" + cellNumber("%+.0f %%", -100.0 * c.relative_improvement) +
         "; pair window MSE " + cellNumber("%.3f", c.mean_window_mse) + " vs " +
         cellNumber("%.3f", c.against_window_mse) + "), p = " + cellNumber("%.4f", c.p_value) +
         (c.p_value_alone != c.p_value ? " (alone " + cellNumber("%.4f", c.p_value_alone) + ")" : std::string()) +
         " over " + std::to_string(c.perturbations) + " perturbations";
}

std::vector<std::string> selectionLines(const EffectSetSelection& selection)
{
  std::vector<std::string> lines;
  for (const EffectSetComparison& c : selection.comparisons)
    lines.push_back(comparisonLine(c) + (c.significant ? ": named" : ": not named"));
  for (const EffectSetComparison& c : selection.rivals)
    lines.push_back("choice " + comparisonLine(c) +
                    (c.significant ? ": separated" : ": not separated, a near tie the data do not decide"));
  lines.push_back("chosen: " + selection.model.name());
  return lines;
}

/// How the rule's choice holds when each run is left out (the choice that run is predicted with):
/// the runs whose choice differs, grouped by the model they get. A choice that changes with one run
/// is one those runs do not make firmly.
std::string choiceWithoutEachRunLine(const CampaignResult& result)
{
  std::map<std::string, std::vector<std::string>> differing;
  for (const EffectSetSelection& selection : result.run_effect_selections)
  {
    if (selection.model.name() != result.effect_selection.model.name())
      differing[selection.model.name()].push_back(selection.excluded_run);
  }
  std::size_t same = result.run_effect_selections.size();
  std::string text;
  for (const auto& [model, runs] : differing)
  {
    same -= runs.size();
    text += "; without " + join(runs, ", ") + ": " + model;
  }
  return "the choice made without each run (what that run is predicted with): the same for " + std::to_string(same) +
         " of " + std::to_string(result.run_effect_selections.size()) + " runs" + text;
}

/// The near ties of the choices made without each run (the stage's choice and a rival the data do
/// not separate from it), each with how many choices it occurs in, its p range, and the runs whose
/// final model then holds the choice but not the rival: what those runs are predicted with is
/// not the data's decision.
std::string nearTiesWithoutEachRunLine(const CampaignResult& result)
{
  struct Tie
  {
    std::size_t choices = 0;
    double p_low = 1.0, p_high = 0.0;
    std::vector<std::string> rival_left_out;
  };
  std::map<std::string, Tie> ties;
  for (const EffectSetSelection& selection : result.run_effect_selections)
  {
    for (const EffectSetComparison* rival : selection.unseparatedRivals())
    {
      Tie& tie = ties[rival->candidate.name() + " over " + rival->against.name()];
      ++tie.choices;
      tie.p_low = std::min(tie.p_low, rival->p_value);
      tie.p_high = std::max(tie.p_high, rival->p_value);
      if (!selection.model.holdsAllOf(rival->against))
        tie.rival_left_out.push_back(selection.excluded_run);
    }
  }
  std::vector<std::string> parts;
  for (const auto& [name, tie] : ties)
    parts.push_back(name + " in " + std::to_string(tie.choices) + " of " +
                    std::to_string(result.run_effect_selections.size()) + " choices (p " +
                    cellNumber("%.2f", tie.p_low) + "-" + cellNumber("%.2f", tie.p_high) + ")" +
                    (tie.rival_left_out.empty() ? std::string(", the final model holding both")
                                                : ", the final model without the rival for " +
                                                      join(tie.rival_left_out, ", ")));
  return "near ties (a stage's choice the data do not separate from a rival): " +
         (parts.empty() ? std::string("none") : join(parts, "; "));
}

/// The median relative dip error of a run's diagnosed chain, scored as every chain is
/// (summarizeDipPredictions), with its dips replaced by alternative model `a`'s when given.
double runMedianDipError(const PlatoonCheck& check, std::optional<std::size_t> a = std::nullopt)
{
  PlatoonCheck scored;
  scored.perturbations = check.perturbations;
  for (PerturbationCheck& p : scored.perturbations)
    for (DipComparison& row : p.positions)
      if (a)
        row.chain_diagnosed.dip_mps = row.chain_alternatives_dip_mps.at(*a);
  return summarizeDipPredictions({scored}, DipPrediction::chain_diagnosed, kScoredMinDipMps, kScoredMinLinkChangeMps, {},
                                 ScoreIntervals::skipped)
      .median_dip_error;
}

/// The runs whose own choice has alternatives (final models the data do not separate from it):
/// each with what its chain's dips become under them.
std::string alternativeModelsLine(const CampaignResult& result)
{
  std::vector<std::string> runs;
  for (std::size_t i = 0; i < result.platoons.size() && i < result.run_effect_selections.size(); ++i)
  {
    const PlatoonCheck& check = result.platoons[i];
    const EffectSetSelection& selection = result.run_effect_selections[i];
    for (std::size_t a = 0; a < selection.alternatives.size(); ++a)
    {
      const EffectSetComparison& c = selection.alternatives[a];
      const double chosen_error = runMedianDipError(check), alternative_error = runMedianDipError(check, a);
      // A run without a scored dip (no perturbation of its first car) has its choice, but nothing
      // for it to change.
      const std::string errors =
          std::isfinite(chosen_error) || std::isfinite(alternative_error)
              ? "its chain's median dip error " + cellNumber("%+.0f %%", 100.0 * chosen_error) + " or " +
                    cellNumber("%+.0f %%", 100.0 * alternative_error)
              : "no dip of its own to predict";
      runs.push_back(check.run + ": " + c.candidate.name() + " or " + c.against.name() + " (loss " +
                     cellNumber("%.3f", c.mean_loss) + " vs " + cellNumber("%.3f", c.against_loss) + ", p = " +
                     cellNumber("%.2f", c.p_value) + "), " + errors);
    }
  }
  return "runs whose final model the data do not separate from another (predicted_dip_mps_alternatives): " +
         (runs.empty() ? std::string("none") : join(runs, "; "));
}

std::vector<std::string> platoonNotes(const CampaignResult& result)
{
  std::vector<std::string> notes;
  for (const PlatoonCheck& check : result.platoons)
  {
    std::size_t growth = 0;
    for (const PerturbationCheck& p : check.perturbations)
      growth += p.data_show_growth ? 1 : 0;
    notes.push_back(check.run + "/" + check.setting + ": " + std::to_string(check.perturbations.size()) +
                    " perturbation(s), " + std::to_string(growth) + " with measured growth along the platoon");
    for (const std::string& note : check.notes)
      notes.push_back(check.run + ": " + note);
  }
  return notes;
}

std::vector<std::vector<std::string>> disagreementRows(const CampaignResult& result)
{
  std::vector<std::vector<std::string>> rows;
  for (const PlatoonCheck& check : result.platoons)
  {
    for (const PerturbationCheck& p : check.perturbations)
    {
      for (const PlatoonDisagreement& d : p.disagreements)
        rows.push_back({check.run, std::to_string(d.perturbation + 1), std::to_string(d.position), d.name, d.what});
    }
  }
  return rows;
}
}  // namespace

namespace
{
nlohmann::json linksJson(const std::vector<LinkEvidence>& links)
{
  nlohmann::json j = nlohmann::json::array();
  for (const LinkEvidence& e : links)
    j.push_back(linkJson(e));
  return j;
}
}  // namespace

nlohmann::json campaignToJson(const CampaignInputs& inputs, const CampaignResult& result,
                              const std::vector<std::string>& input_paths, const CampaignOptions& options)
{
  nlohmann::json files = nlohmann::json::array();
  for (const CampaignFile& file : inputs.files)
  {
    nlohmann::json entry{{"path", file.path}, {"run", file.name}, {"setting", file.setting}};
    if (!file.car_settings.empty())
      entry["car_settings"] = file.car_settings;
    entry["pairs_read"] = nlohmann::json::array();
    for (const InputAccount& pair : file.pairs_read)
      entry["pairs_read"].push_back({{"pair", pair.openacc_pairs.empty() ? "" : pair.openacc_pairs.front()},
                                     {"counts", countsJson(pair)}});
    files.push_back(entry);
  }
  nlohmann::json vehicles = nlohmann::json::array(), platoons = nlohmann::json::array();
  for (std::size_t i = 0; i < result.groups.size(); ++i)
    vehicles.push_back(vehicleJson(inputs, i, result.groups[i]));
  for (std::size_t i = 0; i < result.platoons.size(); ++i)
    platoons.push_back(platoonJson(result.platoons[i], i < result.run_effect_selections.size()
                                                           ? &result.run_effect_selections[i]
                                                           : nullptr));
  const bool diagnosed = !result.run_effect_selections.empty();
  return {{"inputs", {{"arguments", input_paths}, {"files", files}, {"notes", inputs.notes}}},
          {"attribution", kOpenAccAttribution},
          {"options",
           {{"starts", options.group.starts},
            {"alpha", options.group.alpha},
            {"seed", options.group.seed},
            {"platoon_check", options.platoon_check},
            {"platoon_diagnosis", options.platoon_check && options.platoon_diagnosis}}},
          {"vehicles", vehicles},
          {"platoons", platoons},
          {"links", linksJson(result.links)},
          {"platoon_diagnosis",
           diagnosed ? nlohmann::json{{"rule", effectSetSelectionRule(options.effect_selection)},
                                      {"criterion", criterionName(result.effect_selection_criterion)},
                                      {"selection", selectionJson(result.effect_selection)},
                                      {"how_far_the_gap_shrinks", gapJson(result)},
                                      {"shape_passed_on",
                                       {{"first_follower", shapesJson(result.shapes_first_followers)},
                                        {"further_back", shapesJson(result.shapes_further_back)}}}}
                     : nlohmann::json(nullptr)}};
}

namespace
{
/// The headline every report.md of the package has (scripts/report_headline.py): the verdicts,
/// whether the models describe their data, and what data, here counted over the cars.
std::string campaignHeadline(const CampaignResult& result)
{
  std::map<std::string, std::size_t> verdicts;
  std::size_t adequate = 0, assessed = 0, runs = 0;
  for (const GroupResult& g : result.groups)
  {
    ++verdicts[g.stability_test.tested ? verdictInCapitals(g.stability_test.verdict) : std::string("NOT TESTED")];
    assessed += g.model_adequacy.assessed;
    adequate += g.model_adequacy.assessed && g.model_adequacy.adequate;
    runs += g.runs;
  }
  std::ostringstream line;
  line << "**Verdict:** ";
  const char* separator = "";
  for (const auto& [verdict, count] : verdicts)
  {
    line << separator << count << " " << verdict;
    separator = ", ";
  }
  line << " (string-stability test per car and setting) · **Model:** " << adequate << " of " << assessed
       << " cars ADEQUATE · **Data:** " << result.groups.size() << " cars (vehicle, setting), " << runs
       << " car-runs, " << result.platoons.size() << " platoon(s)";
  return line.str();
}

/// The campaign's answer to the paper's question, beside the per-car verdicts: how far the base
/// and the diagnosed models miss what the platoons did ("" without a platoon diagnosis or a scored
/// dip). The intervals are in "How far the gap shrinks".
std::string platoonHeadline(const CampaignResult& result)
{
  const auto find = [&](const std::string& key) {
    return std::find_if(result.gap.begin(), result.gap.end(), [&](const GapSummary& g) { return g.key == key; });
  };
  const auto base = find("chain_base"), diagnosed = find("chain_diagnosed");
  if (base == result.gap.end() || diagnosed == result.gap.end() || base->summary.car_perturbations == 0)
    return "";
  const DipPredictionSummary &b = base->summary, &d = diagnosed->summary;
  std::ostringstream line;
  line << "**Platoons:** over " << b.car_perturbations << " car-perturbations the base models' median dip error is "
       << cellNumber("%+.0f %%", 100.0 * b.median_dip_error) << ", the diagnosed models' "
       << cellNumber("%+.0f %%", 100.0 * d.median_dip_error)
       << " (each run predicted with the effects chosen without it; over all runs the platoon rule names "
       << result.effect_selection.model.name() << "); growth or decay right at "
       << cellNumber("%.0f %%", 100.0 * b.share_links_growth_right) << " and "
       << cellNumber("%.0f %%", 100.0 * d.share_links_growth_right) << " of " << b.links << " links";
  return line.str();
}

/// The report's headlines as plain text, for a terminal.
std::string withoutMarkdownBold(std::string text)
{
  for (std::size_t at = text.find("**"); at != std::string::npos; at = text.find("**", at))
    text.erase(at, 2);
  return text;
}
}  // namespace

void printCampaignTables(const CampaignResult& result, std::ostream& out)
{
  out << "ACC models by vehicle and distance setting (value+-SE where the data determine it, (value+-SE) in "
         "parentheses where they do not, a note says why; \"low to high\": the one-sided 95 % interval of a "
         "quantity held at a bound of the fit, e.g. the margin at tau_e = 0)\n";
  printAligned(kGroupHeader, groupRows(result), out);
  for (const std::string& note : groupNotes(result))
    out << "  note: " << note << "\n";
  if (result.platoons.empty())
    return;
  out << "\nPlatoons predicted from the real first car (leave-one-run-out models; a car with no other run at its "
         "setting: fitted on its run outside the perturbation predicted): speed dips [m/s] and amplification "
         "dip(k)/dip(k-1) (- where there is none)\n";
  printAligned(kPlatoonHeader, platoonRows(result), out);
  for (const std::string& note : platoonNotes(result))
    out << "  " << note << "\n";
  if (!result.run_effect_selections.empty())
  {
    out << "\nPlatoon diagnosis: which unmodelled effect closes the gap (criterion: "
        << criterionName(result.effect_selection_criterion) << ")\n";
    for (const std::string& line : selectionLines(result.effect_selection))
      out << "  " << line << "\n";
    out << "  " << choiceWithoutEachRunLine(result) << "\n";
    out << "  " << nearTiesWithoutEachRunLine(result) << "\n";
    out << "  " << alternativeModelsLine(result) << "\n";
    out << "\nHow far the gap shrinks (each run's diagnosed models chosen without that run)\n";
    printAligned(kGapHeader, gapRows(result), out);
    out << "\nHow much of the car ahead's dip shape each car passes on: its dip, its peak braking and recovery (speed "
           "slope over "
        << rateSpanText()
        << ") over the car ahead's (95 % CI over perturbations, the wild cluster bootstrap-t inverted) and how much "
           "wider its dip is at half "
           "depth (median), against the models driven by the same real leaders\n";
    printAligned(kShapeHeader, shapeRows(result), out);
    out << dipShortfallLine(result) << "\n";
    out << "\nEach car as a link, without a model and beside its models: dip over the dip of the car ahead (95 % "
           "CI over perturbations; inf where they do not bound it; each dip's own, smallest to largest), where the base and diagnosed |Gamma| leave the band of the empirical "
           "one (coherence >= 0.5), the diagnosed model's small-signal peak and its dip ratio over "
        << kLongPlatoonCars << " identical cars behind the real first cars\n";
    printAligned(kLinkHeader, linkRows(result), out);
    out << "\nThe diagnosed models fitted on all of each group's runs, and how precisely the runs pin each effect's "
           "size (z standard errors from none; determined: above the Bonferroni quantile over the model's effects)\n";
    printAligned(kDiagnosedModelHeader, diagnosedModelRows(result), out);
  }
  const auto disagreements = disagreementRows(result);
  out << "\nWhere model and data disagree: " << disagreements.size() << "\n";
  if (!disagreements.empty())
    printAligned({"run", "dip", "pos", "car", "what"}, disagreements, out);
  // The answer last, where a terminal leaves the reader: the report's headlines.
  out << "\n" << withoutMarkdownBold(campaignHeadline(result)) << "\n";
  const std::string platoons = platoonHeadline(result);
  if (!platoons.empty())
    out << withoutMarkdownBold(platoons) << "\n";
}

namespace
{
/// The "Data read" section: how many pairs were read whole, and a row for each of the others.
void printDataRead(const CampaignInputs& inputs, std::ostream& md)
{
  std::size_t pairs = 0;
  std::vector<std::vector<std::string>> rows;
  for (const CampaignFile& file : inputs.files)
    for (const InputAccount& pair : file.pairs_read)
    {
      ++pairs;
      const std::string losses = describeLossesAndRepairs(pair);
      if (losses.empty())
        continue;
      const auto count = [&pair](const std::string& name) {
        const std::optional<std::size_t> n = pair.count(name);
        return n ? std::to_string(*n) : std::string("?");
      };
      rows.push_back({file.name, pair.openacc_pairs.empty() ? "" : pair.openacc_pairs.front(), count("data_rows"),
                      count("samples_used"), count("runs"), losses});
    }
  md << "\n## Data read\n\n" << pairs << " pair(s) in " << inputs.files.size() << " file(s); "
     << pairs - rows.size() << " used row for row as read"
     << (rows.empty() ? ".\n" : "; the others below (the JSON's inputs.files[].pairs_read has every pair's "
                                 "counts, the notes say why).\n\n");
  if (!rows.empty())
    printMarkdownTable({"run", "pair", "rows", "samples used", "runs", "not used or rebuilt"}, rows, md);
}
}  // namespace

std::string campaignReportMarkdown(const CampaignInputs& inputs, const CampaignResult& result,
                                   const std::vector<std::string>& input_paths, bool with_figures)
{
  std::ostringstream md;
  md << "# ACC campaign: models by car and setting, and the platoons they predict\n\n" << campaignHeadline(result)
     << "\n\n";
  const std::string platoons = platoonHeadline(result);
  if (!platoons.empty())
    md << platoons << "\n\n";
  md << "Inputs:";
  for (const std::string& path : input_paths)
    md << " `" << path << "`";
  md << "\n\n## Models by vehicle and distance setting\n\n"
     << "identifyAcc on all of a group's runs (value +- standard error where the data determine it; in "
        "parentheses where they do not, with the reason in the notes; \"low to high\" where a quantity is held "
        "at a bound of the fit, e.g. tau_e at 0 and the margin there at -2, its least: the one-sided 95 % "
        "interval, as +- would reach beyond the bound); margin m = k1 tau_e^2 + 2 k2 tau_e - 2; verdict of the string-stability test on "
        "held-out halves and its p-value with the null hypothesis it tests (H0 stable: small p says unstable; "
        "\"undecided (m = 0 allowed)\" beside a small p: a side is rejected, but the held-out data still allow "
        "the boundary); "
        "whether the fit describes the car's runs (model_adequacy: gap and speed RMSE against their spread, "
        "parameters at a bound, residual correlation, pair-level dips; reasons in the notes); amplified band and "
        "peak gain of the fit (- unless the data determine k1, k2 and tau_e). The notes say why a verdict is undecided.\n\n";
  printMarkdownTable(kGroupHeader, groupRows(result), md);
  for (const std::string& note : groupNotes(result))
    md << "\n- " << note;
  md << "\n\n## Platoons predicted from the real first car\n\n"
     << "Each following car simulated with its model fitted WITHOUT this run (a car with no other run at its "
        "setting: on this run outside the perturbation predicted, one chain per perturbation; only where that "
        "car's fit on its other runs failed, on the first half of each of its segments of this run, and * where "
        "such a half holds the dip, which its model has then seen), from its measured gap and speed, "
        "driven by the predicted speed of the car ahead. Dip = pre-perturbation speed minus the minimum within "
        "the perturbation (+30 s); amplification = dip(k) / dip(k-1); - where there is none (the first car has no "
        "car ahead; a car without data or model, said in the notes).\n\n";
  printMarkdownTable(kPlatoonHeader, platoonRows(result), md);
  md << "\n";
  for (const std::string& note : platoonNotes(result))
    md << "- " << note << "\n";
  if (!result.run_effect_selections.empty())
  {
    md << "\n## Platoon diagnosis: which unmodelled effect closes the gap\n\n";
    for (const std::string& line : selectionLines(result.effect_selection))
      md << "- " << line << "\n";
    md << "- " << choiceWithoutEachRunLine(result) << "\n";
    md << "- " << nearTiesWithoutEachRunLine(result) << "\n";
    md << "- " << alternativeModelsLine(result) << "\n";
    md << "\n### How far the gap shrinks\n\nEach run's diagnosed models use the effect set chosen without that "
          "run, fitted on the car's other runs.\n\n";
    printMarkdownTable(kGapHeader, gapRows(result), md);
    md << "\n### How much of the car ahead's dip shape each car passes on\n\nThe sum of the cars' dips over "
          "the sum of the car ahead's measured dips (each car ahead's above "
       << cellNumber("%g", kMinLeaderDipMps)
       << " m/s): under 1 the place damps a braking, over 1 it amplifies it. The sum of the cars' "
          "peak braking (and recovery) rates, each the steepest least-squares slope of its speed over "
       << rateSpanText()
       << " within the dip, over the sum of the car ahead's measured ones (95 % interval over "
          "perturbations), and the median of how much wider the car's dip is at half depth than the car ahead's. "
          "The models are driven by the same real leaders (pair level), so all three answer the same input. A "
          "ratio near 1 and no widening pass a braking on with its shape; a model that cuts the rates or widens "
          "the dip where the cars do not smooths what they pass on, and that compounds along a chain.\n\n";
    printMarkdownTable(kShapeHeader, shapeRows(result), md);
    md << "\n" << dipShortfallLine(result) << "\n";
    md << "\n### Each car as a link: what the data show without a model\n\nDip ratio: the car's dip over the dip "
          "of the car directly ahead, with a 95 % interval over perturbations (the wild cluster bootstrap-t "
          "inverted; an end is inf where they do not bound it, as two perturbations never do and three of unequal "
          "depth seldom do), and each dip's own ratio, the smallest to the largest. Where the base and the "
          "diagnosed model's |Gamma(jw)| leave the band of the empirical one (Welch, coherence >= 0.5). The "
          "diagnosed model's small-signal peak (a law with branches: the largest of its branches') and the tenth car's dip over "
          "the first in a simulated platoon of ten identical cars behind the runs' real first cars (the tenth "
          "car's dip taken up to the next perturbation; \"collides\" where a car's gap reached 0, \"drives "
          "backwards\" where its speed went below 0: such a chain amplifies, whatever its ratio).\n\n";
    printMarkdownTable(kLinkHeader, linkRows(result), md);
    md << longPlatoonBreakdownLines(result);
    md << "\n### The diagnosed models and what the runs pin\n\nEach car's diagnosed model fitted on all of its "
          "group's runs (the model the link table, the ten-car platoon and the SUMO export use), every effect "
          "parameter with its standard error, and for each effect how far its size stands from none in standard "
          "errors: determined when above the Bonferroni normal quantile over the model's effects at alpha 0.05 "
          "and not at a bound of its range. A size not determined is a fit the runs allow, not a measurement. "
          "Where a car's runs are short (--bootstrap-below), its refitting bootstrap's 95 % interval follows each "
          "value: on short runs standard errors run short, so read \"determined\" there with its interval.\n\n";
    printMarkdownTable(kDiagnosedModelHeader, diagnosedModelRows(result), md);
  }
  md << "\n### Where model and data disagree\n\n";
  const auto disagreements = disagreementRows(result);
  if (disagreements.empty())
    md << "Nowhere.\n";
  else
    printMarkdownTable({"run", "dip", "pos", "car", "what"}, disagreements, md);
  if (with_figures)
  {
    md << "\n## Figures\n\n"
       << "![Parameters by car and setting](parameters.png)\n\n"
       << "![Stability margin and verdicts](margins.png)\n\n"
       << "![Measured and predicted dips by position](platoon_dips.png)\n";
    if (!result.links.empty())
      md << "\n![Empirical and model |Gamma(jw)| by car](link_gain.png)\n";
  }
  printDataRead(inputs, md);
  md << "\n## Attribution\n\n" << kOpenAccAttribution << "\n";
  return md.str();
}

}  // namespace acc
