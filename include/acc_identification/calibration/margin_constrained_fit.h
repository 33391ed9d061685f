#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
/// d m / d (k1, k2, tau_e) = (tau_e^2, 2 tau_e, 2 k1 tau_e + 2 k2).
std::array<double, 3> stabilityMarginGradient(const AccParameters& p);

/// The least and the largest margin of any (k1, k2, tau_e) within the bounds (m grows in each of
/// them on the non-negative orthant): m(lower) and m(upper); -2 and 78 for the default bounds.
double leastMargin(const ParameterBounds& bounds);
double largestMargin(const ParameterBounds& bounds);

/// Which side of a margin a fit must keep to.
enum class MarginSide
{
  AtLeast,  ///< m >= margin: with margin 0, the string-stable models
  AtMost,   ///< m <= margin: with margin 0, the string-unstable models (and the boundary)
  EqualTo   ///< m == margin: one point of the profile of the objective over m
};

/// Points with margin `target` near p, each obtained by changing one parameter: tau_e alone (the
/// positive root of k1 tau^2 + 2 k2 tau = 2 + target), then k2 alone, then k1 alone; only those
/// within the bounds. Empty when none is. The closed form leaves the margin a few ulps off target;
/// the changed parameter is then moved by ulps so that the margin is >= target for AtLeast,
/// <= target for AtMost, and for EqualTo >= target when target >= 0 and <= target when target < 0
/// (a point aimed at the boundary m = 0 is then string stable).
std::vector<AccParameters> projectOntoMargin(const AccParameters& p, double target, const ParameterBounds& bounds,
                                             MarginSide side = MarginSide::EqualTo);

/// How a margin-constrained fit searches.
struct ConstrainedFitOptions
{
  /// Halton starting points in the start box (as calibrateMultistart's); each infeasible one is
  /// first projected onto the constraint (projectOntoMargin). 0: warm starts only.
  std::size_t starts = 30;
  AccParameters start_box_lower{0.0, 0.0, 0.0, 0.0};
  AccParameters start_box_upper{0.5, 1.5, 3.0, 0.0};
  /// Local solves from the Halton starts, best first, skipping a start within cluster_radius (in
  /// units of the start box) of a better one (multi-level single linkage).
  std::size_t max_local_solves = 4;
  /// Local solves from the warm starts (after projection), best first; 0: from every one.
  std::size_t max_warm_solves = 0;
  double cluster_radius = 0.2;
  /// Per local solve: NLopt LD_SLSQP on variables scaled by the start box, the margin as a
  /// nonlinear constraint with its exact gradient, the objective's exact gradient.
  int max_evaluations_per_solve = 150;
  double relative_x_tolerance = 1e-7;
  double relative_f_tolerance = 1e-10;
  /// A point counts as feasible while it violates the constraint by at most this much in m; the
  /// best such point is then moved onto the constraint exactly (projectOntoMargin) and re-scored.
  double feasibility_tolerance = 1e-6;

  /// A refit near a known answer: no Halton starts, warm_solves local solves from the best warm
  /// starts, at most max_evaluations each, relative f tolerance 1e-8 (the margin profile's and
  /// the sequential verdict's refits).
  static ConstrainedFitOptions warmStartsOnly(std::size_t warm_solves, int max_evaluations);
};

/// The best fit found under a margin constraint.
struct ConstrainedFitResult
{
  bool found = false;            ///< a feasible, non-divergent point was found (else the rest is unset)
  AccParameters parameters;      ///< eta at its closed-form optimum for (k1, k2, tau_e)
  /// stabilityMargin(parameters): satisfies an inequality exactly; within a few ulps of an equality
  double margin = 0.0;
  double rmse_speed_mps = 0.0;   ///< on the objective's data
  std::string status;            ///< NLopt's stop reason of the solve that found the best point
  std::size_t local_solves = 0;
  std::size_t evaluations = 0;   ///< objective passes in total
};

/// Minimises the objective's speed RMSE over (k1, k2, tau_e) within its bounds subject to
/// m (>= | <= | ==) margin, from the warm starts (each projected onto the constraint when it
/// violates it: for a constrained optimum on the boundary, the unconstrained optimum's projections
/// are the natural starts) and from options.starts Halton points. Never throws on data problems;
/// never returns NaN.
ConstrainedFitResult fitWithMarginConstraint(const CalibrationObjective& objective, MarginSide side, double margin,
                                             const ConstrainedFitOptions& options,
                                             const std::vector<AccParameters>& warm_starts = {});

}  // namespace acc
