#include "acc_identification/diagnosis/augmented_stability_verdict.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/sample_statistics.h"
#include "acc_identification/model/json_number.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <nlopt.hpp>

#include "acc_identification/calibration/side_fits.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/diagnosis/augmented_stability.h"
#include "acc_identification/model/block_bootstrap.h"
#include "acc_identification/model/halton_sequence.h"
#include "acc_identification/model/parallel_tasks.h"

namespace acc
{
namespace
{
constexpr int kIndexGridPoints = 2000;
constexpr double kIndexLowestFrequencyRadS = 1e-3;
constexpr double kIndexHighestFrequencyRadS = 20.0;

/// The index's logarithmic frequency grid, computed once (the side search evaluates the index
/// thousands of times).
const std::vector<double>& indexFrequencyGridRadS()
{
  static const std::vector<double> grid = [] {
    std::vector<double> w;
    for (int i = 0; i <= kIndexGridPoints; ++i)
    {
      w.push_back(kIndexLowestFrequencyRadS * std::pow(kIndexHighestFrequencyRadS / kIndexLowestFrequencyRadS,
                                                       static_cast<double>(i) / kIndexGridPoints));
    }
    return w;
  }();
  return grid;
}

/// One term of the index: k1 (1 - |Gamma(j w)|^2) / w^2.
double indexTerm(const AccParameters& p, const EffectSettings& effects, double operating_speed_mps, double w)
{
  // Grouped as gridIndex groups it, so that a difference against its value is the term's alone.
  return p.k1_per_s2 * ((1.0 - augmentedTransferGainSquared(p, effects, operating_speed_mps, w)) / (w * w));
}

/// The index and the grid frequency of its least term. The frequency is found for k1 = 0 too
/// (the index is then 0), where the side search still needs the index's slope in k1.
struct GridIndex
{
  double value = 0.0;
  double frequency_rad_s = std::numeric_limits<double>::quiet_NaN();
};

GridIndex gridIndex(const AccParameters& p, const EffectSettings& effects, double operating_speed_mps)
{
  GridIndex least;
  double lowest = std::numeric_limits<double>::infinity();
  for (const double w : indexFrequencyGridRadS())
  {
    const double gain_squared = augmentedTransferGainSquared(p, effects, operating_speed_mps, w);
    const double term = (1.0 - gain_squared) / (w * w);
    if (term < lowest)
    {
      lowest = term;
      least.frequency_rad_s = w;
    }
  }
  least.value = p.k1_per_s2 > 0.0 ? p.k1_per_s2 * lowest : 0.0;
  return least;
}

/// Tracks the best feasible point of one side seen by any solve, whatever NLopt returns.
struct SideSearch
{
  const AugmentedParameterBox* box = nullptr;
  const std::vector<CarFollowingRun>* train = nullptr;
  double operating_speed_mps = 0.0;
  double side = 1.0;  ///< +1: stable (index >= 0), -1: unstable (index <= 0)
  /// Both sides are locally stable models, as every fit is (loopCheckSpeedsMps of the training
  /// data): the test compares the best string-stable and string-unstable cars that can exist.
  std::vector<double> loop_speeds_mps;
  std::vector<double> best_x;
  double best_mse = std::numeric_limits<double>::infinity();
  std::size_t evaluations = 0;

  /// The solver asks for the objective and the constraint at the same point: the index (2,001
  /// transfer-function evaluations) is computed once per point, with the grid frequency where
  /// its minimum lies.
  std::vector<double> indexed_x;
  GridIndex indexed;

  const GridIndex& index(const std::vector<double>& x)
  {
    if (x != indexed_x)
    {
      indexed = gridIndex(AugmentedParameterBox::baseOf(x), box->settingsOf(x), operating_speed_mps);
      indexed_x = x;
    }
    return indexed;
  }
  double objective(const std::vector<double>& unit_x, std::vector<double>& gradient)
  {
    const std::vector<double> x = box->physical(unit_x);
    double mse = 0.0;
    if (gradient.empty())
    {
      mse = augmentedSpeedMse(AugmentedParameterBox::baseOf(x), box->settingsOf(x), *train);
    }
    else
    {
      const MseWithGradient at = augmentedSpeedMseWithGradient(*box, x, *train);
      mse = at.mse;
      if (at.unit_gradient.size() == gradient.size())
        gradient = at.unit_gradient;
      else
        std::fill(gradient.begin(), gradient.end(), 0.0);  // diverged: a plateau, the solver turns back
    }
    ++evaluations;
    if (mse < best_mse && side * index(x).value >= 0.0 &&
        locallyStableAt(AugmentedParameterBox::baseOf(x), box->settingsOf(x), loop_speeds_mps))
    {
      best_mse = mse;
      best_x = x;
    }
    return mse;
  }
};

double sideObjective(const std::vector<double>& unit_x, std::vector<double>& gradient, void* data)
{
  return static_cast<SideSearch*>(data)->objective(unit_x, gradient);
}

/// NLopt's form c(x) <= 0 of side * index(x) >= 0. The index is the least of 2,001 smooth terms,
/// so its gradient is the gradient of the least one (the envelope theorem; not at a tie), taken by
/// forward differences in the unit box at that term's frequency: one transfer-function evaluation
/// per parameter instead of a whole grid.
double sideConstraint(const std::vector<double>& unit_x, std::vector<double>& gradient, void* data)
{
  SideSearch& search = *static_cast<SideSearch*>(data);
  const GridIndex& at = search.index(search.box->physical(unit_x));
  const double value = -search.side * at.value;
  constexpr double kStep = 1e-7;
  for (std::size_t j = 0; j < gradient.size(); ++j)
  {
    std::vector<double> moved = unit_x;
    const double step = moved[j] + kStep <= 1.0 ? kStep : -kStep;
    moved[j] += step;
    const std::vector<double> x = search.box->physical(moved);
    const double term = indexTerm(AugmentedParameterBox::baseOf(x), search.box->settingsOf(x),
                                  search.operating_speed_mps, at.frequency_rad_s);
    gradient[j] = (-search.side * term - value) / step;
  }
  return value;
}

void solveFrom(SideSearch* search, const std::vector<double>& start, const AugmentedStabilityTestOptions& options)
{
  const std::size_t n = search->box->dimension();
  nlopt::opt solver(nlopt::LD_SLSQP, static_cast<unsigned>(n));
  solver.set_lower_bounds(std::vector<double>(n, 0.0));
  solver.set_upper_bounds(std::vector<double>(n, 1.0));
  solver.set_min_objective(sideObjective, search);
  solver.add_inequality_constraint(sideConstraint, search, 1e-9);
  solver.set_maxeval(options.max_evaluations_per_start);
  solver.set_xtol_rel(options.relative_x_tolerance);
  solver.set_ftol_rel(options.relative_mse_tolerance);
  std::vector<double> x = search->box->unit(start);
  double value = 0.0;
  try
  {
    solver.optimize(x, value);
  }
  catch (const std::exception&)
  {
    // Round-off or a forced stop: the search already holds the best feasible point evaluated.
  }
}

/// Every start solved on its own copy of the search, on options.threads; the best feasible point
/// of all wins, the first start's on a tie, so the result does not depend on the thread count.
SideSearch bestOfStarts(const SideSearch& empty, const std::vector<std::vector<double>>& starts,
                        const AugmentedStabilityTestOptions& options)
{
  std::vector<SideSearch> searches(starts.size(), empty);
  runTasksInParallel(starts.size(), effectiveThreadCount(options.threads, starts.size()),
                     [&](std::size_t i) { solveFrom(&searches[i], starts[i], options); });
  SideSearch best = empty;
  for (const SideSearch& one : searches)
  {
    best.evaluations += one.evaluations;
    if (one.best_mse < best.best_mse)
    {
      best.best_mse = one.best_mse;
      best.best_x = one.best_x;
    }
  }
  return best;
}

/// tau_e on the base model's boundary k1 tau^2 + 2 k2 tau = 2 for the start's k1 and k2 (the
/// positive root), so that a start sits where the two sides meet.
std::vector<double> ontoBaseBoundary(std::vector<double> x, const AugmentedParameterBox& box)
{
  const double k1 = x[0], k2 = x[1];
  double tau = k1 > 1e-12 ? (-k2 + std::sqrt(k2 * k2 + 2.0 * k1)) / k1 : (k2 > 1e-12 ? 1.0 / k2 : x[2]);
  x[2] = std::clamp(tau, box.lower[2], box.upper[2]);
  return x;
}

/// The nested test's best model on the side searched, as a point of this model (its new effects
/// off); none when there is no nested test or it found no model on that side.
std::vector<std::vector<double>> nestedSideStart(const AugmentedStabilityTestResult* nested, double side,
                                                 const std::vector<EffectKind>& effects)
{
  if (nested == nullptr)
    return {};
  const AugmentedSideFit& same_side = side > 0.0 ? nested->best_stable : nested->best_unstable;
  if (!same_side.found)
    return {};
  AugmentedFit fit;
  fit.effect = nested->effect;
  fit.effects = nested->effects;
  fit.base = same_side.base;
  fit.effect_values = same_side.effect_values;
  return {nestedStart(effects, fit)};
}

std::vector<std::vector<double>> sideStarts(const std::vector<double>& chosen, const AugmentedParameterBox& box,
                                            const AugmentedCalibrationOptions& bounds,
                                            const AugmentedStabilityTestOptions& options)
{
  std::vector<std::vector<double>> starts = {chosen, ontoBaseBoundary(chosen, box)};
  const AccParameters& lo = bounds.start_lower;
  const AccParameters& hi = bounds.start_upper;
  for (std::size_t i = 1; i <= options.halton_starts; ++i)
  {
    const std::vector<double> h = haltonSequencePoint(i, 3);
    std::vector<double> x = chosen;  // eta and the effect from the chosen fit
    x[0] = lo.k1_per_s2 + h[0] * (hi.k1_per_s2 - lo.k1_per_s2);
    x[1] = lo.k2_per_s + h[1] * (hi.k2_per_s - lo.k2_per_s);
    x[2] = lo.tau_e_s + h[2] * (hi.tau_e_s - lo.tau_e_s);
    starts.push_back(x);
  }
  return starts;
}

std::vector<double> physicalOf(const AugmentedFit& fit)
{
  std::vector<double> x = {fit.base.k1_per_s2, fit.base.k2_per_s, fit.base.tau_e_s, fit.base.eta_m};
  x.insert(x.end(), fit.effect_values.begin(), fit.effect_values.end());
  return x;
}

AugmentedSideFit sideFitOf(const std::vector<double>& x, double train_mse, const AugmentedParameterBox& box,
                           double operating_speed_mps)
{
  AugmentedSideFit side;
  side.found = true;
  side.base = AugmentedParameterBox::baseOf(x);
  side.effect_values = AugmentedParameterBox::effectPart(x);
  side.settings = box.settingsOf(x);
  side.stability_index = augmentedStabilityIndex(side.base, side.settings, operating_speed_mps);
  side.peak_gain_db = analyzeAugmentedStability(side.base, box.effect, side.settings, operating_speed_mps).peak_gain_db;
  side.train_rmse_speed_mps = std::sqrt(train_mse);
  return side;
}

/// The verdict from the two p-values and the sides' indices, with its reason.
void decide(AugmentedStabilityTestResult* r)
{
  const std::string numbers =
      combinedEffectName(r->effects) + " model: " +
      describeComparison(*r, r->best_stable.test_rmse_speed_mps, "index " + significant(r->best_stable.stability_index),
                         r->best_unstable.test_rmse_speed_mps,
                         "index " + significant(r->best_unstable.stability_index));
  if (decideSides(*r, r->best_unstable.stability_index < 0.0, r->best_stable.stability_index > 0.0) ==
      SideDecision::Decided)
  {
    r->reason = numbers + (r->verdict == StabilityVerdict::Unstable ? ": the data reject string stability"
                                                                     : ": the data reject string instability");
    return;
  }
  r->reason = numbers + ": neither side predicts the held-out data significantly better with a model strictly "
                        "inside its side (alpha " + significant(r->alpha) + ")";
}

nlohmann::json sideJson(const AugmentedSideFit& s, const std::vector<EffectKind>& effects)
{
  if (!s.found)
    return nullptr;
  nlohmann::json effect_parameters = nlohmann::json::object();
  const std::vector<std::string> names = effectParameterNames(effects);
  for (std::size_t i = 0; i < names.size() && i < s.effect_values.size(); ++i)
    effect_parameters[names[i]] = jsonNumber(s.effect_values[i]);
  return {{"parameters",
           {{"k1", jsonNumber(s.base.k1_per_s2)},
            {"k2", jsonNumber(s.base.k2_per_s)},
            {"tau_e", jsonNumber(s.base.tau_e_s)},
            {"eta", jsonNumber(s.base.eta_m)}}},
          {"effect_parameters", effect_parameters},
          {"stability_index", jsonNumber(s.stability_index)},
          {"peak_gain_db", jsonNumber(s.peak_gain_db)},
          {"train_rmse_speed", jsonNumber(s.train_rmse_speed_mps)},
          {"test_rmse_speed", jsonNumber(s.test_rmse_speed_mps)}};
}
}  // namespace

double augmentedStabilityIndex(const AccParameters& p, const EffectSettings& effects, double operating_speed_mps)
{
  return gridIndex(p, effects, operating_speed_mps).value;
}

AugmentedStabilityTestResult testAugmentedStringStability(const AugmentedFit& chosen,
                                                          const std::vector<CarFollowingRun>& train,
                                                          const std::vector<CarFollowingRun>& test,
                                                          double operating_speed_mps,
                                                          const AugmentedCalibrationOptions& bounds,
                                                          const AugmentedStabilityTestOptions& options,
                                                          const AugmentedStabilityTestResult* nested)
{
  AugmentedStabilityTestResult r;
  r.effect = chosen.effect;
  r.effects = effectsOf(chosen);
  r.alpha = options.alpha;
  const HeldOutSegments segments = heldOutSegmentsOf(test);
  r.held_out_samples = segments.scored_samples;
  r.held_out_duration_s = segments.duration_s;
  if (const std::string shortage = heldOutShortage(segments, options); !shortage.empty())
  {
    r.reason = shortage;
    return r;
  }
  if (const std::string steady = describeInsufficientExcitation(train, options.excitation); !steady.empty())
  {
    r.reason = "the parts fitted on: " + steady +
               ": they do not decide string stability (calibrate gives no verdict on such data either)";
    return r;
  }

  if (!chosen.locally_stable)
  {
    r.reason = "the fit reached no locally stable model, so neither side's best car is known";
    return r;
  }
  // The chosen fit is one side's best; the other side's is searched over every parameter of the
  // model (all of its effects), as it was fitted.
  const AugmentedParameterBox box(r.effects, bounds);
  const std::vector<double> chosen_x = physicalOf(chosen);
  const bool chosen_stable = augmentedStabilityIndex(chosen.base, chosen.settings, operating_speed_mps) >= 0.0;
  SideSearch search;
  search.box = &box;
  search.train = &train;
  search.operating_speed_mps = operating_speed_mps;
  search.loop_speeds_mps = loopCheckSpeedsMps(train);
  search.side = chosen_stable ? -1.0 : 1.0;
  std::vector<std::vector<double>> starts = sideStarts(chosen_x, box, bounds, options);
  for (std::vector<double>& start : nestedSideStart(nested, search.side, r.effects))
    starts.push_back(std::move(start));
  search = bestOfStarts(search, starts, options);
  r.side_fit_evaluations = search.evaluations;
  AugmentedSideFit chosen_side = sideFitOf(chosen_x, chosen.train_mse_speed, box, operating_speed_mps);
  AugmentedSideFit other_side;
  if (!search.best_x.empty())
    other_side = sideFitOf(search.best_x, search.best_mse, box, operating_speed_mps);
  r.best_stable = chosen_stable ? chosen_side : other_side;
  r.best_unstable = chosen_stable ? other_side : chosen_side;
  if (!other_side.found)
  {
    r.reason = std::string("no ") + (chosen_stable ? "unstable" : "stable") + " " + combinedEffectName(r.effects) +
               " model was found in the search box: the test cannot compare the two sides";
    return r;
  }

  const HeldOutSides sides =
      scoreHeldOutSides(heldOutErrors(r.best_stable.base, r.best_stable.settings, test),
                        heldOutErrors(r.best_unstable.base, r.best_unstable.settings, test), combinedEffectName(r.effects));
  r.best_stable.test_rmse_speed_mps = sides.stable_rmse_speed_mps;
  r.best_unstable.test_rmse_speed_mps = sides.unstable_rmse_speed_mps;
  if (!sides.divergence.empty())
  {
    r.reason = sides.divergence;
    return r;
  }
  HeldOutSideComparison(sides.stable_squared, sides.unstable_squared, segments, options).report(r);
  decide(&r);
  return r;
}

nlohmann::json toJson(const AugmentedStabilityTestResult& r)
{
  return {{"effect", effectName(r.effect)},
          {"effects", effectNames(r.effects)},
          {"verdict", toString(r.verdict)},
          {"p_value", jsonNumber(r.p_value)},
          {"p_value_stable_rejected", jsonNumber(r.p_value_stable_rejected)},
          {"p_value_unstable_rejected", jsonNumber(r.p_value_unstable_rejected)},
          {"alpha", r.alpha},
          {"best_stable", sideJson(r.best_stable, r.effects)},
          {"best_unstable", sideJson(r.best_unstable, r.effects)},
          {"held_out_samples", r.held_out_samples},
          {"block_length_s", jsonNumber(r.block_length_s)},
          {"side_fit_evaluations", r.side_fit_evaluations},
          {"reason", r.reason}};
}

}  // namespace acc
