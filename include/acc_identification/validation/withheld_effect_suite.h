#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"
#include "acc_identification/diagnosis/diagnosis.h"

namespace acc
{
/// Built-in leader speed profiles for the withheld-effect suite, each exercising the effects
/// differently: steps between held speeds (firm accelerations and brakings, speeds above a set
/// speed), slow oscillation (phase lag), a deep dip (hard braking then hard acceleration).
enum class SyntheticLeadProfile
{
  steps,
  oscillation,
  dip,
};

std::string leadProfileName(SyntheticLeadProfile profile);

/// Leader speed sampled every step_s for duration_s [m/s]; deterministic (no randomness).
std::vector<double> syntheticLeaderSpeed(SyntheticLeadProfile profile, double duration_s, double step_s);

/// One synthetic experiment: the truth to hide and how the data are made.
struct WithheldCase
{
  EffectKind truth = EffectKind::none;
  std::vector<double> truth_values;   ///< the effect's parameters (catalogue order)
  /// Further effects withheld at the same time (each with its parameters in catalogue order), for
  /// checks of the forward selection; the suite's grid leaves this empty.
  std::vector<std::pair<EffectKind, std::vector<double>>> also_withheld;
  AccParameters base{0.08, 0.45, 1.2, 4.0};
  SyntheticLeadProfile profile = SyntheticLeadProfile::steps;
  double duration_s = 400.0;
  double step_s = 0.1;                ///< sampling step of the recorded run
  /// The truth is integrated this many times finer than it is recorded, so that the data are not
  /// made by the very Euler recursion the diagnosis fits (no "inverse crime").
  int truth_substeps = 10;
  double speed_noise_std_mps = 0.06;  ///< white noise on both recorded speeds
  double gap_noise_std_m = 0.4;
  std::uint32_t seed = 1;
};

/// The recorded run of a case: the follower is simulated with the effect by
/// simulateFollower() at step_s / truth_substeps from equilibrium with the true leader,
/// then sampled every step_s; a sensor time offset is
/// then applied to the record (leader speed delayed by delta, gap reduced by the distance the
/// leader covered in delta, by the trapezoid rule); then noise is added to all three columns.
CarFollowingRun synthesizeWithheldRun(const WithheldCase& c);

/// What the diagnosis said about one case.
struct WithheldOutcome
{
  WithheldCase input;
  EffectKind dominant = EffectKind::none;
  std::vector<EffectKind> plausible;
  double recovered_magnitude = 0.0;  ///< first parameter of the truth's effect as fitted (NaN for none)
  double recovered_standard_error = 0.0;  ///< its standard error (NaN for none)
  double base_test_rmse_speed_mps = 0.0;
  double effect_test_rmse_speed_mps = 0.0;  ///< of the truth's effect model (base for none)
  /// The effects the training data determine (determinedEffects), whatever the rule names.
  std::vector<EffectKind> determined;
};

WithheldOutcome runWithheldCase(const WithheldCase& c, const DiagnosisOptions& options);

/// none, the six timing and spacing effects and the response effects: the labels of the suites'
/// confusion matrices (every effect the diagnosis can name by default).
std::vector<EffectKind> diagnosableEffects();

/// The grid of cases: none and every effect of the default candidates at several magnitudes, on
/// the given profiles, noise scales and seeds. magnitudes_per_effect picks from a fixed list per
/// effect (1 to 3). `exploratory` adds effects the diagnosis tests only when asked for
/// (leader_acceleration_feedforward, quadratic_closing_response, leader_braking_anticipation) as
/// truths after the others, so that the default grid's cases and seeds stay as they are.
std::vector<WithheldCase> withheldCaseGrid(std::size_t magnitudes_per_effect,
                                           const std::vector<SyntheticLeadProfile>& profiles,
                                           const std::vector<double>& noise_scales, std::size_t seeds,
                                           const std::vector<EffectKind>& exploratory = {});

/// The effects of `candidates` that are not among the diagnosis's default candidates: what a run
/// with --effect adds, and what the withheld grid then hides too.
std::vector<EffectKind> exploratoryCandidates(const std::vector<EffectKind>& candidates);

/// For the suites' tables: effects joined by " + " ("-" for none), and the median of values (NaN
/// for none; the mean of the middle two for an even count).
std::string chainText(const std::vector<EffectKind>& chain);
double medianOf(std::vector<double> values);

/// Rows: truth (none, then the catalogue), columns: the dominant effect named; counts.
struct ConfusionMatrix
{
  std::vector<EffectKind> labels;
  std::vector<std::vector<std::size_t>> counts;
  std::size_t truth_in_plausible = 0;  ///< cases whose truth is in the plausible set (none: empty set)
  std::size_t cases = 0;
};

ConfusionMatrix confusionMatrix(const std::vector<WithheldOutcome>& outcomes);

/// Rows: truth, columns: the effects the training data determine; a case counts once in every
/// column it determines.
struct DeterminedTable
{
  std::vector<EffectKind> labels;
  std::vector<std::vector<std::size_t>> counts;
  std::vector<std::size_t> cases_per_truth;
  /// The cases whose hidden effect has a "none" value (neutralValue), so can be determined at all,
  /// and how many of them determine it.
  std::size_t determinable_cases = 0;
  std::size_t truth_determined = 0;
};

DeterminedTable determinedTable(const std::vector<WithheldOutcome>& outcomes);

/// The matrix as a Markdown table, and a per-effect magnitude recovery table (median absolute
/// and relative error of the first parameter over correctly named cases).
std::string formatConfusionMatrix(const ConfusionMatrix& matrix);
std::string formatDeterminedTable(const DeterminedTable& table);
std::string formatMagnitudeRecovery(const std::vector<WithheldOutcome>& outcomes);

/// Semi-real checks: a real data set with a known effect injected into its record
/// (injected_effect.h). The diagnosis should find the injected effect on top of whatever the real
/// runs already have, which the untouched runs' diagnosis (the baseline) measures.
struct SemiRealSet
{
  std::string name;                   ///< e.g. "casale_parts3-6"
  std::vector<CarFollowingRun> runs;  ///< diagnosed together
};

/// One injection: sensor_time_offset or actuation_lag (none: the untouched runs).
struct SemiRealCase
{
  EffectKind injected = EffectKind::none;
  double magnitude = 0.0;  ///< the effect's first parameter [s]
};

/// Clock offsets of -1, -0.5, 0.5, 1, 2 and 3 s (a real run may have one already: an injection
/// of the other sign cancels it), open-loop actuation lags of 0.5, 1, 1.5 and 2 s: from the sizes
/// production ACCs show to well beyond, so that the tables say from which size on an injection is
/// found. No larger lag: it moves tau_e by T (closedLoopLagParameters), and tau_e + T must stay in
/// the fit's box (4 s; the Toyota runs' tau_e is 1.7 s).
std::vector<SemiRealCase> semiRealCaseGrid();

/// Every run with the case's effect injected (the runs as they are for none). Throws
/// std::invalid_argument for an effect that has no injection.
std::vector<CarFollowingRun> injectCase(const std::vector<CarFollowingRun>& runs, const SemiRealCase& c);

/// The diagnosis the semi-real suite makes: forward selection on (the chain is part of the pass
/// rule), no string-stability test (not the question here, and it doubles the cost).
DiagnosisResult diagnoseSemiReal(const std::vector<CarFollowingRun>& runs, const DiagnosisOptions& options);

/// The first parameter of kind as the diagnosis attributes it to the data: from the last model of
/// the forward-selection chain when kind is in it (the joint fit the diagnosis ends with), else
/// from kind's single-effect fit when kind is the dominant effect; nullopt when not selected.
std::optional<double> selectedMagnitude(const DiagnosisResult& result, EffectKind kind);

struct SemiRealOutcome
{
  std::string set_name;
  SemiRealCase input;
  EffectKind dominant = EffectKind::none;
  std::vector<EffectKind> chain;       ///< the forward selection's effects, dominant first
  std::vector<EffectKind> baseline_chain;  ///< the same on the untouched runs
  bool selected = false;               ///< injected effect dominant or in the chain
  /// Injected effect among the diagnosis's determined effects (determined_effects.h): its size
  /// pinned by the training data, whether or not held-out prediction tells it from the base model.
  bool determined = false;
  double fitted_magnitude = 0.0;       ///< selectedMagnitude (NaN when not selected)
  double baseline_magnitude = 0.0;     ///< the untouched runs' selectedMagnitude (0 when not selected)
  double single_fit_magnitude = 0.0;   ///< the injected effect's single-effect fit, selected or not
  double baseline_single_fit_magnitude = 0.0;  ///< the same fit on the untouched runs
  double base_test_rmse_speed_mps = 0.0;
  double seconds = 0.0;                ///< wall time of the diagnosis
  /// What the diagnosis should attribute to the injection in its model's terms: the offset itself;
  /// for a lag T, closedLoopLagReading(T) of the untouched runs' final model (an open-loop lag
  /// reads as T / (1 + T (k1 tau_e + k2)), e.g. 0.69 s for 1 s on the Toyota runs).
  double expected_magnitude = 0.0;
  /// The untouched runs' own estimate of the effect: its value in their final model (the chain's
  /// last), else its single fit's where determined, else none (0).
  double baseline_estimate = 0.0;
  /// Standard error of the injected effect on the untouched runs: how precisely these data
  /// measure it at all. Its single fit's, where that is finite; where the fit sits at a none value
  /// that carries no information (a lag of 0), the one at the expected net size
  /// (calibrateWithEffectHeld there): how precisely the data would measure the effect were it
  /// that large (at_expected_size true). NaN when neither is finite.
  double baseline_standard_error = 0.0;
  bool standard_error_at_expected_size = false;
  /// The z the determined rule asks for (determinedThreshold at the diagnosis's alpha).
  double detection_z = 0.0;

  /// baseline_estimate + expected_magnitude: what the injected runs hold in all.
  double expectedNet() const { return baseline_estimate + expected_magnitude; }
  /// Decided before the injected runs are diagnosed: the net effect stands detection_z standard
  /// errors (of the untouched runs) away from none. Below that the data cannot be asked to find
  /// it (an injection of -0.5 s on runs that have +0.5 s leaves nothing), and a check there asks
  /// only that nothing wrong is named. True where no standard error is finite (no limit is
  /// stated, so the case must be found).
  bool detectable() const;

  /// fitted minus baseline: what the diagnosis attributes to the injection (NaN when not selected).
  double recoveredMagnitude() const { return fitted_magnitude - baseline_magnitude; }
  /// single_fit_magnitude minus baseline_single_fit_magnitude: how far the injection moves the
  /// effect's own fit, whether or not the selection rule names it (the magnitude check without
  /// the held-out significance question).
  double singleFitShift() const { return single_fit_magnitude - baseline_single_fit_magnitude; }
  /// Found: selected by the held-out rule, or else determined by the training data.
  bool found() const { return selected || determined; }
  /// What the diagnosis attributes to the injection: recoveredMagnitude() when selected, else
  /// singleFitShift() when determined (NaN when not found).
  double foundMagnitude() const;
  /// Found, and foundMagnitude() within tolerance (relative) of expected_magnitude.
  bool foundWithin(double tolerance = 0.25) const;
  /// Another effect than the injected one named beyond the untouched runs' chain, or the injected
  /// one named or determined with a size off by more than the tolerance.
  bool misattributed(double tolerance = 0.25) const;
  /// The check: the injection is found within tolerance, or, below the limit, nothing is
  /// misattributed. A detectable injection must be found; one below the limit that is found at
  /// its size passes as it would above the limit.
  bool passed(double tolerance = 0.25) const;
};

/// Diagnoses the injected runs of one case against the set's baseline diagnosis (of the untouched
/// runs, diagnoseSemiReal). A case with injected none reports the baseline itself.
SemiRealOutcome runSemiRealCase(const SemiRealSet& set, const SemiRealCase& c, const DiagnosisResult& baseline,
                                const DiagnosisOptions& options);

/// Markdown: the confusion table (injected effect, none for the baselines, x dominant named) and
/// one row per case with the magnitudes (fitted, baseline, recovered, error) and the verdict.
std::string formatSemiRealTables(const std::vector<SemiRealOutcome>& outcomes);

}  // namespace acc
