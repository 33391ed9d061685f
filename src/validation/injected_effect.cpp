#include "acc_identification/validation/injected_effect.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace acc
{
namespace
{
/// Distance covered over [t - delta, t] at the interpolated speed, by the trapezoid rule on
/// sub-intervals of at most a quarter of the run's first step: the rule synthesizeWithheldRun uses,
/// so that an injection into a clean synthetic record equals the suite's own offset.
double distanceOver(const CarFollowingRun& run, double t, double delta)
{
  const double step = run.time_s[1] - run.time_s[0];
  const std::size_t substeps =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(std::abs(delta) / step * 4)));
  const double h = delta / static_cast<double>(substeps);
  const double start = t - delta;
  double distance = 0.0;
  for (std::size_t i = 0; i < substeps; ++i)
  {
    const double a = start + h * static_cast<double>(i);
    distance += 0.5 * h *
                (interpolateHeld(run.time_s, run.leader_speed_mps, a) +
                 interpolateHeld(run.time_s, run.leader_speed_mps, a + h));
  }
  return distance;
}

void requireUsable(const CarFollowingRun& run)
{
  if (run.size() < 2)
  {
    throw std::invalid_argument("injection needs a run of at least two samples: " + run.name);
  }
}
}  // namespace

double interpolateHeld(const std::vector<double>& time_s, const std::vector<double>& values, double t)
{
  if (t <= time_s.front())
  {
    return values.front();
  }
  if (t >= time_s.back())
  {
    return values.back();
  }
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(time_s.begin(), time_s.end(), t) - time_s.begin()) - 1;
  const double w = (t - time_s[i]) / (time_s[i + 1] - time_s[i]);
  return values[i] + w * (values[i + 1] - values[i]);
}

CarFollowingRun injectSensorTimeOffset(const CarFollowingRun& run, double offset_s)
{
  requireUsable(run);
  CarFollowingRun out = run;
  if (offset_s == 0.0)
  {
    return out;
  }
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    const double t = run.time_s[k];
    out.leader_speed_mps[k] = interpolateHeld(run.time_s, run.leader_speed_mps, t - offset_s);
    out.space_gap_m[k] = run.space_gap_m[k] - distanceOver(run, t, offset_s);
  }
  return out;
}

CarFollowingRun injectActuationLag(const CarFollowingRun& run, double lag_s)
{
  requireUsable(run);
  if (lag_s < 0.0)
  {
    throw std::invalid_argument("actuation lag must not be negative");
  }
  CarFollowingRun out = run;
  if (lag_s == 0.0)
  {
    return out;
  }
  const std::vector<double>& v = run.follower_speed_mps;
  double lagged = v.front();
  // How far behind the recorded car the lagged one drives: T v_lag + integral (v - v_lag) - T
  // (v_lag - v_lag(t0)), i.e. T v_lag throughout. From T v0 at the start, not 0: the lagged car has
  // followed with its lag before t0 as well, so its gap at speed v is the recorded car's plus T v
  // and the jam distance is unchanged; from 0 the jam distance would drop by T v0 per run.
  double gap_gain_m = lag_s * v.front();
  out.space_gap_m[0] = run.space_gap_m[0] + gap_gain_m;
  for (std::size_t k = 1; k < run.size(); ++k)
  {
    const double h = run.time_s[k] - run.time_s[k - 1];
    const double a = std::exp(-h / lag_s);
    // Exact for v linear over the step (first-order hold): no half-step bias of a zero-order hold.
    const double next = a * lagged + (1.0 - a) * v[k - 1] + (v[k] - v[k - 1]) * (1.0 - lag_s / h * (1.0 - a));
    gap_gain_m += 0.5 * h * ((v[k - 1] - lagged) + (v[k] - next));
    lagged = next;
    out.follower_speed_mps[k] = lagged;
    out.space_gap_m[k] = run.space_gap_m[k] + gap_gain_m;
  }
  return out;
}

double closedLoopLagReading(double lag_s, const AccParameters& p)
{
  return lag_s / (1.0 + lag_s * (p.k1_per_s2 * p.tau_e_s + p.k2_per_s));
}

// With a = F(s, v, u) the recorded car's acceleration and T a_lag' + a_lag = a, substituting the
// recorded state by the lagged one (v = v_lag + T a_lag, s = s_lag - T v_lag) into the model gives
// T a_lag' + c a_lag = k1 (s_lag - eta - (tau_e + T) v_lag) + k2 (u - v_lag): divide by c.
AccParameters closedLoopLagParameters(double lag_s, const AccParameters& p)
{
  const double c = 1.0 + lag_s * (p.k1_per_s2 * p.tau_e_s + p.k2_per_s);
  return AccParameters{p.k1_per_s2 / c, p.k2_per_s / c, p.tau_e_s + lag_s, p.eta_m};
}

}  // namespace acc
