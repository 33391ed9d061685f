#include "acc_identification/model/follower_effects.h"

#include <cmath>
#include <stdexcept>

#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// How both anticipation terms read the leader's acceleration: from kLeaderAccelerationWindowS,
/// so that the text cannot drift from the window the simulator uses.
std::string leaderAccelerationReading()
{
  return printfText("its speed's change over the last %g s", kLeaderAccelerationWindowS);
}
}  // namespace

const std::vector<CandidateEffect>& candidateEffects()
{
  // Bounds: wide enough for any ACC reported in the literature (lags and delays of 0.2-1.5 s,
  // accelerations of 1-3 m/s^2), narrow enough to keep the 10 Hz Euler map stable.
  static const std::vector<CandidateEffect> catalogue = {
      {EffectKind::actuation_lag, "actuation_lag", {{"lag_time_constant_s", 0.0, 3.0, 0.1, 1.5}},
       "realised acceleration follows the commanded one through T a' = f - a (exact discretisation)", true},
      {EffectKind::reaction_delay, "reaction_delay", {{"dead_time_s", 0.0, 3.0, 0.1, 1.5}},
       "the command acting at t is the law evaluated at t - d (commands interpolated in time)", true},
      {EffectKind::acceleration_limits, "acceleration_limits",
       {{"max_acceleration_mps2", 0.2, 10.0, 0.5, 3.0}, {"max_deceleration_mps2", 0.2, 10.0, 1.0, 5.0}},
       "the command is clipped to [-max_deceleration, max_acceleration]"},
      {EffectKind::sensor_time_offset, "sensor_time_offset", {{"time_offset_s", -3.0, 3.0, -1.5, 1.5}},
       "the leader's recorded data lag the truth by delta: the ACC sees u(t + delta), the recorded gap "
       "is the true gap minus delta u", true},
      {EffectKind::speed_dependent_time_gap, "speed_dependent_time_gap",
       {{"time_gap_slope_s2_per_m", -0.05, 0.05, -0.02, 0.02}},
       "desired gap eta + tau_e v + c v^2: the time gap is tau_e + c v"},
      {EffectKind::set_speed_cruise, "set_speed_cruise",
       {{"set_speed_mps", 3.0, 60.0, 10.0, 40.0}, {"cruise_gain_per_s", 0.02, 2.0, 0.1, 0.8}},
       "command = min(following law, cruise_gain (v_set - v)): the ACC holds its set speed when the gap is large"},
  };
  return catalogue;
}

bool isResolvable(EffectKind kind, const std::vector<double>& values, double sample_period_s)
{
  if (!candidateEffect(kind).magnitude_is_time || values.empty())
  {
    return true;
  }
  return std::abs(values.front()) >= sample_period_s;
}

const std::vector<CandidateEffect>& responseEffects()
{
  // Ratios up to 10: SUMO's ACC brakes with a collision-avoidance gap gain of 0.8 against a
  // gap-control gain of 0.45 and speed gain of 0.0125 ... 0.07 (ratios of 2 to 60 between modes);
  // below 0.2 a mode would hardly respond at all.
  static const std::vector<CandidateEffect> extra = {
      {EffectKind::asymmetric_response, "asymmetric_response",
       {{"closing_gain_ratio", 0.2, 10.0, 0.8, 4.0, 1.0}, {"short_gap_gain_ratio", 0.2, 10.0, 0.8, 4.0, 1.0}},
       "k2 times r_c while closing in, k1 times r_s while the gap is shorter than desired"},
      {EffectKind::speed_dependent_gains, "speed_dependent_gains",
       {{"gain_speed_slope_s_per_m", -0.15, 0.15, -0.05, 0.05, 0.0}},
       printfText("k1 and k2 times exp(g (v - %g m/s)): gains scheduled on speed", kGainReferenceSpeedMps)},
      {EffectKind::leader_acceleration_feedforward, "leader_acceleration_feedforward",
       {{"leader_acceleration_gain", 0.0, 1.5, 0.05, 0.8}},
       "command += k_a times the leader's acceleration (" + leaderAccelerationReading() + ")"},
      // c up to 20: closing at 3 m/s on a 10 m gap then adds up to 9 m/s^2, beyond any car's brakes.
      {EffectKind::quadratic_closing_response, "quadratic_closing_response",
       {{"kinematic_braking_ratio", 0.0, 20.0, 0.2, 5.0}},
       "command -= c (u - v)^2 / (2 s) while closing in: c times the deceleration that would just match the "
       "leader's speed within the gap; harder braking for a fast-closing leader on a short gap, none for small "
       "differences"},
      // The same range as the two-sided feedforward's: up to 1.5 times the leader's deceleration.
      {EffectKind::leader_braking_anticipation, "leader_braking_anticipation",
       {{"leader_braking_gain", 0.0, 1.5, 0.05, 0.8}},
       "command += k_b times the leader's acceleration while the leader brakes (" + leaderAccelerationReading() +
           ", negative): the leader's braking anticipated, its pulling away not"},
  };
  return extra;
}

const CandidateEffect& candidateEffect(EffectKind kind)
{
  static const CandidateEffect base{EffectKind::none, "none", {}, "the base OVRV model"};
  if (kind == EffectKind::none)
  {
    return base;
  }
  for (const auto* list : {&candidateEffects(), &responseEffects()})
  {
    for (const CandidateEffect& effect : *list)
    {
      if (effect.kind == kind)
      {
        return effect;
      }
    }
  }
  throw std::invalid_argument("unknown effect kind");
}

std::string effectName(EffectKind kind) { return candidateEffect(kind).name; }

std::vector<std::string> effectNames(const std::vector<EffectKind>& kinds)
{
  std::vector<std::string> names;
  for (EffectKind kind : kinds)
    names.push_back(effectName(kind));
  return names;
}

bool parseEffectName(const std::string& name, EffectKind* kind)
{
  if (name == "none")
  {
    *kind = EffectKind::none;
    return true;
  }
  for (const auto* list : {&candidateEffects(), &responseEffects()})
  {
    for (const CandidateEffect& effect : *list)
    {
      if (effect.name == name)
      {
        *kind = effect.kind;
        return true;
      }
    }
  }
  return false;
}

bool parseEffectNames(const std::vector<std::string>& names, std::vector<EffectKind>* kinds, std::string* unknown)
{
  kinds->clear();
  for (const std::string& name : names)
  {
    EffectKind kind = EffectKind::none;
    if (!parseEffectName(name, &kind) || kind == EffectKind::none)
    {
      *unknown = name;
      return false;
    }
    kinds->push_back(kind);
  }
  return true;
}

EffectSettings makeEffectSettings(EffectKind kind, const std::vector<double>& values)
{
  if (values.size() != candidateEffect(kind).parameters.size())
  {
    throw std::invalid_argument("wrong number of parameters for effect " + effectName(kind));
  }
  EffectSettings s;
  switch (kind)
  {
    case EffectKind::none: break;
    case EffectKind::actuation_lag: s.actuation_lag_s = values[0]; break;
    case EffectKind::reaction_delay: s.reaction_delay_s = values[0]; break;
    case EffectKind::acceleration_limits:
      s.max_acceleration_mps2 = values[0];
      s.max_deceleration_mps2 = values[1];
      break;
    case EffectKind::sensor_time_offset: s.sensor_time_offset_s = values[0]; break;
    case EffectKind::speed_dependent_time_gap: s.time_gap_speed_slope_s2_per_m = values[0]; break;
    case EffectKind::set_speed_cruise:
      s.set_speed_mps = values[0];
      s.cruise_gain_per_s = values[1];
      break;
    case EffectKind::leader_acceleration_feedforward: s.leader_acceleration_gain = values[0]; break;
    case EffectKind::asymmetric_response:
      s.closing_gain_ratio = values[0];
      s.short_gap_gain_ratio = values[1];
      break;
    case EffectKind::speed_dependent_gains: s.gain_speed_slope_s_per_m = values[0]; break;
    case EffectKind::quadratic_closing_response: s.kinematic_braking_ratio = values[0]; break;
    case EffectKind::leader_braking_anticipation: s.leader_braking_gain = values[0]; break;
  }
  return s;
}

std::vector<double> effectValues(EffectKind kind, const EffectSettings& s)
{
  switch (kind)
  {
    case EffectKind::none: return {};
    case EffectKind::actuation_lag: return {s.actuation_lag_s};
    case EffectKind::reaction_delay: return {s.reaction_delay_s};
    case EffectKind::acceleration_limits: return {s.max_acceleration_mps2, s.max_deceleration_mps2};
    case EffectKind::sensor_time_offset: return {s.sensor_time_offset_s};
    case EffectKind::speed_dependent_time_gap: return {s.time_gap_speed_slope_s2_per_m};
    case EffectKind::set_speed_cruise: return {s.set_speed_mps, s.cruise_gain_per_s};
    case EffectKind::leader_acceleration_feedforward: return {s.leader_acceleration_gain};
    case EffectKind::asymmetric_response: return {s.closing_gain_ratio, s.short_gap_gain_ratio};
    case EffectKind::speed_dependent_gains: return {s.gain_speed_slope_s_per_m};
    case EffectKind::quadratic_closing_response: return {s.kinematic_braking_ratio};
    case EffectKind::leader_braking_anticipation: return {s.leader_braking_gain};
  }
  return {};
}

void applyEffectValues(EffectKind kind, const std::vector<double>& values, EffectSettings* settings)
{
  // Only kind's fields are copied: the others keep what earlier effects of the model set.
  const EffectSettings own = makeEffectSettings(kind, values);
  switch (kind)
  {
    case EffectKind::none: break;
    case EffectKind::actuation_lag: settings->actuation_lag_s = own.actuation_lag_s; break;
    case EffectKind::reaction_delay: settings->reaction_delay_s = own.reaction_delay_s; break;
    case EffectKind::acceleration_limits:
      settings->max_acceleration_mps2 = own.max_acceleration_mps2;
      settings->max_deceleration_mps2 = own.max_deceleration_mps2;
      break;
    case EffectKind::sensor_time_offset: settings->sensor_time_offset_s = own.sensor_time_offset_s; break;
    case EffectKind::speed_dependent_time_gap:
      settings->time_gap_speed_slope_s2_per_m = own.time_gap_speed_slope_s2_per_m;
      break;
    case EffectKind::set_speed_cruise:
      settings->set_speed_mps = own.set_speed_mps;
      settings->cruise_gain_per_s = own.cruise_gain_per_s;
      break;
    case EffectKind::leader_acceleration_feedforward:
      settings->leader_acceleration_gain = own.leader_acceleration_gain;
      break;
    case EffectKind::asymmetric_response:
      settings->short_gap_gain_ratio = own.short_gap_gain_ratio;
      settings->closing_gain_ratio = own.closing_gain_ratio;
      break;
    case EffectKind::speed_dependent_gains: settings->gain_speed_slope_s_per_m = own.gain_speed_slope_s_per_m; break;
    case EffectKind::quadratic_closing_response:
      settings->kinematic_braking_ratio = own.kinematic_braking_ratio;
      break;
    case EffectKind::leader_braking_anticipation: settings->leader_braking_gain = own.leader_braking_gain; break;
  }
}

EffectSettings makeCombinedEffectSettings(const std::vector<EffectKind>& kinds, const std::vector<double>& values)
{
  EffectSettings settings;
  std::size_t used = 0;
  for (EffectKind kind : kinds)
  {
    const std::size_t count = candidateEffect(kind).parameters.size();
    if (used + count > values.size())
    {
      throw std::invalid_argument("too few parameters for the effects of a combined model");
    }
    applyEffectValues(kind, std::vector<double>(values.begin() + static_cast<long>(used),
                                                values.begin() + static_cast<long>(used + count)),
                      &settings);
    used += count;
  }
  if (used != values.size())
  {
    throw std::invalid_argument("too many parameters for the effects of a combined model");
  }
  return settings;
}

}  // namespace acc
