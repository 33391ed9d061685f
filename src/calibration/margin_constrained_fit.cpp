#include "acc_identification/calibration/margin_constrained_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlopt.hpp>

#include "acc_identification/calibration/multistart_calibrator.h"

namespace acc
{
ConstrainedFitOptions ConstrainedFitOptions::warmStartsOnly(std::size_t warm_solves, int max_evaluations)
{
  ConstrainedFitOptions options;
  options.starts = 0;
  options.max_local_solves = 0;
  options.max_warm_solves = warm_solves;
  options.max_evaluations_per_solve = max_evaluations;
  options.relative_f_tolerance = 1e-8;
  return options;
}

namespace
{
bool withinBounds(const AccParameters& p, const ParameterBounds& bounds)
{
  return p.k1_per_s2 >= bounds.lower.k1_per_s2 && p.k1_per_s2 <= bounds.upper.k1_per_s2 &&
         p.k2_per_s >= bounds.lower.k2_per_s && p.k2_per_s <= bounds.upper.k2_per_s &&
         p.tau_e_s >= bounds.lower.tau_e_s && p.tau_e_s <= bounds.upper.tau_e_s;
}

/// True when m is on the side of target that projectOntoMargin promises.
bool onPromisedSide(double m, double target, MarginSide side)
{
  switch (side)
  {
    case MarginSide::AtLeast: return m >= target;
    case MarginSide::AtMost: return m <= target;
    case MarginSide::EqualTo: return target >= 0.0 ? m >= target : m <= target;
  }
  return false;
}

/// Moves the one changed parameter by ulps until the margin is on the promised side (rounding of
/// the closed form leaves it a few ulps off). The margin does not decrease in any parameter.
bool nudgeOntoSide(AccParameters& p, double AccParameters::*changed, double target, MarginSide side)
{
  const bool up = side == MarginSide::AtLeast || (side == MarginSide::EqualTo && target >= 0.0);
  const double direction = up ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
  for (int attempt = 0; attempt < 64; ++attempt)
  {
    if (onPromisedSide(stabilityMargin(p), target, side))
    {
      return true;
    }
    p.*changed = std::nextafter(p.*changed, direction);
  }
  return onPromisedSide(stabilityMargin(p), target, side);
}

/// The search variables are theta / scale (the start box), so that a unit step means the same in
/// every direction, as in calibrateMultistart.
struct SearchState
{
  const CalibrationObjective* objective = nullptr;
  std::array<double, 3> scale{};
  MarginSide side = MarginSide::AtLeast;
  double margin = 0.0;
  double feasibility_tolerance = 0.0;
  double objective_scale = 1.0;  ///< the objective is divided by it, so that SLSQP sees values near 1
  std::size_t evaluations = 0;
  double best_mse = std::numeric_limits<double>::infinity();
  std::array<double, 3> best_theta{};
  bool improved_in_this_solve = false;
};

AccParameters toParameters(const std::array<double, 3>& theta)
{
  return AccParameters{theta[0], theta[1], theta[2], 0.0};
}

double violation(const SearchState& state, const std::array<double, 3>& theta)
{
  const double m = stabilityMargin(toParameters(theta));
  switch (state.side)
  {
    case MarginSide::AtLeast: return std::max(0.0, state.margin - m);
    case MarginSide::AtMost: return std::max(0.0, m - state.margin);
    case MarginSide::EqualTo: return std::abs(m - state.margin);
  }
  return 0.0;
}

double nloptObjective(unsigned, const double* x, double* gradient, void* data)
{
  auto& state = *static_cast<SearchState*>(data);
  const std::array<double, 3> theta{x[0] * state.scale[0], x[1] * state.scale[1], x[2] * state.scale[2]};
  const ReducedObjectiveValue value = state.objective->evaluate(theta[0], theta[1], theta[2], gradient != nullptr);
  ++state.evaluations;
  if (gradient != nullptr)
  {
    for (int i = 0; i < 3; ++i)
    {
      gradient[i] = value.gradient[i] * state.scale[i] / state.objective_scale;
    }
  }
  if (!value.diverged && value.mse_speed_mps2 < state.best_mse &&
      violation(state, theta) <= state.feasibility_tolerance)
  {
    state.best_mse = value.mse_speed_mps2;
    state.best_theta = theta;
    state.improved_in_this_solve = true;
  }
  return value.mse_speed_mps2 / state.objective_scale;
}

/// NLopt's constraint c(x) <= 0 (or == 0): sign * (m - margin), with sign -1 for m >= margin.
struct ConstraintData
{
  const SearchState* state = nullptr;
  double sign = 1.0;
};

double nloptConstraint(unsigned, const double* x, double* gradient, void* data)
{
  const auto& constraint = *static_cast<ConstraintData*>(data);
  const SearchState& state = *constraint.state;
  const AccParameters p{x[0] * state.scale[0], x[1] * state.scale[1], x[2] * state.scale[2], 0.0};
  if (gradient != nullptr)
  {
    const auto dm = stabilityMarginGradient(p);
    for (int i = 0; i < 3; ++i)
    {
      gradient[i] = constraint.sign * dm[i] * state.scale[i];
    }
  }
  return constraint.sign * (stabilityMargin(p) - state.margin);
}

std::string solveLocally(nlopt::opt& local, SearchState& state, const std::array<double, 3>& theta)
{
  std::vector<double> x{theta[0] / state.scale[0], theta[1] / state.scale[1], theta[2] / state.scale[2]};
  state.improved_in_this_solve = false;
  try
  {
    double f = 0.0;
    // NLopt's own name of the result ("SUCCESS", "MAXEVAL_REACHED", "ROUNDOFF_LIMITED", ...).
    return nlopt_result_to_string(static_cast<nlopt_result>(local.optimize(x, f)));
  }
  catch (const nlopt::roundoff_limited&)
  {
    return "ROUNDOFF_LIMITED";  // the best feasible point seen is kept
  }
  catch (const std::exception& error)
  {
    return std::string("FAILURE: ") + error.what();
  }
}

bool satisfies(MarginSide side, double m, double margin)
{
  switch (side)
  {
    case MarginSide::AtLeast: return m >= margin;
    case MarginSide::AtMost: return m <= margin;
    case MarginSide::EqualTo: return true;  // projected onto it; a few ulps off at most
  }
  return false;
}

/// A start for the solver: the point itself when it satisfies the constraint, else its
/// projections onto the constraint (all of them for warm starts, the first for Halton points).
std::vector<AccParameters> feasibleStarts(const AccParameters& p, MarginSide side, double margin,
                                          const ParameterBounds& bounds, bool all_projections)
{
  if (side != MarginSide::EqualTo && satisfies(side, stabilityMargin(p), margin))
  {
    return {p};
  }
  std::vector<AccParameters> projections = projectOntoMargin(p, margin, bounds, side);
  if (!all_projections && projections.size() > 1)
  {
    projections.resize(1);
  }
  return projections;
}

struct Start
{
  std::array<double, 3> theta{};
  double mse = 0.0;
};
}  // namespace

std::array<double, 3> stabilityMarginGradient(const AccParameters& p)
{
  return {p.tau_e_s * p.tau_e_s, 2.0 * p.tau_e_s, 2.0 * p.k1_per_s2 * p.tau_e_s + 2.0 * p.k2_per_s};
}

double leastMargin(const ParameterBounds& bounds)
{
  return stabilityMargin(bounds.lower);
}

double largestMargin(const ParameterBounds& bounds)
{
  return stabilityMargin(bounds.upper);
}

std::vector<AccParameters> projectOntoMargin(const AccParameters& p, double target, const ParameterBounds& bounds,
                                             MarginSide side)
{
  std::vector<AccParameters> result;
  const double rhs = 2.0 + target;  // k1 tau^2 + 2 k2 tau must equal this
  if (!(rhs >= 0.0) || !std::isfinite(rhs))
  {
    return result;
  }
  auto keep = [&](AccParameters q, double AccParameters::*changed) {
    if (std::isfinite(q.*changed) && nudgeOntoSide(q, changed, target, side) && withinBounds(q, bounds))
    {
      result.push_back(q);
    }
  };
  const double k1 = p.k1_per_s2, k2 = p.k2_per_s, tau = p.tau_e_s;
  // tau_e alone: the positive root, in the form without cancellation.
  const double denominator = k2 + std::sqrt(k2 * k2 + k1 * rhs);
  if (rhs == 0.0)
  {
    AccParameters q = p;
    q.tau_e_s = 0.0;
    keep(q, &AccParameters::tau_e_s);
  }
  else if (denominator > 0.0)
  {
    AccParameters q = p;
    q.tau_e_s = rhs / denominator;
    keep(q, &AccParameters::tau_e_s);
  }
  if (tau > 0.0)
  {
    AccParameters q = p;
    q.k2_per_s = (rhs - k1 * tau * tau) / (2.0 * tau);
    keep(q, &AccParameters::k2_per_s);
    q = p;
    q.k1_per_s2 = (rhs - 2.0 * k2 * tau) / (tau * tau);
    keep(q, &AccParameters::k1_per_s2);
  }
  return result;
}

namespace
{
/// The search's state, its parameters scaled by the start box's upper corner.
SearchState makeSearchState(const CalibrationObjective& objective, MarginSide side, double margin,
                            const ConstrainedFitOptions& options)
{
  SearchState state;
  state.objective = &objective;
  state.side = side;
  state.margin = margin;
  state.feasibility_tolerance = options.feasibility_tolerance;
  const double upper[3] = {options.start_box_upper.k1_per_s2, options.start_box_upper.k2_per_s,
                           options.start_box_upper.tau_e_s};
  for (int i = 0; i < 3; ++i)
    state.scale[i] = upper[i] > 0.0 ? upper[i] : 1.0;
  return state;
}

/// Evaluates a start and keeps it (and the best so far) unless its simulation diverges.
void evaluateStart(SearchState& state, const AccParameters& p, std::vector<Start>& into)
{
  const ReducedObjectiveValue value = state.objective->evaluate(p.k1_per_s2, p.k2_per_s, p.tau_e_s, false);
  ++state.evaluations;
  if (value.diverged)
    return;
  into.push_back({{p.k1_per_s2, p.k2_per_s, p.tau_e_s}, value.mse_speed_mps2});
  if (value.mse_speed_mps2 < state.best_mse)
  {
    state.best_mse = value.mse_speed_mps2;
    state.best_theta = into.back().theta;
  }
}

/// The warm starts, clamped into the bounds and made feasible, evaluated.
std::vector<Start> warmStarts(SearchState& state, const std::vector<AccParameters>& warm_starts,
                              const ParameterBounds& bounds)
{
  std::vector<Start> warm;
  for (const AccParameters& p : warm_starts)
  {
    if (!(std::isfinite(p.k1_per_s2) && std::isfinite(p.k2_per_s) && std::isfinite(p.tau_e_s)))
      continue;
    AccParameters clamped = p;
    clamped.k1_per_s2 = std::clamp(p.k1_per_s2, bounds.lower.k1_per_s2, bounds.upper.k1_per_s2);
    clamped.k2_per_s = std::clamp(p.k2_per_s, bounds.lower.k2_per_s, bounds.upper.k2_per_s);
    clamped.tau_e_s = std::clamp(p.tau_e_s, bounds.lower.tau_e_s, bounds.upper.tau_e_s);
    for (const AccParameters& start : feasibleStarts(clamped, state.side, state.margin, bounds, true))
      evaluateStart(state, start, warm);
  }
  return warm;
}

/// The Halton points of the start box, made feasible, evaluated.
std::vector<Start> haltonStarts(SearchState& state, const ConstrainedFitOptions& options,
                                const ParameterBounds& bounds)
{
  std::vector<Start> halton;
  const AccParameters& low = options.start_box_lower;
  const AccParameters& high = options.start_box_upper;
  for (std::size_t i = 1; i <= options.starts; ++i)
  {
    const auto unit = haltonPoint(i);
    AccParameters p{std::clamp(low.k1_per_s2 + unit[0] * (high.k1_per_s2 - low.k1_per_s2), bounds.lower.k1_per_s2,
                               bounds.upper.k1_per_s2),
                    std::clamp(low.k2_per_s + unit[1] * (high.k2_per_s - low.k2_per_s), bounds.lower.k2_per_s,
                               bounds.upper.k2_per_s),
                    std::clamp(low.tau_e_s + unit[2] * (high.tau_e_s - low.tau_e_s), bounds.lower.tau_e_s,
                               bounds.upper.tau_e_s),
                    0.0};
    for (const AccParameters& start : feasibleStarts(p, state.side, state.margin, bounds, false))
      evaluateStart(state, start, halton);
  }
  return halton;
}

/// The starts to solve from: the best max_warm_solves warm starts, then multi-level single linkage
/// over the Halton starts (from the best, skipping those close to a better one chosen, at most
/// max_local_solves of them).
std::vector<Start> startsToSolve(std::vector<Start> warm, std::vector<Start> halton, const SearchState& state,
                                 const ConstrainedFitOptions& options)
{
  auto byMse = [](const Start& a, const Start& b) { return a.mse < b.mse; };
  std::sort(halton.begin(), halton.end(), byMse);
  if (options.max_warm_solves > 0 && warm.size() > options.max_warm_solves)
  {
    std::stable_sort(warm.begin(), warm.end(), byMse);
    warm.resize(options.max_warm_solves);
  }
  std::vector<Start> to_solve = warm;
  std::vector<const Start*> chosen;
  for (const Start& start : halton)
  {
    if (chosen.size() >= options.max_local_solves)
      break;
    bool near_better = false;
    for (const Start* better : chosen)
    {
      double d2 = 0.0;
      for (int i = 0; i < 3; ++i)
        d2 += std::pow((start.theta[i] - better->theta[i]) / state.scale[i], 2);
      near_better = near_better || std::sqrt(d2) < options.cluster_radius;
    }
    if (!near_better)
    {
      chosen.push_back(&start);
      to_solve.push_back(start);
    }
  }
  return to_solve;
}

/// NLopt's SLSQP on the scaled parameters within the bounds, with the margin as a constraint
/// (an equality, or an inequality whose sign is the side's).
void configureLocalSolver(nlopt::opt& local, SearchState& state, ConstraintData& constraint,
                          const ParameterBounds& bounds, const ConstrainedFitOptions& options)
{
  local.set_lower_bounds(std::vector<double>{bounds.lower.k1_per_s2 / state.scale[0],
                                             bounds.lower.k2_per_s / state.scale[1],
                                             bounds.lower.tau_e_s / state.scale[2]});
  local.set_upper_bounds(std::vector<double>{bounds.upper.k1_per_s2 / state.scale[0],
                                             bounds.upper.k2_per_s / state.scale[1],
                                             bounds.upper.tau_e_s / state.scale[2]});
  local.set_min_objective(nloptObjective, &state);
  if (state.side == MarginSide::EqualTo)
    local.add_equality_constraint(nloptConstraint, &constraint, 1e-10);
  else
    local.add_inequality_constraint(nloptConstraint, &constraint, 1e-10);
  local.set_maxeval(options.max_evaluations_per_solve);
  local.set_xtol_rel(options.relative_x_tolerance);
  local.set_ftol_rel(options.relative_f_tolerance);
}

/// The best feasible point, moved onto the constraint exactly when it is within the feasibility
/// tolerance of it (on either side): a fit on the boundary then has a margin a few ulps from it.
void finishAtBestPoint(SearchState& state, const ParameterBounds& bounds, const ConstrainedFitOptions& options,
                       ConstrainedFitResult& result)
{
  AccParameters best = toParameters(state.best_theta);
  const double m = stabilityMargin(best);
  if (state.side == MarginSide::EqualTo || !satisfies(state.side, m, state.margin) ||
      std::abs(m - state.margin) <= options.feasibility_tolerance)
  {
    const auto projected = projectOntoMargin(best, state.margin, bounds, state.side);
    if (projected.empty())
    {
      result.status = "NO_FEASIBLE_POINT";
      result.evaluations = state.evaluations;
      return;
    }
    best = projected.front();
  }
  const ReducedObjectiveValue value = state.objective->evaluate(best.k1_per_s2, best.k2_per_s, best.tau_e_s, false);
  ++state.evaluations;
  result.evaluations = state.evaluations;
  if (value.diverged)
  {
    result.status = "DIVERGED";
    return;
  }
  best.eta_m = value.eta_m;
  result.found = true;
  result.parameters = best;
  result.margin = stabilityMargin(best);
  result.rmse_speed_mps = std::sqrt(value.mse_speed_mps2);
}
}  // namespace

ConstrainedFitResult fitWithMarginConstraint(const CalibrationObjective& objective, MarginSide side, double margin,
                                             const ConstrainedFitOptions& options,
                                             const std::vector<AccParameters>& warm_starts)
{
  ConstrainedFitResult result;
  const ParameterBounds& bounds = objective.bounds();
  SearchState state = makeSearchState(objective, side, margin, options);
  std::vector<Start> warm = warmStarts(state, warm_starts, bounds);
  std::vector<Start> halton = haltonStarts(state, options, bounds);
  const std::vector<Start> to_solve = startsToSolve(std::move(warm), std::move(halton), state, options);
  if (!std::isfinite(state.best_mse))
  {
    result.status = "NO_FEASIBLE_START";
    result.evaluations = state.evaluations;
    return result;
  }
  state.objective_scale = std::max(state.best_mse, 1e-12);
  nlopt::opt local(nlopt::LD_SLSQP, 3);
  ConstraintData constraint{&state, side == MarginSide::AtLeast ? -1.0 : 1.0};
  configureLocalSolver(local, state, constraint, bounds, options);
  result.status = "START";
  for (const Start& start : to_solve)
  {
    const std::string status = solveLocally(local, state, start.theta);
    ++result.local_solves;
    if (state.improved_in_this_solve)
      result.status = status;
  }
  finishAtBestPoint(state, bounds, options, result);
  return result;
}

}  // namespace acc
