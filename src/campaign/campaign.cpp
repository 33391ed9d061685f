#include "acc_identification/campaign/campaign.h"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <optional>
#include <utility>

#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/campaign/link_ratio_chain.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/parallel_tasks.h"

namespace acc
{
namespace
{
/// Follower speed spread below which not even a predicting model is fitted (GNSS noise alone is
/// about 0.06 m/s); StabilityTestOptions::min_training_speed_std_mps.
constexpr double kMinPredictionSpeedStdMps = 0.1;

/// One model fit of the platoon check: car `position` of file `file_index`, for every
/// perturbation of the file or, for a car with no other run at its setting, for one: fitted on its
/// run outside that perturbation's window (leave one perturbation out).
struct ModelTask
{
  std::size_t file_index = 0;
  int position = 0;
  std::optional<std::size_t> perturbation;
  std::pair<double, double> held_out_s{0.0, 0.0};  ///< the perturbation's window in the run's clock
  /// Whether the run has a lead perturbation: only then do its dips score the candidates, so only
  /// then are they all fitted for its cars (otherwise the one the run's diagnosed chain needs).
  bool run_has_perturbations = true;
};

/// The first half of every segment (the paper's training half), those long enough to simulate.
std::vector<CarFollowingRun> firstHalves(const std::vector<CarFollowingRun>& segments)
{
  std::vector<CarFollowingRun> halves;
  for (const CarFollowingRun& segment : segments)
  {
    CarFollowingRun half = splitRunInHalf(segment).first;
    if (half.size() >= 2)
      halves.push_back(std::move(half));
  }
  return halves;
}

/// The pieces of the segments outside [first_s, last_s], those long enough to simulate.
std::vector<CarFollowingRun> segmentsOutside(const std::vector<CarFollowingRun>& segments, double first_s, double last_s)
{
  std::vector<CarFollowingRun> pieces;
  auto keep = [&pieces](CarFollowingRun piece) {
    if (piece.size() >= 2)
      pieces.push_back(std::move(piece));
  };
  for (const CarFollowingRun& segment : segments)
  {
    const auto& t = segment.time_s;
    const std::size_t before = std::lower_bound(t.begin(), t.end(), first_s) - t.begin();
    const std::size_t after = std::upper_bound(t.begin(), t.end(), last_s) - t.begin();
    keep(segment.slice(0, before));
    keep(segment.slice(std::max(before, after), t.size()));
  }
  return pieces;
}

/// identifyAcc's fit, or why there is none.
PlatoonCarModel fitModel(const std::vector<CarFollowingRun>& segments, std::size_t starts, const std::string& source)
{
  IdentificationOptions options;
  options.multistart.starts = starts;
  // A prediction needs a fit that predicts, not four parameters pinned one by one: a car that
  // kept a nearly steady speed still gets a model (down to the stability test's own floor).
  options.criteria.min_speed_std_mps = kMinPredictionSpeedStdMps;
  const Identification id = identifyAcc(segments, options);
  if (!id.solved || id.calibration.diverged)
    return {false, {}, source + ": no fit (" + (id.note.empty() ? "diverged" : id.note) + ")"};
  return {true, id.calibration.parameters, source + (id.identifiable ? "" : "; not every parameter determined")};
}

/// fitModel on pieces of the predicted run itself, and the stretches they cover
/// (fitted_on_this_run_s: what the in-sample flag checks against the dip windows).
PlatoonCarModel fitModelOnThisRun(const std::vector<CarFollowingRun>& pieces, std::size_t starts,
                                  const std::string& source)
{
  PlatoonCarModel model = fitModel(pieces, starts, source);
  for (const CarFollowingRun& piece : pieces)
    model.fitted_on_this_run_s.emplace_back(piece.time_s.front(), piece.time_s.back());
  return model;
}

/// Files whose platoon can be checked: a first car and at least one pair.
bool checkable(const CampaignInputs& inputs, std::size_t file_index)
{
  const OpenAccFile& data = inputs.files[file_index].contents;
  if (data.vehicle(1) == nullptr)
    return false;
  for (const CampaignGroup& group : inputs.groups)
  {
    if (group.runIn(file_index) != nullptr)
      return true;
  }
  return false;
}

/// The windows of the file's lead perturbations in its clock (perturbationWindowS); a
/// perturbation whose window holds no sample gets an empty stretch.
std::vector<std::pair<double, double>> leadWindowsS(const OpenAccFile& data, const PlatoonCheckOptions& options)
{
  std::size_t first_row = 0, end_row = 0;
  const std::vector<Perturbation> perturbations = leadPerturbations(data, options, &first_row, &end_row);
  const std::vector<double> time_s = sliceRows(data.time_s, first_row, end_row);
  std::vector<std::pair<double, double>> windows;
  for (const Perturbation& perturbation : perturbations)
    windows.push_back(perturbationWindowS(time_s, perturbation, options).value_or(std::make_pair(0.0, -1.0)));
  return windows;
}

/// Whether the car's model comes from other runs: it has another run at its setting.
bool hasOtherRun(const CampaignInputs& inputs, std::size_t file_index, const std::string& name)
{
  const CampaignGroup* group = inputs.findGroup(name, inputs.files[file_index].settingOf(name));
  return group == nullptr || !group->segmentsExcept(file_index).empty();
}

std::vector<ModelTask> modelTasks(const CampaignInputs& inputs, const PlatoonCheckOptions& options)
{
  std::vector<ModelTask> tasks;
  for (std::size_t f = 0; f < inputs.files.size(); ++f)
  {
    if (!checkable(inputs, f))
      continue;
    const OpenAccFile& data = inputs.files[f].contents;
    const std::vector<std::pair<double, double>> windows = leadWindowsS(data, options);
    for (const OpenAccVehicle& vehicle : data.vehicles)
    {
      if (vehicle.position < 2)
        continue;
      if (windows.empty() || hasOtherRun(inputs, f, data.vehicleName(vehicle.position)))
      {
        tasks.push_back({f, vehicle.position, std::nullopt, {0.0, 0.0}, !windows.empty()});
        continue;
      }
      for (std::size_t k = 0; k < windows.size(); ++k)
        tasks.push_back({f, vehicle.position, k, windows[k], true});
    }
  }
  return tasks;
}

/// The chains a file's platoon is predicted with: one, or one per lead perturbation when a car of
/// it has leave-one-perturbation-out models.
std::size_t chainsOf(std::size_t file_index, const std::vector<ModelTask>& tasks)
{
  std::size_t chains = 1;
  for (const ModelTask& task : tasks)
  {
    if (task.file_index == file_index && task.perturbation)
      chains = std::max(chains, *task.perturbation + 1);
  }
  return chains;
}

/// Whether the task's model serves the chain of the file's perturbation `chain` (chains > 1).
bool servesChain(const ModelTask& task, std::size_t chain)
{
  return !task.perturbation || *task.perturbation == chain;
}

/// The models of one file's cars in one of its chains (chainsOf), indexed by position.
std::vector<PlatoonCarModel> modelsOfFile(const CampaignInputs& inputs, std::size_t file_index, std::size_t chain,
                                          const std::vector<ModelTask>& tasks,
                                          const std::vector<PlatoonCarModel>& fitted)
{
  const OpenAccFile& data = inputs.files[file_index].contents;
  std::size_t positions = data.metadata.vehicle_order.size() + 1;
  for (const OpenAccVehicle& vehicle : data.vehicles)
    positions = std::max<std::size_t>(positions, vehicle.position + 1);
  std::vector<PlatoonCarModel> models(positions, PlatoonCarModel{false, {}, "no data in this run"});
  for (std::size_t i = 0; i < tasks.size(); ++i)
  {
    if (tasks[i].file_index == file_index && servesChain(tasks[i], chain))
      models[tasks[i].position] = fitted[i];
  }
  return models;
}
}  // namespace

namespace
{
/// The base model and the candidate models of one car, its pair-level perturbation scores, and the
/// segments they were fitted on (for the candidates fitted once the run's choice is known).
struct CarModels
{
  PlatoonCarModel base;
  std::vector<PlatoonCarModel> candidates;
  std::vector<PairPerturbationScore> scores;
  std::vector<CarFollowingRun> training;
};

/// fitPlatoonModel, and the segments it was fitted on (empty when none).
PlatoonCarModel fitPlatoonModelOn(const CampaignInputs& inputs, std::size_t file_index, int position,
                                  std::size_t starts, std::vector<CarFollowingRun>* training,
                                  const std::optional<std::pair<double, double>>& held_out);
}  // namespace

PlatoonCarModel fitPlatoonModel(const CampaignInputs& inputs, std::size_t file_index, int position,
                                std::size_t starts, const std::optional<std::pair<double, double>>& held_out)
{
  std::vector<CarFollowingRun> training;
  return fitPlatoonModelOn(inputs, file_index, position, starts, &training, held_out);
}

namespace
{
PlatoonCarModel fitPlatoonModelOn(const CampaignInputs& inputs, std::size_t file_index, int position,
                                  std::size_t starts, std::vector<CarFollowingRun>* training,
                                  const std::optional<std::pair<double, double>>& held_out)
{
  const CampaignFile& file = inputs.files[file_index];
  const std::string name = file.contents.vehicleName(position);
  const CampaignGroup* group = inputs.findGroup(name, file.settingOf(name));
  const CampaignRun* own = group != nullptr ? group->runIn(file_index) : nullptr;
  if (own == nullptr)
    return {false, {}, "no usable pair of this car in this run"};
  const std::vector<CarFollowingRun> others = group->segmentsExcept(file_index);
  std::string fallback = "first half of this run (no other run of " + group->label() + ")";
  if (others.empty() && held_out)
  {
    *training = segmentsOutside(own->segments, held_out->first, held_out->second);
    return fitModelOnThisRun(*training, starts,
                             "leave-one-perturbation-out: this run outside " +
                                 printfText("%.1f-%.1f s", held_out->first, held_out->second) +
                                 ", the window of the perturbation it predicts (no other run of " + group->label() + ")");
  }
  if (!others.empty())
  {
    const std::size_t other_runs = group->runs.size() - 1;
    PlatoonCarModel model =
        fitModel(others, starts, "leave-one-run-out: " + std::to_string(other_runs) + " other run(s) of " + group->label());
    if (model.available)
    {
      *training = others;
      model.step_mismatch = describeStepMismatch(others, medianStepS(own->segments));
      return model;
    }
    fallback = "first half of this run (" + model.source + ")";
  }
  *training = firstHalves(own->segments);
  return fitModelOnThisRun(*training, starts, fallback);
}

/// Car (file, position): its base model, and with the platoon diagnosis its candidate models on
/// the same training data (none yet where the run has no perturbation to score them:
/// fitChosenCandidates) and its pair-level scores.
CarModels fitCarModels(const CampaignInputs& inputs, const ModelTask& task, const CampaignOptions& options)
{
  CarModels out;
  const auto held_out = task.perturbation ? std::make_optional(task.held_out_s) : std::nullopt;
  out.base = fitPlatoonModelOn(inputs, task.file_index, task.position, options.group.starts, &out.training, held_out);
  if (!options.platoon_diagnosis)
    return out;
  out.candidates = fitCandidateModels(out.training, out.base,
                                      task.run_has_perturbations ? std::nullopt
                                                                 : std::make_optional(std::vector<std::size_t>{}));
  std::vector<PlatoonCarModel> all{out.base};
  all.insert(all.end(), out.candidates.begin(), out.candidates.end());
  out.scores = scorePairPerturbations(inputs.files[task.file_index], task.file_index, task.position, all,
                                      options.platoon, task.perturbation);
  return out;
}

/// Each car's fit of candidate `candidate` (platoonCandidates()[candidate - 1]; 0: the base model)
/// in one chain of a file, or its base model (said in the source) where that fit failed.
std::vector<PlatoonCarModel> candidateModels(std::vector<PlatoonCarModel> models, const std::vector<ModelTask>& tasks,
                                             const std::vector<CarModels>& fitted, std::size_t file_index,
                                             std::size_t chain, std::size_t candidate)
{
  for (std::size_t i = 0; candidate > 0 && i < tasks.size(); ++i)
  {
    if (tasks[i].file_index != file_index || !servesChain(tasks[i], chain))
      continue;
    const PlatoonCarModel& fit = fitted[i].candidates[candidate - 1];
    if (fit.available)
      models[tasks[i].position] = fit;
    else
      models[tasks[i].position].source +=
          "; kept the base model (" + platoonCandidates()[candidate - 1].name() + ": " + fit.source + ")";
  }
  return models;
}

/// A file's chains (chainsOf), each with its base models and, given a candidate, each car's model
/// of it (candidateModels) as the diagnosed ones.
std::vector<PlatoonChainModels> chainsOfFile(const CampaignInputs& inputs, std::size_t file_index,
                                             const std::vector<ModelTask>& tasks, const std::vector<CarModels>& fitted,
                                             const std::vector<PlatoonCarModel>& base_models,
                                             std::optional<std::size_t> candidate)
{
  std::vector<PlatoonChainModels> chains;
  for (std::size_t c = 0; c < chainsOf(file_index, tasks); ++c)
  {
    PlatoonChainModels chain{modelsOfFile(inputs, file_index, c, tasks, base_models), {}};
    if (candidate)
      chain.diagnosed = candidateModels(chain.models, tasks, fitted, file_index, c, *candidate);
    chains.push_back(std::move(chain));
  }
  return chains;
}

/// For the cars of runs without a perturbation, the candidate the run's diagnosed chain is predicted
/// with (its choice made without it), fitted now: nothing else of theirs is scored.
void fitChosenCandidates(const std::vector<ModelTask>& tasks, const std::vector<EffectSetSelection>& selections,
                         std::size_t threads, std::vector<CarModels>* fitted)
{
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < tasks.size(); ++i)
  {
    if (!tasks[i].run_has_perturbations && selections[tasks[i].file_index].chosen > 0)
      pending.push_back(i);
  }
  runTasksInParallel(pending.size(), threads, [&](std::size_t k) {
    CarModels& car = (*fitted)[pending[k]];
    car.candidates = fitCandidateModels(car.training, car.base,
                                        std::vector<std::size_t>{selections[tasks[pending[k]].file_index].chosen - 1});
  });
}

/// Every file's platoon predicted with each candidate's models (each car's fit of it, or its base
/// model where that fit failed), and the dips recorded in the scores: what the platoon criterion
/// compares.
void addPlatoonDips(const CampaignInputs& inputs, const std::vector<ModelTask>& tasks,
                    const std::vector<CarModels>& fitted, const std::vector<PlatoonCarModel>& base_models,
                    const CampaignOptions& options, std::vector<PairPerturbationScore>* scores)
{
  const std::size_t models = platoonCandidates().size() + 1;
  std::vector<std::size_t> files;  // the runs with a perturbation: no other run has a dip to score
  for (const ModelTask& task : tasks)
  {
    if (task.run_has_perturbations && (files.empty() || files.back() != task.file_index))
      files.push_back(task.file_index);
  }
  // Per (file, candidate): independent, so spread over the threads; each writes its own slot.
  std::vector<PlatoonCheck> checks(files.size() * models);
  runTasksInParallel(checks.size(), options.threads, [&](std::size_t i) {
    const std::size_t f = files[i / models], m = i % models;
    checks[i] = checkPlatoonByPerturbation(inputs.files[f], chainsOfFile(inputs, f, tasks, fitted, base_models, m),
                                           options.platoon);
  });
  for (std::size_t i = 0; i < checks.size(); ++i)
    addChainDips(checks[i], files[i / models], i % models, models, scores);
}

/// Check (d) of each group's model adequacy: its cars' dips in the platoon runs, each predicted at
/// pair level (driven by the real leader) by the car's leave-one-run-out base model.
void addDipChecks(const std::vector<PlatoonCheck>& platoons, std::vector<GroupResult>& groups)
{
  for (GroupResult& group : groups)
  {
    const DipPredictionSummary dips = summarizeDipPredictions(
        platoons, DipPrediction::pair_base, kScoredMinDipMps, kScoredMinLinkChangeMps, [&group](const PlatoonCheck& check, const DipComparison& row) {
          return row.name == group.vehicle && settingOfCar(check.car_settings, check.setting, row.name) == group.setting;
        }, ScoreIntervals::skipped);
    addDipCheck(group.model_adequacy, dips.car_perturbations, dips.median_abs_dip_error);
  }
}
}  // namespace


CampaignResult runCampaign(const CampaignInputs& inputs, const CampaignOptions& options)
{
  const auto started = std::chrono::steady_clock::now();
  CampaignResult result;
  result.groups.resize(inputs.groups.size());
  const std::vector<ModelTask> tasks =
      options.platoon_check ? modelTasks(inputs, options.platoon) : std::vector<ModelTask>{};
  std::vector<CarModels> fitted(tasks.size());
  const std::size_t group_count = inputs.groups.size();
  // One pool for both kinds of task, groups first (the longest), so that no core idles between them.
  auto task = [&](std::size_t i) {
    if (i < group_count)
      result.groups[i] = identifyGroup(inputs.groups[i], options.group);
    else
      fitted[i - group_count] = fitCarModels(inputs, tasks[i - group_count], options);
  };
  std::size_t groups_done = 0, fits_done = 0;
  std::mutex mutex;
  auto progress_of = [&](std::size_t i) {
    if (!options.progress)
      return;
    const std::lock_guard<std::mutex> lock(mutex);
    if (i < group_count)
      options.progress("groups", ++groups_done, group_count);
    else
      options.progress("platoon fits", ++fits_done, tasks.size());
  };
  result.threads = effectiveThreadCount(options.threads, group_count + tasks.size());
  runTasksInParallel(group_count + tasks.size(), options.threads, [&](std::size_t i) {
    task(i);
    progress_of(i);
  });
  std::vector<PlatoonCarModel> base_models(tasks.size());
  for (std::size_t i = 0; i < tasks.size(); ++i)
  {
    base_models[i] = fitted[i].base;
    result.pair_scores.insert(result.pair_scores.end(), fitted[i].scores.begin(), fitted[i].scores.end());
  }
  const bool diagnose = options.platoon_check && options.platoon_diagnosis;
  if (diagnose)
  {
    addPlatoonDips(inputs, tasks, fitted, base_models, options, &result.pair_scores);
    result.effect_selection_criterion = options.effect_selection.criterion;
    result.effect_selection = selectEffectSet(result.pair_scores, inputs.files.size(), "", options.effect_selection);
  }
  // The run's own effect set is chosen without it: its dips judge a choice they did not make.
  std::vector<EffectSetSelection> selections(inputs.files.size());
  for (std::size_t f = 0; diagnose && f < inputs.files.size(); ++f)
  {
    if (checkable(inputs, f))
      selections[f] = selectEffectSet(result.pair_scores, f, inputs.files[f].name, options.effect_selection);
  }
  if (diagnose)
    fitChosenCandidates(tasks, selections, options.threads, &fitted);
  for (std::size_t f = 0; options.platoon_check && f < inputs.files.size(); ++f)
  {
    if (!checkable(inputs, f))
      continue;
    const std::optional<std::size_t> diagnosed = diagnose ? std::make_optional(selections[f].chosen) : std::nullopt;
    result.platoons.push_back(checkPlatoonByPerturbation(
        inputs.files[f], chainsOfFile(inputs, f, tasks, fitted, base_models, diagnosed), options.platoon));
    if (diagnose)
    {
      addAlternativeDips(result.pair_scores, f, selections[f], &result.platoons.back());
      result.run_effect_selections.push_back(selections[f]);
    }
  }
  addLinkRatioChains(result.platoons, kScoredMinDipMps);
  addDipChecks(result.platoons, result.groups);
  if (diagnose)
  {
    result.links = gatherLinkEvidence(inputs, result.groups, result.platoons, result.effect_selection.model,
                                      options.threads, options.platoon, options.group.bootstrap);
    const EffectSetSelectionOptions& draws = options.effect_selection;
    result.shapes_first_followers = summarizeShapeTransfer(result.platoons, isFirstFollower, draws.replicates, draws.seed);
    result.shapes_further_back = summarizeShapeTransfer(result.platoons, isFurtherBack, draws.replicates, draws.seed);
    result.gap = summarizeGap(result.platoons);
  }
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace acc
