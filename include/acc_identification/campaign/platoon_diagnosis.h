#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "acc_identification/campaign/campaign_inputs.h"
#include "acc_identification/campaign/platoon_check.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// One model the platoon diagnosis tries: effects added to the paper's law, and the objective the
/// model is calibrated with.
struct PlatoonCandidate
{
  std::vector<EffectKind> effects;
  FitObjective objective = FitObjective::speed;
  /// What the candidate adds to the base model (its effects, and a non-speed objective): a
  /// candidate extends another when it adds exactly one thing to it.
  std::vector<std::string> features() const;
  /// Whether this candidate holds every feature of `other` (and perhaps more).
  bool holdsAllOf(const PlatoonCandidate& other) const;
  /// "asymmetric_response + reaction_delay", "none (speed_and_gap objective)".
  std::string name() const;
  /// The same effects (in any order: "reaction_delay,leader_braking_anticipation" is the
  /// candidate listed the other way round) and the same objective.
  bool operator==(const PlatoonCandidate& other) const
  {
    std::vector<EffectKind> own = effects, theirs = other.effects;
    std::sort(own.begin(), own.end());
    std::sort(theirs.begin(), theirs.end());
    return own == theirs && objective == other.objective;
  }
};

/// The candidates the platoon diagnosis tries beside the base model (speed objective, no effect):
/// each response and timing effect alone, the gap and normalised speed+gap objectives, then
/// combinations of two. Index i + 1 in every score vector below (index 0 is the base model).
const std::vector<PlatoonCandidate>& platoonCandidates();

/// Parses "reaction_delay", "asymmetric_response,reaction_delay", "none@gap",
/// "reaction_delay@speed_and_gap" (effects joined by commas, then @objective); false when unknown.
bool parsePlatoonCandidate(const std::string& text, PlatoonCandidate* candidate);

/// The candidate as parsePlatoonCandidate reads it: "asymmetric_response,reaction_delay",
/// "none@gap" (its inverse, for messages that list what may be given).
std::string platoonCandidateText(const PlatoonCandidate& candidate);

/// Whether candidate is the base model or one of platoonCandidates(): what may be forced.
bool isPlatoonCandidate(const PlatoonCandidate& candidate);

/// The options every candidate model of a car is fitted with (calibrateAugmentedSet): the
/// candidate's objective and the platoon diagnosis's number of effect starts.
AugmentedCalibrationOptions candidateCalibrationOptions(const PlatoonCandidate& candidate);

/// candidate fitted on training as every candidate model of a car is (calibrateAugmentedSet with
/// candidateCalibrationOptions, warm-started from `warm`, the base model or a candidate it extends;
/// with a timing effect, also from cold starts, the better of the two on training kept): one rule
/// for the leave-one-run-out models, a car's model on all its runs (fitOnAllRuns) and that model's
/// bootstrap refits.
AugmentedFit fitCandidate(const PlatoonCandidate& candidate, const std::vector<CarFollowingRun>& training,
                          const AugmentedFit& warm);

/// fitCandidate from each of several warm starts (the cold starts of a timing effect made once),
/// the best on training kept (betterFit). warm_starts must not be empty.
AugmentedFit fitCandidate(const PlatoonCandidate& candidate, const std::vector<CarFollowingRun>& training,
                          const std::vector<AugmentedFit>& warm_starts);

/// Each candidate's model of one car, fitted (calibrateAugmentedSet with the candidate's
/// objective) on the same training segments as its base model, warm-started from it; a candidate
/// that extends another is warm-started from that one's fit. One entry per platoonCandidates();
/// available false where the fit failed or diverged, or where `wanted` (indices into
/// platoonCandidates(); every one when absent) leaves the candidate out. A wanted candidate's warm
/// starts are fitted with it, so that its fit is the same whatever else is wanted.
std::vector<PlatoonCarModel> fitCandidateModels(const std::vector<CarFollowingRun>& training,
                                                const PlatoonCarModel& base,
                                                const std::optional<std::vector<std::size_t>>& wanted = std::nullopt);

/// What one car did in one perturbation against what each model predicted for it: at pair level
/// (driven by its real leader's measured speed: nothing compounds) and in the platoon (driven by
/// the predicted car ahead, the chain from the real first car).
struct PairPerturbationScore
{
  std::size_t file_index = 0;
  int position = 0;
  std::size_t perturbation = 0;  ///< index among the file's lead perturbations
  double measured_dip_mps = 0.0;
  /// Per model (0: base, i + 1: candidate i), NaN where not predicted: the pair level's mean
  /// squared speed error over the window [onset - pre_window_s, window_end) [m^2/s^2] and its dip,
  /// and the platoon's dip (addChainDips; empty until then).
  std::vector<double> window_mse;
  std::vector<double> predicted_dip_mps;
  std::vector<double> chain_dip_mps;
};

/// The scores of car `position` of a file in each of the file's lead perturbations (only the one
/// given: models fitted without its window), for the base model and every candidate (models[0]
/// base, models[i + 1] candidate i): the pair-level part.
std::vector<PairPerturbationScore> scorePairPerturbations(const CampaignFile& file, std::size_t file_index,
                                                          int position, const std::vector<PlatoonCarModel>& models,
                                                          const PlatoonCheckOptions& options,
                                                          std::optional<std::size_t> only_perturbation = std::nullopt);

/// Records the platoon dips of a check made with model `model_index` as the diagnosed models
/// (checkPlatoon with them; model 0 reads the check's base prediction) into the scores of the
/// same file, position and perturbation. models is the number of models (base + candidates).
void addChainDips(const PlatoonCheck& check, std::size_t file_index, std::size_t model_index, std::size_t models,
                  std::vector<PairPerturbationScore>* scores);

/// What the rule compares models on.
enum class SelectionCriterion
{
  /// The platoon's dips, predicted from the real first car: the squared log ratio of predicted to
  /// measured dip per car-perturbation (measured dips above 0.3 m/s; a prediction below a tenth
  /// of the measured dip scored as a tenth: kLossMinPredictedDipShare). What the platoon question is.
  platoon_dips,
  /// The pair level's mean squared speed error in the perturbation windows.
  pair_windows,
};

std::string criterionName(SelectionCriterion criterion);

struct EffectSetSelectionOptions
{
  SelectionCriterion criterion = SelectionCriterion::platoon_dips;
  /// Family-wise error rate of the comparisons of one stage (the joint max-t of the wild cluster
  /// bootstrap over its candidates, wildClusterMaxT); the level of each single comparison of a
  /// choice with a rival or an alternative.
  double alpha = 0.05;
  /// A candidate must also lower the window MSE by at least this fraction (practical relevance).
  double min_relative_improvement = 0.10;
  /// With the platoon-dips criterion, a candidate must also lower the root of the mean loss (the
  /// RMS log ratio of predicted to measured dip: about the RMS relative dip error) by at least this
  /// much. Where the models already predict the dips within a few percent, a relative gain closes
  /// no gap: a dip is the minimum of a noisy speed, and even the smoothed OpenACC speeds leave it
  /// uncertain by 1-6 % (docs/PLATOON_DIAGNOSIS.md, "noise deepening the measured dips").
  double min_rms_dip_error_reduction = 0.01;
  std::size_t replicates = 1999;  ///< wild cluster bootstrap patterns drawn beyond seven perturbations
  std::uint64_t seed = 20191008;
  /// When set, this candidate (one of platoonCandidates(), or the base model) is taken instead of
  /// the rule's choice; the comparisons are still made and reported.
  bool force = false;
  PlatoonCandidate forced;
};

/// One candidate set's comparison with the model it must beat.
struct EffectSetComparison
{
  PlatoonCandidate candidate;
  PlatoonCandidate against;  ///< the base model or the first stage's choice
  std::size_t car_perturbations = 0;
  std::size_t perturbations = 0;  ///< clusters of the bootstrap
  double mean_loss = 0.0;             ///< the criterion's mean over the car-perturbations compared
  double against_loss = 0.0;
  double relative_improvement = 0.0;  ///< 1 - mean_loss / against_loss
  /// The other criterion on the same car-perturbations, for the report (NaN where not scored).
  double mean_window_mse = 0.0;
  double against_window_mse = 0.0;
  /// H0: no lower loss, by the wild cluster bootstrap-t over perturbations. p_value is the one the
  /// rule uses: within the stage's family (max-t) for a stage's comparison, alone for a rival or an
  /// alternative; p_value_alone is this comparison's own.
  double p_value = 1.0;
  double p_value_alone = 1.0;
  bool significant = false;           ///< p_value <= alpha and the improvement is relevant
};

/// The rule's outcome: the candidate chosen (index into platoonCandidates() + 1, 0 for the base
/// model) and every comparison made.
struct EffectSetSelection
{
  std::size_t chosen = 0;
  PlatoonCandidate model;
  std::vector<EffectSetComparison> comparisons;
  /// At each stage that names a candidate, the one chosen (candidate) against every other one
  /// named there (against), by the same test at alpha: significant when the data separate the
  /// choice from that rival, else the stage's choice is a near tie the data do not make.
  std::vector<EffectSetComparison> rivals;
  /// The final models the rule reaches when it goes on from an unseparated rival instead (the
  /// same stages from there; one branch deep), each compared with the choice (candidate: the
  /// choice, against: the alternative), kept when the data do not separate the two: models the
  /// run could as well be predicted with.
  std::vector<EffectSetComparison> alternatives;
  std::string excluded_run;  ///< the run left out of the choice ("" when none)

  /// The rivals the data do not separate from the choice made at their stage.
  std::vector<const EffectSetComparison*> unseparatedRivals() const;
};

/// The stated rule over the pair-level scores of every file but `exclude_file` (pass a value
/// >= the number of files to use all): stage 1 compares each candidate that adds one thing to the
/// base model with it, paired over car-perturbations, and keeps the lowest mean loss among
/// those with a significant, relevant improvement; each further stage compares each candidate that
/// adds one thing to the last choice with it, by the same test, until none is named or none
/// extends the choice. The test, the wild cluster bootstrap-t (wild_cluster_bootstrap.h), weighs
/// whole perturbations (every car of one perturbation together, as they share its input). The
/// stage's choice is then compared
/// with every other candidate named at that stage (rivals), to say whether the data separate them.
EffectSetSelection selectEffectSet(const std::vector<PairPerturbationScore>& scores, std::size_t exclude_file,
                                   const std::string& excluded_run, const EffectSetSelectionOptions& options);

/// The reverse of addChainDips for a run's alternative models: check (the run of file
/// file_index) gets their names, and each of its DipComparisons the chain dips the scores hold
/// for them (the first car: its own dip, the chain's input; NaN where no score is).
void addAlternativeDips(const std::vector<PairPerturbationScore>& scores, std::size_t file_index,
                        const EffectSetSelection& selection, PlatoonCheck* check);

/// The rule in words, for reports and JSON.
std::string effectSetSelectionRule(const EffectSetSelectionOptions& options);

}  // namespace acc

namespace acc
{
/// How well one kind of prediction matches what the cars did, over every car-perturbation of the
/// platoons: positions 2 on with a measured dip above min_dip_mps; links (a car and the one ahead)
/// whose measured dips differ by more than min_link_change_mps.
struct DipPredictionSummary
{
  std::size_t car_perturbations = 0;
  double median_dip_error = 0.0;          ///< median of (predicted - measured) / measured
  double median_abs_dip_error = 0.0;
  double share_within_30_percent = 0.0;
  std::size_t links = 0;
  double share_links_growth_right = 0.0;  ///< predicted growth (or decay) where the data show it
  /// How sure the two scores are: 95 % intervals that weigh whole perturbations (every car of one
  /// shares its input) and hold their coverage with a handful of them, by inverting the wild
  /// cluster bootstrap-t (clusteredMedian, wildClusterShareInterval; every weight pattern with up
  /// to seven perturbations, else 1999 drawn from a fixed seed). NaN with fewer than two
  /// perturbations.
  double median_abs_dip_error_lower = 0.0, median_abs_dip_error_upper = 0.0;
  double share_links_growth_right_lower = 0.0, share_links_growth_right_upper = 0.0;
  /// Median of (predicted - measured) / measured distance lost (distanceLostM) over the same
  /// car-perturbations, where both are known: whether a dip predicted right lasts as long.
  double median_distance_lost_error = 0.0;
  std::size_t distance_lost_scored = 0;
  /// Median of (predicted - measured) / measured dip width at half depth (DipShape::width_s), where
  /// both are known: whether a dip lasts as long, apart from its tails.
  double median_dip_width_error = 0.0;
  std::size_t dip_width_scored = 0;
};

/// Which prediction to summarise.
enum class DipPrediction
{
  chain_base,
  chain_diagnosed,
  pair_base,
  pair_diagnosed,
  /// No model: every car dips as deep as the first car did (a platoon that passes a braking on
  /// unchanged, Newell's time-shifted copy; behind a restarted chain, as the real car driving it),
  /// scored on the car-perturbations the base chain predicts. The reference a model must beat to
  /// say anything about growth or decay.
  unchanged_dip,
  /// No model either: each car's dip chained with its own link ratio measured in its other runs
  /// (addLinkRatioChains; the dip only). Whether a car's past brakings say what it does in this one.
  link_ratio_chain
};

/// The car-perturbations scored: a measured dip above this [m/s] (what platoon_score.py scores).
constexpr double kScoredMinDipMps = 0.3;
/// The platoon-dip loss scores a predicted dip below this share of the measured one (no dip at
/// all, or the car speeding up) as this share: the loss of a prediction ten times too small. The
/// log ratio has no value there, and a car left out of a candidate's loss for it would spare the
/// candidate its worst predictions.
constexpr double kLossMinPredictedDipShare = 0.1;
/// The links scored: measured dips of the car and the one ahead more than this apart [m/s].
constexpr double kScoredMinLinkChangeMps = 0.2;

/// Only the car-perturbations `include` accepts (all when empty): e.g. one car and setting, for its
/// model's adequacy.
using DipRowFilter = std::function<bool(const PlatoonCheck&, const DipComparison&)>;

/// The first follower (behind the platoon's real first car) apart from the cars further back: the
/// place where the models' recovery departs most (docs/PLATOON_DIAGNOSIS.md).
inline bool isFirstFollower(const PlatoonCheck&, const DipComparison& row) { return row.position == 2; }
inline bool isFurtherBack(const PlatoonCheck&, const DipComparison& row) { return row.position > 2; }

/// Whether a summary carries the two target scores' intervals (DipPredictionSummary), which cost
/// far more than the scores: skipped where only a score is read.
enum class ScoreIntervals
{
  computed,
  skipped  ///< the interval fields are NaN
};

DipPredictionSummary summarizeDipPredictions(const std::vector<PlatoonCheck>& platoons, DipPrediction which,
                                             double min_dip_mps = kScoredMinDipMps,
                                             double min_link_change_mps = kScoredMinLinkChangeMps,
                                             const DipRowFilter& include = {},
                                             ScoreIntervals intervals = ScoreIntervals::computed);

}  // namespace acc
