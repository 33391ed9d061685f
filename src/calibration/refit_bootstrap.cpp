#include "acc_identification/calibration/refit_bootstrap.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <ostream>
#include <random>

#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/calibration/margin_constrained_fit.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/json_number.h"
#include "acc_identification/model/normal_source.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/parallel_tasks.h"
#include "acc_identification/model/portable_uniform.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr const char* kQuantityNames[] = {"k1", "k2", "tau_e", "eta", "stability_margin"};

/// What a replicate is built from, per run: the fit's simulated speeds, the centred speed
/// residuals after the measured start, and the gap's sample noise.
struct RunModel
{
  std::vector<double> simulated_speed_mps;
  std::vector<double> residual_mps;
  double gap_noise_m = 0.0;
};

/// The runs' models from the fit's simulation of each.
std::vector<RunModel> modelRuns(const std::vector<std::vector<double>>& simulated_speed_mps,
                                const std::vector<CarFollowingRun>& runs)
{
  std::vector<RunModel> models;
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    const CarFollowingRun& run = runs[r];
    RunModel model;
    model.simulated_speed_mps = simulated_speed_mps[r];
    double sum = 0.0;
    for (std::size_t k = 1; k < run.size(); ++k)  // the first residual is 0 by construction
    {
      model.residual_mps.push_back(run.follower_speed_mps[k] - model.simulated_speed_mps[k]);
      sum += model.residual_mps.back();
    }
    for (double& e : model.residual_mps)
      e -= sum / static_cast<double>(model.residual_mps.size());
    const double gap_noise = gapSampleNoiseM(run);
    model.gap_noise_m = std::isfinite(gap_noise) ? gap_noise : 0.0;
    models.push_back(std::move(model));
  }
  return models;
}

/// One replicate drive of a run: the simulation plus circular blocks of residuals, the gap shifted.
CarFollowingRun replicateRun(const CarFollowingRun& run, const RunModel& model, std::size_t block_samples,
                             std::mt19937_64& engine, NormalSource& normal)
{
  CarFollowingRun replicate = run;
  const std::size_t n = model.residual_mps.size();
  const std::size_t length = std::max<std::size_t>(1, std::min(block_samples, n));
  std::size_t k = 0;
  while (k < run.size())
  {
    const std::size_t start = static_cast<std::size_t>(uniformBelow(engine, n));
    for (std::size_t j = 0; j < length && k < run.size(); ++j, ++k)
      replicate.follower_speed_mps[k] = model.simulated_speed_mps[k] + model.residual_mps[(start + j) % n];
  }
  const double gap_shift_m = model.gap_noise_m * normal.standardNormal();
  for (double& s : replicate.space_gap_m)
    s += gap_shift_m;
  return replicate;
}

/// The base model's five quantities of one fit, with their sandwich standard errors (NaN where
/// held at a bound).
BootstrapDraw drawOf(const IdentifiableQuantities& quantities)
{
  BootstrapDraw draw;
  for (const char* name : kQuantityNames)
  {
    const QuantityEstimate* q = quantities.find(name);
    draw.value.push_back(q ? q->value : kNaN);
    draw.held_by_bound.push_back(q ? q->held_by_bound : "");
    draw.standard_error.push_back(q && q->held_by_bound.empty() ? q->standard_error : kNaN);
  }
  return draw;
}

/// Quantity i's entry in a list of bounds, or `none` where the list has none (short, or NaN).
double boundOf(const std::vector<double>& bounds, std::size_t i, double none)
{
  return i < bounds.size() && !std::isnan(bounds[i]) ? bounds[i] : none;
}

/// Why quantity i is near a bound of the fit's range, or "": within 1.96 of its standard errors,
/// where value +- 1.96 se would cross it. There the refits pile up against the bound and their
/// own standard errors say little, so that the studentised interval can come out far narrower
/// than their spread (Andrews 2000: a parameter near the boundary, not only on it).
std::string nearBound(const FittedDrives& fitted, std::size_t i)
{
  const double value = fitted.at_fit.value[i], reach = 1.96 * fitted.at_fit.standard_error[i];
  const double lower = boundOf(fitted.lower_bound, i, -kInfinity), upper = boundOf(fitted.upper_bound, i, kInfinity);
  if (!std::isfinite(reach) || (value - reach > lower && value + reach < upper))
    return "";
  const bool low = value - lower <= upper - value;
  return printfText("%s = %.4g within 1.96 standard errors (%.3g) of its %s bound %g", fitted.quantity_names[i].c_str(),
                    value, reach / 1.96, low ? "lower" : "upper", low ? lower : upper);
}

/// Which parameter of the fit sits at or near a bound ("tau_e at its lower bound 0"), or "".
std::string parameterAtBound(const FittedDrives& fitted)
{
  const BootstrapDraw& at_fit = fitted.at_fit;
  for (std::size_t i = 0; i < fitted.parameter_count && i < at_fit.held_by_bound.size(); ++i)
    if (!at_fit.held_by_bound[i].empty())
      return at_fit.held_by_bound[i];
  for (std::size_t i = 0; i < fitted.parameter_count && i < at_fit.value.size(); ++i)
  {
    const std::string near = nearBound(fitted, i);
    if (!near.empty())
      return near;
  }
  return "";
}

/// One replicate's refit: nullopt when it diverged.
using Refit = std::optional<BootstrapDraw>;

/// Builds replicate `index` (its own random stream, so that threads do not change the draws) and
/// refits it.
Refit refitReplicate(std::size_t index, const std::vector<CarFollowingRun>& runs, const std::vector<RunModel>& models,
                     std::size_t block_samples, const ReplicateRefit& refit, std::uint64_t seed)
{
  std::mt19937_64 engine(streamSeed(seed, 2 * index));
  NormalSource normal(streamSeed(seed, 2 * index + 1));
  std::vector<CarFollowingRun> replicate;
  for (std::size_t r = 0; r < runs.size(); ++r)
    replicate.push_back(replicateRun(runs[r], models[r], block_samples, engine, normal));
  return refit(replicate);
}

/// The interval and spread of quantity i from the refits.
BootstrapQuantity summarise(std::size_t i, const FittedDrives& fitted, const std::vector<Refit>& refits)
{
  const BootstrapDraw& at_fit = fitted.at_fit;
  BootstrapQuantity q;
  q.name = fitted.quantity_names[i];
  q.value = at_fit.value[i];
  std::vector<double> values, studentised, refit_errors;
  for (const Refit& refit : refits)
  {
    if (!refit || i >= refit->value.size())
      continue;
    values.push_back(refit->value[i]);
    const double se = refit->standard_error[i];
    if (std::isfinite(se) && se > 0.0)
    {
      studentised.push_back((refit->value[i] - q.value) / se);
      refit_errors.push_back(se);
    }
  }
  q.fit_standard_error = at_fit.standard_error[i];
  if (!refit_errors.empty())
    q.refits_standard_error_median = interpolatedQuantile(refit_errors, 0.5);
  if (values.size() >= 2)
  {
    const double mean = meanOf(values);
    std::vector<double> squared_deviations;
    for (double v : values)
      squared_deviations.push_back((v - mean) * (v - mean));
    q.standard_error = std::sqrt(meanOf(squared_deviations) * values.size() / (values.size() - 1.0));
    q.bias = mean - q.value;
  }
  const double se = at_fit.standard_error[i];
  const std::string near = nearBound(fitted, i);
  if (!at_fit.held_by_bound[i].empty())
    q.note = at_fit.held_by_bound[i] + ": the bootstrap does not hold at a bound" + fitted.at_bound_hint;
  else if (!std::isfinite(se))
    q.note = "no standard error at the fit";
  else if (!near.empty())
    q.note = near + ": the bootstrap does not hold near a bound";
  else if (2 * studentised.size() < refits.size())
    q.note = "fewer than half the refits have a standard error";
  else if (studentised.size() < kMinRefitsFor95Interval)
    q.note = std::to_string(studentised.size()) + " refits with a standard error: a 95 % interval needs at least " +
             std::to_string(kMinRefitsFor95Interval);
  else
  {
    // A refit whose own standard error came out small gives a large t: the interval can reach
    // past what the parameter can be, and there it is cut at the fit's range.
    q.interval_95_low = std::max(q.value - interpolatedQuantile(studentised, 0.975) * se, boundOf(fitted.lower_bound, i, -kInfinity));
    q.interval_95_high =
        std::min(q.value - interpolatedQuantile(studentised, 0.025) * se, boundOf(fitted.upper_bound, i, kInfinity));
  }
  return q;
}

}  // namespace

const BootstrapQuantity* RefitBootstrap::find(const std::string& name) const
{
  for (const BootstrapQuantity& q : quantities)
    if (q.name == name)
      return &q;
  return nullptr;
}

std::string RefitBootstrap::caution() const
{
  return held_near_bound.empty()
             ? ""
             : held_near_bound + ": the other intervals are approximate (a bootstrap does not hold at or near a bound)";
}

RefitBootstrap RefitBootstrap::notMade(std::size_t replicates, const std::string& why)
{
  RefitBootstrap none;
  none.replicates = replicates;
  none.note = why;
  return none;
}

std::string simulateFittedDrives(const AccParameters& parameters, const EffectSettings& effects,
                                 const std::vector<CarFollowingRun>& runs, FittedDrives& fitted)
{
  fitted.simulated_speed_mps.clear();
  for (const CarFollowingRun& run : runs)
  {
    const SimulatedFollower sim = simulateFollower(parameters, effects, run);
    if (sim.diverged)
      return "the fit's simulation of " + run.name + " diverges";
    fitted.simulated_speed_mps.push_back(sim.speed_mps);
  }
  return "";
}

RefitBootstrap bootstrapFittedDrives(const FittedDrives& fitted, const std::vector<CarFollowingRun>& runs,
                                     const ReplicateRefit& refit, const RefitBootstrapOptions& options)
{
  const auto started = std::chrono::steady_clock::now();
  RefitBootstrap result;
  result.replicates = options.replicates;
  result.block_length_s = fitted.block_length_s;
  const std::vector<RunModel> models = modelRuns(fitted.simulated_speed_mps, runs);
  result.held_near_bound = parameterAtBound(fitted);
  const double step_s = medianStepS(runs);
  const std::size_t block_samples =
      std::isfinite(step_s) && step_s > 0.0 ? static_cast<std::size_t>(std::lround(result.block_length_s / step_s)) : 1;
  std::vector<Refit> refits(options.replicates);
  runTasksInParallel(options.replicates, effectiveThreadCount(options.threads, options.replicates), [&](std::size_t b) {
    refits[b] = refitReplicate(b, runs, models, block_samples, refit, options.seed);
  });
  result.refitted = static_cast<std::size_t>(
      std::count_if(refits.begin(), refits.end(), [](const Refit& r) { return r.has_value(); }));
  for (std::size_t i = 0; i < fitted.quantity_names.size(); ++i)
    result.quantities.push_back(summarise(i, fitted, refits));
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

MultistartResult refitBaseModel(const AccParameters& fit, const std::vector<CarFollowingRun>& replicate,
                                const RefitBootstrapOptions& options)
{
  MultistartOptions multistart;
  multistart.starts = options.starts;
  return calibrateMultistart(CalibrationObjective(replicate, options.bounds), multistart, {fit});
}

RefitBootstrap bootstrapRefits(const AccParameters& fit, const std::vector<CarFollowingRun>& runs,
                               const RefitBootstrapOptions& options)
{
  FittedDrives fitted;
  fitted.quantity_names.assign(std::begin(kQuantityNames), std::end(kQuantityNames));
  fitted.parameter_count = 4;  // k1, k2, tau_e, eta; the margin follows from them
  const ParameterBounds& b = options.bounds;
  // The margin k1 tau_e^2 + 2 k2 tau_e - 2 grows with each of k1, k2, tau_e (none negative): its
  // range is its value at the box's corners, -2 at the least. Without it a margin near -2 got an
  // interval reaching below -2, where no parameters can put it.
  fitted.lower_bound = {b.lower.k1_per_s2, b.lower.k2_per_s, b.lower.tau_e_s, b.lower.eta_m, stabilityMargin(b.lower)};
  fitted.upper_bound = {b.upper.k1_per_s2, b.upper.k2_per_s, b.upper.tau_e_s, b.upper.eta_m, stabilityMargin(b.upper)};
  fitted.at_bound_hint = " (the one-sided interval above does)";  // calibrate's quantity table
  const std::string not_made = simulateFittedDrives(fit, EffectSettings{}, runs, fitted);
  if (!not_made.empty())
    return RefitBootstrap::notMade(options.replicates, not_made);
  const ParameterUncertainty uncertainty = estimateUncertainty(fit, runs);
  fitted.at_fit = drawOf(assessQuantities(fit, uncertainty, runs, options.bounds));
  fitted.block_length_s = uncertainty.block_length_s;
  // Each replicate is refitted exactly as the data were: multistart from the fit and Halton points.
  const ReplicateRefit refit = [&](const std::vector<CarFollowingRun>& replicate) -> std::optional<BootstrapDraw> {
    const MultistartResult result = refitBaseModel(fit, replicate, options);
    if (result.diverged)
      return std::nullopt;
    return drawOf(assessQuantities(result.parameters, estimateUncertainty(result.parameters, replicate), replicate,
                                   options.bounds));
  };
  return bootstrapFittedDrives(fitted, runs, refit, options);
}

void printRefitBootstrap(const RefitBootstrap& bootstrap, std::ostream& out)
{
  if (!bootstrap.note.empty())
  {
    out << "Refitting bootstrap: not made: " << bootstrap.note << "\n";
    return;
  }
  char line[384];
  std::snprintf(line, sizeof line,
                "Refitting bootstrap (%zu drives the fit could have given, %zu refitted; residual blocks of %.1f s; "
                "%.1f s): 95 %% intervals (bootstrap-t) for short data, where value +- t se runs short\n",
                bootstrap.replicates, bootstrap.refitted, bootstrap.block_length_s, bootstrap.wall_time_s);
  out << line;
  if (!bootstrap.held_near_bound.empty())
    out << "  caution: " << bootstrap.caution() << "\n";
  int width = 17;  // the base model's names; a diagnosed model's effect parameters are longer
  for (const BootstrapQuantity& q : bootstrap.quantities)
    width = std::max(width, static_cast<int>(q.name.size()));
  for (const BootstrapQuantity& q : bootstrap.quantities)
  {
    if (q.hasInterval())
      std::snprintf(line, sizeof line,
                    "  %-*s %-11.5g 95 %% [%.5g, %.5g]   refits' spread %.3g, bias %+.3g; standard error at the fit "
                    "%.3g, the refits' own %.3g (median)\n",
                    width, q.name.c_str(), q.value, q.interval_95_low, q.interval_95_high, q.standard_error, q.bias,
                    q.fit_standard_error, q.refits_standard_error_median);
    else
      std::snprintf(line, sizeof line, "  %-*s %-11.5g no interval: %s\n", width, q.name.c_str(), q.value,
                    q.note.c_str());
    out << line;
  }
}

nlohmann::json toJson(const RefitBootstrap& bootstrap)
{
  nlohmann::json quantities = nlohmann::json::object();
  for (const BootstrapQuantity& q : bootstrap.quantities)
  {
    quantities[q.name] = {{"value", jsonNumber(q.value)},
                          {"standard_error", jsonNumber(q.standard_error)},
                          {"bias", jsonNumber(q.bias)},
                          {"fit_standard_error", jsonNumber(q.fit_standard_error)},
                          {"refits_standard_error_median", jsonNumber(q.refits_standard_error_median)},
                          {"interval_95", q.hasInterval()
                                              ? nlohmann::json{q.interval_95_low, q.interval_95_high}
                                              : nlohmann::json(nullptr)},
                          {"note", q.note}};
  }
  return {{"replicates", bootstrap.replicates}, {"refitted", bootstrap.refitted},
          {"block_length_s", jsonNumber(bootstrap.block_length_s)}, {"wall_time_s", jsonNumber(bootstrap.wall_time_s)},
          {"note", bootstrap.note}, {"caution", bootstrap.caution()}, {"quantities", quantities}};
}

}  // namespace acc
