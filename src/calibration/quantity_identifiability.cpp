#include "acc_identification/calibration/quantity_identifiability.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/model/json_number.h"
#include "acc_identification/model/sample_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <ostream>
#include <limits>
#include <sstream>
#include <tuple>

#include <Eigen/Core>

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool covarianceUsable(const ParameterUncertainty& u)
{
  return u.covariance.allFinite();
}

/// Standard error of g^T theta by the delta method; NaN when the covariance is not available.
double deltaMethodError(const Eigen::Vector4d& gradient, const ParameterUncertainty& u)
{
  if (!covarianceUsable(u))
  {
    return kNaN;
  }
  const double variance = gradient.dot(u.covariance * gradient);
  return std::sqrt(std::max(0.0, variance));
}

QuantityEstimate judge(const std::string& name, const std::string& unit, double value, double standard_error,
                       double scale, double max_error, const ParameterUncertainty& u, const std::string& threshold)
{
  QuantityEstimate q;
  q.name = name;
  q.unit = unit;
  q.value = value;
  q.standard_error = standard_error;
  q.speed_mps = kNaN;
  std::ostringstream why;
  if (!std::isfinite(value))
  {
    why << "no finite fit";
  }
  else if (!std::isfinite(standard_error))
  {
    why << "no standard error: the Gauss-Newton matrix is singular (reciprocal condition " << u.reciprocal_condition
        << ") or too few residual blocks; some parameter combination does not change the simulated speed";
  }
  else
  {
    q.determined = standard_error <= max_error;
    const std::string suffix = unit.empty() ? "" : " " + unit;
    why << name << " = " << value << " +- " << standard_error << suffix << ": standard error "
        << (q.determined ? "<= " : "> ") << max_error << suffix << " (" << threshold << ", scale " << scale << suffix
        << ")";
  }
  q.reason = why.str();
  return q;
}

const char* const kParameterNames[4] = {"k1", "k2", "tau_e", "eta"};
const char* const kParameterUnits[4] = {"1/s^2", "1/s", "s", "m"};

/// A quantity of the four parameters (k1, k2, tau_e, eta): its function and its exact gradient at the fit.
struct QuantityDefinition
{
  const char* name;
  const char* unit;
  std::function<double(const Eigen::Vector4d&)> value;
  Eigen::Vector4d gradient;
};

/// What every quantity of one fit is assessed against.
struct QuantityContext
{
  const Eigen::Vector4d& theta;
  const ParameterUncertainty& uncertainty;
  const ParameterBounds& bounds;
  const QuantityCriteria& criteria;
};

Eigen::Vector4d asVector(const AccParameters& p)
{
  return {p.k1_per_s2, p.k2_per_s, p.tau_e_s, p.eta_m};
}

/// Where each parameter sits: +1 at its lower bound (the range lies above), -1 at its upper, 0 inside.
Eigen::Vector4d boundSides(const QuantityContext& c)
{
  const Eigen::Vector4d lower = asVector(c.bounds.lower), upper = asVector(c.bounds.upper);
  Eigen::Vector4d sides = Eigen::Vector4d::Zero();
  for (int i = 0; i < 4; ++i)
  {
    const BoundSide side = boundSide(c.theta[i], lower[i], upper[i], c.criteria.bound_fraction);
    sides[i] = side == BoundSide::lower ? 1.0 : side == BoundSide::upper ? -1.0 : 0.0;
  }
  return sides;
}

/// Sets q.held_by_bound and q.one_sided_limit when every parameter q moves with sits at a bound
/// (the free ones carry at most 1 % of its delta-method variance; without a covariance: their
/// gradient is 0), and says so in the reason.
void assessBoundHold(const QuantityContext& c, const QuantityDefinition& d, QuantityEstimate& q)
{
  const Eigen::Vector4d sides = boundSides(c);
  Eigen::Vector4d held = d.gradient, free = d.gradient;
  for (int i = 0; i < 4; ++i)
    (sides[i] != 0.0 ? free : held)[i] = 0.0;
  if (held.isZero(0.0) || !std::isfinite(q.value))
    return;
  const Eigen::Matrix4d& covariance = c.uncertainty.covariance;
  const bool usable = covarianceUsable(c.uncertainty);
  if (usable ? free.dot(covariance * free) > 0.01 * d.gradient.dot(covariance * d.gradient) : !free.isZero(0.0))
    return;
  // One-sided 95 %: Student's t with the sandwich's blocks - 1 degrees of freedom (batch means have
  // that many), the normal's 1.645 when the blocks are not known.
  const double dof = static_cast<double>(c.uncertainty.blocks) - 1.0;
  const double z = dof >= 1.0 ? studentTUpperQuantile(0.05, dof) : twoSidedNormalQuantile(0.10);
  const Eigen::Vector4d lower = asVector(c.bounds.lower), upper = asVector(c.bounds.upper);
  Eigen::Vector4d moved = c.theta;
  std::ostringstream which;
  for (int i = 0; i < 4; ++i)
  {
    if (held[i] == 0.0)
      continue;
    which << (which.tellp() > 0 ? " and " : "") << kParameterNames[i] << " at its "
          << (sides[i] > 0.0 ? "lower bound " : "upper bound ") << (sides[i] > 0.0 ? lower[i] : upper[i]);
    moved[i] = std::clamp(c.theta[i] + sides[i] * z * std::sqrt(covariance(i, i)), lower[i], upper[i]);
  }
  q.held_by_bound = which.str();
  q.one_sided_limit = usable ? d.value(moved) : kNaN;
  std::ostringstream why;
  why << "; " << q.held_by_bound << ", so the interval is one-sided";
  if (usable)
  {
    const auto [low, high] = q.boundInterval();
    why << ": 95 % [" << low << ", " << high << "]" << (q.unit.empty() ? "" : " " + q.unit);
    if (dof >= 1.0)
      why << " (Student's t, " << dof << " degrees of freedom)";
  }
  q.reason += why.str();
}

/// The 95 % interval: the one-sided one at a bound, else value +- t(blocks - 1) standard errors
/// cut at the quantity's range over the fit's bounds. Every quantity here (a parameter, eta +
/// tau_e v, the margin) grows with each parameter, none negative: its range is its value at the
/// bounds' corners. Uncut, a tau_e near 0 got [-3.2, 3.5] s and a margin near -2 went below -2.
void setInterval(const QuantityContext& c, const QuantityDefinition& d, QuantityEstimate& q)
{
  const ParameterUncertainty& u = c.uncertainty;
  if (q.hasBoundInterval())
  {
    std::tie(q.interval_95_low, q.interval_95_high) = q.boundInterval();
    return;
  }
  if (!q.held_by_bound.empty() || !std::isfinite(q.standard_error) || !std::isfinite(q.value))
    return;
  const double t = intervalFactor95(u.blocks);
  q.interval_95_low = std::max(q.value - t * q.standard_error, d.value(asVector(c.bounds.lower)));
  q.interval_95_high = std::min(q.value + t * q.standard_error, d.value(asVector(c.bounds.upper)));
}

/// The quantity's value, standard error (delta method), determination, bound and interval.
QuantityEstimate assess(const QuantityContext& c, const QuantityDefinition& d, double scale, double max_error,
                        const std::string& threshold)
{
  QuantityEstimate q = judge(d.name, d.unit, d.value(c.theta), deltaMethodError(d.gradient, c.uncertainty), scale,
                             max_error, c.uncertainty, threshold);
  assessBoundHold(c, d, q);
  setInterval(c, d, q);
  return q;
}
}  // namespace

bool QuantityEstimate::hasBoundInterval() const
{
  return !held_by_bound.empty() && std::isfinite(one_sided_limit);
}

std::pair<double, double> QuantityEstimate::boundInterval() const
{
  return std::minmax(value, one_sided_limit);
}

const QuantityEstimate* IdentifiableQuantities::find(const std::string& name) const
{
  for (const QuantityEstimate& q : quantities)
  {
    if (q.name == name)
    {
      return &q;
    }
  }
  return nullptr;
}

bool allDetermined(const IdentifiableQuantities& quantities, std::initializer_list<const char*> names)
{
  for (const char* name : names)
  {
    const QuantityEstimate* q = quantities.find(name);
    if (q == nullptr || !q->determined)
      return false;
  }
  return true;
}

double intervalFactor95(std::size_t blocks)
{
  const double dof = static_cast<double>(blocks) - 1.0;
  return dof >= 1.0 ? studentTUpperQuantile(0.025, dof) : twoSidedNormalQuantile(0.05);
}

IdentifiableQuantities assessQuantities(const AccParameters& fit, const ParameterUncertainty& uncertainty,
                                        const std::vector<CarFollowingRun>& runs, const ParameterBounds& bounds,
                                        const QuantityCriteria& criteria)
{
  IdentifiableQuantities result;
  result.reciprocal_condition = uncertainty.reciprocal_condition;
  result.start_gap_noise_m = uncertainty.start_gap_noise_m;
  result.eta_start_gap_error_m = uncertainty.eta_start_gap_error_m;
  std::ostringstream basis;
  basis << "Gauss-Newton sandwich covariance (batch means) at the fit";
  if (std::isfinite(uncertainty.start_gap_noise_m))
    basis << ", plus the measured start gaps' noise (" << std::setprecision(2) << uncertainty.start_gap_noise_m
          << " m, eta +- " << uncertainty.eta_start_gap_error_m << " m from it alone)";
  basis << ", delta method for derived quantities";
  result.basis = basis.str();
  const Eigen::Vector4d theta = asVector(fit);
  const QuantityContext context{theta, uncertainty, bounds, criteria};
  const double floors[4] = {criteria.parameter_scale_floor.k1_per_s2, criteria.parameter_scale_floor.k2_per_s,
                            criteria.parameter_scale_floor.tau_e_s, criteria.parameter_scale_floor.eta_m};
  std::ostringstream fraction;
  fraction << criteria.max_relative_error_parameter << " of max(|value|, floor)";
  for (int i = 0; i < 4; ++i)
  {
    const double scale = std::max(std::abs(theta[i]), floors[i]);
    result.quantities.push_back(assess(context, {kParameterNames[i], kParameterUnits[i],
                                                 [i](const Eigen::Vector4d& t) { return t[i]; },
                                                 Eigen::Vector4d::Unit(i)},
                                       scale, criteria.max_relative_error_parameter * scale, fraction.str()));
  }

  // Equilibrium gaps at the speeds driven.
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest, sum = 0.0;
  std::size_t count = 0;
  for (const CarFollowingRun& run : runs)
  {
    for (double v : run.follower_speed_mps)
    {
      if (std::isfinite(v))
      {
        lowest = std::min(lowest, v);
        highest = std::max(highest, v);
        sum += v;
        ++count;
      }
    }
  }
  const double mean = count > 0 ? sum / static_cast<double>(count) : kNaN;
  if (count == 0)
  {
    lowest = highest = kNaN;
  }
  std::ostringstream gap_fraction;
  gap_fraction << criteria.max_relative_error_gap << " of max(|value|, " << criteria.gap_scale_floor_m << " m)";
  const std::pair<const char*, double> speeds[3] = {
      {"equilibrium_gap_at_min_speed", lowest}, {"equilibrium_gap_at_mean_speed", mean},
      {"equilibrium_gap_at_max_speed", highest}};
  for (const auto& [name, v] : speeds)
  {
    const double speed = std::isfinite(v) ? v : 0.0;
    const QuantityDefinition gap{name, "m", [speed](const Eigen::Vector4d& t) { return t[3] + t[2] * speed; },
                                 Eigen::Vector4d(0.0, 0.0, speed, 1.0)};
    const double scale = std::max(std::abs(gap.value(theta)), criteria.gap_scale_floor_m);
    QuantityEstimate q;
    if (std::isfinite(v))
      q = assess(context, gap, scale, criteria.max_relative_error_gap * scale, gap_fraction.str());
    else
    {
      q = judge(name, "m", gap.value(theta), kNaN, scale, 0.0, uncertainty, "");
      q.reason = "no follower speed in the data";
    }
    q.speed_mps = v;
    result.quantities.push_back(q);
  }

  const double k1 = fit.k1_per_s2, k2 = fit.k2_per_s, tau = fit.tau_e_s;
  const QuantityDefinition margin{
      "stability_margin", "", [](const Eigen::Vector4d& t) { return t[0] * t[2] * t[2] + 2.0 * t[1] * t[2] - 2.0; },
      Eigen::Vector4d(tau * tau, 2.0 * tau, 2.0 * k1 * tau + 2.0 * k2, 0.0)};
  std::ostringstream margin_threshold;
  margin_threshold << "a fixed " << criteria.max_error_margin << " against the margin's scale 2";
  result.quantities.push_back(assess(context, margin, 2.0, criteria.max_error_margin, margin_threshold.str()));
  return result;
}

nlohmann::json toJson(const IdentifiableQuantities& quantities)
{
  nlohmann::json json;
  json["basis"] = quantities.basis;
  json["reciprocal_condition"] = jsonNumber(quantities.reciprocal_condition);
  json["start_gap_noise_m"] = jsonNumber(quantities.start_gap_noise_m);
  json["eta_start_gap_error_m"] = jsonNumber(quantities.eta_start_gap_error_m);
  nlohmann::json items = nlohmann::json::object();
  for (const QuantityEstimate& q : quantities.quantities)
  {
    nlohmann::json item{{"value", jsonNumber(q.value)},
                        {"standard_error", jsonNumber(q.standard_error)},
                        {"unit", q.unit},
                        {"determined", q.determined},
                        {"reason", q.reason}};
    item["interval_95"] = std::isfinite(q.interval_95_low) ? nlohmann::json{q.interval_95_low, q.interval_95_high}
                                                            : nlohmann::json();
    if (std::isfinite(q.speed_mps))
    {
      item["speed_mps"] = q.speed_mps;
    }
    if (!q.held_by_bound.empty())
      item["held_by_bound"] = q.held_by_bound;
    items[q.name] = item;
  }
  json["quantities"] = items;
  return json;
}

void printQuantities(const IdentifiableQuantities& quantities, std::ostream& out)
{
  out << "What the data determine (" << quantities.basis << "):\n";
  char line[640];
  for (const QuantityEstimate& q : quantities.quantities)
  {
    std::string name = q.name;
    if (!std::isnan(q.speed_mps))
    {
      char at[48];
      std::snprintf(at, sizeof at, " (v = %.1f m/s)", q.speed_mps);
      name += at;
    }
    // value +- error, or "low to high" at a bound; in parentheses where not determined, so that the
    // fit's value is seen and not taken for a result; "-" for an error the covariance cannot give.
    char value[32], error[32];
    const char* open = q.determined ? "" : "(";
    const char* close = q.determined ? "" : ")";
    const bool interval = q.hasBoundInterval();
    const auto [low, high] = q.boundInterval();
    std::snprintf(value, sizeof value, "%s%.4g", open, interval ? low : q.value);
    if (interval)
      std::snprintf(error, sizeof error, "%.4g%s", high, close);
    else if (std::isfinite(q.standard_error))
      std::snprintf(error, sizeof error, "%.3g%s", q.standard_error, close);
    else
      std::snprintf(error, sizeof error, "-%s", close);
    char interval_text[96] = "";
    if (q.determined && !interval && std::isfinite(q.interval_95_low))
      std::snprintf(interval_text, sizeof interval_text, ", 95 %% [%.4g, %.4g]", q.interval_95_low, q.interval_95_high);
    const std::string verdict = q.determined ? "determined" + std::string(interval_text) : "NOT determined: " + q.reason;
    const std::string bound = q.determined && !q.held_by_bound.empty() ? " (" + q.held_by_bound + ": one-sided)" : "";
    std::snprintf(line, sizeof line, "  %-44s %10s %s %-9s %-6s %s%s\n", name.c_str(), value, interval ? "to" : "+-",
                  error, q.unit.c_str(), verdict.c_str(), bound.c_str());
    out << line;
  }
}

}  // namespace acc
