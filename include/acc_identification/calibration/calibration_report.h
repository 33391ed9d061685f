#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/euler_step_bias.h"
#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/calibration/grid_search.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/calibration/model_dip_check.h"
#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/calibration/quantity_identifiability.h"
#include "acc_identification/calibration/refit_bootstrap.h"
#include "acc_identification/calibration/string_stability_verdict.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
/// One run of a calibration, scored on its training part and, with a split, on its test part.
struct RunScore
{
  std::string name;
  std::string path;
  FitQuality train;
  std::optional<FitQuality> test;
};

/// Everything the calibrate tool reports.
struct CalibrationReport
{
  MultistartResult calibration;
  std::size_t training_samples = 0;
  ParameterUncertainty uncertainty;
  StringStabilityReport stability;
  std::string identifiability_note;  ///< empty when identifiable
  std::vector<RunScore> runs;
  FitQuality summary_train;
  std::optional<FitQuality> summary_test;
  std::optional<GridSearchResult> grid;
  std::optional<MultistartResult> grid_polished;  ///< local solve from the grid's best node
  /// What the data determine quantity by quantity (of the fit above, on its training data).
  std::optional<IdentifiableQuantities> quantities;
  /// Resampling intervals of the same quantities, made on short data (CalibrateSettings).
  std::optional<RefitBootstrap> refit_bootstrap;
  /// How far the Euler step at the data's rate moves the fit from the continuous law's parameters.
  std::optional<EulerStepBias> euler_step_bias;
  /// Is the ACC string stable, decided on held-out halves even where the parameters are not pinned.
  std::optional<StabilityTestResult> stability_test;
  /// Does the fitted model describe its training data well enough for that verdict to mean anything.
  std::optional<ModelAdequacy> model_adequacy;
  std::string model_adequacy_data;  ///< which data it was judged on, in words
  /// What the runs' own dips say without a model (every run, whole), the fitted model's dips
  /// beside them, and the sentence when the verdict and the dips disagree (empty when not).
  std::optional<PairDipEvidence> dip_evidence;
  std::optional<ModelDipCheck> model_dips;
  std::string verdict_contradiction;
};

/// What valid data that cannot be fitted (steady speed, too short) still decide, for the JSON
/// calibrate writes instead of no file.
struct UnfittedDataSummary
{
  std::string reason;                 ///< why there is no fit
  std::size_t runs = 0;
  std::size_t samples = 0;
  double duration_s = 0.0;            ///< summed over runs
  double follower_speed_mean_mps = 0.0;
  double follower_speed_spread_mps = 0.0;  ///< standard deviation
  double gap_mean_m = 0.0;
  double gap_spread_m = 0.0;
  /// At steady following (follower speed spread below steady_speed_spread_mps) the mean gap IS the
  /// equilibrium gap eta + tau_e v at the mean speed, whatever eta and tau_e are; NaN otherwise.
  double equilibrium_gap_m = 0.0;
  double steady_speed_spread_mps = 0.0;
  /// What the runs' own dips say without a model (pairDipEvidence): decided by the data even
  /// where no model can be fitted.
  std::optional<PairDipEvidence> dip_evidence;
};

/// The summary of the runs, with `reason`. Steady: follower speed spread below steady_speed_spread_mps.
UnfittedDataSummary summarizeUnfittedData(const std::vector<CarFollowingRun>& runs, const std::string& reason,
                                          double steady_speed_spread_mps);

/// {fitted: false, reason, data: {runs, samples, duration_s, follower_speed_mean_mps,
/// follower_speed_spread_mps, gap_mean_m, gap_spread_m, equilibrium_gap_m (null unless steady),
/// equilibrium_gap_note}, parameters: null, stability: null, model_adequacy: null}.
nlohmann::json unfittedToJson(const UnfittedDataSummary& summary);

/// The same in words.
void printUnfitted(const UnfittedDataSummary& summary, std::ostream& out);

/// The --json document. Keys "parameters" (k1_per_s2, k2_per_s, tau_e_s, eta_m),
/// "standard_errors", "stability", "objective", "runs", "summary" are read by other tools;
/// "identifiable_quantities", "refit_bootstrap" (refit_bootstrap.h) and "stability_test" (string_stability_verdict.h) when they were computed;
/// "fitted": true; "model_adequacy" (model_adequacy.h) when assessed. stability.string_stable is
/// null where lambda2 is NaN.
nlohmann::json reportToJson(const CalibrationReport& report);

/// The tables of the paper's Tables I and II: per run and summary RMSEs, then the parameters
/// with standard errors, lambda2 and the verdict.
void printReport(const CalibrationReport& report, std::ostream& out);

}  // namespace acc
