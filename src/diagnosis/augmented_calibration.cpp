#include "acc_identification/diagnosis/augmented_calibration.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "acc_identification/diagnosis/augmented_stability.h"
#include "acc_identification/diagnosis/augmented_standard_errors.h"
#include "acc_identification/evidence/perturbation_windows.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
AugmentedParameterBox::AugmentedParameterBox(EffectKind kind, const AugmentedCalibrationOptions& options)
  : AugmentedParameterBox(kind == EffectKind::none ? std::vector<EffectKind>{} : std::vector<EffectKind>{kind}, options)
{
}

AugmentedParameterBox::AugmentedParameterBox(const std::vector<EffectKind>& kinds,
                                             const AugmentedCalibrationOptions& options)
  : effect(kinds.empty() ? EffectKind::none : kinds.back()), effects(kinds)
{
  lower = {options.lower.k1_per_s2, options.lower.k2_per_s, options.lower.tau_e_s, options.lower.eta_m};
  upper = {options.upper.k1_per_s2, options.upper.k2_per_s, options.upper.tau_e_s, options.upper.eta_m};
  for (EffectKind kind : kinds)
  {
    for (const EffectParameterSpec& spec : candidateEffect(kind).parameters)
    {
      lower.push_back(spec.lower);
      upper.push_back(spec.upper);
    }
  }
}

std::vector<double> AugmentedParameterBox::physical(const std::vector<double>& unit) const
{
  std::vector<double> x(unit.size());
  for (std::size_t i = 0; i < unit.size(); ++i)
  {
    x[i] = lower[i] + std::clamp(unit[i], 0.0, 1.0) * (upper[i] - lower[i]);
  }
  return x;
}

std::vector<double> AugmentedParameterBox::unit(const std::vector<double>& x) const
{
  std::vector<double> u(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    // A held coordinate (lower == upper) has one value: unit 0.
    u[i] = upper[i] > lower[i] ? std::clamp((x[i] - lower[i]) / (upper[i] - lower[i]), 0.0, 1.0) : 0.0;
  }
  return u;
}

namespace
{
AccParameters baseOf(const std::vector<double>& x) { return AugmentedParameterBox::baseOf(x); }
std::vector<double> effectPart(const std::vector<double>& x) { return AugmentedParameterBox::effectPart(x); }


/// The objective and its Gauss-Newton normal equations at one point, in unit coordinates u of the
/// box: J = d v / d u over every sample of every segment, normal = J^T J, descent = J^T r (r the
/// speed residuals), so that the step delta of (normal + lambda D) delta = descent lowers the MSE.
struct GaussNewtonPass
{
  double mse = kDivergedObjective;  ///< as augmentedSpeedMse, number for number
  bool diverged = true;
  Eigen::MatrixXd normal;  ///< zero when the pass was asked for the descent alone
  Eigen::VectorXd descent;
  std::size_t samples = 0;  ///< the samples the MSE averages over
  bool locally_stable = true;  ///< the model's own loop (locallyStableAt), set by ObjectiveTracker
};

/// Weights of the speed and gap residuals in the objective (squared weights multiply the squares).
struct ResidualWeights
{
  double speed = 1.0;
  double gap = 0.0;
  /// Per segment, per sample, a further factor on the speed residual; empty: 1 everywhere.
  std::vector<std::vector<double>> speed_per_sample;
};

/// speed_and_windows: sum/N + window sum/N_w = sum over samples of (1 + N/N_w inside a window) e^2
/// over N, so each sample inside a window gets the factor sqrt(1 + N/N_w).
ResidualWeights perturbationWindowWeights(const std::vector<CarFollowingRun>& segments)
{
  std::vector<std::vector<bool>> inside;
  std::size_t samples = 0, inside_samples = 0;
  for (const CarFollowingRun& run : segments)
  {
    inside.push_back(insidePerturbationWindows(run.time_s, run.leader_speed_mps));
    inside_samples += static_cast<std::size_t>(std::count(inside.back().begin(), inside.back().end(), true));
    samples += run.size();
  }
  ResidualWeights weights;
  if (inside_samples == 0)
    return weights;  // no braking to weigh: the speed objective
  const double factor = std::sqrt(1.0 + static_cast<double>(samples) / static_cast<double>(inside_samples));
  for (const std::vector<bool>& flags : inside)
  {
    std::vector<double> per_sample(flags.size(), 1.0);
    for (std::size_t k = 0; k < flags.size(); ++k)
      per_sample[k] = flags[k] ? factor : 1.0;
    weights.speed_per_sample.push_back(std::move(per_sample));
  }
  return weights;
}

/// The variance of a column over every sample of the segments (1 when it has none or no spread,
/// so that a weight never becomes infinite).
template <typename Column>
double pooledVariance(const std::vector<CarFollowingRun>& segments, Column column)
{
  double sum = 0.0, sum_squares = 0.0;
  std::size_t n = 0;
  for (const CarFollowingRun& run : segments)
  {
    for (double value : column(run))
    {
      sum += value;
      sum_squares += value * value;
      ++n;
    }
  }
  const double variance = n > 1 ? (sum_squares - sum * sum / static_cast<double>(n)) / static_cast<double>(n - 1) : 0.0;
  return variance > 1e-12 ? variance : 1.0;
}

ResidualWeights residualWeights(FitObjective objective, const std::vector<CarFollowingRun>& segments)
{
  switch (objective)
  {
    case FitObjective::speed: return {1.0, 0.0, {}};
    case FitObjective::gap: return {0.0, 1.0, {}};
    case FitObjective::speed_and_gap:
      return {1.0 / std::sqrt(pooledVariance(segments, [](const CarFollowingRun& r) { return r.follower_speed_mps; })),
              1.0 / std::sqrt(pooledVariance(segments, [](const CarFollowingRun& r) { return r.space_gap_m; })),
              {}};
    case FitObjective::speed_and_windows: return perturbationWindowWeights(segments);
  }
  return {};
}

/// The gap-objective part of a pass: the simulated gap s[k+1] = s[k] + h (u[k] - v[k]) from the
/// measured start, and its derivatives ds[k+1] = ds[k] - h dv[k] (no clock offset in the model).
void addGapResiduals(const CarFollowingRun& run, const FollowerSpeedSensitivities& sim, double weight,
                     Eigen::MatrixXd* normal, Eigen::VectorXd* descent, double* sum)
{
  const std::size_t p = sim.dimension;
  double gap = run.space_gap_m[0];
  Eigen::VectorXd derivative = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(p));
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    if (k > 0)
    {
      const double step_s = run.time_s[k] - run.time_s[k - 1];
      gap += step_s * (run.leader_speed_mps[k - 1] - sim.speed_mps[k - 1]);
      derivative -= step_s * Eigen::Map<const Eigen::VectorXd>(&sim.speed_derivatives[(k - 1) * p],
                                                               static_cast<Eigen::Index>(p));
    }
    const double error = weight * (run.space_gap_m[k] - gap);
    *sum += error * error;
    const Eigen::VectorXd row = weight * derivative;
    normal->selfadjointView<Eigen::Upper>().rankUpdate(row);
    *descent += row * error;
  }
}

/// The speed residuals with a factor per sample (w_k (v_k - v^_k), rows w_k dv^_k): the normal
/// equations summed over the runs of equal factor, so that no weighted copy of J is made.
void addWeightedSpeedResiduals(const CarFollowingRun& run, const FollowerSpeedSensitivities& sim,
                               const std::vector<double>& per_sample, bool with_normal, GaussNewtonPass* pass,
                               double* sum)
{
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const auto p = static_cast<Eigen::Index>(sim.dimension);
  const Eigen::Map<const RowMajor> jacobian(sim.speed_derivatives.data(), static_cast<Eigen::Index>(run.size()), p);
  Eigen::VectorXd residual(static_cast<Eigen::Index>(run.size()));
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    const double error = per_sample[k] * (run.follower_speed_mps[k] - sim.speed_mps[k]);
    *sum += error * error;
    residual[static_cast<Eigen::Index>(k)] = error;
  }
  for (std::size_t first = 0; first < run.size();)
  {
    std::size_t end = first + 1;
    while (end < run.size() && per_sample[end] == per_sample[first])
      ++end;
    const auto rows = static_cast<Eigen::Index>(end - first);
    const auto block = jacobian.middleRows(static_cast<Eigen::Index>(first), rows);
    if (with_normal)
      pass->normal.selfadjointView<Eigen::Upper>().rankUpdate(block.transpose(), per_sample[first] * per_sample[first]);
    pass->descent += per_sample[first] * (block.transpose() * residual.segment(static_cast<Eigen::Index>(first), rows));
    first = end;
  }
}

/// with_normal false: the descent J^T r alone (all a gradient needs), without the p^2 work per
/// sample of J^T J.
GaussNewtonPass gaussNewtonPass(const AugmentedParameterBox& box, const std::vector<double>& x,
                                const std::vector<CarFollowingRun>& segments, const ResidualWeights& weights,
                                bool with_normal = true)
{
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const auto p = static_cast<Eigen::Index>(x.size());
  GaussNewtonPass pass;
  pass.normal = Eigen::MatrixXd::Zero(p, p);
  pass.descent = Eigen::VectorXd::Zero(p);
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t segment = 0; segment < segments.size(); ++segment)
  {
    const CarFollowingRun& run = segments[segment];
    const FollowerSpeedSensitivities sim = simulateFollowerSensitivities(box.effects, x, run);
    if (sim.diverged)
    {
      return pass;
    }
    const auto n = static_cast<Eigen::Index>(run.size());
    if (!weights.speed_per_sample.empty())
    {
      addWeightedSpeedResiduals(run, sim, weights.speed_per_sample[segment], with_normal, &pass, &sum);
    }
    else if (weights.speed != 0.0)
    {
      Eigen::VectorXd residual(n);
      for (std::size_t k = 0; k < run.size(); ++k)
      {
        // Unweighted for the paper's objective, so the values agree exactly with augmentedSpeedMse.
        const double error = weights.speed == 1.0 ? run.follower_speed_mps[k] - sim.speed_mps[k]
                                                  : weights.speed * (run.follower_speed_mps[k] - sim.speed_mps[k]);
        sum += error * error;
        residual[static_cast<Eigen::Index>(k)] = error;
      }
      const Eigen::Map<const RowMajor> jacobian(sim.speed_derivatives.data(), n, p);
      if (with_normal)
        pass.normal.selfadjointView<Eigen::Upper>().rankUpdate(jacobian.transpose(), weights.speed * weights.speed);
      if (weights.speed == 1.0)
        pass.descent += jacobian.transpose() * residual;
      else
        pass.descent += weights.speed * (jacobian.transpose() * residual);
    }
    if (weights.gap != 0.0)
    {
      addGapResiduals(run, sim, weights.gap, &pass.normal, &pass.descent, &sum);
    }
    count += run.size();
  }
  pass.normal = pass.normal.selfadjointView<Eigen::Upper>();
  // From physical to unit coordinates: x = lower + u (upper - lower).
  const Eigen::VectorXd width =
      Eigen::Map<const Eigen::VectorXd>(box.upper.data(), p) - Eigen::Map<const Eigen::VectorXd>(box.lower.data(), p);
  pass.normal = width.asDiagonal() * pass.normal * width.asDiagonal();
  pass.descent = width.asDiagonal() * pass.descent;
  const double mse = count > 0 ? sum / static_cast<double>(count) : 0.0;
  pass.samples = count;
  pass.mse = std::isfinite(mse) ? std::min(mse, kDivergedObjective) : kDivergedObjective;
  pass.diverged = !(pass.mse < kDivergedObjective);
  return pass;
}

/// The objective of gaussNewtonPass alone, from the plain simulator (whose values agree with the
/// dual-number pass bit for bit), summed in the same order so that it is the same number:
/// kDivergedObjective when a simulation diverges. `samples` gets the samples it averages over.
double plainObjective(const AccParameters& base, const EffectSettings& settings,
                      const std::vector<CarFollowingRun>& segments, const ResidualWeights& weights,
                      std::size_t* samples)
{
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t segment = 0; segment < segments.size(); ++segment)
  {
    const CarFollowingRun& run = segments[segment];
    const SimulatedFollower sim = simulateFollower(base, settings, run);
    if (sim.diverged)
      return kDivergedObjective;
    const std::vector<double>* per_sample =
        weights.speed_per_sample.empty() ? nullptr : &weights.speed_per_sample[segment];
    for (std::size_t k = 0; weights.speed != 0.0 && k < run.size(); ++k)
    {
      const double error = per_sample != nullptr ? (*per_sample)[k] * (run.follower_speed_mps[k] - sim.speed_mps[k])
                           : weights.speed == 1.0 ? run.follower_speed_mps[k] - sim.speed_mps[k]
                                                  : weights.speed * (run.follower_speed_mps[k] - sim.speed_mps[k]);
      sum += error * error;
    }
    double gap = run.space_gap_m.empty() ? 0.0 : run.space_gap_m[0];
    for (std::size_t k = 0; weights.gap != 0.0 && k < run.size(); ++k)
    {
      if (k > 0)
        gap += (run.time_s[k] - run.time_s[k - 1]) * (run.leader_speed_mps[k - 1] - sim.speed_mps[k - 1]);
      const double error = weights.gap * (run.space_gap_m[k] - gap);
      sum += error * error;
    }
    count += run.size();
  }
  *samples = count;
  const double mse = count > 0 ? sum / static_cast<double>(count) : 0.0;
  return std::isfinite(mse) ? std::min(mse, kDivergedObjective) : kDivergedObjective;
}

/// What a trial step needs to be accepted or refused, at a fraction of the Jacobian's cost.
GaussNewtonPass objectivePass(const AugmentedParameterBox& box, const std::vector<double>& x,
                              const std::vector<CarFollowingRun>& segments, const ResidualWeights& weights)
{
  GaussNewtonPass pass;
  pass.mse = plainObjective(AugmentedParameterBox::baseOf(x), box.settingsOf(x), segments, weights, &pass.samples);
  pass.diverged = !(pass.mse < kDivergedObjective);
  return pass;
}

/// Evaluates the objective at physical points and remembers the best locally stable one ever
/// seen, so the result never depends on where the local solver happens to stop; and the best
/// unstable one, kept only for a fit that never reaches a stable model.
struct ObjectiveTracker
{
  /// The tracker of one fit: the objective's weights and the loop-check speeds of the segments.
  ObjectiveTracker(const AugmentedParameterBox* search_box, const std::vector<CarFollowingRun>* fitted,
                   FitObjective objective)
    : box(search_box), segments(fitted), weights(residualWeights(objective, *fitted)),
      loop_speeds_mps(loopCheckSpeedsMps(*fitted))
  {
  }

  const AugmentedParameterBox* box;
  const std::vector<CarFollowingRun>* segments;
  ResidualWeights weights;
  std::vector<double> loop_speeds_mps;
  std::vector<double> best_x;
  double best_value = std::numeric_limits<double>::infinity();
  std::vector<double> best_unstable_x;
  double best_unstable_value = std::numeric_limits<double>::infinity();
  std::size_t evaluations = 0;

  /// The objective at unit_x, with its Jacobian's normal equations or (with_jacobian false, for a
  /// trial step) without.
  GaussNewtonPass operator()(const Eigen::VectorXd& unit_x, bool with_jacobian = true)
  {
    const std::vector<double> x = physicalOf(unit_x);
    GaussNewtonPass pass = with_jacobian ? gaussNewtonPass(*box, x, *segments, weights)
                                         : objectivePass(*box, x, *segments, weights);
    ++evaluations;
    pass.locally_stable = locallyStableAt(AugmentedParameterBox::baseOf(x), box->settingsOf(x), loop_speeds_mps);
    double& best = pass.locally_stable ? best_value : best_unstable_value;
    if (pass.mse < best)
    {
      best = pass.mse;
      (pass.locally_stable ? best_x : best_unstable_x) = x;
    }
    return pass;
  }

  /// The Jacobian at a point already evaluated (value_pass): not counted again, nor recorded.
  GaussNewtonPass jacobianAt(const Eigen::VectorXd& unit_x, const GaussNewtonPass& value_pass) const
  {
    GaussNewtonPass pass = gaussNewtonPass(*box, physicalOf(unit_x), *segments, weights);
    pass.locally_stable = value_pass.locally_stable;
    return pass;
  }

  std::vector<double> physicalOf(const Eigen::VectorXd& unit_x) const
  {
    return box->physical(std::vector<double>(unit_x.data(), unit_x.data() + unit_x.size()));
  }
};

/// Whether the local solver takes a trial step: it must lower the objective, and once the solver
/// stands on a locally stable model it must stay on one (a start that is not stable may step
/// onto a stable model at any cost, and the stable set is then never left).
bool acceptsStep(const GaussNewtonPass& at, const GaussNewtonPass& trial)
{
  if (trial.diverged)
    return false;
  if (at.locally_stable && !trial.locally_stable)
    return false;
  return trial.mse < at.mse || (trial.locally_stable && !at.locally_stable);
}

/// Coordinates held at a bound because the descent direction points out of the box there.
std::vector<Eigen::Index> freeCoordinates(const Eigen::VectorXd& u, const Eigen::VectorXd& descent)
{
  std::vector<Eigen::Index> free;
  for (Eigen::Index j = 0; j < u.size(); ++j)
  {
    const bool pushed_below = u[j] <= 0.0 && descent[j] < 0.0;
    const bool pushed_above = u[j] >= 1.0 && descent[j] > 0.0;
    if (!pushed_below && !pushed_above)
    {
      free.push_back(j);
    }
  }
  return free;
}

/// The damped Gauss-Newton step on the free coordinates (Marquardt's scaling by the diagonal, so
/// that a flat direction, such as a limit the commands never reach, takes no wild step), clamped
/// into the unit box.
Eigen::VectorXd dampedStep(const GaussNewtonPass& at, const Eigen::VectorXd& u, const std::vector<Eigen::Index>& free,
                           double damping)
{
  const auto m = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd system(m, m);
  Eigen::VectorXd rhs(m);
  const double largest = at.normal.diagonal().maxCoeff();
  for (Eigen::Index a = 0; a < m; ++a)
  {
    rhs[a] = at.descent[free[static_cast<std::size_t>(a)]];
    for (Eigen::Index b = 0; b < m; ++b)
    {
      system(a, b) = at.normal(free[static_cast<std::size_t>(a)], free[static_cast<std::size_t>(b)]);
    }
    system(a, a) += damping * std::max(system(a, a), 1e-12 * largest + 1e-300);
  }
  const Eigen::VectorXd delta = system.ldlt().solve(rhs);
  Eigen::VectorXd next = u;
  for (Eigen::Index a = 0; a < m; ++a)
  {
    const Eigen::Index j = free[static_cast<std::size_t>(a)];
    next[j] = std::clamp(u[j] + delta[a], 0.0, 1.0);
  }
  return next;
}

/// Levenberg-Marquardt from one start on the unit box, with the exact Jacobian of the augmented
/// simulator: a few dozen passes where a derivative-free search needs hundreds. Stops when the
/// step or the relative decrease of the MSE falls below the tolerances, or at the evaluation cap.
void localSolve(ObjectiveTracker* tracker, const std::vector<double>& start_physical,
                const AugmentedCalibrationOptions& options)
{
  const std::vector<double> start_unit = tracker->box->unit(start_physical);  // clamped into the box
  Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(start_unit.data(), static_cast<Eigen::Index>(start_unit.size()));
  GaussNewtonPass at = (*tracker)(u);
  double damping = options.initial_damping;
  for (int evaluation = 1; evaluation < options.max_evaluations_per_start && !at.diverged; ++evaluation)
  {
    const std::vector<Eigen::Index> free = freeCoordinates(u, at.descent);
    if (free.empty())
    {
      return;
    }
    const Eigen::VectorXd next = dampedStep(at, u, free, damping);
    if ((next - u).lpNorm<Eigen::Infinity>() <= options.relative_x_tolerance * (1.0 + u.lpNorm<Eigen::Infinity>()))
    {
      return;
    }
    // The trial's objective first: only a step taken needs the Jacobian at its end, and the last
    // one (a negligible decrease) none.
    const GaussNewtonPass trial = (*tracker)(next, false);
    if (acceptsStep(at, trial))
    {
      const bool negligible = at.locally_stable == trial.locally_stable &&
                              at.mse - trial.mse <= options.relative_mse_tolerance * at.mse;
      if (negligible)
      {
        return;
      }
      u = next;
      at = tracker->jacobianAt(u, trial);
      damping = std::max(damping / 3.0, 1e-12);
    }
    else if ((damping *= 4.0) > 1e12)
    {
      return;
    }
  }
}

/// eta where a follower at the segments' speeds would sit with time gap tau: mean(s - tau v).
double equilibriumJamDistance(const std::vector<CarFollowingRun>& segments, double tau_s,
                              const AugmentedCalibrationOptions& options)
{
  double sum = 0.0;
  std::size_t count = 0;
  for (const CarFollowingRun& run : segments)
  {
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      sum += run.space_gap_m[k] - tau_s * run.follower_speed_mps[k];
      ++count;
    }
  }
  const double eta = count > 0 ? sum / static_cast<double>(count) : 0.0;
  return std::clamp(eta, options.lower.eta_m, options.upper.eta_m);
}

std::vector<std::vector<double>> baseStarts(const std::vector<CarFollowingRun>& segments,
                                            const AugmentedCalibrationOptions& options)
{
  std::vector<std::vector<double>> starts;
  const AccParameters& lo = options.start_lower;
  const AccParameters& hi = options.start_upper;
  for (std::size_t i = 1; i <= options.base_starts; ++i)
  {
    const std::vector<double> h = haltonSequencePoint(i, 3);
    const double k1 = lo.k1_per_s2 + h[0] * (hi.k1_per_s2 - lo.k1_per_s2);
    const double k2 = lo.k2_per_s + h[1] * (hi.k2_per_s - lo.k2_per_s);
    const double tau = lo.tau_e_s + h[2] * (hi.tau_e_s - lo.tau_e_s);
    starts.push_back({k1, k2, tau, equilibriumJamDistance(segments, tau, options)});
  }
  return starts;
}

/// The "almost off" values of an effect: the edge of its start range closest to the base model.
std::vector<double> nearOffValues(EffectKind effect)
{
  const auto& specs = candidateEffect(effect).parameters;
  const bool off_at_upper = effect == EffectKind::acceleration_limits || effect == EffectKind::set_speed_cruise;
  std::vector<double> values;
  for (const EffectParameterSpec& spec : specs)
  {
    if (std::isfinite(spec.neutral))
      values.push_back(spec.neutral);  // an interior "off" (a gain ratio of 1)
    else
      values.push_back(off_at_upper ? spec.upper : (spec.lower < 0.0 ? 0.0 : spec.lower));
  }
  if (effect == EffectKind::set_speed_cruise)
  {
    values[1] = specs[1].start_upper;
  }
  return values;
}

/// The values of `kind` in a fit, if the fit has that effect.
bool valuesIn(const AugmentedFit& fit, EffectKind kind, std::vector<double>* values)
{
  std::size_t offset = 0;
  for (EffectKind own : effectsOf(fit))
  {
    const std::size_t count = candidateEffect(own).parameters.size();
    if (own == kind && offset + count <= fit.effect_values.size())
    {
      values->assign(fit.effect_values.begin() + static_cast<long>(offset),
                     fit.effect_values.begin() + static_cast<long>(offset + count));
      return true;
    }
    offset += count;
  }
  return false;
}

/// Warm starts: the warm fit's base and known effect values; the effects it lacks at Halton points
/// of their start ranges (one low-discrepancy sequence over all their parameters), then at their
/// "almost off" values, so that the fit can never end worse than the warm fit it starts from.
std::vector<std::vector<double>> effectStarts(const std::vector<EffectKind>& effects, const AugmentedFit& warm,
                                              const AugmentedCalibrationOptions& options)
{
  std::vector<double> start = {warm.base.k1_per_s2, warm.base.k2_per_s, warm.base.tau_e_s, warm.base.eta_m};
  const std::vector<double> near_off = nestedStart(effects, warm);
  std::vector<std::size_t> new_positions;
  std::vector<const EffectParameterSpec*> new_specs;
  for (EffectKind kind : effects)
  {
    std::vector<double> known;
    if (valuesIn(warm, kind, &known))
    {
      start.insert(start.end(), known.begin(), known.end());
      continue;
    }
    for (const EffectParameterSpec& spec : candidateEffect(kind).parameters)
    {
      new_positions.push_back(start.size());
      new_specs.push_back(&spec);
      start.push_back(0.0);
    }
  }
  if (new_specs.empty())
  {
    return {start};
  }
  std::vector<std::vector<double>> starts;
  for (std::size_t i = 1; i <= options.effect_starts; ++i)
  {
    const std::vector<double> h = haltonSequencePoint(i, new_specs.size());
    for (std::size_t j = 0; j < new_specs.size(); ++j)
    {
      start[new_positions[j]] = new_specs[j]->start_lower + h[j] * (new_specs[j]->start_upper - new_specs[j]->start_lower);
    }
    starts.push_back(start);
  }
  starts.push_back(near_off);
  return starts;
}
}  // namespace

double augmentedSpeedMse(const AccParameters& p, const EffectSettings& effects,
                         const std::vector<CarFollowingRun>& segments)
{
  std::size_t samples = 0;
  return plainObjective(p, effects, segments, ResidualWeights{}, &samples);
}

MseWithGradient augmentedSpeedMseWithGradient(const AugmentedParameterBox& box, const std::vector<double>& x,
                                              const std::vector<CarFollowingRun>& segments)
{
  const GaussNewtonPass pass = gaussNewtonPass(box, x, segments, ResidualWeights{}, false);
  MseWithGradient result;
  result.mse = pass.mse;
  if (pass.diverged || pass.samples == 0)
    return result;
  // descent = J^T r with r = measured - simulated, so d mse / d u = -2 J^T r / n.
  const Eigen::VectorXd gradient = -2.0 / static_cast<double>(pass.samples) * pass.descent;
  result.unit_gradient.assign(gradient.data(), gradient.data() + gradient.size());
  return result;
}

std::vector<double> loopCheckSpeedsMps(const std::vector<CarFollowingRun>& segments)
{
  std::vector<double> speeds;
  for (const CarFollowingRun& run : segments)
    speeds.insert(speeds.end(), run.follower_speed_mps.begin(), run.follower_speed_mps.end());
  if (speeds.empty())
    return {};
  return {interpolatedQuantile(speeds, 0.0), interpolatedQuantile(speeds, 0.5), interpolatedQuantile(speeds, 1.0)};
}

AugmentedFit calibrateAugmented(EffectKind effect, const std::vector<CarFollowingRun>& segments,
                                const AugmentedCalibrationOptions& options, const AugmentedFit* warm_start)
{
  const std::vector<EffectKind> effects =
      effect == EffectKind::none ? std::vector<EffectKind>{} : std::vector<EffectKind>{effect};
  return calibrateAugmentedSet(effects, segments, options, warm_start);
}

namespace
{
/// Cold starts: Halton points of the base box (after the warm base, if any), every effect at the
/// middle of its start range.
std::vector<std::vector<double>> coldStarts(const std::vector<EffectKind>& effects,
                                            const std::vector<CarFollowingRun>& segments,
                                            const AugmentedCalibrationOptions& options, const AugmentedFit* warm_start)
{
  std::vector<std::vector<double>> starts = baseStarts(segments, options);
  if (warm_start != nullptr)
  {
    const AccParameters& w = warm_start->base;
    starts.insert(starts.begin(), {w.k1_per_s2, w.k2_per_s, w.tau_e_s, w.eta_m});
  }
  for (std::vector<double>& start : starts)
  {
    for (EffectKind kind : effects)
    {
      for (const EffectParameterSpec& spec : candidateEffect(kind).parameters)
      {
        start.push_back(0.5 * (spec.start_lower + spec.start_upper));
      }
    }
  }
  return starts;
}
}  // namespace

namespace
{
void checkSegmentsAndObjective(const std::vector<EffectKind>& effects, const std::vector<CarFollowingRun>& segments,
                               const AugmentedCalibrationOptions& options)
{
  for (const CarFollowingRun& run : segments)
  {
    const std::string problem = describeRunProblem(run);
    if (!problem.empty())
    {
      throw std::invalid_argument("cannot calibrate on segment '" + run.name + "': " + problem);
    }
  }
  if ((options.objective == FitObjective::gap || options.objective == FitObjective::speed_and_gap) &&
      std::find(effects.begin(), effects.end(), EffectKind::sensor_time_offset) != effects.end())
  {
    throw std::invalid_argument("a clock offset can only be fitted with a speed objective");
  }
}

/// The fit the tracker's best point makes; its standard errors are taken in `error_box` (the
/// search box, or the unheld box of a fit with an effect held).
AugmentedFit fitAtBest(ObjectiveTracker* tracker, const AugmentedParameterBox& error_box,
                       const std::vector<CarFollowingRun>& segments, const AugmentedCalibrationOptions& options)
{
  const AugmentedParameterBox& box = *tracker->box;
  AugmentedFit fit;
  fit.locally_stable = !tracker->best_x.empty() || tracker->best_unstable_x.empty();
  if (!fit.locally_stable)
  {
    tracker->best_x = tracker->best_unstable_x;
    tracker->best_value = tracker->best_unstable_value;
  }
  fit.effect = box.effect;
  fit.effects = box.effects;
  fit.evaluations = tracker->evaluations;
  fit.objective = options.objective;
  fit.train_objective = tracker->best_value;
  fit.train_mse_speed = tracker->best_value;
  fit.diverged = !(tracker->best_value < kDivergedObjective);
  if (tracker->best_x.empty())
  {
    fit.diverged = true;
    return fit;
  }
  fit.base = baseOf(tracker->best_x);
  fit.effect_values = effectPart(tracker->best_x);
  fit.settings = box.settingsOf(tracker->best_x);
  if (options.objective != FitObjective::speed)
  {
    fit.train_mse_speed = augmentedSpeedMse(fit.base, fit.settings, segments);
  }
  fit.standard_errors = fit.diverged ? std::vector<double>(box.dimension(), std::numeric_limits<double>::quiet_NaN())
                                     : augmentedStandardErrors(tracker->best_x, error_box, segments);
  return fit;
}
}  // namespace

AugmentedFit calibrateAugmentedSet(const std::vector<EffectKind>& effects, const std::vector<CarFollowingRun>& segments,
                                   const AugmentedCalibrationOptions& options, const AugmentedFit* warm_start)
{
  checkSegmentsAndObjective(effects, segments, options);
  const AugmentedParameterBox box(effects, options);
  ObjectiveTracker tracker(&box, &segments, options.objective);
  const std::vector<std::vector<double>> starts = warm_start != nullptr && !effects.empty()
                                                      ? effectStarts(effects, *warm_start, options)
                                                      : coldStarts(effects, segments, options, warm_start);
  for (const std::vector<double>& start : starts)
  {
    localSolve(&tracker, start, options);
  }
  return fitAtBest(&tracker, box, segments, options);
}

AugmentedFit calibrateWithEffectHeld(EffectKind effect, const std::vector<double>& held_values,
                                     const std::vector<CarFollowingRun>& segments,
                                     const AugmentedCalibrationOptions& options, const AugmentedFit* warm_start)
{
  checkSegmentsAndObjective({effect}, segments, options);
  const AugmentedParameterBox box(effect, options);
  if (effect == EffectKind::none || held_values.size() != box.dimension() - AugmentedParameterBox::kBaseDimension)
  {
    throw std::invalid_argument("calibrateWithEffectHeld: " + std::to_string(held_values.size()) +
                                " values for effect " + combinedEffectName({effect}));
  }
  AugmentedParameterBox held = box;
  for (std::size_t i = 0; i < held_values.size(); ++i)
  {
    const std::size_t j = AugmentedParameterBox::kBaseDimension + i;
    held.lower[j] = held.upper[j] = std::clamp(held_values[i], box.lower[j], box.upper[j]);
  }
  ObjectiveTracker tracker(&held, &segments, options.objective);
  // The held coordinates have zero width, so the unit-scaled normal equations never move them.
  for (const std::vector<double>& start : coldStarts({effect}, segments, options, warm_start))
  {
    localSolve(&tracker, start, options);
  }
  return fitAtBest(&tracker, box, segments, options);
}

std::string objectiveName(FitObjective objective)
{
  switch (objective)
  {
    case FitObjective::speed: return "speed";
    case FitObjective::gap: return "gap";
    case FitObjective::speed_and_gap: return "speed_and_gap";
    case FitObjective::speed_and_windows: return "speed_and_windows";
  }
  return "";
}

std::vector<double> nestedStart(const std::vector<EffectKind>& effects, const AugmentedFit& nested)
{
  std::vector<double> x = {nested.base.k1_per_s2, nested.base.k2_per_s, nested.base.tau_e_s, nested.base.eta_m};
  for (EffectKind kind : effects)
  {
    std::vector<double> values;
    if (!valuesIn(nested, kind, &values))
      values = nearOffValues(kind);
    x.insert(x.end(), values.begin(), values.end());
  }
  return x;
}

bool betterFit(const AugmentedFit& a, const AugmentedFit& b)
{
  if (a.usable() != b.usable())
    return a.usable();
  return !a.diverged && (b.diverged || a.train_objective < b.train_objective);
}

std::vector<EffectKind> effectsOf(const AugmentedFit& fit)
{
  if (!fit.effects.empty() || fit.effect == EffectKind::none)
  {
    return fit.effects;
  }
  return {fit.effect};
}

std::string combinedEffectName(const std::vector<EffectKind>& effects)
{
  if (effects.empty())
  {
    return effectName(EffectKind::none);
  }
  std::string name;
  for (EffectKind kind : effects)
  {
    name += (name.empty() ? "" : " + ") + effectName(kind);
  }
  return name;
}

std::vector<std::string> effectParameterNames(const std::vector<EffectKind>& effects)
{
  std::vector<std::string> names;
  for (EffectKind kind : effects)
  {
    for (const EffectParameterSpec& spec : candidateEffect(kind).parameters)
    {
      names.push_back(spec.name);
    }
  }
  return names;
}

}  // namespace acc
