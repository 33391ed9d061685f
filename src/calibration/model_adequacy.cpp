#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/json_number.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/pooled_moments.h"

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// (a): an RMSE is a miss when it is both a large part of the data's own spread and above the
/// floor that noise alone reaches.
void checkRmse(const char* what, const char* unit, double rmse, double spread, double max_over_spread, double floor,
               ModelAdequacy& out)
{
  if (!std::isfinite(rmse) || !std::isfinite(spread))
    return;
  if (rmse > floor && rmse > max_over_spread * spread)
    out.reasons.push_back(printfText("%s RMSE %.2f %s against a %s spread (standard deviation) of %.2f %s", what, rmse,
                                 unit, what, spread, unit));
}

/// (b): each parameter held by a bound of the fit where the data pin it there.
void checkBounds(const AccParameters& p, const std::optional<AccParameters>& standard_errors,
                 const ModelAdequacyOptions& options, ModelAdequacy& out)
{
  struct Named
  {
    const char* name;
    double value, lower, upper, standard_error;
  };
  const ParameterBounds& b = options.bounds;
  // Without standard errors every parameter at a bound counts (0: pinned).
  const AccParameters se = standard_errors.value_or(AccParameters{0.0, 0.0, 0.0, 0.0});
  const Named parameters[] = {{"k1_per_s2", p.k1_per_s2, b.lower.k1_per_s2, b.upper.k1_per_s2, se.k1_per_s2},
                              {"k2_per_s", p.k2_per_s, b.lower.k2_per_s, b.upper.k2_per_s, se.k2_per_s},
                              {"tau_e_s", p.tau_e_s, b.lower.tau_e_s, b.upper.tau_e_s, se.tau_e_s},
                              {"eta_m", p.eta_m, b.lower.eta_m, b.upper.eta_m, se.eta_m}};
  for (const Named& q : parameters)
  {
    const double range = q.upper - q.lower;
    const std::string text = atBoundText(q.name, q.value, q.lower, q.upper, options.bound_fraction);
    if (text.empty())
      continue;
    out.checks.parameters_at_bound.push_back(text);
    // NaN (unknown) fails this comparison too: such a parameter is listed, not held against the model.
    const std::string error = standard_errors ? printfText(" +- %.3g", q.standard_error) : "";
    if (q.standard_error < options.max_standard_error_at_bound_fraction * range)
      out.reasons.push_back(text + error + ": held by the bound, not by the data");
  }
}

/// (c): residual structure far slower than the model's own dynamics.
void checkCorrelation(const ModelAdequacyOptions& options, ModelAdequacy& out)
{
  const double correlation = out.checks.residual_correlation_time_s, response = out.checks.model_response_time_s;
  if (!std::isfinite(response) || std::isnan(correlation))
    return;
  if (correlation > options.max_correlation_over_response_time * response)
  {
    out.reasons.push_back(std::isinf(correlation)
                              ? printfText("the speed residual stays correlated over a quarter of the longest run "
                                       "(model response time %.1f s): structure left unexplained",
                                       response)
                              : printfText("speed residual correlation time %.0f s against the model's response time "
                                       "%.1f s: structure left unexplained",
                                       correlation, response));
  }
}

/// Pooled autocorrelation of the residuals at a lag of `lag` samples (around their pooled mean).
double autocorrelationAt(const std::vector<std::vector<double>>& residuals, double mean, double variance,
                         std::size_t lag)
{
  double sum = 0.0;
  std::size_t pairs = 0;
  for (const std::vector<double>& r : residuals)
  {
    for (std::size_t k = 0; k + lag < r.size(); ++k, ++pairs)
      sum += (r[k] - mean) * (r[k + lag] - mean);
  }
  return pairs == 0 ? kNaN : sum / static_cast<double>(pairs) / variance;
}
}  // namespace

double modelResponseTimeS(const AccParameters& p)
{
  const double k1 = p.k1_per_s2, damping = p.k2_per_s + p.k1_per_s2 * p.tau_e_s;
  if (!(k1 > 0.0))
    return p.k2_per_s > 0.0 ? 1.0 / p.k2_per_s : kInf;
  const double discriminant = damping * damping - 4.0 * k1;
  // Complex roots decay at damping / 2; real ones at the slower root's rate.
  const double slowest = discriminant < 0.0 ? damping / 2.0 : (damping - std::sqrt(discriminant)) / 2.0;
  return slowest > 0.0 ? 1.0 / slowest : kInf;
}

double residualCorrelationTimeS(const std::vector<std::vector<double>>& segment_times,
                                const std::vector<std::vector<double>>& segment_residuals)
{
  double sum = 0.0, sum_sq = 0.0, duration = 0.0;
  std::size_t n = 0, steps = 0, longest = 0;
  for (std::size_t i = 0; i < segment_residuals.size(); ++i)
  {
    for (double r : segment_residuals[i])
    {
      sum += r;
      sum_sq += r * r;
    }
    n += segment_residuals[i].size();
    longest = std::max(longest, segment_residuals[i].size());
    if (segment_times[i].size() >= 2)
    {
      duration += segment_times[i].back() - segment_times[i].front();
      steps += segment_times[i].size() - 1;
    }
  }
  if (n < 2 || steps == 0)
    return kNaN;
  const double mean = sum / static_cast<double>(n), variance = sum_sq / static_cast<double>(n) - mean * mean;
  if (!(variance > 0.0))
    return kNaN;
  const double step_s = duration / static_cast<double>(steps), threshold = std::exp(-1.0);
  // Lags grow by a tenth each time: the crossing is found to 10 % in O(n log L), not O(n L), so
  // that a 3-hour drive costs milliseconds.
  double previous_lag = 0.0, previous_value = 1.0;
  for (std::size_t lag = 1; lag <= longest / 4; lag = std::max(lag + 1, lag + lag / 10))
  {
    const double value = autocorrelationAt(segment_residuals, mean, variance, lag);
    if (value < threshold)
    {
      const double fraction = (previous_value - threshold) / (previous_value - value);
      return (previous_lag + fraction * (static_cast<double>(lag) - previous_lag)) * step_s;
    }
    previous_lag = static_cast<double>(lag);
    previous_value = value;
  }
  return kInf;
}

ModelAdequacy assessModelAdequacy(const AccParameters& p, const std::vector<CarFollowingRun>& runs,
                                  const ModelAdequacyOptions& options,
                                  const std::optional<AccParameters>& standard_errors)
{
  return assessModelAdequacy(p, EffectSettings{}, runs, options, standard_errors);
}

ModelAdequacy assessModelAdequacy(const AccParameters& p, const EffectSettings& effects,
                                  const std::vector<CarFollowingRun>& runs, const ModelAdequacyOptions& options,
                                  const std::optional<AccParameters>& standard_errors)
{
  ModelAdequacy out;
  for (const CarFollowingRun& run : runs)
  {
    const std::string problem = describeRunProblem(run);
    if (!problem.empty())
    {
      out.reasons.push_back("not assessed: run '" + run.name + "': " + problem);
      return out;
    }
  }
  if (runs.empty())
  {
    out.reasons.push_back("not assessed: no data");
    return out;
  }
  out.assessed = true;
  const FitQuality fit = evaluateFit(p, effects, runs);
  out.checks.samples = fit.samples;
  if (fit.diverged)
  {
    out.reasons.push_back("the model's simulation of the data diverges");
    return out;
  }
  out.checks.gap_rmse_m = fit.rmse_gap_m;
  out.checks.speed_rmse_mps = fit.rmse_speed_mps;
  out.checks.gap_spread_m = pooledMoments(runs, &CarFollowingRun::space_gap_m).standard_deviation;
  out.checks.speed_spread_mps = pooledMoments(runs, &CarFollowingRun::follower_speed_mps).standard_deviation;
  std::vector<std::vector<double>> times, residuals;
  for (const CarFollowingRun& run : runs)
  {
    const SimulatedFollower simulated = simulateFollower(p, effects, run);
    std::vector<double> residual(run.size());
    for (std::size_t k = 0; k < run.size(); ++k)
      residual[k] = run.follower_speed_mps[k] - simulated.speed_mps[k];
    times.push_back(run.time_s);
    residuals.push_back(std::move(residual));
  }
  out.checks.residual_correlation_time_s = residualCorrelationTimeS(times, residuals);
  out.checks.model_response_time_s = modelResponseTimeS(p);

  checkRmse("gap", "m", fit.rmse_gap_m, out.checks.gap_spread_m, options.max_gap_rmse_over_spread,
            options.gap_rmse_floor_m, out);
  checkRmse("speed", "m/s", fit.rmse_speed_mps, out.checks.speed_spread_mps, options.max_speed_rmse_over_spread,
            options.speed_rmse_floor_mps, out);
  checkBounds(p, standard_errors, options, out);
  checkCorrelation(options, out);
  out.adequate = out.reasons.empty();
  return out;
}

void addDipCheck(ModelAdequacy& adequacy, std::size_t perturbations, double median_dip_error,
                 const ModelAdequacyOptions& options)
{
  adequacy.checks.dip_perturbations = perturbations;
  adequacy.checks.median_dip_error = median_dip_error;
  if (!adequacy.assessed || perturbations < options.min_dip_perturbations || !std::isfinite(median_dip_error))
    return;
  if (median_dip_error > options.max_median_dip_error)
  {
    adequacy.reasons.push_back(printfText("its dips miss the measured ones by %.1f %% (median over %zu "
                                      "car-perturbations; limit %.0f %%)",
                                      100.0 * median_dip_error, perturbations, 100.0 * options.max_median_dip_error));
    adequacy.adequate = false;
  }
}

nlohmann::json toJson(const ModelAdequacy& adequacy)
{
  const AdequacyChecks& c = adequacy.checks;
  return {{"assessed", adequacy.assessed},
          {"adequate", adequacy.assessed ? nlohmann::json(adequacy.adequate) : nlohmann::json()},
          {"reasons", adequacy.reasons},
          {"checks",
           {{"samples", c.samples},
            {"gap_rmse_m", jsonNumber(c.gap_rmse_m)},
            {"gap_spread_m", jsonNumber(c.gap_spread_m)},
            {"speed_rmse_mps", jsonNumber(c.speed_rmse_mps)},
            {"speed_spread_mps", jsonNumber(c.speed_spread_mps)},
            {"parameters_at_bound", c.parameters_at_bound},
            {"residual_correlation_time_s", jsonNumber(c.residual_correlation_time_s)},
            // +inf would be null like "not computed": say it.
            {"residual_correlated_beyond_quarter_run", std::isinf(c.residual_correlation_time_s)},
            {"model_response_time_s", jsonNumber(c.model_response_time_s)},
            {"dip_perturbations", c.dip_perturbations},
            {"median_dip_error", jsonNumber(c.median_dip_error)}}}};
}

std::string describeAdequacy(const ModelAdequacy& adequacy)
{
  std::string reasons;
  for (const std::string& reason : adequacy.reasons)
    reasons += (reasons.empty() ? "" : "; ") + reason;
  if (!adequacy.assessed)
    return "not assessed (" + reasons + ")";
  return adequacy.adequate ? "ADEQUATE" : "NOT ADEQUATE (" + reasons + ")";
}

BoundSide boundSide(double value, double lower, double upper, double bound_fraction)
{
  const double tolerance = bound_fraction * (upper - lower);
  return value <= lower + tolerance ? BoundSide::lower : value >= upper - tolerance ? BoundSide::upper : BoundSide::inside;
}

std::string atBoundText(const std::string& name, double value, double lower, double upper, double bound_fraction)
{
  const BoundSide side = boundSide(value, lower, upper, bound_fraction);
  if (side == BoundSide::inside)
    return "";
  const bool at_lower = side == BoundSide::lower;
  return printfText("%s = %.4g at its %s bound %g", name.c_str(), value, at_lower ? "lower" : "upper",
                    at_lower ? lower : upper);
}

}  // namespace acc
