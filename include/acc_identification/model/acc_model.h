#pragma once

#include "acc_identification/model/acc_parameters.h"

namespace acc
{
/// Partial derivatives of the acceleration law f(s, v, dv), taken at fixed dv as in the paper
/// and in Wilson & Ward (2011): f_s = k1, f_v = -k1 tau_e, f_dv = k2. They do not depend on the
/// state because the law is linear.
struct AccelerationPartials
{
  double f_s = 0.0;   ///< d f / d s  [1/s^2]
  double f_v = 0.0;   ///< d f / d v  [1/s]
  double f_dv = 0.0;  ///< d f / d dv [1/s]
};

/// The ACC acceleration law f(s, v, dv) = k1 (s - eta - tau_e v) + k2 dv [m/s^2].
/// @param space_gap_m      bumper-to-bumper gap s
/// @param speed_mps        follower speed v
/// @param relative_speed_mps leader minus follower speed dv
double accelerationMps2(const AccParameters& p, double space_gap_m, double speed_mps,
                        double relative_speed_mps);
/// The same law for any scalar type: the augmented simulator runs it on dual numbers to carry
/// exact derivatives (model/forward_dual.h). accelerationMps2 is this with doubles.
template <typename Scalar>
#if defined(__GNUC__)
// Inlined into the simulator's step even for dual numbers, where GCC's size heuristic would
// otherwise make it a call per sample (a tenth of a diagnose).
__attribute__((always_inline))
#endif
inline Scalar accelerationLaw(const Scalar& k1, const Scalar& k2, const Scalar& tau_e, const Scalar& eta,
                       const Scalar& space_gap, const Scalar& speed, const Scalar& relative_speed)
{
  return k1 * (space_gap - eta - tau_e * speed) + k2 * relative_speed;
}

AccelerationPartials accelerationPartials(const AccParameters& p);

/// The rational driving constraints (paper eq. 5-7): f_s >= 0, f_dv >= 0, f_v <= 0. For this
/// model they hold exactly when k1, k2, tau_e >= 0; eta >= 0 is added for physical sense (a
/// negative jam distance means collision at standstill). Non-finite values fail.
bool satisfiesRationalDrivingConstraints(const AccParameters& p);

/// Space gap at which a follower at constant speed v feels no acceleration: eta + tau_e v [m].
double equilibriumSpaceGapM(const AccParameters& p, double speed_mps);

}  // namespace acc
