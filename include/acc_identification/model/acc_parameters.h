#pragma once

namespace acc
{
/// Parameters of the constant-effective-time-gap OVRV model of an ACC (Gunter et al., eq. 4):
///   dv/dt = k1 (s - eta - tau_e v) + k2 (v_leader - v)
/// s is the bumper-to-bumper space gap and v the follower's speed.
struct AccParameters
{
  double k1_per_s2 = 0.0;  ///< gain on the spacing error [1/s^2]
  double k2_per_s = 0.0;   ///< gain on the relative speed [1/s]
  double tau_e_s = 0.0;    ///< effective time gap [s]
  double eta_m = 0.0;      ///< jam distance: the space gap at standstill [m]
};

/// The model's domain for a gain or time gap the tools take from a user: 0 or more (a negative one
/// turns lambda2's sign against |Gamma|), and at most this much, far beyond any car (calibration
/// searches k1 <= 2, k2 <= 3, tau_e <= 5) yet small enough that lambda2's powers of the
/// parameters stay finite (1e300 made them NaN and the verdict with them).
constexpr double kLargestModelGainOrTimeGap = 1e6;

}  // namespace acc
