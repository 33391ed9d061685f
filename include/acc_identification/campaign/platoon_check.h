#pragma once

#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/campaign/campaign_inputs.h"
#include "acc_identification/evidence/perturbation.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// The model a platoon check simulates one following car with.
struct PlatoonCarModel
{
  PlatoonCarModel() = default;
  PlatoonCarModel(bool available_, const AccParameters& parameters_, std::string source_)
    : available(available_), parameters(parameters_), source(std::move(source_))
  {
  }
  bool available = false;
  AccParameters parameters;
  /// Where it comes from: "leave-one-run-out: 3 other runs", "first half of this run (no other
  /// run of this car and setting)"; or why there is none.
  std::string source;
  /// The stretches [first, last] of the predicted run's own clock the model was fitted on [s]: the
  /// fallback's first halves; empty for a model fitted on other runs. A dip inside one is judged
  /// by a model that saw it (PerturbationCheck::fitted_on_it).
  std::vector<std::pair<double, double>> fitted_on_this_run_s;
  /// The unmodelled effects the model adds to the paper's law (empty: the base model), their
  /// values in the catalogue's order, the settings they make, and the standard errors of
  /// (k1, k2, tau_e, eta, effect values) where the fit gives them.
  std::vector<EffectKind> effects;
  std::vector<double> effect_values;
  EffectSettings settings;
  std::vector<double> standard_errors;
  /// Non-empty when the model was fitted on runs sampled at another step than the run it predicts
  /// (by more than kStepMismatchShare): the fitted parameters are those of the Euler map at the
  /// training data's step (calibration/euler_step_bias.h), and the prediction steps at this run's.
  /// "fitted on runs at 0.1 s steps, this run is at 0.2 s: ...".
  std::string step_mismatch;
};

/// How far the predicted run's median step may lie from its model's training runs' (relative)
/// before the prediction says so: jitter of a 10 Hz logger stays well inside it, 10 Hz against
/// 5 Hz does not.
constexpr double kStepMismatchShare = 0.1;

/// PlatoonCarModel::step_mismatch for a model fitted on `training` (each segment's median step
/// judged on its own: a long run at one step does not hide a short one at another) that predicts a
/// run of median step `run_step_s`; "" when every segment's agrees with it within
/// kStepMismatchShare (or a step is unknown).
std::string describeStepMismatch(const std::vector<CarFollowingRun>& training, double run_step_s);

/// What one speed series did in one perturbation: its dip, the distance it lost against its
/// pre-perturbation speed (distanceLostM), and how hard it braked and recovered and how long it
/// stayed below half its dip (dipShape). NaN where there is no such series or the window is not
/// covered.
struct DipMeasures
{
  double dip_mps = std::numeric_limits<double>::quiet_NaN();
  double distance_lost_m = std::numeric_limits<double>::quiet_NaN();
  DipShape shape{};
};

/// One car's measured and predicted dip in one perturbation.
struct DipComparison
{
  int position = 0;  ///< 1 = the platoon's first car (the input: predicted = measured)
  std::string name;
  DipMeasures measured;  ///< NaN without data
  /// Chained from the real first car (each car driven by the prediction ahead of it), with the base
  /// models and with each car's diagnosed model; NaN where the car could not be predicted. Behind
  /// such a car the chain restarts from its measured speed (checkPlatoon).
  DipMeasures chain, chain_diagnosed;
  /// The position of the real car whose measured speed drives chain (chain_diagnosed): 1, the first
  /// car, unless the chain restarted behind a car it could not predict; 0 where not predicted.
  int chain_driven_by = 0, chain_diagnosed_driven_by = 0;
  /// Pair level: the car driven by its REAL leader's measured speed (nothing compounds), base and
  /// diagnosed model.
  DipMeasures pair, pair_diagnosed;
  /// dip(k) / dip(k-1), measured and chained (behind the real car driving the chain, over its
  /// measured dip); NaN for the first car, without data, or behind a dip too shallow for a ratio.
  double measured_amplification = std::numeric_limits<double>::quiet_NaN();
  double chain_amplification = std::numeric_limits<double>::quiet_NaN();
  double chain_amplification_diagnosed = std::numeric_limits<double>::quiet_NaN();
  /// No model: the dip chained with each car's link ratio from its other runs (addLinkRatioChains;
  /// NaN until then, and where a car on the way has none).
  double link_ratio_chain_dip_mps = std::numeric_limits<double>::quiet_NaN();
  /// The chain's dip with each of the run's alternative models (PlatoonCheck::alternative_models:
  /// final models the data do not separate from the diagnosed one), in that order; NaN where not
  /// predicted.
  std::vector<double> chain_alternatives_dip_mps;
};

/// Where the model and the data disagree.
struct PlatoonDisagreement
{
  std::size_t perturbation = 0;  ///< index into PlatoonCheck::perturbations
  int position = 0;
  std::string name;
  std::string what;  ///< "predicted amplification 1.31, measured attenuation 0.84", "dip error +45 %"
};

/// A car whose models in one perturbation's own chain are not the ones the check's traces show
/// (checkPlatoonByPerturbation: fitted without that perturbation's window).
struct PerturbationCarModels
{
  int position = 0;
  std::string name;
  PlatoonCarModel model;
  PlatoonCarModel diagnosed;  ///< available false without diagnosed models
};

struct PerturbationCheck
{
  Perturbation perturbation;
  std::vector<DipComparison> positions;  ///< every car of the file, by position
  /// The measured dip of the last car with data exceeds the first car's.
  bool data_show_growth = false;
  /// Positions whose car was not on ACC somewhere from the checked stretch's start to this window's
  /// end (onAccThroughout): their predictions, and the chains driven through them, are not compared
  /// (NaN); their measured dips stay.
  std::vector<int> driven_by_hand;
  /// Positions whose car's models were fitted on a stretch of this run that overlaps this
  /// perturbation's window (from the pre-window to the dip window's end): the fallback of a car
  /// with no other run (PlatoonCarModel::fitted_on_this_run_s). Their predictions here, and the
  /// chains' behind them, are not out of sample; they are compared, and said in a note.
  std::vector<int> fitted_on_it;
  /// The cars this perturbation was predicted with other models than PlatoonCheck::cars show
  /// (its own chain's; empty with one chain).
  std::vector<PerturbationCarModels> own_chain_models;
  std::vector<PlatoonDisagreement> disagreements;
};

/// One car of the chain: its model and the prediction made with it.
struct PlatoonCarPrediction
{
  int position = 0;
  std::string name;
  PlatoonCarModel model;
  bool predicted = false;
  std::size_t start_row = 0;                ///< the prediction starts at its measured gap and speed here
  /// The position of the real car whose measured speed drives the prediction, through the predicted
  /// cars between: 1 for the chain from the first car, position - 1 at pair level; 0 if not predicted.
  int driven_by_position = 0;
  std::vector<double> predicted_speed_mps;  ///< per row of the file; NaN outside the prediction
  /// The first row the simulation did not reach when it stopped early (it ran away, or its input
  /// has a hole); 0 when it ran to the end. A dip window it cuts is not measured.
  std::size_t stopped_at_row = 0;
  double rmse_speed_mps = 0.0;              ///< predicted against measured speed where both exist; NaN if never
  std::string note;                         ///< why not predicted
  /// Where the prediction collides with the car ahead or drives backwards (describeBreakdown): a
  /// model's unphysical state, said in the run's notes; "" when it does neither.
  std::string breakdown;
};

/// The whole platoon of one run predicted from its real first car.
struct PlatoonCheck
{
  std::string run;      ///< the file's name
  std::string setting;  ///< the file's
  std::map<std::string, std::string> car_settings;  ///< as CampaignFile::car_settings (a resolved mixed run)
  std::size_t first_row = 0, end_row = 0;  ///< the rows simulated (the first car's longest stretch with data)
  std::vector<PlatoonCarPrediction> cars;  ///< position 2 onwards
  /// The same chain with each car's diagnosed model (empty when none were given).
  std::vector<PlatoonCarPrediction> cars_diagnosed;
  /// Pair level: each car driven by its real leader, base and diagnosed model (position 2 onwards).
  std::vector<PlatoonCarPrediction> pairs, pairs_diagnosed;
  std::vector<PerturbationCheck> perturbations;
  std::vector<std::string> notes;          ///< chain stops and other caveats
  /// The names of the run's alternative models (EffectSetSelection::alternatives), whose dips each
  /// DipComparison holds in chain_alternatives_dip_mps.
  std::vector<std::string> alternative_models;
};

struct PlatoonCheckOptions
{
  PerturbationCriteria perturbation;
  /// A dip whose prediction is off by more than this fraction of the measured dip is a disagreement.
  double max_relative_dip_error = 0.3;
  /// Steps longer than this end the first car's stretch (a hole in the data).
  double max_time_step_s = 0.5;
};

/// Whether the car at `position` was on ACC in every row of [from_row, to_row) (isOnAccAt). Where
/// it was not, its ACC model's prediction is no prediction of what it did (it runs free from the
/// stretch's start, so a stretch driven by hand before a perturbation counts too), and a chain
/// driven through it none of the cars behind.
bool onAccThroughout(const OpenAccFile& file, int position, std::size_t from_row, std::size_t to_row);

/// Predicts every following car of the file: car k is simulated (simulateFollower) with
/// models[k] (index = position; entries 0 and 1 unused) from its measured gap and speed at the
/// first row where it has both, driven by the PREDICTED speed of car k-1 (for k = 2 the measured
/// first car's). The chain stops at a car with no data, no model, or a diverged simulation, and
/// restarts behind it, driven by its measured speed (none: the next car with speed data); notes
/// say where it stopped and restarted. Then each perturbation of the first car is measured
/// (findPerturbations, dipDepthMps) on the measured and the predicted speeds of every position.
/// With diagnosed models (same indexing; may be nullptr), the chain and the pair-level predictions
/// are made with them too and every DipComparison gets its *_diagnosed values.
PlatoonCheck checkPlatoon(const CampaignFile& file, const std::vector<PlatoonCarModel>& models,
                          const PlatoonCheckOptions& options = {},
                          const std::vector<PlatoonCarModel>* diagnosed = nullptr);

/// The models one chain of checkPlatoon simulates the cars with, indexed by position as its models
/// and diagnosed (empty: no diagnosed models).
struct PlatoonChainModels
{
  std::vector<PlatoonCarModel> models;
  std::vector<PlatoonCarModel> diagnosed;
};

/// checkPlatoon with one chain per lead perturbation: perturbation i is predicted and compared with
/// chains[i]'s models. That is how a car with no other run at its setting is judged out of sample:
/// each of its models is fitted on its run outside one perturbation's window
/// (perturbationWindowS). The check's traces (cars, pairs) are chains[0]'s; the notes of the other
/// chains that differ are added. One chain: checkPlatoon. Throws std::invalid_argument unless
/// there is one chain or one per lead perturbation (leadPerturbations).
PlatoonCheck checkPlatoonByPerturbation(const CampaignFile& file, const std::vector<PlatoonChainModels>& chains,
                                        const PlatoonCheckOptions& options = {});

/// The stretch of the run's clock [first, last] a perturbation is judged on (from the pre-window
/// to the dip window's end; time_s the check's rows, as the perturbation's indices): what a model
/// must not be fitted on to predict it out of sample. None when the window holds no sample.
std::optional<std::pair<double, double>> perturbationWindowS(const std::vector<double>& time_s,
                                                             const Perturbation& perturbation,
                                                             const PlatoonCheckOptions& options);

/// Car `position` driven by the measured speed of the car directly ahead (pair level), from its
/// measured gap and speed at the first row of [first_row, end_row) where all three are known.
/// Not predicted (with the reason in note) when the data or the model are missing.
PlatoonCarPrediction predictPair(const OpenAccFile& file, int position, const PlatoonCarModel& model,
                                 std::size_t first_row, std::size_t end_row);

/// The first car's perturbations within its longest stretch [first_row, end_row) (times relative to
/// that stretch's rows: index 0 is first_row), as checkPlatoon finds them.
std::vector<Perturbation> leadPerturbations(const OpenAccFile& file, const PlatoonCheckOptions& options,
                                            std::size_t* first_row, std::size_t* end_row);

/// The rows [first, end) of the longest stretch where time and the first car's speed are finite
/// and time increases by at most max_time_step_s.
std::pair<std::size_t, std::size_t> longestLeadStretch(const OpenAccFile& file, double max_time_step_s);

/// The note that says which rows a check of the stretch [first_row, end_row) leaves out, and why.
std::string describeRowsLeftOut(const OpenAccFile& file, std::size_t first_row, std::size_t end_row);

}  // namespace acc
