#include "acc_identification/diagnosis/augmented_calibration.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <nlopt.hpp>

#include "acc_identification/model/batch_means.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
AugmentedParameterBox::AugmentedParameterBox(EffectKind kind, const AugmentedCalibrationOptions& options)
  : effect(kind)
{
  lower = {options.lower.k1_per_s2, options.lower.k2_per_s, options.lower.tau_e_s, options.lower.eta_m};
  upper = {options.upper.k1_per_s2, options.upper.k2_per_s, options.upper.tau_e_s, options.upper.eta_m};
  for (const EffectParameterSpec& spec : candidateEffect(kind).parameters)
  {
    lower.push_back(spec.lower);
    upper.push_back(spec.upper);
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
    u[i] = std::clamp((x[i] - lower[i]) / (upper[i] - lower[i]), 0.0, 1.0);
  }
  return u;
}

namespace
{
constexpr std::size_t kBaseDimension = AugmentedParameterBox::kBaseDimension;
AccParameters baseOf(const std::vector<double>& x) { return AugmentedParameterBox::baseOf(x); }
std::vector<double> effectPart(const std::vector<double>& x) { return AugmentedParameterBox::effectPart(x); }


/// Evaluates the objective at physical points and remembers the best one ever seen, so the
/// result never depends on where NLopt happens to stop or whether it throws.
struct ObjectiveTracker
{
  const AugmentedParameterBox* box;
  const std::vector<CarFollowingRun>* segments;
  std::vector<double> best_x;
  double best_value = std::numeric_limits<double>::infinity();
  std::size_t evaluations = 0;

  double operator()(const std::vector<double>& unit_x)
  {
    const std::vector<double> x = box->physical(unit_x);
    const double value =
        augmentedSpeedMse(baseOf(x), makeEffectSettings(box->effect, effectPart(x)), *segments);
    ++evaluations;
    if (value < best_value)
    {
      best_value = value;
      best_x = x;
    }
    return value;
  }
};

double nloptObjective(const std::vector<double>& x, std::vector<double>& /*gradient*/, void* data)
{
  return (*static_cast<ObjectiveTracker*>(data))(x);
}

void localSolve(ObjectiveTracker* tracker, const std::vector<double>& start_physical,
                const AugmentedCalibrationOptions& options)
{
  const AugmentedParameterBox& box = *tracker->box;
  nlopt::opt solver(nlopt::LN_BOBYQA, static_cast<unsigned>(box.dimension()));
  solver.set_lower_bounds(std::vector<double>(box.dimension(), 0.0));
  solver.set_upper_bounds(std::vector<double>(box.dimension(), 1.0));
  solver.set_min_objective(nloptObjective, tracker);
  solver.set_maxeval(options.max_evaluations_per_start);
  solver.set_xtol_rel(options.relative_x_tolerance);
  solver.set_initial_step(0.05);
  std::vector<double> x = box.unit(start_physical);  // clamped into the box
  double value = 0.0;
  try
  {
    solver.optimize(x, value);
  }
  catch (const std::exception&)
  {
    // Round-off or a forced stop: the tracker already holds the best point evaluated.
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

std::vector<std::vector<double>> effectStarts(EffectKind effect, const AugmentedFit& warm,
                                              const std::vector<CarFollowingRun>& segments,
                                              const AugmentedCalibrationOptions& options)
{
  const auto& specs = candidateEffect(effect).parameters;
  const std::vector<double> base = {warm.base.k1_per_s2, warm.base.k2_per_s, warm.base.tau_e_s, warm.base.eta_m};
  std::vector<std::vector<double>> starts;
  for (std::size_t i = 1; i <= options.effect_starts; ++i)
  {
    const std::vector<double> h = haltonSequencePoint(i, specs.size());
    std::vector<double> start = base;
    for (std::size_t j = 0; j < specs.size(); ++j)
    {
      start.push_back(specs[j].start_lower + h[j] * (specs[j].start_upper - specs[j].start_lower));
    }
    starts.push_back(start);
  }
  // The effect "almost off" (at the edge of its start range that is closest to the base model),
  // so that the augmented fit can never end worse than the base fit it starts from.
  std::vector<double> near_off = base;
  for (const EffectParameterSpec& spec : specs)
  {
    const bool off_at_upper = effect == EffectKind::acceleration_limits || effect == EffectKind::set_speed_cruise;
    near_off.push_back(off_at_upper ? spec.upper : (spec.lower < 0.0 ? 0.0 : spec.lower));
  }
  if (effect == EffectKind::set_speed_cruise)
  {
    near_off[kBaseDimension + 1] = specs[1].start_upper;
  }
  starts.push_back(near_off);
  (void)segments;
  return starts;
}


std::vector<double> simulatedSpeeds(const std::vector<double>& x, EffectKind effect,
                                    const std::vector<CarFollowingRun>& segments)
{
  std::vector<double> speeds;
  const EffectSettings settings = makeEffectSettings(effect, effectPart(x));
  for (const CarFollowingRun& run : segments)
  {
    const SimulatedFollower sim = simulateFollower(baseOf(x), settings, run);
    speeds.insert(speeds.end(), sim.speed_mps.begin(), sim.speed_mps.end());
  }
  return speeds;
}

std::vector<double> standardErrors(const std::vector<double>& x, const AugmentedParameterBox& box,
                                   const std::vector<CarFollowingRun>& segments)
{
  const std::size_t p = x.size();
  std::vector<double> measured;
  for (const CarFollowingRun& run : segments)
  {
    measured.insert(measured.end(), run.follower_speed_mps.begin(), run.follower_speed_mps.end());
  }
  const std::vector<double> fitted = simulatedSpeeds(x, box.effect, segments);
  const std::size_t n = measured.size();
  std::vector<double> nan(p, std::numeric_limits<double>::quiet_NaN());
  if (n <= p)
  {
    return nan;
  }
  Eigen::MatrixXd jacobian(n, p);
  for (std::size_t j = 0; j < p; ++j)
  {
    // Central differences of 1e-4 of the box width, one-sided at a bound.
    const double step = 1e-4 * (box.upper[j] - box.lower[j]);
    std::vector<double> plus = x;
    std::vector<double> minus = x;
    plus[j] = std::min(x[j] + step, box.upper[j]);
    minus[j] = std::max(x[j] - step, box.lower[j]);
    const std::vector<double> up = simulatedSpeeds(plus, box.effect, segments);
    const std::vector<double> down = simulatedSpeeds(minus, box.effect, segments);
    for (std::size_t i = 0; i < n; ++i)
    {
      jacobian(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = (up[i] - down[i]) / (plus[j] - minus[j]);
    }
  }
  std::vector<double> residuals(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    residuals[i] = measured[i] - fitted[i];
  }
  // A column that does not move the speed (e.g. a limit never reached) is not determined: its
  // error is NaN, and the others are computed without it.
  std::vector<Eigen::Index> active;
  for (std::size_t j = 0; j < p; ++j)
  {
    if (jacobian.col(static_cast<Eigen::Index>(j)).norm() > 1e-9 * std::sqrt(static_cast<double>(n)))
    {
      active.push_back(static_cast<Eigen::Index>(j));
    }
  }
  Eigen::MatrixXd reduced(n, active.size());
  for (std::size_t a = 0; a < active.size(); ++a)
  {
    reduced.col(static_cast<Eigen::Index>(a)) = jacobian.col(active[a]);
  }
  const Eigen::MatrixXd information = reduced.transpose() * reduced;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(information);
  // Sandwich with the batch-means covariance of the scores J_k r_k: honest when the residuals are
  // correlated over seconds, as model errors are. Blocks do not straddle segments.
  std::vector<std::vector<double>> times;
  for (const CarFollowingRun& run : segments)
  {
    times.push_back(run.time_s);
  }
  const Eigen::VectorXd residual_vector = Eigen::Map<const Eigen::VectorXd>(residuals.data(), static_cast<Eigen::Index>(n));
  const double block_s = batchMeansBlockLength(times, residual_vector, 10.0).block_length_s;
  std::size_t blocks = 0;
  const Eigen::MatrixXd scores_covariance = batchMeansScoreCovariance(times, reduced, residual_vector, block_s, &blocks);
  if (!lu.isInvertible() || blocks < 4)
  {
    return nan;
  }
  const Eigen::MatrixXd inverse = lu.inverse();
  const Eigen::MatrixXd covariance = inverse * scores_covariance * inverse;
  for (std::size_t a = 0; a < active.size(); ++a)
  {
    const double variance = covariance(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(a));
    nan[static_cast<std::size_t>(active[a])] = variance >= 0.0 ? std::sqrt(variance) : nan[0];
  }
  return nan;
}
}  // namespace

double augmentedSpeedMse(const AccParameters& p, const EffectSettings& effects,
                         const std::vector<CarFollowingRun>& segments)
{
  double sum = 0.0;
  std::size_t count = 0;
  for (const CarFollowingRun& run : segments)
  {
    const SimulatedFollower sim = simulateFollower(p, effects, run);
    if (sim.diverged)
    {
      return kDivergedObjective;
    }
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      const double error = run.follower_speed_mps[k] - sim.speed_mps[k];
      sum += error * error;
    }
    count += run.size();
  }
  const double mse = count > 0 ? sum / static_cast<double>(count) : 0.0;
  return std::isfinite(mse) ? std::min(mse, kDivergedObjective) : kDivergedObjective;
}

AugmentedFit calibrateAugmented(EffectKind effect, const std::vector<CarFollowingRun>& segments,
                                const AugmentedCalibrationOptions& options, const AugmentedFit* warm_start)
{
  for (const CarFollowingRun& run : segments)
  {
    const std::string problem = describeRunProblem(run);
    if (!problem.empty())
    {
      throw std::invalid_argument("cannot calibrate on segment '" + run.name + "': " + problem);
    }
  }
  const AugmentedParameterBox box(effect, options);
  ObjectiveTracker tracker{&box, &segments, {}, std::numeric_limits<double>::infinity(), 0};
  std::vector<std::vector<double>> starts;
  if (warm_start != nullptr && effect != EffectKind::none)
  {
    starts = effectStarts(effect, *warm_start, segments, options);
  }
  else
  {
    starts = baseStarts(segments, options);
    if (warm_start != nullptr)
    {
      const AccParameters& w = warm_start->base;
      starts.insert(starts.begin(), {w.k1_per_s2, w.k2_per_s, w.tau_e_s, w.eta_m});
    }
    if (effect != EffectKind::none)
    {
      // No base fit given: append the effect's mid-range values to each base start.
      for (std::vector<double>& start : starts)
      {
        for (const EffectParameterSpec& spec : candidateEffect(effect).parameters)
        {
          start.push_back(0.5 * (spec.start_lower + spec.start_upper));
        }
      }
    }
  }
  for (const std::vector<double>& start : starts)
  {
    localSolve(&tracker, start, options);
  }
  AugmentedFit fit;
  fit.effect = effect;
  fit.evaluations = tracker.evaluations;
  fit.train_mse_speed = tracker.best_value;
  fit.diverged = !(tracker.best_value < kDivergedObjective);
  if (tracker.best_x.empty())
  {
    fit.diverged = true;
    return fit;
  }
  fit.base = baseOf(tracker.best_x);
  fit.effect_values = effectPart(tracker.best_x);
  fit.settings = makeEffectSettings(effect, fit.effect_values);
  fit.standard_errors = fit.diverged ? std::vector<double>(box.dimension(), std::numeric_limits<double>::quiet_NaN())
                                     : standardErrors(tracker.best_x, box, segments);
  return fit;
}


}  // namespace acc
