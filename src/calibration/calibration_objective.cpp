#include "acc_identification/calibration/calibration_objective.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
/// Sums over samples from which the reduced objective follows (e = v_measured - v_a):
/// SSR(eta) = ee - 2 eta eg + eta^2 gg, and for each parameter i
/// dSSR/dtheta_i = -2 (e_dva[i] + eta e_dvg[i] - eta g_dva[i] - eta^2 g_dvg[i]).
struct PassSums
{
  double ee = 0.0, eg = 0.0, gg = 0.0;
  std::array<double, 3> e_dva{}, e_dvg{}, g_dva{}, g_dvg{};
  bool diverged = false;
};

/// Two doubles in one SSE2 register (x86-64's baseline, so no special build flags): the eta = 0
/// simulation and the unit-eta response advance with the same coefficients, side by side.
typedef double Pair __attribute__((vector_size(16)));

/// One Euler pass over a segment: the eta = 0 simulation (s_a, v_a) and the unit-eta response
/// (s_g, v_g), as the pairs S = (s_a, s_g), V = (v_a, v_g), and, when WithGradient, their
/// sensitivities dS[i], dV[i] to (k1, k2, tau_e). After each step visit(k + 1, V, dV) sees the
/// state at sample k + 1 (sample 0 is the measured start: zero error and zero sensitivity).
/// Returns false when the recursion ran away (the visits then stop).
template <bool WithGradient, typename Segment, typename Visitor>
bool eulerPass(const Segment& seg, double k1, double k2, double tau, Visitor&& visit)
{
  Pair S = {seg.initial_gap_m, 0.0}, V = {seg.initial_speed_mps, 0.0};
  Pair dS[3] = {{0, 0}, {0, 0}, {0, 0}}, dV[3] = {{0, 0}, {0, 0}, {0, 0}};
  const Pair unit_eta = {0.0, 1.0};  // eta enters the g system only, as a unit constant
  const std::size_t steps = seg.step_s.size();
  const double* step = seg.step_s.data();
  const double* leader = seg.leader_speed_mps.data();
  const double damping = k1 * tau + k2;
  for (std::size_t k = 0; k < steps; ++k)
  {
    // The recursion of simulateFollower(), v' = v + h (k1 (s - eta - tau v) + k2 (u - v)),
    // regrouped as v' = (1 - h (k1 tau + k2)) v + h k1 s + ...: the coefficients do not depend on
    // the state, so the chain from one sample to the next is one multiply-add long.
    const double h = step[k];
    const Pair u = {leader[k], 0.0};
    const double keep = 1.0 - h * damping;
    const double h_k1 = h * k1;
    if constexpr (WithGradient)
    {
      // Explicit partial derivatives of h f with respect to k1, k2, tau_e.
      const Pair explicit_partials[3] = {h * (S - tau * V - unit_eta), h * (u - V), -h_k1 * V};
      for (int i = 0; i < 3; ++i)
      {
        const Pair next_dV = keep * dV[i] + h_k1 * dS[i] + explicit_partials[i];
        dS[i] -= h * dV[i];
        dV[i] = next_dV;
      }
    }
    const Pair next_V = keep * V + h_k1 * (S - unit_eta) + (h * k2) * u;
    S += h * (u - V);
    V = next_V;
    if (isRunaway(V[0], S[0]) || isRunaway(V[1], S[1]))
    {
      return false;
    }
    visit(k + 1, V, static_cast<const Pair*>(dV));
  }
  return true;
}

/// The objective's sums over one segment. They are locals of this function, so that the compiler
/// keeps them in registers through the inlined visits.
template <bool WithGradient, typename Segment>
PassSums simulatePass(const Segment& seg, double k1, double k2, double tau)
{
  PassSums sums;
  Pair e_dV[3] = {{0, 0}, {0, 0}, {0, 0}}, g_dV[3] = {{0, 0}, {0, 0}, {0, 0}};
  double ee = 0.0, eg = 0.0, gg = 0.0;
  const double* measured = seg.follower_speed_mps.data();
  const bool finite = eulerPass<WithGradient>(seg, k1, k2, tau, [&](std::size_t k, const Pair& V, const Pair* dV) {
    const double e = measured[k] - V[0];
    const double g = V[1];
    ee += e * e;
    eg += e * g;
    gg += g * g;
    if constexpr (WithGradient)
    {
      for (int i = 0; i < 3; ++i)
      {
        e_dV[i] += e * dV[i];
        g_dV[i] += g * dV[i];
      }
    }
  });
  if (!finite)
  {
    sums.diverged = true;
    return sums;
  }
  sums.ee = ee;
  sums.eg = eg;
  sums.gg = gg;
  for (int i = 0; i < 3; ++i)
  {
    sums.e_dva[i] = e_dV[i][0];
    sums.e_dvg[i] = e_dV[i][1];
    sums.g_dva[i] = g_dV[i][0];
    sums.g_dvg[i] = g_dV[i][1];
  }
  return sums;
}

void addPass(const PassSums& sums, PassSums& total)
{
  total.ee += sums.ee;
  total.eg += sums.eg;
  total.gg += sums.gg;
  for (int i = 0; i < 3; ++i)
  {
    total.e_dva[i] += sums.e_dva[i];
    total.e_dvg[i] += sums.e_dvg[i];
    total.g_dva[i] += sums.g_dva[i];
    total.g_dvg[i] += sums.g_dvg[i];
  }
  total.diverged = total.diverged || sums.diverged;
}
}  // namespace

CalibrationObjective::CalibrationObjective(const std::vector<CarFollowingRun>& segments,
                                           ParameterBounds bounds)
  : bounds_(bounds)
{
  for (const CarFollowingRun& run : segments)
  {
    const std::string problem = describeRunProblem(run);
    if (!problem.empty())
    {
      throw std::invalid_argument("segment '" + run.name + "' cannot be simulated: " + problem);
    }
    Segment seg;
    seg.initial_gap_m = run.space_gap_m[0];
    seg.initial_speed_mps = run.follower_speed_mps[0];
    for (std::size_t k = 0; k + 1 < run.size(); ++k)
    {
      seg.step_s.push_back(run.time_s[k + 1] - run.time_s[k]);
    }
    seg.leader_speed_mps = run.leader_speed_mps;
    seg.follower_speed_mps = run.follower_speed_mps;
    sample_count_ += run.size();
    segments_.push_back(std::move(seg));
  }
  if (segments_.empty())
  {
    throw std::invalid_argument("calibration needs at least one segment");
  }
}

ReducedObjectiveValue CalibrationObjective::evaluate(double k1, double k2, double tau,
                                                     bool with_gradient) const
{
  PassSums sums;
  for (const Segment& seg : segments_)
  {
    if (with_gradient)
    {
      addPass(simulatePass<true>(seg, k1, k2, tau), sums);
    }
    else
    {
      addPass(simulatePass<false>(seg, k1, k2, tau), sums);
    }
    if (sums.diverged)
    {
      break;
    }
  }
  ReducedObjectiveValue value;
  if (sums.diverged)
  {
    value.diverged = true;
    value.mse_speed_mps2 = kDivergedMseMps2;
    value.eta_m = bounds_.lower.eta_m;
    return value;
  }
  // With k1 = 0 eta has no effect (gg = 0): any eta fits; report the lower bound.
  const double eta = sums.gg > 0.0 ? std::clamp(sums.eg / sums.gg, bounds_.lower.eta_m, bounds_.upper.eta_m)
                                   : bounds_.lower.eta_m;
  const double n = static_cast<double>(sample_count_);
  // The expansion cancels terms of order (eta / tau_e)^2 against each other: a relative rounding of
  // about 1e-12 of the MSE, far below any tolerance of the search. Clamp the last few ulps at 0.
  value.mse_speed_mps2 = std::max(0.0, (sums.ee - 2.0 * eta * sums.eg + eta * eta * sums.gg) / n);
  value.eta_m = eta;
  if (with_gradient)
  {
    for (int i = 0; i < 3; ++i)
    {
      value.gradient[i] = -2.0 *
                          (sums.e_dva[i] + eta * sums.e_dvg[i] - eta * sums.g_dva[i] - eta * eta * sums.g_dvg[i]) / n;
    }
  }
  return value;
}

SensitivityRows sensitivityRows(const AccParameters& p, const CarFollowingRun& run)
{
  struct RunSegment
  {
    double initial_gap_m, initial_speed_mps;
    std::vector<double> step_s;
    const std::vector<double>& leader_speed_mps;
  } seg{run.space_gap_m[0], run.follower_speed_mps[0], {}, run.leader_speed_mps};
  for (std::size_t k = 0; k + 1 < run.size(); ++k)
  {
    seg.step_s.push_back(run.time_s[k + 1] - run.time_s[k]);
  }
  const double eta = p.eta_m;
  SensitivityRows rows;
  rows.time_s.push_back(run.time_s[0]);
  rows.residual.push_back(0.0);  // the first sample is the measured start
  rows.row.push_back(Eigen::Vector4d::Zero());
  rows.diverged = !eulerPass<true>(seg, p.k1_per_s2, p.k2_per_s, p.tau_e_s,
                                   [&](std::size_t k, const Pair& V, const Pair* dV) {
                                     // v = v_a + eta v_g, so d v / d theta_i = dv_a[i] + eta dv_g[i].
                                     rows.time_s.push_back(run.time_s[k]);
                                     rows.residual.push_back(run.follower_speed_mps[k] - (V[0] + eta * V[1]));
                                     rows.row.push_back(Eigen::Vector4d(dV[0][0] + eta * dV[0][1],
                                                                        dV[1][0] + eta * dV[1][1],
                                                                        dV[2][0] + eta * dV[2][1], V[1]));
                                   });
  return rows;
}

}  // namespace acc
