#pragma once

#include <initializer_list>
#include <iosfwd>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// When a quantity counts as determined by the data: its standard error is at most
/// `max_relative_error` times its scale, the scale being max(|value|, floor). The floors keep a
/// quantity whose value is near 0 from being called undetermined just for that (tau_e = 0.05 +- 0.1 s
/// is determined; tau_e = 0 +- 0.67 s is not).
struct QuantityCriteria
{
  /// k1, k2, tau_e, eta: determined when the standard error is at most this fraction of
  /// max(|value|, floor) (the identifier node's ~max_relative_standard_error).
  double max_relative_error_parameter = 0.5;
  AccParameters parameter_scale_floor{0.01, 0.05, 0.2, 1.0};
  /// The equilibrium gap eta + tau_e v: known to 10 % (and the floor: 2 m).
  double max_relative_error_gap = 0.1;
  double gap_scale_floor_m = 2.0;
  /// The stability margin m = k1 tau_e^2 + 2 k2 tau_e - 2: its scale is 2 (m runs from -2 for
  /// tau_e = 0 upwards); determined when its standard error is at most a quarter of that.
  double max_error_margin = 0.5;
  /// A parameter within this fraction of its range from a bound of the fit sits at that bound (an
  /// optimiser stops on an active bound, not near it; as ModelAdequacyOptions::bound_fraction).
  double bound_fraction = 0.001;
};

/// One derived quantity of a fit.
struct QuantityEstimate
{
  std::string name;      ///< "k1", "k2", "tau_e", "eta", "equilibrium_gap_at_min_speed", ..., "stability_margin"
  std::string unit;
  double value = 0.0;    ///< the fit's value (always finite for a finite fit)
  double standard_error = 0.0;  ///< delta method from the sandwich covariance; NaN when that is singular
  double speed_mps = 0.0;       ///< for the equilibrium gaps: the follower speed it is taken at; else NaN
  bool determined = false;
  std::string reason;    ///< why determined or not, with the threshold
  /// Held at a bound of the fit's range: "tau_e at its lower bound 0" when every parameter the
  /// quantity moves with (beyond 1 % of its delta-method variance) sits at a bound; empty when it
  /// is free. The estimate then never falls beyond the bound, so value +- standard_error is no
  /// interval (tau_e = 0 +- 0.54 s, margin -2 +- 0.38 where -2 is the least margin there is).
  std::string held_by_bound;
  /// With held_by_bound: the 95 % interval's other end, on the range's side of the value. A
  /// parameter fitted at its bound b with standard error se is at b with probability >= 5 % for
  /// true values up to b + t se (the fit is the bound whenever the unconstrained one falls beyond
  /// it: Self & Liang 1987, a one-sided test at the boundary), so the quantity is evaluated with
  /// each held parameter moved t se into the range (clamped to it); t is Student's one-sided 95 %
  /// quantile with the sandwich's blocks - 1 degrees of freedom (1.895 for 8 blocks), the normal
  /// 1.645 when the blocks are not known. NaN without a standard error.
  double one_sided_limit = std::numeric_limits<double>::quiet_NaN();
  /// The 95 % interval [low, high]: boundInterval() where held at a bound; elsewhere value +- t
  /// standard errors, t Student's two-sided 95 % quantile with the sandwich's blocks - 1 degrees of
  /// freedom (2.228 for 11 blocks; 1.96 when the blocks are not known): batch means over B blocks
  /// carry B - 1 of them; cut at the quantity's range over the fit's bounds (a time gap never
  /// below 0, a margin never below -2). NaN without a standard error. On short drives even these
  /// run short
  /// (docs/RESULTS.md, "What the standard errors cover"); calibrate then adds the refitting
  /// bootstrap's (refit_bootstrap.h).
  double interval_95_low = std::numeric_limits<double>::quiet_NaN();
  double interval_95_high = std::numeric_limits<double>::quiet_NaN();

  /// Held at a bound with a one-sided limit to show (not without a standard error).
  bool hasBoundInterval() const;
  /// [low, high] of the 95 % interval at a bound: the value and the one-sided limit, ordered.
  std::pair<double, double> boundInterval() const;
};

/// What the data determine, quantity by quantity.
struct IdentifiableQuantities
{
  std::vector<QuantityEstimate> quantities;  ///< in the order of the names above
  double reciprocal_condition = 0.0;         ///< of J^T J (fit_statistics), for the report
  std::string basis;                         ///< which fit and data the standard errors come from
  /// The gap's sample-to-sample noise the covariance's start-gap term took (fit_statistics.h) [m],
  /// and eta's standard error from that term alone [m]; NaN and 0 when it was left out.
  double start_gap_noise_m = std::numeric_limits<double>::quiet_NaN();
  double eta_start_gap_error_m = 0.0;

  /// The quantity of this name, or nullptr.
  const QuantityEstimate* find(const std::string& name) const;
};

/// The factor of a standard error from batch means over `blocks` blocks that makes a two-sided
/// 95 % interval, value +- factor x standard error: Student's t with blocks - 1 degrees of freedom
/// (2.228 for 11 blocks, 2.365 for 8), the normal 1.96 when fewer than two blocks are known.
double intervalFactor95(std::size_t blocks);

/// Whether every named quantity is assessed and determined. lambda2, the amplified band and the
/// peak need {"k1", "k2", "tau_e"} (eta does not enter the linearised dynamics); "identifiable"
/// needs those and "eta".
bool allDetermined(const IdentifiableQuantities& quantities, std::initializer_list<const char*> names);

/// Value, standard error (delta method with the covariance of estimateUncertainty()), determined
/// and reason for k1, k2, tau_e, eta, the equilibrium gap eta + tau_e v at the lowest, the mean
/// and the highest follower speed in `runs` (the data the fit saw), and the margin
/// m = k1 tau_e^2 + 2 k2 tau_e - 2 (gradient (tau^2, 2 tau, 2 k1 tau + 2 k2, 0)). A quantity
/// held at a bound of `bounds` (the fit's) gets its one-sided interval (held_by_bound); whether
/// it is determined is still its standard error against the threshold.
/// Typical use: assessQuantities(id.calibration.parameters, id.uncertainty, segments, options.bounds).
IdentifiableQuantities assessQuantities(const AccParameters& fit, const ParameterUncertainty& uncertainty,
                                        const std::vector<CarFollowingRun>& runs, const ParameterBounds& bounds,
                                        const QuantityCriteria& criteria = {});

/// {"basis", "reciprocal_condition", "start_gap_noise_m", "eta_start_gap_error_m", "quantities": {name: {value, standard_error, unit, determined,
/// reason (with the threshold applied), interval_95: [low, high] (null without a standard
/// error)[, speed_mps][, held_by_bound]}}}; NaN as null.
nlohmann::json toJson(const IdentifiableQuantities& quantities);

/// One line per quantity: value +- standard error and its 95 % interval where determined ("low to
/// high" and the bound where held at one); where not, the same in parentheses and the reason.
void printQuantities(const IdentifiableQuantities& quantities, std::ostream& out);

}  // namespace acc
