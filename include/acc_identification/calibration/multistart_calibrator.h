#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/calibration/calibration_objective.h"

namespace acc
{
/// How the multistart search runs.
struct MultistartOptions
{
  /// Low-discrepancy starting points (Halton) in the start box, as the paper's 100 random starts.
  std::size_t starts = 100;
  /// Where starting (k1, k2, tau_e) are drawn: the region where ACC fits are found, narrower than
  /// the bounds so that starts are not wasted on sluggish or violent corners.
  AccParameters start_box_lower{0.0, 0.0, 0.0, 0.0};
  AccParameters start_box_upper{0.5, 1.5, 3.0, 0.0};
  /// Per local solve (NLopt LD_LBFGS on scaled variables, bounds respected).
  int max_evaluations_per_start = 200;
  double relative_x_tolerance = 1e-7;
  double relative_f_tolerance = 1e-12;
  /// A local solve stops early when it comes within join_radius (in units of the start box) of a
  /// minimum that an earlier solve converged to, with an MSE within join_relative_mse of that
  /// minimum's: the rest of it would retrace that solve. (Clustering multistart, as in
  /// Rinnooy Kan and Timmer's multi-level single linkage.) join_radius = 0 turns this off.
  double join_radius = 0.05;
  double join_relative_mse = 0.1;
  /// Every start is evaluated first; a local solve runs from a start only when no better start
  /// lies within cluster_radius (in units of the start box): the better one's solve covers that
  /// basin (multi-level single linkage). Warm starts are always solved. 0 solves from every start.
  double cluster_radius = 0.2;
  /// Called after each local solve with (done, total); for progress display. May be empty.
  std::function<void(std::size_t, std::size_t)> progress;
};

/// Result of a multistart calibration.
struct MultistartResult
{
  AccParameters parameters;           ///< the best point seen over all starts and evaluations
  double rmse_speed_mps = 0.0;        ///< sqrt of the objective there
  bool diverged = false;              ///< true only if every start diverged (then no fit exists)
  std::string status;                 ///< NLopt's stop reason of the local solve that found the best
  std::size_t starts = 0;             ///< starting points evaluated (warm starts included)
  std::size_t local_solves = 0;       ///< local solves run
  std::size_t clustered_starts = 0;   ///< starts not solved: a better start lies close
  std::size_t local_minima = 0;       ///< distinct local minima the solves converged to
  std::size_t divergent_starts = 0;   ///< starts whose simulation diverged and were pulled back
  std::size_t joined_starts = 0;      ///< solves stopped on reaching an already known minimum
  std::size_t evaluations = 0;        ///< objective passes in total
  std::size_t best_start = 0;         ///< index of the start that led to the best (warm starts first)
  double solve_time_s = 0.0;          ///< wall time of the whole search
};

/// Minimises the speed RMSE over (k1, k2, tau_e) within the bounds (eta in closed form) from the
/// warm starts (e.g. the previous window's fit) and then from options.starts Halton points
/// (those with a better start close by are left to that start's solve).
/// A start whose simulation diverges is moved halfway towards a well-damped reference
/// (k1 0.05, k2 0.5, tau_e 1.5) until it does not (counted in divergent_starts). Every objective
/// evaluation is tracked, so the result is never worse than any start, and never NaN.
MultistartResult calibrateMultistart(const CalibrationObjective& objective, const MultistartOptions& options,
                                     const std::vector<AccParameters>& warm_starts = {});

/// The i-th point (i >= 1) of the Halton sequence in bases 2, 3, 5, in [0, 1)^3
/// (haltonSequencePoint of model/halton_sequence.h, as an array).
std::array<double, 3> haltonPoint(std::size_t index);

}  // namespace acc
