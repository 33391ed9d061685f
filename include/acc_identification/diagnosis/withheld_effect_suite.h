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
};

WithheldOutcome runWithheldCase(const WithheldCase& c, const DiagnosisOptions& options);

/// The grid of cases: every effect at several magnitudes and none, on the given profiles, noise
/// scales and seeds. magnitudes_per_effect picks from a fixed list per effect (1 to 3).
std::vector<WithheldCase> withheldCaseGrid(std::size_t magnitudes_per_effect,
                                           const std::vector<SyntheticLeadProfile>& profiles,
                                           const std::vector<double>& noise_scales, std::size_t seeds);

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

/// The matrix as a Markdown table, and a per-effect magnitude recovery table (median absolute
/// and relative error of the first parameter over correctly named cases).
std::string formatConfusionMatrix(const ConfusionMatrix& matrix);
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
/// of the other sign cancels it), actuation lags of 0.5, 1, 2 and 3 s: from the sizes production
/// ACCs show to well beyond, so that the tables say from which size on an injection is named.
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
  /// Found, and foundMagnitude() within tolerance (relative) of the injected magnitude.
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
