#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/calibration/refit_bootstrap.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/diagnosis/augmented_stability.h"
#include "acc_identification/diagnosis/augmented_stability_verdict.h"
#include "acc_identification/diagnosis/determined_effects.h"
#include "acc_identification/model/follower_effects.h"
#include "acc_identification/diagnosis/effect_selection.h"
#include "acc_identification/diagnosis/perturbation_window_criterion.h"
#include "acc_identification/diagnosis/residual_breakdown.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
struct DiagnosisOptions
{
  /// Each run is fitted on its first train_fraction of time and scored on the rest.
  double train_fraction = 0.5;
  /// Halves (train or test) shorter than this are not used (listed in notes).
  std::size_t min_samples_per_half = 50;
  /// The six timing and spacing effects, then two response effects. The leader-acceleration
  /// feedforward is tested only when asked for (--effect): on 10 Hz data a feedforward of about
  /// 0.02 stands in for the explicit Euler model's half-step lag, and the rule names it where no
  /// effect is (2 of 2 effect-free synthetic drives did); the platoon diagnosis judges it on dips.
  std::vector<EffectKind> candidates = {EffectKind::actuation_lag,       EffectKind::reaction_delay,
                                        EffectKind::acceleration_limits, EffectKind::sensor_time_offset,
                                        EffectKind::speed_dependent_time_gap, EffectKind::set_speed_cruise,
                                        EffectKind::asymmetric_response, EffectKind::speed_dependent_gains};
  AugmentedCalibrationOptions calibration;
  SelectionOptions selection;
  /// The pair-level judge beside the whole-run rule: each effect on the leaders' perturbation
  /// windows of the held-out parts (perturbation_window_criterion.h).
  PerturbationWindowOptions perturbation_windows;
  BreakdownOptions breakdown;
  /// The string-stability test of the chosen model (dominant effect, or the base model).
  bool with_stability_test = true;
  AugmentedStabilityTestOptions stability_test;
  /// Effects in combination: after the dominant effect, every remaining candidate is fitted on
  /// top of the current model (warm-started from it) and compared with it by the same rule
  /// (the family-wise level over the remaining candidates, the practical threshold relative to the current
  /// model's held-out MSE, timing effects resolvable); the best significant one is added, until
  /// none is or the chain holds max_chain_length effects. Each step's model also gets the
  /// string-stability test when with_stability_test is set.
  bool forward_selection = true;
  std::size_t max_chain_length = 3;
  /// Threads for the independent fits (the six effects, then each forward round's candidates);
  /// 0: every core. The result does not depend on it (each fit is stored by its index).
  std::size_t threads = 0;
  /// The refitting bootstrap of the final model (bootstrapDiagnosedModel) when its training data
  /// span less than bootstrap_below_s: intervals for its sizes that hold on short data. 0
  /// replicates (here): none; diagnose asks for 199, as calibrate does. bootstrap.threads 0 takes
  /// `threads`.
  std::size_t bootstrap_replicates = 0;
  double bootstrap_below_s = 300.0;
  RefitBootstrapOptions bootstrap;
};

/// One model (base or augmented) fitted on the training halves and scored on the held-out halves.
struct ModelDiagnosis
{
  AugmentedFit fit;
  double train_rmse_speed_mps = 0.0;
  double test_rmse_speed_mps = 0.0;
  double test_rmse_gap_m = 0.0;
  bool test_diverged = false;   ///< some held-out simulation blew up (its errors are then huge)
  ImprovementEstimate improvement;  ///< versus the base model (zero for the base model)
  bool significant = false;
  bool resolvable = true;       ///< the fitted magnitude is above the data's resolution (isResolvable)
  AugmentedStability stability;
  bool stability_verdict_changes = false;  ///< string_stable differs from the base model's
  std::vector<SimulatedFollower> test_simulations;  ///< one per held-out half
};

/// One step of the forward selection: the model with every effect chosen so far.
struct ForwardSelectionStep
{
  EffectKind added = EffectKind::none;
  /// fit.effects lists the chain up to this step; improvement is versus the previous step's model
  /// (the base model for the first step), relative to that model's held-out MSE.
  ModelDiagnosis model;
  std::optional<AugmentedStabilityTestResult> stability_test;
  /// How precisely the training data pin the added effect's size in this step's model, at the
  /// determined effects' threshold (determinedThreshold over the candidates).
  EffectSize added_size;
};

struct DiagnosisResult
{
  std::vector<CarFollowingRun> train;  ///< the first halves used for fitting (whole runs: diagnoseHeldOutRuns)
  std::vector<CarFollowingRun> test;   ///< the held-out halves (whole runs kept aside: diagnoseHeldOutRuns)
  /// The held-out parts are whole runs kept aside (diagnoseHeldOutRuns), not the later parts of
  /// the runs fitted.
  bool held_out_whole_runs = false;
  std::vector<std::string> notes;      ///< runs or halves that were not used, and why
  /// Why the parts fitted on are too steady for calibrate to fit ("" when they are not): the fits
  /// below then say what they leave open, and no model's stability is stated (nor a verdict: the
  /// stability test refuses such data too).
  std::string steady_training;
  double operating_speed_mps = 0.0;    ///< median follower speed of the training data (for linearisation)
  double sample_period_s = 0.0;        ///< median step of the data
  ModelDiagnosis baseline;
  std::vector<ModelDiagnosis> effects;  ///< in the order of options.candidates
  SelectionResult selection;
  std::string selection_rule;
  /// Each effect's model inside the leaders' perturbations of the held-out parts, beside the
  /// whole-run rule (which names the dominant effect): where a braking passed on shows.
  PerturbationWindowCriterion perturbation_windows;
  ResidualBreakdown where;             ///< base model's held-out residual; "after" is the dominant effect
  /// Is the chosen model (dominantModel()) string stable, decided from the held-out data
  /// (testAugmentedStringStability); unset when options.with_stability_test is false.
  std::optional<AugmentedStabilityTestResult> stability_test;
  /// Forward selection (options.forward_selection): the chain, starting with the dominant effect;
  /// empty when none is significant or forward selection is off.
  std::vector<ForwardSelectionStep> selected_effects;
  /// The comparisons made on top of each step's model (the candidates are the effects not yet in
  /// it; the last one is why the chain stopped, unless it reached its maximum length).
  std::vector<SelectionResult> forward_rounds;
  std::string forward_stop_reason;
  /// Effects whose size the training data pin away from none (determined_effects.h), whether or
  /// not the held-out rule names them: what a timing effect absorbed by tau_e leaves to see.
  std::vector<DeterminedEffect> determined;
  /// Effects whose fit sits at none where it carries no information (a lag of 0), asked at a
  /// typical size instead: what these data could not see (determined_effects.h).
  std::vector<UnmeasuredEffect> unmeasured;
  /// Does the base model, and the model the diagnosis ends with (finalModel), describe the
  /// training and the held-out parts (model_adequacy.h, with the diagnosis's own parameter box).
  ModelAdequacy baseline_adequacy;
  ModelAdequacy final_adequacy;
  /// The final model's refitting bootstrap (options.bootstrap_replicates, on short training data).
  std::optional<RefitBootstrap> final_bootstrap;
};

/// Splits every run, fits the base model and each candidate effect on the first parts, scores
/// them on the held-out parts, applies the selection rule and breaks the residual down.
/// Throws std::invalid_argument when no run leaves enough samples on both sides of the split, or
/// when the first parts together hold less than calibrate fits on (IdentifiabilityCriteria's
/// samples and seconds).
DiagnosisResult diagnoseRuns(const std::vector<CarFollowingRun>& runs, const DiagnosisOptions& options);

/// As diagnoseRuns, with runs kept aside instead of each run's later part: every model is fitted
/// on `fitted` whole and scored on `held_out` whole (a run the fits never saw, as the campaign's
/// leave-one-run-out; the way to judge a run too short to halve). A run with fewer samples than
/// min_samples_per_half is not used, said in the notes. Throws std::invalid_argument when either
/// side is left without a run, or the fitted runs hold less than calibrate fits on.
DiagnosisResult diagnoseHeldOutRuns(const std::vector<CarFollowingRun>& fitted,
                                    const std::vector<CarFollowingRun>& held_out, const DiagnosisOptions& options);

/// The model of the dominant effect, or the baseline when none.
const ModelDiagnosis& dominantModel(const DiagnosisResult& result);

/// The model the diagnosis ends with: the last of the forward-selection chain, or the baseline
/// when the chain is empty.
const ModelDiagnosis& finalModel(const DiagnosisResult& result);

/// The string-stability test of finalModel(): the chain's last step's, or the diagnosis's own when
/// the chain is empty and no effect was named (it is then the base model's); nullptr when that
/// model was not tested.
const AugmentedStabilityTestResult* finalModelStabilityTest(const DiagnosisResult& result);

/// THE verdict of a diagnosis, stated once: the final model's string-stability test when the
/// diagnosis ends with a better model than the base (the chain is not empty), else the base
/// model's; why, with the held-out RMSEs and each model's adequacy.
struct DiagnosisVerdict
{
  std::string model;  ///< "final model (effect + effect)" or "base model"
  const AugmentedStabilityTestResult* test = nullptr;  ///< nullptr: that model was not tested
  bool model_adequate = false;
  std::string why;
};

DiagnosisVerdict statedVerdict(const DiagnosisResult& result);

/// The effects of the forward-selection chain in the order they were added (empty when none).
std::vector<EffectKind> selectedChain(const DiagnosisResult& result);

}  // namespace acc
