#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// Does the fitted model describe the data well enough for its string-stability verdict to mean
/// anything? A test that compares the best stable and the best unstable version of a model that
/// misses the gap by 40 m answers the wrong question: this says so before the verdict is read.
///
/// Every threshold below was set on measurements (docs/RESULTS.md, "Model adequacy"): synthetic
/// drives made by the model itself pass every check; a synthetic drive whose ACC also cruises at
/// a set speed, and the 25-minute Casale part 6, fail.
struct ModelAdequacyOptions
{
  /// (a) Space gap: inadequate when the gap RMSE (each run simulated from its measured start)
  /// exceeds this fraction of the measured gap's standard deviation AND the absolute floor below.
  /// A model that tracks the gap explains most of its variation; one that drifts away from it
  /// (set-speed cruising, a speed-dependent time gap) has an RMSE of the order of the spread.
  double max_gap_rmse_over_spread = 0.5;
  /// The gap RMSE under which no gap is called missed, whatever its spread: GNSS gaps carry about
  /// 0.5 m of noise and a good fit drifts by a few metres over minutes (on steady driving the
  /// spread itself is that small).
  double gap_rmse_floor_m = 3.0;
  /// (a) Follower speed: the same with the speed RMSE and the follower speed's spread (0.5: the
  /// model leaves more than a quarter of the speed's variance). A floor of 0.3 m/s: five times the
  /// GNSS Doppler noise (~0.06 m/s).
  double max_speed_rmse_over_spread = 0.5;
  double speed_rmse_floor_mps = 0.3;
  /// (b) A parameter within this fraction of its range [lower, upper] of ParameterBounds from a
  /// bound (an optimiser stops on an active bound, not near it): the optimum is held by the bound,
  /// not by the data (eta at its 50 m upper bound is how a missing set speed shows on Casale) ...
  double bound_fraction = 0.001;
  /// ... provided the data pin the parameter there: its standard error (when given) below this
  /// fraction of the range. tau_e = 0 +- 1.2 s at ZalaZone's short setting (one speed band, where
  /// tau_e and eta trade off) is a parameter the data do not determine, not a model that misses.
  double max_standard_error_at_bound_fraction = 0.1;
  /// (c) Residual structure: the speed residual's correlation time (first lag where its
  /// autocorrelation falls below 1/e) over the model's own response time (1 / the slowest decay
  /// rate of its linearised closed loop). Residuals of a right model are leader-noise filtered by
  /// that loop, a few response times long; a slow systematic miss lasts far longer.
  double max_correlation_over_response_time = 10.0;
  /// (d) Dips of perturbations (campaign): inadequate when the median |predicted - measured| /
  /// measured dip over at least min_dip_perturbations car-perturbations exceeds this (the platoon
  /// check's own max_relative_dip_error).
  double max_median_dip_error = 0.3;
  std::size_t min_dip_perturbations = 3;
  ParameterBounds bounds;
};

/// The numbers every check was decided on (NaN where a check could not be made).
struct AdequacyChecks
{
  std::size_t samples = 0;
  double gap_rmse_m = std::numeric_limits<double>::quiet_NaN();
  double gap_spread_m = std::numeric_limits<double>::quiet_NaN();  ///< standard deviation of the measured gap
  double speed_rmse_mps = std::numeric_limits<double>::quiet_NaN();
  double speed_spread_mps = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> parameters_at_bound;  ///< "eta_m at its upper bound 50"
  double residual_correlation_time_s = std::numeric_limits<double>::quiet_NaN();
  double model_response_time_s = std::numeric_limits<double>::quiet_NaN();
  /// The dip check (campaign only): car-perturbations scored and their median relative error.
  std::size_t dip_perturbations = 0;
  double median_dip_error = std::numeric_limits<double>::quiet_NaN();
};

struct ModelAdequacy
{
  bool assessed = false;  ///< false: no model or no data to judge (reasons says why)
  bool adequate = false;
  /// One short sentence with its numbers per failed check (empty when adequate), or why the
  /// adequacy was not assessed.
  std::vector<std::string> reasons;
  AdequacyChecks checks;
};

/// Which bound of the range [lower, upper] a fitted value is held by: within bound_fraction of the
/// range from that end (an optimiser stops on an active bound, not exactly at it). One rule for the
/// adequacy checks, the quantities' one-sided limits, the bootstraps and the determined effects.
enum class BoundSide
{
  inside,
  lower,
  upper
};
BoundSide boundSide(double value, double lower, double upper, double bound_fraction);

/// "name = value at its lower bound L" (or upper) when value lies within bound_fraction of the range
/// [lower, upper] from one of its ends, else "": a parameter held by the bound of a fit, in one
/// rule and one wording for the adequacy checks and the bootstraps of diagnosed models.
std::string atBoundText(const std::string& name, double value, double lower, double upper, double bound_fraction);

/// Checks (a)-(c) of the model p on the runs: each run simulated from its measured start
/// (evaluateFit), gap and speed spreads pooled over the runs, the residual correlation time over
/// all runs. Never throws: runs that cannot be simulated give "not assessed" with the reason.
/// standard_errors: of p (NaN where unknown, then that parameter is not judged at a bound);
/// without them every parameter at a bound is.
ModelAdequacy assessModelAdequacy(const AccParameters& p, const std::vector<CarFollowingRun>& runs,
                                  const ModelAdequacyOptions& options = {},
                                  const std::optional<AccParameters>& standard_errors = std::nullopt);

/// The same for the model with unmodelled effects (the diagnosis's augmented models); the bound
/// check (b) then covers the four base parameters only, and the response time is the base law's.
ModelAdequacy assessModelAdequacy(const AccParameters& p, const EffectSettings& effects,
                                  const std::vector<CarFollowingRun>& runs, const ModelAdequacyOptions& options = {},
                                  const std::optional<AccParameters>& standard_errors = std::nullopt);

/// Adds check (d) from the dips of perturbations: median |predicted - measured| / measured dip
/// over `perturbations` car-perturbations (not decided below options.min_dip_perturbations).
void addDipCheck(ModelAdequacy& adequacy, std::size_t perturbations, double median_dip_error,
                 const ModelAdequacyOptions& options = {});

/// 1 / the slowest decay rate of the model's linearised closed loop s'' + (k2 + k1 tau_e) s' + k1 s
/// = 0 [s]; 1 / k2 when k1 = 0; +inf when nothing decays.
double modelResponseTimeS(const AccParameters& p);

/// The first lag at which the pooled autocorrelation of the residuals (within segments; times
/// and residuals per segment) falls below 1/e [s]; +inf when it never does up to a quarter of
/// the longest segment; NaN without residuals.
double residualCorrelationTimeS(const std::vector<std::vector<double>>& segment_times,
                                const std::vector<std::vector<double>>& segment_residuals);

/// {assessed, adequate (null when not assessed), reasons, checks: {...}}.
nlohmann::json toJson(const ModelAdequacy& adequacy);

/// "ADEQUATE", "NOT ADEQUATE (gap RMSE 40.1 m against a gap spread of 12.0 m; eta_m at its upper
/// bound 50)" or "not assessed (why)".
std::string describeAdequacy(const ModelAdequacy& adequacy);

}  // namespace acc
