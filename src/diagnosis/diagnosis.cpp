#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/model/car_following_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "acc_identification/calibration/identification.h"
#include "acc_identification/diagnosis/final_model_bootstrap.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/parallel_tasks.h"

namespace acc
{
namespace
{
void splitRuns(const std::vector<CarFollowingRun>& runs, const DiagnosisOptions& options, DiagnosisResult* out)
{
  for (const CarFollowingRun& run : runs)
  {
    const std::string problem = describeRunProblem(run);
    if (!problem.empty())
    {
      out->notes.push_back("run '" + run.name + "' not used: " + problem);
      continue;
    }
    const double split_time = run.time_s.front() + options.train_fraction * run.durationS();
    const std::size_t split = static_cast<std::size_t>(
        std::lower_bound(run.time_s.begin(), run.time_s.end(), split_time) - run.time_s.begin());
    if (split < options.min_samples_per_half || run.size() - split < options.min_samples_per_half)
    {
      out->notes.push_back("run '" + run.name + "' not used: " + std::to_string(run.size()) +
                           " samples leave fewer than " + std::to_string(options.min_samples_per_half) +
                           " on one side of the train/test split");
      continue;
    }
    out->train.push_back(run.slice(0, split, "[train]"));
    out->test.push_back(run.slice(split, run.size(), "[test]"));
  }
}

/// Whole runs onto one side (train or test), each checked as splitRuns checks a part.
void addWholeRuns(const std::vector<CarFollowingRun>& runs, const DiagnosisOptions& options, const std::string& tag,
                  std::vector<CarFollowingRun>* side, std::vector<std::string>* notes)
{
  for (const CarFollowingRun& run : runs)
  {
    std::string problem = describeRunProblem(run);
    if (problem.empty() && run.size() < options.min_samples_per_half)
      problem = std::to_string(run.size()) + " samples, fewer than " + std::to_string(options.min_samples_per_half);
    if (!problem.empty())
      notes->push_back("run '" + run.name + "' not used: " + problem);
    else
      side->push_back(run.slice(0, run.size(), tag));
  }
}

double median(std::vector<double> values)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

/// Timing effects (lag, delay, clock offset) each trade off with tau_e and k2, and on real runs
/// their fits can land in different valleys of that trade-off: from the base fit the lag fit may
/// return to "no lag" (k2 near 0, tau_e large) where started from the offset's base parameters it
/// finds a lower training error (a 2 s lag injected into the Toyota runs: 0.3255 -> 0.3247 m/s,
/// docs/RESULTS.md, semi-real checks). So a timing effect's fit is started again from the base parameters of
/// the best other timing effect's fit when that fits the training data better, and the better of
/// the two is kept: never worse than the first fit, and the same for any thread count. One restart
/// (from the best), not one per better fit: each is a whole multistart fit.
AugmentedFit refitFromBestTimingFit(std::size_t index, const std::vector<AugmentedFit>& first_fits,
                                    const std::vector<CarFollowingRun>& train,
                                    const AugmentedCalibrationOptions& calibration, const AugmentedFit& base_fit)
{
  const AugmentedFit& first = first_fits[index];
  const AugmentedFit* best_other = nullptr;
  for (std::size_t j = 0; candidateEffect(first.effect).magnitude_is_time && j < first_fits.size(); ++j)
  {
    const AugmentedFit& other = first_fits[j];
    if (j != index && candidateEffect(other.effect).magnitude_is_time && !other.diverged &&
        other.train_mse_speed < first.train_mse_speed &&
        (best_other == nullptr || other.train_mse_speed < best_other->train_mse_speed))
    {
      best_other = &other;
    }
  }
  if (best_other == nullptr)
  {
    return first;
  }
  AugmentedFit warm = base_fit;
  warm.base = best_other->base;
  AugmentedFit refit = calibrateAugmented(first.effect, train, calibration, &warm);
  const std::size_t evaluations = first.evaluations + refit.evaluations;  // the work of every start
  AugmentedFit best = refit.train_mse_speed < first.train_mse_speed ? std::move(refit) : first;
  best.evaluations = evaluations;
  return best;
}

/// Scores a fit on the held-out halves; keeps the simulations and per-sample squared errors.
ModelDiagnosis scoreModel(const AugmentedFit& fit, const DiagnosisResult& data, SquaredErrorsByRun* squared_errors)
{
  ModelDiagnosis model;
  model.fit = fit;
  model.train_rmse_speed_mps = std::sqrt(fit.train_mse_speed);
  double speed_sum = 0.0;
  double gap_sum = 0.0;
  std::size_t count = 0;
  squared_errors->clear();
  for (const CarFollowingRun& run : data.test)
  {
    SimulatedFollower sim = simulateFollower(fit.base, fit.settings, run);
    model.test_diverged = model.test_diverged || sim.diverged;
    std::vector<double> errors(run.size());
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      // A diverged simulation is scored at the divergence bound: a huge, finite error.
      const bool lost = sim.diverged && k >= sim.diverged_at_index;
      const double e = lost ? kDivergenceBound : run.follower_speed_mps[k] - sim.speed_mps[k];
      const double g = lost ? kDivergenceBound : run.space_gap_m[k] - sim.space_gap_m[k];
      errors[k] = e * e;
      speed_sum += e * e;
      gap_sum += g * g;
    }
    count += run.size();
    squared_errors->push_back(errors);
    model.test_simulations.push_back(std::move(sim));
  }
  model.test_rmse_speed_mps = count > 0 ? std::sqrt(speed_sum / static_cast<double>(count)) : 0.0;
  model.test_rmse_gap_m = count > 0 ? std::sqrt(gap_sum / static_cast<double>(count)) : 0.0;
  return model;
}

/// The values of the last effect of a combined fit (the one a step adds).
std::vector<double> lastEffectValues(const AugmentedFit& fit)
{
  const std::size_t count = std::min(candidateEffect(fit.effect).parameters.size(), fit.effect_values.size());
  return std::vector<double>(fit.effect_values.end() - static_cast<long>(count), fit.effect_values.end());
}

/// The candidate models of one forward round: each remaining effect fitted on top of `current`.
struct ForwardRound
{
  std::vector<ModelDiagnosis> models;
  std::vector<SquaredErrorsByRun> errors;
  std::vector<bool> resolvable;
};

ForwardRound fitOnTop(const AugmentedFit& current, const std::vector<EffectKind>& remaining,
                      const DiagnosisOptions& options, const DiagnosisResult& data)
{
  ForwardRound round;
  round.models.resize(remaining.size());
  round.errors.resize(remaining.size());
  // The fits are independent: run on options.threads, each stored by its index, so the round is
  // the same for any number of threads.
  runTasksInParallel(remaining.size(), effectiveThreadCount(options.threads, remaining.size()), [&](std::size_t i) {
    std::vector<EffectKind> kinds = effectsOf(current);
    kinds.push_back(remaining[i]);
    const AugmentedFit fit = calibrateAugmentedSet(kinds, data.train, options.calibration, &current);
    round.models[i] = scoreModel(fit, data, &round.errors[i]);
    round.models[i].resolvable = isResolvable(remaining[i], lastEffectValues(fit), data.sample_period_s);
  });
  for (const ModelDiagnosis& model : round.models)
  {
    round.resolvable.push_back(model.resolvable);
  }
  return round;
}

/// How precisely the training data pin the size of the effect a chain step adds, at the
/// determined effects' threshold over the candidates.
EffectSize addedEffectSize(const AugmentedFit& fit, EffectKind added, const DiagnosisOptions& options)
{
  return effectSizeIn(fit, added, determinedThreshold(options.selection.alpha, options.candidates));
}

/// The stability test's options, on the diagnosis's threads.
AugmentedStabilityTestOptions stabilityTestOptions(const DiagnosisOptions& options)
{
  AugmentedStabilityTestOptions test = options.stability_test;
  test.threads = options.threads;
  return test;
}

/// The model of one chosen step: its small-signal stability and, if asked, the held-out test.
ForwardSelectionStep makeStep(EffectKind added, ModelDiagnosis model, const ImprovementEstimate& improvement,
                              const DiagnosisOptions& options, const DiagnosisResult& data)
{
  ForwardSelectionStep step;
  step.added = added;
  step.model = std::move(model);
  step.model.improvement = improvement;
  step.model.significant = true;
  step.model.stability = analyzeAugmentedStability(step.model.fit.base, effectsOf(step.model.fit),
                                                   step.model.fit.settings, data.operating_speed_mps);
  step.model.stability_verdict_changes = step.model.stability.string_stable != data.baseline.stability.string_stable;
  step.added_size = addedEffectSize(step.model.fit, added, options);
  if (options.with_stability_test)
  {
    // The previous step's model is nested in this one: its side models are starts of this test's.
    const AugmentedStabilityTestResult* nested =
        data.selected_effects.empty() || !data.selected_effects.back().stability_test
            ? nullptr
            : &*data.selected_effects.back().stability_test;
    step.stability_test = testAugmentedStringStability(step.model.fit, data.train, data.test, data.operating_speed_mps,
                                                       options.calibration, stabilityTestOptions(options), nested);
  }
  return step;
}

std::size_t indexOf(const std::vector<EffectKind>& kinds, EffectKind kind)
{
  return static_cast<std::size_t>(std::find(kinds.begin(), kinds.end(), kind) - kinds.begin());
}

/// Adds effects to the dominant one while the rule finds one that improves on the current model.
void forwardSelect(const DiagnosisOptions& options, const std::vector<SquaredErrorsByRun>& candidate_errors,
                   DiagnosisResult* result)
{
  if (!options.forward_selection || options.max_chain_length == 0)
  {
    result->forward_stop_reason = "forward selection off";
    return;
  }
  if (result->selection.dominant == EffectKind::none)
  {
    result->forward_stop_reason = "no effect improves significantly on the base model";
    return;
  }
  // Step 1 is the dominant model exactly as selected against the base model (and tested above).
  const std::size_t first = indexOf(options.candidates, result->selection.dominant);
  result->selected_effects.push_back({result->selection.dominant, result->effects[first], result->stability_test,
                                      addedEffectSize(result->effects[first].fit, result->selection.dominant, options)});
  SquaredErrorsByRun current_errors = candidate_errors[first];
  std::vector<EffectKind> remaining = options.candidates;
  remaining.erase(remaining.begin() + static_cast<long>(first));
  while (result->selected_effects.size() < options.max_chain_length && !remaining.empty())
  {
    const AugmentedFit current = result->selected_effects.back().model.fit;
    ForwardRound round = fitOnTop(current, remaining, options, *result);
    result->forward_rounds.push_back(selectEffect(current_errors, round.errors, remaining, result->sample_period_s,
                                                  options.selection, round.resolvable));
    const SelectionResult& selection = result->forward_rounds.back();
    if (selection.dominant == EffectKind::none)
    {
      result->forward_stop_reason =
          "no remaining effect improves significantly on the " + combinedEffectName(effectsOf(current)) + " model";
      return;
    }
    const std::size_t k = indexOf(remaining, selection.dominant);
    result->selected_effects.push_back(
        makeStep(selection.dominant, std::move(round.models[k]), selection.versus_base[k], options, *result));
    current_errors = std::move(round.errors[k]);
    remaining.erase(remaining.begin() + static_cast<long>(k));
  }
  result->forward_stop_reason = remaining.empty() ? "every candidate is in the model"
                                                  : "the chain reached its maximum length (" +
                                                        std::to_string(options.max_chain_length) + ")";
}
}  // namespace

namespace
{
/// The standard errors of (k1, k2, tau_e, eta) of a fit; none when it has none (diverged).
std::optional<AccParameters> baseStandardErrors(const AugmentedFit& fit)
{
  const std::vector<double>& se = fit.standard_errors;
  if (se.size() < AugmentedParameterBox::kBaseDimension)
    return std::nullopt;
  return AccParameters{se[0], se[1], se[2], se[3]};
}

/// Model adequacy of the base and the final model on the training and the held-out parts (the
/// verdicts are judged on the held-out ones), with the diagnosis's own bounds on the base
/// parameters.
void assessAdequacy(const DiagnosisOptions& options, DiagnosisResult* result)
{
  ModelAdequacyOptions adequacy;
  adequacy.bounds = {options.calibration.lower, options.calibration.upper};
  std::vector<CarFollowingRun> parts = result->train;
  parts.insert(parts.end(), result->test.begin(), result->test.end());
  const AugmentedFit& base = result->baseline.fit;
  const AugmentedFit& final_fit = finalModel(*result).fit;
  result->baseline_adequacy = assessModelAdequacy(base.base, base.settings, parts, adequacy, baseStandardErrors(base));
  result->final_adequacy =
      assessModelAdequacy(final_fit.base, final_fit.settings, parts, adequacy, baseStandardErrors(final_fit));
}

/// The final model's refitting bootstrap when the training data are short (DiagnosisOptions).
void bootstrapShortTraining(const DiagnosisOptions& options, DiagnosisResult* result)
{
  if (options.bootstrap_replicates == 0 || !(totalDurationS(result->train) < options.bootstrap_below_s))
    return;
  RefitBootstrapOptions bootstrap = options.bootstrap;
  bootstrap.replicates = options.bootstrap_replicates;
  if (bootstrap.threads == 0)
    bootstrap.threads = options.threads;
  result->final_bootstrap = bootstrapDiagnosedModel(finalModel(*result).fit, result->train, options.calibration, bootstrap);
  if (!result->selected_effects.empty())  // the last step's size is taken in the final model
  {
    ForwardSelectionStep& last = result->selected_effects.back();
    judgeByBootstrap(last.added, *result->final_bootstrap, &last.added_size);
  }
}
}  // namespace

namespace
{
/// The diagnosis of runs already parted into result.train and result.test.
DiagnosisResult diagnoseParts(DiagnosisResult result, const DiagnosisOptions& options)
{
  std::vector<double> speeds;
  for (const CarFollowingRun& run : result.train)
  {
    speeds.insert(speeds.end(), run.follower_speed_mps.begin(), run.follower_speed_mps.end());
  }
  result.operating_speed_mps = median(speeds);
  result.sample_period_s = medianStepS(result.train);
  result.steady_training = describeInsufficientExcitation(result.train, IdentifiabilityCriteria{});

  SquaredErrorsByRun base_errors;
  const AugmentedFit base_fit = calibrateAugmented(EffectKind::none, result.train, options.calibration);
  result.baseline = scoreModel(base_fit, result, &base_errors);
  result.baseline.stability =
      analyzeAugmentedStability(base_fit.base, EffectKind::none, base_fit.settings, result.operating_speed_mps);

  const std::size_t count = options.candidates.size();
  std::vector<SquaredErrorsByRun> candidate_errors(count);
  result.effects.resize(count);
  // The effect fits are independent (each warm-started from the base fit): run on
  // options.threads, each stored by its index, so the result is the same for any number of threads.
  std::vector<AugmentedFit> first_fits(count);
  runTasksInParallel(count, effectiveThreadCount(options.threads, count), [&](std::size_t i) {
    first_fits[i] = calibrateAugmented(options.candidates[i], result.train, options.calibration, &base_fit);
  });
  runTasksInParallel(count, effectiveThreadCount(options.threads, count), [&](std::size_t i) {
    const EffectKind kind = options.candidates[i];
    const AugmentedFit fit = refitFromBestTimingFit(i, first_fits, result.train, options.calibration, base_fit);
    ModelDiagnosis& model = result.effects[i];
    model = scoreModel(fit, result, &candidate_errors[i]);
    model.stability = analyzeAugmentedStability(fit.base, kind, fit.settings, result.operating_speed_mps);
    model.stability_verdict_changes = model.stability.string_stable != result.baseline.stability.string_stable;
    model.resolvable = isResolvable(kind, fit.effect_values, result.sample_period_s);
  });
  std::vector<bool> resolvable;
  for (const ModelDiagnosis& model : result.effects)
  {
    resolvable.push_back(model.resolvable);
  }
  result.selection = selectEffect(base_errors, candidate_errors, options.candidates, result.sample_period_s,
                                  options.selection, resolvable);
  result.selection_rule = describeSelectionRule(options.selection, options.candidates.size());
  std::vector<HeldOutPredictions> effect_predictions;
  for (const ModelDiagnosis& model : result.effects)
    effect_predictions.emplace_back(model.fit.effect, &model.test_simulations);
  result.perturbation_windows = judgeOnPerturbationWindows(result.test, result.baseline.test_simulations,
                                                           effect_predictions, options.perturbation_windows);
  std::vector<AugmentedFit> effect_fits;
  for (const ModelDiagnosis& model : result.effects)
  {
    effect_fits.push_back(model.fit);
  }
  result.determined = determinedEffects(base_fit, effect_fits, result.sample_period_s, options.selection.alpha);
  result.unmeasured = unmeasuredEffects(base_fit, effect_fits, result.train, options.calibration,
                                        determinedThreshold(options.selection.alpha, options.candidates));
  for (std::size_t k = 0; k < result.effects.size(); ++k)
  {
    result.effects[k].improvement = result.selection.versus_base[k];
    result.effects[k].significant = result.selection.significant[k];
  }
  result.where = breakDownResiduals(result.test, result.baseline.test_simulations,
                                    dominantModel(result).test_simulations, options.breakdown);
  if (options.with_stability_test)
  {
    result.stability_test = testAugmentedStringStability(dominantModel(result).fit, result.train, result.test,
                                                         result.operating_speed_mps, options.calibration,
                                                         stabilityTestOptions(options));
  }
  forwardSelect(options, candidate_errors, &result);
  assessAdequacy(options, &result);
  bootstrapShortTraining(options, &result);
  return result;
}

/// Refuses fitting parts that together hold less than calibrate fits on (its samples and seconds):
/// a model fitted on seconds of driving is no base for naming an effect or a verdict.
void requireEnoughToFit(const std::vector<CarFollowingRun>& train, const std::string& remedy)
{
  IdentifiabilityCriteria amount;
  amount.min_speed_std_mps = 0.0;  // the amount only: a steady drive's fits say what they leave open
  const std::string shortage = describeInsufficientExcitation(train, amount);
  if (!shortage.empty())
    throw std::invalid_argument("the parts to fit on hold " + shortage + ": " + remedy);
}
}  // namespace

DiagnosisResult diagnoseRuns(const std::vector<CarFollowingRun>& runs, const DiagnosisOptions& options)
{
  DiagnosisResult result;
  splitRuns(inNaturalNameOrder(runs), options, &result);
  if (result.train.empty())
  {
    throw std::invalid_argument("no run is long enough to fit on one part and score on the other");
  }
  requireEnoughToFit(result.train, "longer runs, or a larger share to fit on (--train-fraction)");
  return diagnoseParts(std::move(result), options);
}

DiagnosisResult diagnoseHeldOutRuns(const std::vector<CarFollowingRun>& fitted,
                                    const std::vector<CarFollowingRun>& held_out, const DiagnosisOptions& options)
{
  DiagnosisResult result;
  result.held_out_whole_runs = true;
  addWholeRuns(inNaturalNameOrder(fitted), options, "[train]", &result.train, &result.notes);
  addWholeRuns(inNaturalNameOrder(held_out), options, "[held out]", &result.test, &result.notes);
  if (result.train.empty() || result.test.empty())
    throw std::invalid_argument(std::string("no usable ") + (result.train.empty() ? "run to fit" : "held-out run") +
                                " (each needs " + std::to_string(options.min_samples_per_half) + " samples)");
  requireEnoughToFit(result.train, "more or longer runs to fit");
  return diagnoseParts(std::move(result), options);
}

const ModelDiagnosis& dominantModel(const DiagnosisResult& result)
{
  for (const ModelDiagnosis& model : result.effects)
  {
    if (result.selection.dominant != EffectKind::none && model.fit.effect == result.selection.dominant)
    {
      return model;
    }
  }
  return result.baseline;
}

const ModelDiagnosis& finalModel(const DiagnosisResult& result)
{
  return result.selected_effects.empty() ? result.baseline : result.selected_effects.back().model;
}

const AugmentedStabilityTestResult* finalModelStabilityTest(const DiagnosisResult& result)
{
  if (!result.selected_effects.empty())
  {
    const auto& test = result.selected_effects.back().stability_test;
    return test ? &*test : nullptr;
  }
  return result.selection.dominant == EffectKind::none && result.stability_test ? &*result.stability_test : nullptr;
}

DiagnosisVerdict statedVerdict(const DiagnosisResult& result)
{
  DiagnosisVerdict out;
  out.test = finalModelStabilityTest(result);
  out.model_adequate = result.final_adequacy.adequate;
  char text[400];
  if (!result.selected_effects.empty())
  {
    std::string chain;
    for (EffectKind kind : selectedChain(result))
      chain += (chain.empty() ? "" : " + ") + effectName(kind);
    out.model = "final model (" + chain + ")";
    std::snprintf(text, sizeof text,
                  "the final model predicts the held-out parts better than the base model (speed RMSE %.3f against "
                  "%.3f m/s, gap RMSE %.2f against %.2f m)",
                  finalModel(result).test_rmse_speed_mps, result.baseline.test_rmse_speed_mps,
                  finalModel(result).test_rmse_gap_m, result.baseline.test_rmse_gap_m);
    out.why = text;
  }
  else
  {
    out.model = "base model";
    out.why = "no effect improves the base model significantly";
  }
  if (result.final_adequacy.assessed && !result.final_adequacy.adequate)
    out.why += "; but this model still misses the data (" + describeAdequacy(result.final_adequacy) +
               "): its verdict compares two versions of a model that misses";
  if (out.test == nullptr)
    out.why += "; this model's string stability was not tested";
  return out;
}

std::vector<EffectKind> selectedChain(const DiagnosisResult& result)
{
  std::vector<EffectKind> chain;
  for (const ForwardSelectionStep& step : result.selected_effects)
  {
    chain.push_back(step.added);
  }
  return chain;
}

}  // namespace acc
