#pragma once

#include <limits>
#include <string>
#include <vector>

namespace acc
{
/// The physical effects the base OVRV model lacks that the diagnosis can test, one at a time.
enum class EffectKind
{
  none,                      ///< the base model of the paper
  actuation_lag,             ///< first-order lag between commanded and realised acceleration
  reaction_delay,            ///< dead time between the state and the command acting on it
  acceleration_limits,       ///< the largest acceleration and deceleration the ACC commands
  sensor_time_offset,        ///< clock offset between the two receivers (also biases the gap)
  speed_dependent_time_gap,  ///< spacing policy eta + tau v + c v^2 instead of linear in speed
  set_speed_cruise,          ///< the ACC drives at its set speed when the gap is large
  /// Anticipation: the ACC also responds to the leader's acceleration, as a radar-tracked
  /// acceleration estimate allows (a response effect, responseEffects()).
  leader_acceleration_feedforward,
  /// Different gains for closing in (k2, the effect's magnitude: what braking dips pin) and for a
  /// gap shorter than desired (k1): ACCs brake hard
  /// for a short, closing gap and accelerate gently otherwise (FHWA's piecewise ACC model, SUMO's
  /// ACC with its own collision-avoidance gains).
  asymmetric_response,
  /// Gains that scale with speed, exp(g (v - v_ref)): a controller scheduled on speed.
  speed_dependent_gains,
  /// Braking that grows with the square of the closing speed over the gap, c (u - v)^2 / (2 s)
  /// while closing in: c times the kinematic deceleration, the constant deceleration that would
  /// just match the leader's speed within the gap. An ACC that ignores small speed differences yet
  /// answers a fast-closing leader on a short gap harder than in proportion (IDM's
  /// intelligent-braking term, Gipps' safe speed, the constant-acceleration heuristic of Kesting,
  /// Treiber and Helbing's ACC model). Small signals see no change.
  quadratic_closing_response,
  /// Anticipation of the leader's braking only: command += k_b min(a_leader, 0). Radar ACCs
  /// estimate the leader's acceleration, and are built to brake early for a braking leader yet to
  /// accelerate gently (the asymmetry of FHWA's and SUMO's ACC models): the feedforward acts on
  /// the braking side alone, so a leader pulling away is followed through the linear law.
  leader_braking_anticipation,
};

/// The speed at which speed_dependent_gains leaves k1 and k2 as they are [m/s]: a reparametrisation
/// only (k1 and k2 are then the gains at this speed), chosen inside every campaign's range.
constexpr double kGainReferenceSpeedMps = 15.0;

/// The gap below which quadratic_closing_response's kinematic deceleration stops growing [m]: a
/// simulated gap near zero is a collision, and the term must not divide by it.
constexpr double kKinematicBrakingMinGapM = 2.0;

/// The span W over which the two anticipation terms read the leader's acceleration [s]:
/// a_leader(t) = (u(t) - u(t - W)) / W, the leader's mean acceleration over the last W seconds.
/// A radar ACC estimates the leader's acceleration through a filter, not from one sample: read
/// over one 10 Hz sample, white speed noise of 0.06 m/s (raw GNSS Doppler) becomes 0.85 m/s^2 of
/// acceleration noise, which min(a, 0) rectifies into brakings that are not there (k_b came out
/// 18 % high on a synthetic drive); over 0.5 s it is 0.17 m/s^2. The lag it adds (W / 2) is a
/// quarter of a second, within what the reaction delay absorbs. Fixed, not fitted: one more
/// timing parameter beside the delay would be left for the same brakings to pin.
constexpr double kLeaderAccelerationWindowS = 0.5;

/// Every option of the augmented follower model. The defaults switch every effect off, and the
/// augmented simulator then reduces exactly to simulateFollower().
struct EffectSettings
{
  double actuation_lag_s = 0.0;  ///< T in T a' = f - a (0: realised = commanded)
  double reaction_delay_s = 0.0; ///< d: the command acting at t was computed at t - d
  double max_acceleration_mps2 = std::numeric_limits<double>::infinity();
  double max_deceleration_mps2 = std::numeric_limits<double>::infinity();  ///< a positive number
  /// delta: the recorded leader data lag the truth by delta, recorded(t) = true(t - delta), so the
  /// ACC really saw u(t) = u_recorded(t + delta) and the recorded gap reads the true gap minus
  /// delta u (the distance the leader covers during the offset).
  double sensor_time_offset_s = 0.0;
  /// c in the desired gap eta + tau_e v + c v^2 [s^2/m]: the time gap grows (c > 0) or shrinks
  /// with speed as tau_e + c v.
  double time_gap_speed_slope_s2_per_m = 0.0;
  /// Cruise mode: command = min(following law, cruise_gain (v_set - v)); infinity: no set speed.
  double set_speed_mps = std::numeric_limits<double>::infinity();
  double cruise_gain_per_s = 0.0;
  /// k_a: command += k_a a_leader, a_leader the leader's acceleration the ACC saw, read over
  /// kLeaderAccelerationWindowS (0 at the first sample) [dimensionless].
  double leader_acceleration_gain = 0.0;
  /// r_s: k1 is multiplied by r_s while the spacing error s - eta - tau_e v - c v^2 is negative
  /// (the gap is shorter than desired) [dimensionless; 1: symmetric].
  double short_gap_gain_ratio = 1.0;
  /// r_c: k2 is multiplied by r_c while the follower closes in (leader speed - v < 0) [1: symmetric].
  double closing_gain_ratio = 1.0;
  /// g: k1 and k2 are multiplied by exp(g (v - kGainReferenceSpeedMps)) [s/m; 0: constant gains].
  double gain_speed_slope_s_per_m = 0.0;
  /// c: command -= c (u - v)^2 / (2 max(s, kKinematicBrakingMinGapM)) while the follower closes
  /// in (u - v < 0), s the true gap [dimensionless: multiples of the kinematic deceleration; 0: off].
  double kinematic_braking_ratio = 0.0;
  /// k_b: command += k_b min(a_leader, 0), a_leader as for leader_acceleration_gain: only a
  /// braking leader enters [dimensionless; 0: off].
  double leader_braking_gain = 0.0;
};

/// One calibrated parameter of an effect: its name with unit, the hard bounds of the search and
/// the narrower range the multistart draws its starting values from.
struct EffectParameterSpec
{
  std::string name;
  double lower = 0.0;
  double upper = 0.0;
  double start_lower = 0.0;
  double start_upper = 0.0;
  /// The value at which the parameter switches its effect off, where that is an interior value
  /// (a gain ratio of 1); NaN where "off" is a bound (see the diagnosis's near-off starts).
  double neutral = std::numeric_limits<double>::quiet_NaN();
};

/// An entry of the effect catalogue.
struct CandidateEffect
{
  EffectKind kind = EffectKind::none;
  std::string name;                           ///< e.g. "actuation_lag" (used in all output)
  std::vector<EffectParameterSpec> parameters;  ///< the first one is the effect's magnitude
  std::string how_it_enters;                  ///< one sentence for reports
  /// The magnitude is a time: below one sample period the data cannot resolve it (the explicit
  /// Euler model itself lags a continuous car by about half a step, which a 0.05 s offset or
  /// delay would otherwise "explain" at 10 Hz).
  bool magnitude_is_time = false;
};

/// Whether the fitted values of kind are large enough for data sampled every sample_period_s to
/// resolve: |first value| >= sample_period_s for timing effects, always for the others.
bool isResolvable(EffectKind kind, const std::vector<double>& values, double sample_period_s);

/// The six candidate effects of the issue, in a fixed order (EffectKind::none is not among them).
const std::vector<CandidateEffect>& candidateEffects();

/// The response effects: how the ACC answers, beyond the linear law's two constant gains
/// (asymmetric_response, speed_dependent_gains, leader_acceleration_feedforward,
/// quadratic_closing_response, leader_braking_anticipation). Candidates of
/// the diagnosis beside the six above, and of the campaign's platoon diagnosis.
const std::vector<CandidateEffect>& responseEffects();

/// The catalogue entry of kind (kind none gives an entry with no parameters).
const CandidateEffect& candidateEffect(EffectKind kind);

/// "none" or the effect's name.
std::string effectName(EffectKind kind);

/// The names of effects, in order (for JSON lists: an empty list is []).
std::vector<std::string> effectNames(const std::vector<EffectKind>& kinds);

/// Parses a name as printed by effectName(); false when unknown.
bool parseEffectName(const std::string& name, EffectKind* kind);

/// Parses the names of effects (not "none"), in order; false with the first name that is not one
/// in *unknown.
bool parseEffectNames(const std::vector<std::string>& names, std::vector<EffectKind>* kinds, std::string* unknown);

/// The settings with kind's parameters set to values (in the catalogue's order); every other
/// effect stays off. values.size() must equal the number of the effect's parameters.
EffectSettings makeEffectSettings(EffectKind kind, const std::vector<double>& values);

/// The values of kind's parameters read back from settings (inverse of makeEffectSettings).
std::vector<double> effectValues(EffectKind kind, const EffectSettings& settings);

/// Sets kind's parameters in settings to values (catalogue order) and leaves every other effect as
/// it is, so that several effects can be switched on in one model.
void applyEffectValues(EffectKind kind, const std::vector<double>& values, EffectSettings* settings);

/// The settings of a model with several effects at once: values holds each kind's parameters in
/// the catalogue's order, concatenated in the order of kinds. An empty list is the base model, a
/// single kind equals makeEffectSettings(kind, values).
EffectSettings makeCombinedEffectSettings(const std::vector<EffectKind>& kinds, const std::vector<double>& values);

}  // namespace acc
