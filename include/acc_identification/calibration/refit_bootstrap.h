#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/calibration/quantity_identifiability.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// The fewest refits with a standard error that give a 95 % interval: 39, the fewest whose 2.5 %
/// tails each hold a refit ((39 + 1) x 0.025 = 1). With fewer the tails are extrapolated from the
/// extreme refits (with one refit the "interval" is a point).
constexpr std::size_t kMinRefitsFor95Interval = 39;

/// How the refitting bootstrap runs.
struct RefitBootstrapOptions
{
  std::size_t replicates = 199;
  std::uint64_t seed = 20261202;
  /// Halton starts of each refit beside the warm start at the fit: a replicate whose best fit lies
  /// in another basin must be able to reach it, or the spread is understated.
  std::size_t starts = 20;
  ParameterBounds bounds;  ///< of the base model's refits (bootstrapRefits)
  std::size_t threads = 0;  ///< 0: hardware_concurrency
};

/// One quantity's bootstrap interval.
struct BootstrapQuantity
{
  std::string name;      ///< "k1", "k2", "tau_e", "eta", "stability_margin"; a diagnosed model's parameter names
  double value = 0.0;    ///< the fit's
  /// The spread of the refits: their standard deviation, and their mean less the fit's value (the
  /// estimator's bias on data like these, which the delta method cannot see).
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  double bias = std::numeric_limits<double>::quiet_NaN();
  /// The sandwich standard error at the fit, which scales the interval, and the median of the
  /// refits' own: where the fit's is several times the refits' (TOYOTA_RAV4 at L: a delay of 0.57 s
  /// against 0.063 s, spread 0.24 s), the data pin the quantity less well than drives of the
  /// fitted model do, and the interval follows the data's (docs/PLATOON_DIAGNOSIS.md).
  double fit_standard_error = std::numeric_limits<double>::quiet_NaN();
  double refits_standard_error_median = std::numeric_limits<double>::quiet_NaN();
  /// The 95 % interval, bootstrap-t: value - t*_0.975 se, value - t*_0.025 se, with se the fit's
  /// sandwich standard error and t*_q the q-quantile of (refit - value) / (refit's own sandwich
  /// standard error), cut at the range the fit searched. NaN where held at a bound of the fit or
  /// within 1.96 standard errors of one (the bootstrap is not valid there: Andrews 2000; near a
  /// bound the refits' own standard errors say little, and the interval came out narrower than
  /// their spread), or where fewer than half the refits, or fewer than kMinRefitsFor95Interval,
  /// have a standard error.
  double interval_95_low = std::numeric_limits<double>::quiet_NaN();
  double interval_95_high = std::numeric_limits<double>::quiet_NaN();
  std::string note;      ///< why there is no interval; empty with one
  bool hasInterval() const { return std::isfinite(interval_95_low) && std::isfinite(interval_95_high); }
};

struct RefitBootstrap
{
  std::size_t replicates = 0;         ///< asked for
  std::size_t refitted = 0;           ///< replicates whose refit did not diverge (the rest are left out, counted)
  double block_length_s = 0.0;        ///< of the resampled residuals (the fit's batch-means block)
  std::vector<BootstrapQuantity> quantities;
  std::string note;                   ///< why no bootstrap was made; empty when one was
  /// The parameter of the fit that sits at or near a bound ("name = value at its lower bound L",
  /// or "... within 1.96 standard errors ... of ..."), "" when none: its refits pile up there, and
  /// the bootstrap's intervals of the others are then approximate (Andrews 2000).
  std::string held_near_bound;
  double wall_time_s = 0.0;               ///< wall time
  /// What held_near_bound means for the intervals, in a sentence; "" when nothing is.
  std::string caution() const;
  /// The quantity of this name, or nullptr.
  const BootstrapQuantity* find(const std::string& name) const;
  /// A bootstrap of `replicates` not made, and why (RefitBootstrap::note).
  static RefitBootstrap notMade(std::size_t replicates, const std::string& why);
};

/// One fit as the bootstrap sees it, quantity by quantity: its value, its sandwich standard error
/// (NaN: none) and, when the fit holds it at a bound, why ("" otherwise).
struct BootstrapDraw
{
  std::vector<double> value;
  std::vector<double> standard_error;
  std::vector<std::string> held_by_bound;
};

/// A fitted follower model on its runs, as the residual bootstrap needs it; any model the package
/// fits (the base law, or the diagnosis's final model with its effects).
struct FittedDrives
{
  std::vector<std::string> quantity_names;
  /// The first parameter_count quantities are the fit's parameters (one at a bound makes every
  /// interval approximate); the rest follow from them (the stability margin).
  std::size_t parameter_count = 0;
  BootstrapDraw at_fit;
  /// Per run, the fit's simulation from the measured start, driven by the measured leader.
  std::vector<std::vector<double>> simulated_speed_mps;
  double block_length_s = 0.0;  ///< of the resampled residuals: the fit's batch-means block
  /// The range of each quantity the fit searched (shorter lists or NaN: unbounded): an interval is
  /// cut there.
  std::vector<double> lower_bound;
  std::vector<double> upper_bound;
  /// Appended to the note of a quantity held at a bound: where else to look.
  std::string at_bound_hint;
};

/// The fitted model's simulation of each run (from the measured start, driven by the measured
/// leader) into fitted.simulated_speed_mps: "" when made, else why not (a run whose simulation
/// diverges), for RefitBootstrap::note.
std::string simulateFittedDrives(const AccParameters& parameters, const EffectSettings& effects,
                                 const std::vector<CarFollowingRun>& runs, FittedDrives& fitted);

/// The refit of one replicate's runs, exactly as the data were fitted; nullopt when it diverged.
using ReplicateRefit = std::function<std::optional<BootstrapDraw>(const std::vector<CarFollowingRun>& replicate)>;

/// The residual bootstrap of any fitted model (bootstrapRefits below for the method): replicate
/// drives from `fitted`'s simulations and resampled residuals, each refitted by `refit` (called
/// from options.threads threads at once). options.starts and options.bounds are not used here.
RefitBootstrap bootstrapFittedDrives(const FittedDrives& fitted, const std::vector<CarFollowingRun>& runs,
                                     const ReplicateRefit& refit, const RefitBootstrapOptions& options);

/// A resampling interval for the fit `fit` of `runs` (the calibration's multistart optimum), for
/// drives too short for the sandwich standard errors (a minute of data fits nonlinearly in its
/// noise: docs/RESULTS.md, "What the standard errors cover").
///
/// Each replicate is a drive the fitted model could have given: per run, the fit's own simulation
/// (simulateFollower from the measured start, driven by the measured leader) plus the run's speed
/// residuals, centred and resampled in circular blocks (the fit's batch-means block length, so
/// that their correlation in time is kept), the start speed included; the run's gap is shifted by
/// a normal draw of its sample noise (gapSampleNoiseM), the error the start gap puts on eta. Each
/// replicate is refitted exactly as the data were (calibrateMultistart from the fit and `starts`
/// Halton points), and its sandwich standard errors are computed, so that the interval is the
/// studentised (bootstrap-t) one: second-order accurate where value +- t se is first-order, and it
/// carries the estimator's bias and skew. Seeded: the same seed gives the same intervals on every
/// platform and with any number of threads. Cost: replicates x (one multistart calibration of
/// `starts` points); bench/bench_calibration.cpp (BM_RefitBootstrap).
RefitBootstrap bootstrapRefits(const AccParameters& fit, const std::vector<CarFollowingRun>& runs,
                               const RefitBootstrapOptions& options = {});

/// A replicate's base model refitted as bootstrapRefits refits it: multistart from the fit and
/// options.starts Halton points in options.bounds.
MultistartResult refitBaseModel(const AccParameters& fit, const std::vector<CarFollowingRun>& replicate,
                                const RefitBootstrapOptions& options);

/// One line per quantity: the fit's value, the bootstrap-t 95 % interval, the refits' spread and
/// bias; or why there is none.
void printRefitBootstrap(const RefitBootstrap& bootstrap, std::ostream& out);

/// {"replicates", "refitted", "block_length_s", "wall_time_s", "note", "caution", "quantities": {name: {value,
/// standard_error, bias, fit_standard_error, refits_standard_error_median, interval_95: [low, high] or null,
/// note}}}; NaN as null.
nlohmann::json toJson(const RefitBootstrap& bootstrap);

}  // namespace acc
