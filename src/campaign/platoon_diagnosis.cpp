#include "acc_identification/campaign/platoon_diagnosis.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/evidence/clustered_median.h"
#include "acc_identification/evidence/clustered_ratio.h"
#include "acc_identification/evidence/perturbation_windows.h"
#include "acc_identification/evidence/wild_cluster_interval.h"
#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Starts of every candidate fit: the warm start's effect values at this many low-discrepancy
/// points (plus "almost off"), and for timing effects this many cold starts (Halton points of the
/// base box) beside. Fewer than the diagnosis's own (6 and 12): a campaign fits every candidate for
/// every car of every run.
constexpr std::size_t kEffectStarts = 3;
constexpr std::size_t kColdStarts = 4;
/// The scores' intervals over perturbations (DipPredictionSummary): replicates and a fixed seed,
/// so that a report says the same interval every time.
constexpr std::size_t kScoreIntervalReplicates = 1999;
constexpr std::uint64_t kScoreIntervalSeed = 20210422;

/// The model a fit makes, with its source.
PlatoonCarModel modelOf(const AugmentedFit& fit, const std::string& source)
{
  PlatoonCarModel model;
  // A model whose own loop is unstable cannot be a car's: its chain would oscillate without bound.
  model.available = fit.usable();
  model.parameters = fit.base;
  model.effects = fit.effects;
  model.effect_values = fit.effect_values;
  model.settings = fit.settings;
  model.standard_errors = fit.standard_errors;
  model.source = source + (fit.diverged            ? ": no fit (diverged)"
                           : !fit.locally_stable ? ": no fit (no start reached a locally stable model)"
                                                  : "");
  return model;
}

/// The criterion's loss of model m for one score; NaN where the model was not scored.
double lossOf(const PairPerturbationScore& s, std::size_t m, SelectionCriterion criterion)
{
  if (criterion == SelectionCriterion::pair_windows)
    return m < s.window_mse.size() ? s.window_mse[m] : kNaN;
  if (m >= s.chain_dip_mps.size() || !(s.measured_dip_mps > kScoredMinDipMps) || !std::isfinite(s.chain_dip_mps[m]))
    return kNaN;
  const double predicted_mps = std::max(s.chain_dip_mps[m], kLossMinPredictedDipShare * s.measured_dip_mps);
  const double log_ratio = std::log(predicted_mps / s.measured_dip_mps);
  return log_ratio * log_ratio;
}

/// A perturbation of a run: (file index, perturbation index).
using PerturbationKey = std::pair<std::size_t, std::size_t>;

/// The clusters of two models' losses (a against, b candidate): one per perturbation, its cars'
/// losses summed, since they share its input.
std::map<PerturbationKey, LossCluster> clustersOf(const std::vector<PairPerturbationScore>& scores,
                                                  std::size_t exclude_file, std::size_t a, std::size_t b,
                                                  SelectionCriterion criterion)
{
  std::map<PerturbationKey, LossCluster> by_perturbation;
  for (const PairPerturbationScore& s : scores)
  {
    const double loss_a = lossOf(s, a, criterion), loss_b = lossOf(s, b, criterion);
    if (s.file_index == exclude_file || !std::isfinite(loss_a) || !std::isfinite(loss_b))
      continue;
    LossCluster& c = by_perturbation[{s.file_index, s.perturbation}];
    c.against += loss_a;
    c.candidate += loss_b;
    ++c.n;
  }
  return by_perturbation;
}

std::vector<LossCluster> valuesOf(const std::map<PerturbationKey, LossCluster>& clusters)
{
  std::vector<LossCluster> out;
  for (const auto& entry : clusters)
    out.push_back(entry.second);
  return out;
}

/// Whether a candidate's gain on the platoon dips is larger than what a measured dip can tell
/// (EffectSetSelectionOptions::min_rms_dip_error_reduction); the pair-window criterion has no
/// such floor (its loss is a speed MSE with units).
bool closesAGap(const PairedLossComparison& losses, const EffectSetSelectionOptions& options)
{
  if (options.criterion != SelectionCriterion::platoon_dips)
    return true;
  return std::sqrt(losses.against_loss) - std::sqrt(losses.candidate_loss) >= options.min_rms_dip_error_reduction;
}

/// Whether the rule names a comparison at p: p at most alpha, the mean loss at least
/// min_relative_improvement lower, and (on the platoon dips) a gain above what a dip can tell.
bool namedAt(const PairedLossComparison& losses, double p, const EffectSetSelectionOptions& options)
{
  return namedByRule(losses, p, options.alpha, options.min_relative_improvement) && closesAGap(losses, options);
}

/// Model `candidate` against model `against`: mean losses and the relative improvement, and with
/// `replicates` > 0 the comparison's own wild cluster bootstrap-t p of "no improvement"
/// (comparePairedLosses), which is then the rule's; the pair-window criterion's means beside. A
/// stage member's p comes from its family instead (runStage). `losses` receives the comparison.
EffectSetComparison compare(const std::vector<PairPerturbationScore>& scores, std::size_t exclude_file,
                            std::size_t candidate, std::size_t against, const EffectSetSelectionOptions& options,
                            std::size_t replicates, PairedLossComparison* losses_out = nullptr)
{
  EffectSetComparison out;
  const std::vector<LossCluster> clusters = valuesOf(clustersOf(scores, exclude_file, against, candidate, options.criterion));
  const PairedLossComparison losses =
      replicates > 0 ? comparePairedLosses(clusters, replicates, options.seed) : pairedLossMeans(clusters);
  out.car_perturbations = losses.entries;
  out.perturbations = losses.clusters;
  out.against_loss = losses.against_loss;
  out.mean_loss = losses.candidate_loss;
  out.relative_improvement = losses.relative_improvement;
  out.p_value_alone = losses.p_value;
  out.p_value = losses.p_value;
  out.significant = namedAt(losses, losses.p_value, options);
  const PairedLossComparison windows =
      pairedLossMeans(valuesOf(clustersOf(scores, exclude_file, against, candidate, SelectionCriterion::pair_windows)));
  out.against_window_mse = windows.against_loss;
  out.mean_window_mse = windows.candidate_loss;
  if (losses_out != nullptr)
    *losses_out = losses;
  return out;
}

/// The stage's candidates against `against` as one family: each one's clusters numbered by the
/// perturbations any of them scored, so that one replicate weighs a perturbation alike in all.
std::vector<ClusteredDifferences> stageFamily(const std::vector<PairPerturbationScore>& scores,
                                              std::size_t exclude_file, const std::vector<std::size_t>& candidates,
                                              std::size_t against, SelectionCriterion criterion,
                                              std::size_t* family_clusters)
{
  std::vector<std::map<PerturbationKey, LossCluster>> members;
  std::map<PerturbationKey, std::size_t> numbers;
  for (std::size_t candidate : candidates)
  {
    members.push_back(clustersOf(scores, exclude_file, against, candidate, criterion));
    for (const auto& entry : members.back())
      numbers.emplace(entry.first, 0);
  }
  std::size_t next = 0;
  for (auto& entry : numbers)
    entry.second = next++;
  std::vector<ClusteredDifferences> family;
  for (const auto& member : members)
  {
    std::vector<std::size_t> member_numbers;
    for (const auto& entry : member)
      member_numbers.push_back(numbers.at(entry.first));
    family.push_back(differencesOf(valuesOf(member), member_numbers));
  }
  *family_clusters = numbers.size();
  return family;
}

/// Whether `candidate` adds exactly one feature (an effect or an objective) to `base`.
bool extendsByOne(const PlatoonCandidate& candidate, const PlatoonCandidate& base)
{
  return candidate.features().size() == base.features().size() + 1 && candidate.holdsAllOf(base);
}

const PlatoonCandidate& candidateAt(std::size_t index)
{
  static const PlatoonCandidate base{};
  return index == 0 ? base : platoonCandidates()[index - 1];
}

/// The inverse of candidateAt: 0 for the base model, i + 1 for platoonCandidates()[i]; nothing
/// for what is not a candidate.
std::optional<std::size_t> candidateIndex(const PlatoonCandidate& candidate)
{
  if (candidate == PlatoonCandidate{})
    return 0;
  const std::vector<PlatoonCandidate>& candidates = platoonCandidates();
  const auto found = std::find(candidates.begin(), candidates.end(), candidate);
  if (found == candidates.end())
    return std::nullopt;
  return static_cast<std::size_t>(found - candidates.begin()) + 1;
}

/// The stage's choice against each other candidate named at the stage (by the stage's
/// comparisons, the last `stage_size` of selection->comparisons), one test each at alpha.
void compareRivals(const std::vector<PairPerturbationScore>& scores, std::size_t exclude_file,
                   const std::vector<std::size_t>& candidates, std::size_t chosen,
                   const EffectSetSelectionOptions& options, EffectSetSelection* selection)
{
  const std::size_t first = selection->comparisons.size() - candidates.size();
  for (std::size_t i = 0; i < candidates.size(); ++i)
  {
    if (candidates[i] == chosen || !selection->comparisons[first + i].significant)
      continue;
    EffectSetComparison rival = compare(scores, exclude_file, chosen, candidates[i], options, options.replicates);
    rival.candidate = candidateAt(chosen);
    rival.against = candidateAt(candidates[i]);
    selection->rivals.push_back(std::move(rival));
  }
}

/// One stage: each candidate index against `against`; returns the significant one with the lowest
/// mean loss (or `against` when none is), compared with its rivals.
std::size_t runStage(const std::vector<PairPerturbationScore>& scores, std::size_t exclude_file,
                     const std::vector<std::size_t>& candidates, std::size_t against,
                     const EffectSetSelectionOptions& options, EffectSetSelection* selection)
{
  std::size_t family_clusters = 0;
  const std::vector<ClusteredDifferences> family =
      stageFamily(scores, exclude_file, candidates, against, options.criterion, &family_clusters);
  const std::vector<WildClusterTest> tests =
      wildClusterMaxT(family, family_clusters, options.replicates, options.seed);
  std::size_t best = against;
  double best_loss = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < candidates.size(); ++i)
  {
    PairedLossComparison losses;
    EffectSetComparison c = compare(scores, exclude_file, candidates[i], against, options, 0, &losses);
    c.candidate = candidateAt(candidates[i]);
    c.against = candidateAt(against);
    c.p_value_alone = tests[i].p_value;
    c.p_value = tests[i].family_p_value;
    c.significant = namedAt(losses, c.p_value, options);
    if (c.significant && c.mean_loss < best_loss)
    {
      best = candidates[i];
      best_loss = c.mean_loss;
    }
    selection->comparisons.push_back(std::move(c));
  }
  if (best != against)
    compareRivals(scores, exclude_file, candidates, best, options, selection);
  return best;
}

/// The indices of the candidates that add one thing to candidate `of`.
std::vector<std::size_t> extensionsOf(std::size_t of)
{
  std::vector<std::size_t> out;
  for (std::size_t i = 1; i <= platoonCandidates().size(); ++i)
  {
    if (extendsByOne(candidateAt(i), candidateAt(of)))
      out.push_back(i);
  }
  return out;
}

bool hasTimingEffect(const PlatoonCandidate& candidate)
{
  for (EffectKind kind : candidate.effects)
  {
    if (kind == EffectKind::reaction_delay || kind == EffectKind::actuation_lag)
      return true;
  }
  return false;
}

bool parseObjective(const std::string& text, FitObjective* objective)
{
  for (FitObjective option :
       {FitObjective::speed, FitObjective::gap, FitObjective::speed_and_gap, FitObjective::speed_and_windows})
  {
    if (objectiveName(option) == text)
    {
      *objective = option;
      return true;
    }
  }
  return false;
}
}  // namespace

std::vector<const EffectSetComparison*> EffectSetSelection::unseparatedRivals() const
{
  std::vector<const EffectSetComparison*> out;
  for (const EffectSetComparison& rival : rivals)
  {
    if (!rival.significant)
      out.push_back(&rival);
  }
  return out;
}

bool PlatoonCandidate::holdsAllOf(const PlatoonCandidate& other) const
{
  const std::vector<std::string> own = features();
  for (const std::string& feature : other.features())
  {
    if (std::find(own.begin(), own.end(), feature) == own.end())
      return false;
  }
  return true;
}

std::vector<std::string> PlatoonCandidate::features() const
{
  std::vector<std::string> out = effectNames(effects);
  if (objective != FitObjective::speed)
    out.push_back(objectiveName(objective) + " objective");
  return out;
}

std::string PlatoonCandidate::name() const
{
  const std::string effects_name = combinedEffectName(effects);
  return objective == FitObjective::speed ? effects_name
                                                  : effects_name + " (" + objectiveName(objective) + " objective)";
}

const std::vector<PlatoonCandidate>& platoonCandidates()
{
  using E = EffectKind;
  using O = FitObjective;
  static const std::vector<PlatoonCandidate> candidates = {
      {{E::asymmetric_response}, O::speed},
      {{E::leader_braking_anticipation}, O::speed},
      {{E::reaction_delay}, O::speed},
      {{E::actuation_lag}, O::speed},
      {{E::quadratic_closing_response}, O::speed},
      {{}, O::gap},
      {{}, O::speed_and_gap},
      {{E::asymmetric_response, E::reaction_delay}, O::speed},
      {{E::asymmetric_response, E::actuation_lag}, O::speed},
      {{E::leader_braking_anticipation, E::reaction_delay}, O::speed},
      {{E::quadratic_closing_response, E::reaction_delay}, O::speed},
      {{E::reaction_delay}, O::speed_and_gap},
      {{E::actuation_lag}, O::speed_and_gap},
      // The two hard-braking responses together, on top of the delay.
      {{E::leader_braking_anticipation, E::quadratic_closing_response, E::reaction_delay}, O::speed},
      // The fit weighted to the brakings, at each stage of the effects a stage may choose.
      {{}, O::speed_and_windows},
      {{E::reaction_delay}, O::speed_and_windows},
      {{E::leader_braking_anticipation, E::reaction_delay}, O::speed_and_windows},
      {{E::quadratic_closing_response, E::reaction_delay}, O::speed_and_windows},
  };
  return candidates;
}

bool parsePlatoonCandidate(const std::string& text, PlatoonCandidate* candidate)
{
  PlatoonCandidate parsed;
  const std::size_t at = text.find('@');
  if (at != std::string::npos && !parseObjective(text.substr(at + 1), &parsed.objective))
    return false;
  const std::string effects = text.substr(0, at);
  std::size_t start = 0;
  while (true)
  {
    const std::size_t comma = effects.find(',', start);
    EffectKind kind = EffectKind::none;
    if (!parseEffectName(effects.substr(start, comma == std::string::npos ? std::string::npos : comma - start), &kind))
      return false;
    if (kind != EffectKind::none)
      parsed.effects.push_back(kind);
    if (comma == std::string::npos)
      break;
    start = comma + 1;
  }
  *candidate = parsed;
  return true;
}

std::string platoonCandidateText(const PlatoonCandidate& candidate)
{
  std::string text;
  for (const std::string& effect : effectNames(candidate.effects))
    text += (text.empty() ? "" : ",") + effect;
  if (candidate.objective != FitObjective::speed)
    text = (text.empty() ? "none" : text) + "@" + objectiveName(candidate.objective);
  return text.empty() ? "none" : text;
}

bool isPlatoonCandidate(const PlatoonCandidate& candidate) { return candidateIndex(candidate).has_value(); }

namespace
{
/// Which candidates to fit: the wanted ones (all when absent) and, recursively, every candidate
/// one of them extends by one (fitCandidateModels warm-starts it from the last of those).
std::vector<bool> candidatesToFit(const std::optional<std::vector<std::size_t>>& wanted)
{
  const auto& candidates = platoonCandidates();
  std::vector<bool> fit(candidates.size(), !wanted.has_value());
  for (std::size_t i : wanted.value_or(std::vector<std::size_t>{}))
    fit.at(i) = true;
  for (std::size_t i = candidates.size(); i-- > 0;)
  {
    for (std::size_t j = 0; fit[i] && j < i; ++j)
      fit[j] = fit[j] || extendsByOne(candidates[i], candidates[j]);
  }
  return fit;
}
}  // namespace

AugmentedCalibrationOptions candidateCalibrationOptions(const PlatoonCandidate& candidate)
{
  AugmentedCalibrationOptions options;
  options.objective = candidate.objective;
  options.effect_starts = kEffectStarts;
  return options;
}

AugmentedFit fitCandidate(const PlatoonCandidate& candidate, const std::vector<CarFollowingRun>& training,
                          const AugmentedFit& warm)
{
  return fitCandidate(candidate, training, std::vector<AugmentedFit>{warm});
}

AugmentedFit fitCandidate(const PlatoonCandidate& candidate, const std::vector<CarFollowingRun>& training,
                          const std::vector<AugmentedFit>& warm_starts)
{
  const AugmentedCalibrationOptions options = candidateCalibrationOptions(candidate);
  AugmentedFit fit = calibrateAugmentedSet(candidate.effects, training, options, &warm_starts.at(0));
  for (std::size_t i = 1; i < warm_starts.size(); ++i)
  {
    const AugmentedFit other = calibrateAugmentedSet(candidate.effects, training, options, &warm_starts[i]);
    if (betterFit(other, fit))
      fit = other;
  }
  // Timing effects trade off with tau_e and k2 and have two valleys: from the base model's
  // parameters a 1 s delay was fitted as 0.35 s on synthetic platoons, from cold starts at its
  // size. For them the better of both on the training data is kept.
  if (hasTimingEffect(candidate))
  {
    AugmentedCalibrationOptions cold_options = options;
    cold_options.base_starts = kColdStarts;
    const AugmentedFit cold = calibrateAugmentedSet(candidate.effects, training, cold_options, nullptr);
    if (betterFit(cold, fit))
      fit = cold;
  }
  return fit;
}

std::vector<PlatoonCarModel> fitCandidateModels(const std::vector<CarFollowingRun>& training,
                                                const PlatoonCarModel& base,
                                                const std::optional<std::vector<std::size_t>>& wanted)
{
  const auto& candidates = platoonCandidates();
  std::vector<PlatoonCarModel> models(candidates.size(), PlatoonCarModel{false, {}, base.source + ": no base model"});
  if (!base.available || training.empty())
    return models;
  AugmentedFit warm;  // the base model: the warm start of every candidate that extends it
  warm.base = base.parameters;
  std::vector<AugmentedFit> fits(candidates.size());
  const std::vector<bool> fit_it = candidatesToFit(wanted);
  for (std::size_t i = 0; i < candidates.size(); ++i)
  {
    if (!fit_it[i])
    {
      models[i] = PlatoonCarModel{false, {}, "not fitted: not needed"};
      continue;
    }
    // A candidate that adds one thing to an earlier one starts from that one's fit, so that it
    // refines a model that already holds the rest.
    const AugmentedFit* start = &warm;
    for (std::size_t j = 0; j < i; ++j)
    {
      if (extendsByOne(candidates[i], candidates[j]) && fits[j].usable())
        start = &fits[j];
    }
    fits[i] = fitCandidate(candidates[i], training, *start);
    models[i] = modelOf(fits[i], base.source);
    models[i].fitted_on_this_run_s = base.fitted_on_this_run_s;  // the same training data
  }
  return models;
}

std::vector<PairPerturbationScore> scorePairPerturbations(const CampaignFile& file, std::size_t file_index,
                                                          int position, const std::vector<PlatoonCarModel>& models,
                                                          const PlatoonCheckOptions& options,
                                                          std::optional<std::size_t> only_perturbation)
{
  const OpenAccFile& data = file.contents;
  std::size_t first_row = 0, end_row = 0;
  const std::vector<Perturbation> perturbations = leadPerturbations(data, options, &first_row, &end_row);
  const OpenAccVehicle* car = data.vehicle(position);
  if (perturbations.empty() || car == nullptr || !car->has_speed)
    return {};
  std::vector<PlatoonCarPrediction> predictions;
  for (const PlatoonCarModel& model : models)
    predictions.push_back(predictPair(data, position, model, first_row, end_row));
  const std::vector<double> time_s = sliceRows(data.time_s, first_row, end_row);
  const std::vector<double> measured = sliceRows(car->speed_mps, first_row, end_row);
  std::vector<PairPerturbationScore> scores;
  for (std::size_t p = 0; p < perturbations.size(); ++p)
  {
    if (only_perturbation && p != *only_perturbation)
      continue;
    const Perturbation& perturbation = perturbations[p];
    PairPerturbationScore score;
    score.file_index = file_index;
    score.position = position;
    score.perturbation = p;
    score.measured_dip_mps = dipDepthMps(time_s, measured, perturbation, options.perturbation);
    for (const PlatoonCarPrediction& prediction : predictions)
    {
      const std::vector<double> predicted = prediction.predicted
                                                ? sliceRows(prediction.predicted_speed_mps, first_row, end_row)
                                                : std::vector<double>(time_s.size(), kNaN);
      score.window_mse.push_back(perturbationWindowMse(time_s, predicted, measured, perturbation, options.perturbation));
      score.predicted_dip_mps.push_back(dipDepthMps(time_s, predicted, perturbation, options.perturbation));
    }
    // As the platoon check: a car driven by hand before the window's end is not scored.
    if (std::isfinite(score.measured_dip_mps) &&
        onAccThroughout(data, position, first_row, first_row + perturbation.window_end))
      scores.push_back(std::move(score));
  }
  return scores;
}

void addChainDips(const PlatoonCheck& check, std::size_t file_index, std::size_t model_index, std::size_t models,
                  std::vector<PairPerturbationScore>* scores)
{
  for (PairPerturbationScore& score : *scores)
  {
    if (score.file_index != file_index || score.perturbation >= check.perturbations.size())
      continue;
    for (const DipComparison& row : check.perturbations[score.perturbation].positions)
    {
      if (row.position != score.position)
        continue;
      score.chain_dip_mps.resize(models, kNaN);
      score.chain_dip_mps[model_index] = model_index == 0 ? row.chain.dip_mps : row.chain_diagnosed.dip_mps;
    }
  }
}

std::string criterionName(SelectionCriterion criterion)
{
  return criterion == SelectionCriterion::platoon_dips ? "platoon_dips" : "pair_windows";
}

namespace
{
/// The stages from candidate `start` on: each tries what adds one thing to the last choice, until
/// nothing is named or no candidate extends it. Returns the last choice; the comparisons go to
/// `record`.
std::size_t forwardSelect(const std::vector<PairPerturbationScore>& scores, std::size_t exclude_file,
                          std::size_t start, const EffectSetSelectionOptions& options, EffectSetSelection* record)
{
  std::size_t chosen = start;
  for (std::vector<std::size_t> extensions = extensionsOf(start); !extensions.empty();
       extensions = extensionsOf(chosen))
  {
    const std::size_t next = runStage(scores, exclude_file, extensions, chosen, options, record);
    if (next == chosen)
      break;
    chosen = next;
  }
  return chosen;
}

/// The final models reached from each unseparated rival that the data do not separate from the
/// choice, into selection->alternatives.
void addAlternatives(const std::vector<PairPerturbationScore>& scores, std::size_t exclude_file, std::size_t chosen,
                     const EffectSetSelectionOptions& options, EffectSetSelection* selection)
{
  for (const EffectSetComparison* rival : selection->unseparatedRivals())
  {
    EffectSetSelection branch;
    const std::size_t reached = forwardSelect(scores, exclude_file, *candidateIndex(rival->against), options, &branch);
    const auto& known = selection->alternatives;
    if (reached == chosen || std::any_of(known.begin(), known.end(), [&](const EffectSetComparison& a) {
          return a.against == candidateAt(reached);
        }))
      continue;
    EffectSetComparison versus = compare(scores, exclude_file, chosen, reached, options, options.replicates);
    if (versus.significant)
      continue;
    versus.candidate = candidateAt(chosen);
    versus.against = candidateAt(reached);
    selection->alternatives.push_back(std::move(versus));
  }
}
}  // namespace

EffectSetSelection selectEffectSet(const std::vector<PairPerturbationScore>& scores, std::size_t exclude_file,
                                   const std::string& excluded_run, const EffectSetSelectionOptions& options)
{
  EffectSetSelection selection;
  selection.excluded_run = excluded_run;
  std::size_t chosen = forwardSelect(scores, exclude_file, 0, options, &selection);
  addAlternatives(scores, exclude_file, chosen, options, &selection);
  if (options.force)
  {
    const std::optional<std::size_t> forced = candidateIndex(options.forced);
    if (!forced)
      throw std::invalid_argument(options.forced.name() + " is not among the platoon diagnosis's candidates");
    chosen = *forced;
    selection.alternatives.clear();  // they are the rule's choice's, not the forced model's
  }
  selection.chosen = chosen;
  selection.model = candidateAt(chosen);
  return selection;
}

void addAlternativeDips(const std::vector<PairPerturbationScore>& scores, std::size_t file_index,
                        const EffectSetSelection& selection, PlatoonCheck* check)
{
  std::vector<std::size_t> indices;  // into each score's models
  for (const EffectSetComparison& alternative : selection.alternatives)
  {
    check->alternative_models.push_back(alternative.against.name());
    indices.push_back(*candidateIndex(alternative.against));
  }
  for (std::size_t p = 0; p < check->perturbations.size(); ++p)
    for (DipComparison& row : check->perturbations[p].positions)
    {
      // The first car is the chain's input, whatever the model: its dip as the diagnosed chain's.
      row.chain_alternatives_dip_mps.assign(indices.size(),
                                            row.position == 1 ? row.chain_diagnosed.dip_mps : kNaN);
      for (const PairPerturbationScore& s : scores)
      {
        if (s.file_index != file_index || s.perturbation != p || s.position != row.position)
          continue;
        for (std::size_t a = 0; a < indices.size(); ++a)
          if (indices[a] < s.chain_dip_mps.size())
            row.chain_alternatives_dip_mps[a] = s.chain_dip_mps[indices[a]];
      }
    }
}

std::string effectSetSelectionRule(const EffectSetSelectionOptions& options)
{
  const std::string loss =
      options.criterion == SelectionCriterion::platoon_dips
          ? "per car and perturbation of the platoon predicted from its real first car, the squared log ratio of "
            "predicted to measured dip (measured dips above 0.3 m/s; a predicted dip below a tenth of the measured, "
            "or none, scored as a tenth)"
          : "per car and perturbation, the car predicted from its real leader, the mean squared speed error from the "
            "pre-window before the onset to the end of the dip window";
  const std::string floor =
      options.criterion == SelectionCriterion::platoon_dips
          ? ", its root at least " + printfText("%.3g", options.min_rms_dip_error_reduction) +
                " lower (a smaller change in the RMS relative dip error is within what a measured dip can tell),"
          : "";
  char text[1600];
  std::snprintf(text, sizeof text,
                "every car's models fitted on its other runs (leave-one-run-out); the loss: %s. Stage 1: each "
                "candidate adding one effect or objective to the base model against it; each further stage: each "
                "candidate adding one more to the last stage's choice against that, until none is named. A "
                "candidate is named when its mean loss is at "
                "least %.0f %% lower%s and the wild cluster bootstrap-t over perturbations (Webb "
                "weights, every pattern visited with up to seven perturbations, else %zu drawn; every car of a "
                "perturbation weighed together, the null imposed) gives a p <= %.3g within "
                "the stage's candidates (the joint max-t: the family-wise level); the lowest loss among those named "
                "wins. A run's own diagnosed models use the choice made without that run.",
                loss.c_str(), 100.0 * options.min_relative_improvement, floor.c_str(), options.replicates,
                options.alpha);
  return text;
}

}  // namespace acc

namespace acc
{
namespace
{
/// What a row holds for the measurement and each prediction.
enum class Quantity
{
  dip,
  distance_lost,
  width
};

double quantityOf(const DipMeasures& dip, Quantity quantity)
{
  switch (quantity)
  {
    case Quantity::dip: return dip.dip_mps;
    case Quantity::distance_lost: return dip.distance_lost_m;
    case Quantity::width: return dip.shape.width_s;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double measuredOf(const DipComparison& row, Quantity quantity) { return quantityOf(row.measured, quantity); }

/// The predicted quantity of rows[i] (rows[0] the first car, the input).
double predictedOf(const std::vector<DipComparison>& rows, std::size_t i, DipPrediction which, Quantity quantity)
{
  const DipComparison& row = rows[i];
  switch (which)
  {
    case DipPrediction::unchanged_dip:  // as the real car driving the base chain (rows are by position)
      return std::isfinite(row.chain.dip_mps) && row.chain_driven_by >= 1
                 ? measuredOf(rows[static_cast<std::size_t>(row.chain_driven_by - 1)], quantity)
                 : std::numeric_limits<double>::quiet_NaN();
    case DipPrediction::link_ratio_chain:
      return quantity == Quantity::dip ? row.link_ratio_chain_dip_mps : std::numeric_limits<double>::quiet_NaN();
    case DipPrediction::chain_base: return quantityOf(row.chain, quantity);
    case DipPrediction::chain_diagnosed: return quantityOf(row.chain_diagnosed, quantity);
    case DipPrediction::pair_base: return quantityOf(row.pair, quantity);
    case DipPrediction::pair_diagnosed: return quantityOf(row.pair_diagnosed, quantity);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// (predicted - measured) / measured of rows[i]'s quantity, appended where both are known.
void addRelativeError(const std::vector<DipComparison>& rows, std::size_t i, DipPrediction which, Quantity quantity,
                      std::vector<double>* errors)
{
  const double measured = measuredOf(rows[i], quantity), predicted = predictedOf(rows, i, which, quantity);
  if (measured > 0.0 && std::isfinite(predicted))
    errors->push_back((predicted - measured) / measured);
}

}  // namespace

DipPredictionSummary summarizeDipPredictions(const std::vector<PlatoonCheck>& platoons, DipPrediction which,
                                             double min_dip_mps, double min_link_change_mps,
                                             const DipRowFilter& include, ScoreIntervals intervals)
{
  std::vector<double> errors, lost_errors, width_errors;
  std::size_t right = 0;
  DipPredictionSummary out;
  // Per perturbation: its cars' |dip errors| and its links (right, scored), for the intervals.
  std::vector<std::vector<double>> abs_errors_by_perturbation;
  std::vector<RatioCluster> links_by_perturbation;
  for (const PlatoonCheck& check : platoons)
  {
    for (const PerturbationCheck& perturbation : check.perturbations)
    {
      const std::size_t errors_before = errors.size(), links_before = out.links, right_before = right;
      const auto& rows = perturbation.positions;
      for (std::size_t i = 1; i < rows.size(); ++i)
      {
        // The first car is the input: its "prediction" is the measurement, whatever the model.
        const double ahead_predicted =
            i == 1 ? rows[0].measured.dip_mps : predictedOf(rows, i - 1, which, Quantity::dip);
        const double measured = rows[i].measured.dip_mps, predicted = predictedOf(rows, i, which, Quantity::dip);
        if (!(measured > min_dip_mps) || !std::isfinite(predicted) || (include && !include(check, rows[i])))
          continue;
        errors.push_back((predicted - measured) / measured);
        addRelativeError(rows, i, which, Quantity::distance_lost, &lost_errors);
        addRelativeError(rows, i, which, Quantity::width, &width_errors);
        const double ahead_measured = rows[i - 1].measured.dip_mps;
        if (std::isfinite(ahead_measured) && std::isfinite(ahead_predicted) &&
            std::abs(measured - ahead_measured) > min_link_change_mps)
        {
          ++out.links;
          right += (measured > ahead_measured) == (predicted > ahead_predicted) ? 1 : 0;
        }
      }
      // Like the links, a perturbation without a scored car is no cluster of this score.
      if (errors.size() > errors_before)
        abs_errors_by_perturbation.emplace_back();
      for (std::size_t e = errors_before; e < errors.size(); ++e)
        abs_errors_by_perturbation.back().push_back(std::abs(errors[e]));
      if (out.links > links_before)
        links_by_perturbation.push_back({static_cast<double>(right - right_before),
                                         static_cast<double>(out.links - links_before), out.links - links_before});
    }
  }
  out.median_abs_dip_error_lower = out.median_abs_dip_error_upper = kNaN;
  out.share_links_growth_right_lower = out.share_links_growth_right_upper = kNaN;
  if (intervals == ScoreIntervals::computed)
  {
    const ClusteredMedian abs_error = clusteredMedian(abs_errors_by_perturbation, kScoreIntervalReplicates, kScoreIntervalSeed);
    out.median_abs_dip_error_lower = abs_error.lower;
    out.median_abs_dip_error_upper = abs_error.upper;
    std::tie(out.share_links_growth_right_lower, out.share_links_growth_right_upper) =
        wildClusterShareInterval(links_by_perturbation, 0.95, kScoreIntervalReplicates, kScoreIntervalSeed);
  }
  out.car_perturbations = errors.size();
  out.median_dip_error = finiteMedian(errors);
  out.distance_lost_scored = lost_errors.size();
  out.median_distance_lost_error = finiteMedian(lost_errors);
  out.dip_width_scored = width_errors.size();
  out.median_dip_width_error = finiteMedian(width_errors);
  std::vector<double> absolute;
  std::size_t within = 0;
  for (double e : errors)
  {
    absolute.push_back(std::abs(e));
    within += std::abs(e) <= 0.3 ? 1 : 0;
  }
  out.median_abs_dip_error = finiteMedian(absolute);
  out.share_within_30_percent = errors.empty() ? std::numeric_limits<double>::quiet_NaN()
                                               : static_cast<double>(within) / static_cast<double>(errors.size());
  out.share_links_growth_right = out.links == 0 ? std::numeric_limits<double>::quiet_NaN()
                                                : static_cast<double>(right) / static_cast<double>(out.links);
  return out;
}

}  // namespace acc
