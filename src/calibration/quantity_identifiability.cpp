#include "acc_identification/calibration/quantity_identifiability.h"
#include "acc_identification/model/json_number.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <limits>
#include <sstream>

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
}  // namespace

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

IdentifiableQuantities assessQuantities(const AccParameters& fit, const ParameterUncertainty& uncertainty,
                                        const std::vector<CarFollowingRun>& runs, const QuantityCriteria& criteria)
{
  IdentifiableQuantities result;
  result.reciprocal_condition = uncertainty.reciprocal_condition;
  result.basis = "Gauss-Newton sandwich covariance (batch means) at the fit, delta method for derived quantities";
  const double theta[4] = {fit.k1_per_s2, fit.k2_per_s, fit.tau_e_s, fit.eta_m};
  const double floors[4] = {criteria.parameter_scale_floor.k1_per_s2, criteria.parameter_scale_floor.k2_per_s,
                            criteria.parameter_scale_floor.tau_e_s, criteria.parameter_scale_floor.eta_m};
  const char* names[4] = {"k1", "k2", "tau_e", "eta"};
  const char* units[4] = {"1/s^2", "1/s", "s", "m"};
  std::ostringstream fraction;
  fraction << criteria.max_relative_error_parameter << " of max(|value|, floor)";
  for (int i = 0; i < 4; ++i)
  {
    Eigen::Vector4d gradient = Eigen::Vector4d::Zero();
    gradient(i) = 1.0;
    const double scale = std::max(std::abs(theta[i]), floors[i]);
    result.quantities.push_back(judge(names[i], units[i], theta[i], deltaMethodError(gradient, uncertainty), scale,
                                      criteria.max_relative_error_parameter * scale, uncertainty, fraction.str()));
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
    const double value = fit.eta_m + fit.tau_e_s * v;
    const Eigen::Vector4d gradient(0.0, 0.0, v, 1.0);
    const double scale = std::max(std::abs(value), criteria.gap_scale_floor_m);
    const double error = std::isfinite(v) ? deltaMethodError(gradient, uncertainty) : kNaN;
    QuantityEstimate q = judge(name, "m", value, error, scale, criteria.max_relative_error_gap * scale, uncertainty,
                               gap_fraction.str());
    q.speed_mps = v;
    if (!std::isfinite(v))
    {
      q.determined = false;
      q.reason = "no follower speed in the data";
    }
    result.quantities.push_back(q);
  }

  const double k1 = fit.k1_per_s2, k2 = fit.k2_per_s, tau = fit.tau_e_s;
  const double margin = k1 * tau * tau + 2.0 * k2 * tau - 2.0;
  const Eigen::Vector4d margin_gradient(tau * tau, 2.0 * tau, 2.0 * k1 * tau + 2.0 * k2, 0.0);
  std::ostringstream margin_threshold;
  margin_threshold << "a fixed " << criteria.max_error_margin << " against the margin's scale 2";
  result.quantities.push_back(judge("stability_margin", "", margin, deltaMethodError(margin_gradient, uncertainty), 2.0,
                                    criteria.max_error_margin, uncertainty, margin_threshold.str()));
  return result;
}

nlohmann::json toJson(const IdentifiableQuantities& quantities)
{
  nlohmann::json json;
  json["basis"] = quantities.basis;
  json["reciprocal_condition"] = jsonNumber(quantities.reciprocal_condition);
  nlohmann::json items = nlohmann::json::object();
  for (const QuantityEstimate& q : quantities.quantities)
  {
    nlohmann::json item{{"value", jsonNumber(q.value)},
                        {"standard_error", jsonNumber(q.standard_error)},
                        {"unit", q.unit},
                        {"determined", q.determined},
                        {"reason", q.reason}};
    if (std::isfinite(q.speed_mps))
    {
      item["speed_mps"] = q.speed_mps;
    }
    items[q.name] = item;
  }
  json["quantities"] = items;
  return json;
}

void printQuantities(const IdentifiableQuantities& quantities, std::ostream& out)
{
  out << "What the data determine (" << quantities.basis << "):\n";
  char line[400];
  for (const QuantityEstimate& q : quantities.quantities)
  {
    std::string name = q.name;
    if (!std::isnan(q.speed_mps))
    {
      char at[48];
      std::snprintf(at, sizeof at, " (v = %.1f m/s)", q.speed_mps);
      name += at;
    }
    if (q.determined)
      std::snprintf(line, sizeof line, "  %-44s %10.4g +- %-9.3g %-6s determined\n", name.c_str(), q.value,
                    q.standard_error, q.unit.c_str());
    else
    {
      // The fit's value in parentheses, so that it is seen and not taken for a result; "-" for an
      // error the covariance cannot give (singular).
      char value[32], error[32];
      std::snprintf(value, sizeof value, "(%.4g", q.value);
      if (std::isfinite(q.standard_error))
        std::snprintf(error, sizeof error, "%.3g)", q.standard_error);
      else
        std::snprintf(error, sizeof error, "-)");
      std::snprintf(line, sizeof line, "  %-44s %10s +- %-9s %-6s NOT determined: %s\n", name.c_str(), value, error,
                    q.unit.c_str(), q.reason.c_str());
    }
    out << line;
  }
}

}  // namespace acc
