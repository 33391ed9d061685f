#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/model/halton_sequence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <nlopt.hpp>

namespace acc
{
namespace
{

/// The search runs on x_i = theta_i / scale_i with the scales of the start box, so that a unit
/// step means the same in every direction to the quasi-Newton method.
struct SearchState
{
  const CalibrationObjective* objective = nullptr;
  std::array<double, 3> scale{};
  std::size_t evaluations = 0;
  double best_mse = std::numeric_limits<double>::infinity();
  std::array<double, 3> best_theta{};
  double best_eta = 0.0;
  bool improved_in_this_solve = false;
  /// Local minima found by earlier solves (scaled x, mse), and the test for joining one of them.
  std::vector<std::pair<std::array<double, 3>, double>> minima;
  double join_radius = 0.0;
  double join_relative_mse = 0.0;
  bool joined = false;
  std::array<double, 3> solve_best_x{};  ///< this solve's best point, scaled
  double solve_best_mse = std::numeric_limits<double>::infinity();
  nlopt::opt* local = nullptr;
};

/// True when x is so close to a known local minimum, at nearly its value, that the rest of this
/// solve could only retrace the solve that found it.
bool joinsKnownMinimum(const SearchState& state, const double* x, double mse)
{
  for (const auto& [minimum_x, minimum_mse] : state.minima)
  {
    const double distance = std::hypot(x[0] - minimum_x[0], x[1] - minimum_x[1], x[2] - minimum_x[2]);
    if (distance < state.join_radius && mse <= minimum_mse * (1.0 + state.join_relative_mse))
    {
      return true;
    }
  }
  return false;
}

double nloptObjective(unsigned n, const double* x, double* gradient, void* data)
{
  auto& state = *static_cast<SearchState*>(data);
  (void)n;
  const std::array<double, 3> theta{x[0] * state.scale[0], x[1] * state.scale[1], x[2] * state.scale[2]};
  const ReducedObjectiveValue value = state.objective->evaluate(theta[0], theta[1], theta[2], gradient != nullptr);
  ++state.evaluations;
  if (gradient != nullptr)
  {
    for (int i = 0; i < 3; ++i)
    {
      gradient[i] = value.gradient[i] * state.scale[i];
    }
  }
  if (!value.diverged && value.mse_speed_mps2 < state.best_mse)
  {
    state.best_mse = value.mse_speed_mps2;
    state.best_theta = theta;
    state.best_eta = value.eta_m;
    state.improved_in_this_solve = true;
  }
  if (!value.diverged && value.mse_speed_mps2 < state.solve_best_mse)
  {
    state.solve_best_mse = value.mse_speed_mps2;
    state.solve_best_x = {x[0], x[1], x[2]};
  }
  if (!value.diverged && joinsKnownMinimum(state, x, value.mse_speed_mps2))
  {
    state.joined = true;
    state.local->force_stop();
  }
  return value.mse_speed_mps2;
}

/// Pulls a divergent start halfway towards a well-damped reference until it simulates.
std::array<double, 3> tameStart(const CalibrationObjective& objective, std::array<double, 3> theta,
                                bool& was_divergent, std::size_t& evaluations)
{
  static const std::array<double, 3> kReference{0.05, 0.5, 1.5};
  was_divergent = false;
  for (int attempt = 0; attempt < 20; ++attempt)
  {
    ++evaluations;
    if (!objective.evaluate(theta[0], theta[1], theta[2], false).diverged)
    {
      return theta;
    }
    was_divergent = true;
    for (int i = 0; i < 3; ++i)
    {
      theta[i] = 0.5 * (theta[i] + kReference[i]);
    }
  }
  return kReference;
}

/// A starting point after taming, with its objective value.
struct EvaluatedStart
{
  std::array<double, 3> x{};  ///< scaled
  double mse = 0.0;
  bool warm = false;
  std::size_t index = 0;      ///< in the order given: warm starts, then Halton points
};

std::vector<EvaluatedStart> evaluateStarts(const std::vector<std::array<double, 3>>& starts, std::size_t warm_count,
                                           const std::array<double, 3>& lower, const std::array<double, 3>& upper,
                                           SearchState& state, std::size_t& divergent_starts)
{
  std::vector<EvaluatedStart> evaluated;
  for (std::size_t s = 0; s < starts.size(); ++s)
  {
    std::array<double, 3> theta = starts[s];
    for (int i = 0; i < 3; ++i)
    {
      theta[i] = std::clamp(theta[i], lower[i], upper[i]);
    }
    bool was_divergent = false;
    theta = tameStart(*state.objective, theta, was_divergent, state.evaluations);
    divergent_starts += was_divergent ? 1 : 0;
    EvaluatedStart start;
    start.x = {theta[0] / state.scale[0], theta[1] / state.scale[1], theta[2] / state.scale[2]};
    start.mse = nloptObjective(3, start.x.data(), nullptr, &state);
    start.warm = s < warm_count;
    start.index = s;
    evaluated.push_back(start);
  }
  // Warm starts first (they are usually next to the answer), then the best starts first, so that
  // a start is skipped when a better one lies close to it (multi-level single linkage).
  std::stable_sort(evaluated.begin(), evaluated.end(), [](const EvaluatedStart& a, const EvaluatedStart& b) {
    return a.warm != b.warm ? a.warm : a.mse < b.mse;
  });
  return evaluated;
}

bool hasBetterStartNearby(const std::vector<EvaluatedStart>& sorted, std::size_t position, double radius)
{
  for (std::size_t j = 0; j < position; ++j)
  {
    const auto& a = sorted[j].x;
    const auto& b = sorted[position].x;
    if (std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < radius)
    {
      return true;
    }
  }
  return false;
}

/// One NLopt local solve from x; returns NLopt's stop reason.
std::string solveLocally(nlopt::opt& local, SearchState& state, std::array<double, 3> start)
{
  std::vector<double> x(start.begin(), start.end());
  state.improved_in_this_solve = false;
  state.joined = false;
  state.solve_best_mse = std::numeric_limits<double>::infinity();
  try
  {
    double f = 0.0;
    // NLopt's own name of the result ("SUCCESS", "MAXEVAL_REACHED", "ROUNDOFF_LIMITED", ...).
    return nlopt_result_to_string(static_cast<nlopt_result>(local.optimize(x, f)));
  }
  catch (const nlopt::forced_stop&)
  {
    return "JOINED_KNOWN_MINIMUM";
  }
  catch (const nlopt::roundoff_limited&)
  {
    return "ROUNDOFF_LIMITED";  // converged as far as doubles allow; the best point seen is kept
  }
  catch (const std::exception& error)
  {
    return std::string("FAILURE: ") + error.what();
  }
}
}  // namespace

std::array<double, 3> haltonPoint(std::size_t index)
{
  const std::vector<double> point = haltonSequencePoint(index, 3);
  return {point[0], point[1], point[2]};
}

MultistartResult calibrateMultistart(const CalibrationObjective& objective, const MultistartOptions& options,
                                     const std::vector<AccParameters>& warm_starts)
{
  const auto started = std::chrono::steady_clock::now();
  const ParameterBounds& bounds = objective.bounds();
  SearchState state;
  state.objective = &objective;
  state.scale = {options.start_box_upper.k1_per_s2, options.start_box_upper.k2_per_s, options.start_box_upper.tau_e_s};
  state.join_radius = options.join_radius;
  state.join_relative_mse = options.join_relative_mse;

  std::vector<std::array<double, 3>> starts;
  for (const AccParameters& warm : warm_starts)
  {
    if (std::isfinite(warm.k1_per_s2) && std::isfinite(warm.k2_per_s) && std::isfinite(warm.tau_e_s))
    {
      starts.push_back({warm.k1_per_s2, warm.k2_per_s, warm.tau_e_s});
    }
  }
  const std::size_t warm_count = starts.size();
  const AccParameters& box_low = options.start_box_lower;
  const AccParameters& box_high = options.start_box_upper;
  for (std::size_t i = 1; i <= options.starts; ++i)
  {
    const auto unit = haltonPoint(i);
    starts.push_back({box_low.k1_per_s2 + unit[0] * (box_high.k1_per_s2 - box_low.k1_per_s2),
                      box_low.k2_per_s + unit[1] * (box_high.k2_per_s - box_low.k2_per_s),
                      box_low.tau_e_s + unit[2] * (box_high.tau_e_s - box_low.tau_e_s)});
  }

  const std::array<double, 3> lower{bounds.lower.k1_per_s2, bounds.lower.k2_per_s, bounds.lower.tau_e_s};
  const std::array<double, 3> upper{bounds.upper.k1_per_s2, bounds.upper.k2_per_s, bounds.upper.tau_e_s};
  nlopt::opt local(nlopt::LD_LBFGS, 3);
  std::vector<double> lower_x(3), upper_x(3);
  for (int i = 0; i < 3; ++i)
  {
    lower_x[i] = lower[i] / state.scale[i];
    upper_x[i] = upper[i] / state.scale[i];
  }
  local.set_lower_bounds(lower_x);
  local.set_upper_bounds(upper_x);
  local.set_min_objective(nloptObjective, &state);
  local.set_maxeval(options.max_evaluations_per_start);
  local.set_xtol_rel(options.relative_x_tolerance);
  local.set_ftol_rel(options.relative_f_tolerance);
  state.local = &local;

  MultistartResult result;
  result.starts = starts.size();
  const auto sorted = evaluateStarts(starts, warm_count, lower, upper, state, result.divergent_starts);
  result.status = "NO_LOCAL_SOLVE";
  for (std::size_t position = 0; position < sorted.size(); ++position)
  {
    const EvaluatedStart& start = sorted[position];
    if (!start.warm && hasBetterStartNearby(sorted, position, options.cluster_radius))
    {
      ++result.clustered_starts;
    }
    else
    {
      const std::string status = solveLocally(local, state, start.x);
      ++result.local_solves;
      if (state.joined)
      {
        ++result.joined_starts;
      }
      else if (std::isfinite(state.solve_best_mse))
      {
        state.minima.push_back({state.solve_best_x, state.solve_best_mse});
      }
      if (state.improved_in_this_solve)
      {
        result.status = status;
        result.best_start = start.index;
      }
    }
    if (options.progress)
    {
      options.progress(position + 1, sorted.size());
    }
  }
  result.local_minima = state.minima.size();
  result.evaluations = state.evaluations;
  result.diverged = !std::isfinite(state.best_mse);
  if (result.diverged)
  {
    result.parameters = AccParameters{};
    result.rmse_speed_mps = std::sqrt(kDivergedMseMps2);
    result.status = "DIVERGED";
  }
  else
  {
    result.parameters = AccParameters{state.best_theta[0], state.best_theta[1], state.best_theta[2], state.best_eta};
    result.rmse_speed_mps = std::sqrt(state.best_mse);
  }
  result.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace acc
