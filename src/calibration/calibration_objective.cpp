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

bool isRunaway(double a, double b, double c, double d)
{
  // Written so that NaN counts as runaway too.
  return !(std::abs(a) < kDivergenceBound && std::abs(b) < kDivergenceBound &&
           std::abs(c) < kDivergenceBound && std::abs(d) < kDivergenceBound);
}

/// Two doubles in one SSE2 register (x86-64's baseline, so no special build flags): the eta = 0
/// simulation and the unit-eta response advance with the same coefficients, side by side.
typedef double Pair __attribute__((vector_size(16)));

/// One Euler pass over a segment: the eta = 0 simulation (s_a, v_a) and the unit-eta response
/// (s_g, v_g), as the pairs S = (s_a, s_g), V = (v_a, v_g), and, when WithGradient, their
/// sensitivities dS[i], dV[i] to (k1, k2, tau_e). The sums are local so that the compiler keeps
/// them in registers.
template <bool WithGradient, typename Segment>
PassSums simulatePass(const Segment& seg, double k1, double k2, double tau)
{
  PassSums sums;
  Pair S = {seg.initial_gap_m, 0.0}, V = {seg.initial_speed_mps, 0.0};
  Pair dS[3] = {{0, 0}, {0, 0}, {0, 0}}, dV[3] = {{0, 0}, {0, 0}, {0, 0}};
  Pair e_dV[3] = {{0, 0}, {0, 0}, {0, 0}}, g_dV[3] = {{0, 0}, {0, 0}, {0, 0}};
  const Pair unit_eta = {0.0, 1.0};  // eta enters the g system only, as a unit constant
  const std::size_t steps = seg.step_s.size();
  const double* step = seg.step_s.data();
  const double* leader = seg.leader_speed_mps.data();
  const double* measured = seg.follower_speed_mps.data();
  const double damping = k1 * tau + k2;
  // Sample 0 is the measured start: zero error and zero sensitivity, nothing to add.
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
    if (isRunaway(S[0], V[0], S[1], V[1]))
    {
      sums.diverged = true;
      return sums;
    }
    const double e = measured[k + 1] - V[0];
    const double g = V[1];
    sums.ee += e * e;
    sums.eg += e * g;
    sums.gg += g * g;
    if constexpr (WithGradient)
    {
      for (int i = 0; i < 3; ++i)
      {
        e_dV[i] += e * dV[i];
        g_dV[i] += g * dV[i];
      }
    }
  }
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

}  // namespace acc
