#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// Speed and gap of a simulated follower at the run's sample times.
struct SimulatedFollower
{
  std::vector<double> speed_mps;
  std::vector<double> space_gap_m;
  /// True when the recursion blew up (|v| or |s| beyond the divergence bound, or non-finite).
  /// From diverged_at_index on, the samples hold the last finite state and must not be scored.
  bool diverged = false;
  std::size_t diverged_at_index = 0;
};

/// Speed or gap magnitude beyond which a simulation is declared divergent. Far above anything a
/// road vehicle reaches, far below where doubles lose meaning.
constexpr double kDivergenceBound = 1.0e4;

/// Whether a simulated state left the plausible range (|v| or |s| at or beyond kDivergenceBound,
/// or not finite): the one runaway test of every simulation of the package.
inline bool isRunaway(double speed_mps, double space_gap_m)
{
  // Written so that NaN counts as runaway too.
  return !(std::abs(speed_mps) < kDivergenceBound && std::abs(space_gap_m) < kDivergenceBound);
}

/// The package's one follower simulator: explicit Euler driven by the measured leader speed, one
/// step per sample, started from the measured s(0) and v(0), exactly as Section IV of the paper
/// calibrates the model:
///   v[k+1] = v[k] + h_k f(s[k], v[k], u[k] - v[k])
///   s[k+1] = s[k] + h_k (u[k] - v[k]),   h_k = t[k+1] - t[k] (the data's own step)
/// with the unmodelled effects of `effects` as options (all off by default: the paper's model).
/// Per step k:
///   u_k   = recorded leader speed at t_k + delta (linear interpolation, held at the ends)
///   f_k   = k1 (s - eta - tau_e v - c v^2) + k2 (u_k - v) + k_a (u_k - u_k-1) / h_k-1,
///           then min(f_k, g (v_set - v)),
///           then clipped to [-b_max, a_max]
///   c_k   = f at t_k - d (linear interpolation in the commands computed so far; f_0 before t_0)
///   a_k+1 = a_k + (1 - exp(-h / T)) (c_k - a_k)       (a_k+1 = c_k when T = 0; a_0 = c_0)
///   v_k+1 = v_k + h a_k+1,   s_k+1 = s_k + h (u_k - v_k)
/// with the true initial gap s_0 = recorded gap + delta u_0; the returned gap is what the recorder
/// would show (true gap - delta u_k), so that it compares with the run's gap column. With every
/// effect off the arithmetic is the paper's recursion above. The calibration's objective
/// (calibration/calibration_objective.h) runs the same recursion regrouped for speed, with forward
/// sensitivities; a test holds it to this simulator. The run must satisfy
/// describeRunProblem() == "".
SimulatedFollower simulateFollower(const AccParameters& p, const EffectSettings& effects, const CarFollowingRun& run);

/// Simulated speeds and their exact derivatives with respect to the model's parameters.
struct FollowerSpeedSensitivities
{
  std::vector<double> speed_mps;
  /// d speed[k] / d x[j] at [k * dimension + j] (row k is 0 at the measured start).
  std::vector<double> speed_derivatives;
  std::size_t dimension = 0;
  bool diverged = false;  ///< as SimulatedFollower: from diverged_at_index on, rows are 0, not to be scored
  std::size_t diverged_at_index = 0;
};

/// simulateFollower() of the model with `effects` switched on, x = (k1, k2, tau_e, eta, then the
/// effects' values as makeCombinedEffectSettings(effects, ...) takes them), with forward
/// sensitivities: the same recursion run on dual numbers (model/forward_dual.h), so the speeds
/// equal simulateFollower's bit for bit and the derivatives are exact (one-sided at the kinks of
/// the limits, the cruise switch and the interpolations). At most 16 parameters.
FollowerSpeedSensitivities simulateFollowerSensitivities(const std::vector<EffectKind>& effects,
                                                         const std::vector<double>& x, const CarFollowingRun& run);

/// The simulation with NaN from where it diverged on (speed and gap): what may be scored, for
/// scores that skip NaN samples.
SimulatedFollower scorable(SimulatedFollower simulated);

/// Where a simulated car first collides with the car ahead (gap at or below 0) or drives backwards
/// (speed below 0), before any divergence; "" when it does neither. *collision, when given: which
/// of the two.
std::string describeBreakdown(const SimulatedFollower& simulated, const std::vector<double>& time_s,
                              bool* collision = nullptr);

/// The paper's model: every effect off.
inline SimulatedFollower simulateFollower(const AccParameters& p, const CarFollowingRun& run)
{
  return simulateFollower(p, EffectSettings{}, run);
}

}  // namespace acc
