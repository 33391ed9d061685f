#pragma once

#include <limits>
#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// String stability of the augmented model, from its small-signal speed-to-speed transfer
/// function evaluated numerically:
///   Gamma(s) = e^{-s d} (k_a A(s) + k2 s + k1) / ((T s + 1) s^2 + e^{-s d} ((k2 + k1 tau_lin) s + k1))
/// T the actuation lag, d the reaction delay, k_a the leader-acceleration feedforward (the braking
/// anticipation's k_b on the branch where the leader brakes), A(s) = s (1 - e^{-s W}) / W the leader's
/// acceleration read over W = kLeaderAccelerationWindowS (s^2 as W -> 0), and tau_lin = tau_e + 2 c v0 the time gap of the
/// speed-dependent spacing policy linearised at the operating speed v0 (d(c v^2)/dv = 2 c v0).
/// Gains scheduled on speed enter at v0: k exp(g (v0 - 15 m/s)). A law with branches has no single
/// transfer function (its gains switch at equilibrium): an asymmetric law's four, (k1 or k1 r_s) x
/// (k2 or k2 r_c), the braking anticipation's two (with and without k_b). A braking meets each of
/// them (the short, closing gap first, the others on the way back), so the law is held to all:
/// |Gamma| is the largest of its branches' at each frequency, its loop stable only where each
/// branch's is, lambda2 the least stable branch's. (Judged on the braking branch alone, a "stable"
/// law could amplify on its recovery branch.)
/// With T = d = c = 0 this is the paper's eq. 9. Acceleration limits and the set-speed cruise
/// do not act on small disturbances around an unsaturated following equilibrium, and a clock
/// offset between receivers changes the record, not the vehicle: for those Gamma is the base one.
///
/// Gamma describes what a car passes on only when the car's own loop is stable: a car whose loop
/// L(s) = e^{-s d} ((k2 + k1 tau_lin) s + k1) / ((T s + 1) s^2) is unstable oscillates with
/// growing amplitude behind a steady leader, whatever |Gamma(j w)| says (see localLoopStability).
/// Such a model is not string stable.
struct AugmentedStability
{
  double peak_gain_db = 0.0;           ///< max over the grid of 20 log10 |Gamma(j w)|
  double peak_frequency_rad_s = 0.0;
  bool string_stable = true;           ///< locally stable and |Gamma(j w)| <= 1 on the whole grid
  bool locally_stable = true;          ///< the car's own loop is stable (localLoopStability)
  double phase_margin_deg = std::numeric_limits<double>::quiet_NaN();  ///< of L(j w) at its crossover
  double crossover_rad_s = std::numeric_limits<double>::quiet_NaN();   ///< where |L(j w)| = 1
  double lambda2 = 0.0;                ///< Wilson & Ward's lambda2 of the linearised law (no lag/delay term)
  std::string note;                    ///< how the effect enters the small-signal model
};

/// Whether a car's own loop is stable: its characteristic equation
///   (T s + 1) s^2 + e^{-s d} (b s + k1) = 0,  b = k2 + k1 tau_lin,
/// has no root in the closed right half-plane. |L(j w)| falls monotonically in w (its log-log slope
/// is below -1), so it crosses 1 once, at w_c; without the delay the cubic is stable iff its
/// Routh condition b > T k1 holds, which is a positive phase margin; and as the delay grows, roots
/// can cross the imaginary axis only at w_c, each time to the right (Cooke and van den Driessche's
/// single-crossing case). So the loop is stable iff the unwrapped phase margin
///   atan2(b w_c, k1) - atan(T w_c) - w_c d
/// is positive. Without any feedback (k1 = b = 0) the car does not follow: not stable.
/// Fills locally_stable, phase_margin_deg and crossover_rad_s of `out`.
void localLoopStability(const AccParameters& linear_gains, double actuation_lag_s, double reaction_delay_s,
                        AugmentedStability* out);

/// Whether the car of the model (p, effects) is locally stable at each of the operating speeds,
/// its loop linearised there as analyzeAugmentedStability linearises it. A production ACC is
/// locally stable, so a fitted model is held to this (calibrateAugmentedSet).
bool locallyStableAt(const AccParameters& p, const EffectSettings& effects,
                     const std::vector<double>& operating_speeds_mps);

/// |Gamma(j w)| of the augmented model as a ratio; of a law with branches (asymmetric gains, the
/// anticipation of the leader's braking) the largest of its branches'.
double augmentedTransferGain(const AccParameters& p, const EffectSettings& effects, double operating_speed_mps,
                             double frequency_rad_s);

/// |Gamma(j w)|^2, what the stability index needs (augmentedTransferGain is its square root).
double augmentedTransferGainSquared(const AccParameters& p, const EffectSettings& effects, double operating_speed_mps,
                                    double frequency_rad_s);

/// Peak of |Gamma| on a logarithmic grid of 4000 frequencies from 1e-4 to 20 rad/s (10 Hz data
/// cannot show faster dynamics), plus the closed-form base peak frequency so that the base
/// verdict is reproduced exactly.
AugmentedStability analyzeAugmentedStability(const AccParameters& p, EffectKind effect, const EffectSettings& effects,
                                             double operating_speed_mps);

/// The same for a model of several effects (none: the base model): the gain does not depend on
/// the list, the note says how each effect enters the small-signal model, joined by "; ".
AugmentedStability analyzeAugmentedStability(const AccParameters& p, const std::vector<EffectKind>& kinds,
                                             const EffectSettings& effects, double operating_speed_mps);

}  // namespace acc
