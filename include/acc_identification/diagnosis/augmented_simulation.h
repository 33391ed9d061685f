#pragma once

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/diagnosis/candidate_effects.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
/// Explicit-Euler simulation of one follower with the effects of `effects` switched on, driven by
/// the run's recorded leader speed and started from its recorded gap and speed, one step per
/// sample as simulateFollower(). Per step k (h = t[k+1] - t[k]):
///   u_k   = recorded leader speed at t_k + delta (linear interpolation, held at the ends)
///   f_k   = k1 (s - eta - tau_e v - c v^2) + k2 (u_k - v) + k_a (u_k - u_k-1) / h_k-1,
///           then min(f_k, g (v_set - v)),
///           then clipped to [-b_max, a_max]
///   c_k   = f at t_k - d (linear interpolation in the commands computed so far; f_0 before t_0)
///   a_k+1 = a_k + (1 - exp(-h / T)) (c_k - a_k)       (a_k+1 = c_k when T = 0; a_0 = c_0)
///   v_k+1 = v_k + h a_k+1,   s_k+1 = s_k + h (u_k - v_k)
/// with the true initial gap s_0 = recorded gap + delta u_0. The returned gap is what the
/// recorder would show (true gap - delta u_k), so that it compares with the run's gap column.
/// With every effect off the arithmetic is that of simulateFollower(), bit for bit.
/// The run must satisfy describeRunProblem() == "".
SimulatedFollower simulateAugmentedFollower(const AccParameters& p, const EffectSettings& effects,
                                            const CarFollowingRun& run);

}  // namespace acc
