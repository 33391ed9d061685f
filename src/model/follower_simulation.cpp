#include "acc_identification/model/follower_simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "acc_identification/model/acc_model.h"
#include "acc_identification/model/forward_dual.h"
#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// Linear interpolation of values(t) at t_query, held constant outside [t_0, t_end]. `cursor` is
/// a search hint for queries that move forward in time (every use here), keeping a pass O(n).
/// Generic so that the values or the query time may carry derivatives (ForwardDual).
template <typename Result, typename Value, typename Time>
Result interpolateForward(const std::vector<double>& time_s, const std::vector<Value>& values, std::size_t available,
                          const Time& t_query, std::size_t* cursor)
{
  const double t = valueOf(t_query);
  if (t <= time_s[0])
  {
    return values[0];
  }
  if (t >= time_s[available - 1])
  {
    return values[available - 1];
  }
  std::size_t i = std::min(*cursor, available - 2);
  while (i > 0 && time_s[i] > t)
  {
    --i;
  }
  while (i + 2 < available && time_s[i + 1] <= t)
  {
    ++i;
  }
  *cursor = i;
  const Time w = (t_query - time_s[i]) / (time_s[i + 1] - time_s[i]);
  return values[i] + w * (values[i + 1] - values[i]);
}

/// std::min and std::max, choosing by value (the derivative follows the branch taken).
template <typename Scalar>
const Scalar& smallerOf(const Scalar& a, const Scalar& b)
{
  return valueOf(b) < valueOf(a) ? b : a;
}
template <typename Scalar>
const Scalar& largerOf(const Scalar& a, const Scalar& b)
{
  return valueOf(a) < valueOf(b) ? b : a;
}

/// Whether a term enters the law: nonzero, or (for a dual number) a parameter being differentiated,
/// whose derivative must flow even where its value is 0.
bool entersModel(double x) { return x != 0.0; }
template <std::size_t N>
bool entersModel(const ForwardDual<N>& x)
{
  return x.value != 0.0 || x.derivative != std::array<double, N>{};
}

/// Every quantity of the law in one scalar type: plain doubles, or dual numbers seeded with the
/// parameters being differentiated.
template <typename Scalar>
struct ModelScalars
{
  Scalar k1, k2, tau_e, eta;
  Scalar actuation_lag_s, reaction_delay_s, max_acceleration_mps2, max_deceleration_mps2;
  Scalar sensor_time_offset_s, time_gap_speed_slope_s2_per_m, set_speed_mps, cruise_gain_per_s,
      leader_acceleration_gain;
  Scalar short_gap_gain_ratio, closing_gain_ratio, gain_speed_slope_s_per_m, kinematic_braking_ratio;
  Scalar leader_braking_gain;
};

ModelScalars<double> plainScalars(const AccParameters& p, const EffectSettings& e)
{
  return {p.k1_per_s2,          p.k2_per_s,           p.tau_e_s,
          p.eta_m,              e.actuation_lag_s,    e.reaction_delay_s,
          e.max_acceleration_mps2, e.max_deceleration_mps2, e.sensor_time_offset_s,
          e.time_gap_speed_slope_s2_per_m, e.set_speed_mps, e.cruise_gain_per_s,
          e.leader_acceleration_gain, e.short_gap_gain_ratio, e.closing_gain_ratio,
          e.gain_speed_slope_s_per_m, e.kinematic_braking_ratio, e.leader_braking_gain};
}

/// The leader speed the ACC really saw at each sample: recorded at t + delta (only made when a
/// clock offset enters the model: the paper's model reads the recorded speeds in place).
template <typename Scalar>
std::vector<Scalar> shiftedLeaderSpeed(const CarFollowingRun& run, const Scalar& offset_s)
{
  std::vector<Scalar> shifted(run.size());
  std::size_t cursor = 0;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    shifted[k] = interpolateForward<Scalar>(run.time_s, run.leader_speed_mps, run.size(), run.time_s[k] + offset_s,
                                            &cursor);
  }
  return shifted;
}

/// Whether a gain ratio departs from symmetry: not 1, or a parameter being differentiated.
bool ratioEntersModel(double ratio) { return ratio != 1.0; }
template <std::size_t N>
bool ratioEntersModel(const ForwardDual<N>& ratio)
{
  return ratio.value != 1.0 || ratio.derivative != std::array<double, N>{};
}

/// Which optional terms enter the law: decided once per simulation rather than at every step (a
/// dual number's test looks at its every derivative), with the same outcome.
struct LawTerms
{
  bool shaped = false;             ///< response options: a gain ratio or a gain schedule
  bool gain_schedule = false;      ///< gains scheduled on speed
  bool gap_slope = false;          ///< time gap growing with speed
  bool feedforward = false;        ///< the leader's acceleration
  bool braking_anticipation = false;  ///< the leader's acceleration while it brakes
  bool kinematic_braking = false;  ///< the quadratic closing response
  bool cruise = false;             ///< a set speed caps the command
  bool acceleration_limit = false, deceleration_limit = false;
};

template <typename Scalar>
LawTerms lawTermsOf(const ModelScalars<Scalar>& m)
{
  LawTerms terms;
  terms.gain_schedule = entersModel(m.gain_speed_slope_s_per_m);
  terms.shaped = ratioEntersModel(m.short_gap_gain_ratio) || ratioEntersModel(m.closing_gain_ratio) ||
                 terms.gain_schedule;
  terms.gap_slope = entersModel(m.time_gap_speed_slope_s2_per_m);
  terms.feedforward = entersModel(m.leader_acceleration_gain);
  terms.braking_anticipation = entersModel(m.leader_braking_gain);
  terms.kinematic_braking = entersModel(m.kinematic_braking_ratio);
  terms.cruise = std::isfinite(valueOf(m.set_speed_mps));
  // An infinite limit never binds (a non-finite command runs away either way).
  terms.acceleration_limit = std::isfinite(valueOf(m.max_acceleration_mps2));
  terms.deceleration_limit = std::isfinite(valueOf(m.max_deceleration_mps2));
  return terms;
}

/// The law with response options: gains scheduled on speed, and each gain multiplied by its ratio
/// on its own side (k1 while the spacing error is negative, k2 while closing in). Only called when
/// one of them enters the model, so that the paper's arithmetic stays as it is otherwise.
template <typename Scalar, typename Leader>
Scalar shapedLaw(const ModelScalars<Scalar>& m, const LawTerms& terms, const Scalar& gap, const Scalar& speed,
                 const Leader& leader_speed)
{
  using std::exp;
  Scalar spacing_error = gap - m.eta - m.tau_e * speed;
  if (terms.gap_slope)
  {
    spacing_error = spacing_error - m.time_gap_speed_slope_s2_per_m * speed * speed;
  }
  const Scalar relative_speed = leader_speed - speed;
  Scalar k1 = m.k1;
  Scalar k2 = m.k2;
  if (terms.gain_schedule)
  {
    const Scalar schedule = exp(m.gain_speed_slope_s_per_m * (speed - kGainReferenceSpeedMps));
    k1 = k1 * schedule;
    k2 = k2 * schedule;
  }
  if (valueOf(spacing_error) < 0.0)
  {
    k1 = k1 * m.short_gap_gain_ratio;
  }
  if (valueOf(relative_speed) < 0.0)
  {
    k2 = k2 * m.closing_gain_ratio;
  }
  return k1 * spacing_error + k2 * relative_speed;
}

/// The law with the spacing-policy, response and cruise options, then the actuator's limits.
template <typename Scalar, typename Leader>
Scalar commandedAcceleration(const ModelScalars<Scalar>& m, const LawTerms& terms, const Scalar& gap,
                             const Scalar& speed, const Leader& leader_speed, const Leader& leader_acceleration)
{
  Scalar command = terms.shaped
                       ? shapedLaw(m, terms, gap, speed, leader_speed)
                       : accelerationLaw<Scalar>(m.k1, m.k2, m.tau_e, m.eta, gap, speed, leader_speed - speed);
  if (terms.feedforward)
  {
    command += m.leader_acceleration_gain * leader_acceleration;
  }
  if (terms.braking_anticipation && valueOf(leader_acceleration) < 0.0)
  {
    command += m.leader_braking_gain * leader_acceleration;
  }
  if (terms.kinematic_braking)
  {
    const Scalar relative_speed = leader_speed - speed;
    if (valueOf(relative_speed) < 0.0)
    {
      const Scalar kinematic_deceleration =
          relative_speed * relative_speed / (2.0 * largerOf(Scalar(kKinematicBrakingMinGapM), gap));
      command = command - m.kinematic_braking_ratio * kinematic_deceleration;
    }
  }
  if (!terms.shaped && terms.gap_slope)
  {
    command = command - m.k1 * m.time_gap_speed_slope_s2_per_m * speed * speed;
  }
  if (terms.cruise)
  {
    const Scalar cruise = m.cruise_gain_per_s * (m.set_speed_mps - speed);
    command = smallerOf(command, cruise);
  }
  if (terms.acceleration_limit)
  {
    command = smallerOf(m.max_acceleration_mps2, command);
  }
  if (terms.deceleration_limit)
  {
    const Scalar floor = -m.max_deceleration_mps2;
    command = largerOf(floor, command);
  }
  return command;
}

/// The leader's acceleration as the ACC reads it at sample k: its speed's change over the last
/// kLeaderAccelerationWindowS (over what there is of it near the start; 0 at k = 0). `from` is a
/// cursor that only moves forward, keeping a pass O(n); the tolerance keeps a 10 Hz clock's
/// rounding from dropping a sample of the window.
template <typename Leader>
Leader leaderAccelerationAt(const CarFollowingRun& run, const std::vector<Leader>& leader, std::size_t k,
                            std::size_t* from)
{
  if (k == 0)
    return Leader(0.0);
  while (*from + 1 < k && run.time_s[k] - run.time_s[*from + 1] >= kLeaderAccelerationWindowS - 1e-9)
    ++*from;
  return Leader((leader[k] - leader[*from]) / (run.time_s[k] - run.time_s[*from]));
}

/// The recursion of simulateFollower() for any scalar type, `leader` the speeds the ACC saw.
/// visit(k, speed, true_gap) sees every sample from 0 on; returns the index of the first runaway
/// sample (never visited), or the run's size.
template <typename Scalar, typename Leader, typename Visitor>
std::size_t runRecursion(const ModelScalars<Scalar>& m, const CarFollowingRun& run, const std::vector<Leader>& leader,
                         Visitor&& visit)
{
  using std::exp;
  const std::size_t n = run.size();
  // The commands so far, kept only when a reaction delay reads them back.
  const bool delayed = valueOf(m.reaction_delay_s) > 0.0;
  const LawTerms terms = lawTermsOf(m);
  std::vector<Scalar> commands(delayed ? n : 0, Scalar(0.0));
  std::size_t delay_cursor = 0;
  std::size_t acceleration_cursor = 0;
  Scalar speed = run.follower_speed_mps[0];
  Scalar gap = run.space_gap_m[0] + m.sensor_time_offset_s * leader[0];
  Scalar realised = 0.0;
  visit(0, speed, gap);
  for (std::size_t k = 0; k + 1 < n; ++k)
  {
    const double step_s = run.time_s[k + 1] - run.time_s[k];
    const Scalar relative_speed = leader[k] - speed;
    const Leader leader_acceleration = terms.feedforward || terms.braking_anticipation
                                           ? leaderAccelerationAt(run, leader, k, &acceleration_cursor)
                                           : Leader(0.0);
    const Scalar command = commandedAcceleration<Scalar>(m, terms, gap, speed, leader[k], leader_acceleration);
    Scalar applied = command;
    if (delayed)
    {
      commands[k] = command;
      applied = interpolateForward<Scalar>(run.time_s, commands, k + 1, run.time_s[k] - m.reaction_delay_s,
                                           &delay_cursor);
    }
    if (valueOf(m.actuation_lag_s) > 0.0 && k > 0)
    {
      realised += (1.0 - exp(-step_s / m.actuation_lag_s)) * (applied - realised);
    }
    else
    {
      realised = applied;  // no lag, or the first step: realised equals commanded at the start
    }
    const Scalar next_speed = speed + step_s * realised;
    const Scalar next_gap = gap + step_s * relative_speed;
    if (isRunaway(valueOf(next_speed), valueOf(next_gap)))
    {
      return k + 1;
    }
    speed = next_speed;
    gap = next_gap;
    visit(k + 1, speed, gap);
  }
  return n;
}

/// runRecursion with the leader the ACC saw: the recorded speeds in place when no clock offset
/// enters the model, the shifted ones otherwise.
template <typename Scalar, typename Visitor>
std::size_t runWithLeader(const ModelScalars<Scalar>& m, const CarFollowingRun& run, Visitor&& visit)
{
  if (entersModel(m.sensor_time_offset_s))
  {
    return runRecursion(m, run, shiftedLeaderSpeed(run, m.sensor_time_offset_s), visit);
  }
  return runRecursion(m, run, run.leader_speed_mps, visit);
}

/// ModelScalars whose entries are the parameters x (base, then the effects' values): each entry
/// seeded as parameter number i of the dual numbers.
template <std::size_t N>
ModelScalars<ForwardDual<N>> seededScalars(const std::vector<EffectKind>& kinds, const std::vector<double>& x)
{
  using Dual = ForwardDual<N>;
  const EffectSettings values = makeCombinedEffectSettings(kinds, std::vector<double>(x.begin() + 4, x.end()));
  // Which entry of x sets each field: the catalogue's own mapping applied to the entries' indices
  // (4, 5, ...), so that it is not written a second time. A field no effect sets keeps its
  // default (0 or infinity), never an index >= 4.
  std::vector<double> indices;
  for (std::size_t i = 4; i < x.size(); ++i)
  {
    indices.push_back(static_cast<double>(i));
  }
  const EffectSettings index_of = makeCombinedEffectSettings(kinds, indices);
  const ModelScalars<double> plain = plainScalars(AccParameters{x[0], x[1], x[2], x[3]}, values);
  const ModelScalars<double> where = plainScalars(AccParameters{}, index_of);
  // The base entries are parameters 0..3; an effect field is one when its index is >= 4.
  auto seed = [](double value, double index) {
    return std::isfinite(index) && index >= 4.0 ? Dual::parameter(value, static_cast<std::size_t>(index)) : Dual(value);
  };
  return {Dual::parameter(plain.k1, 0),
          Dual::parameter(plain.k2, 1),
          Dual::parameter(plain.tau_e, 2),
          Dual::parameter(plain.eta, 3),
          seed(plain.actuation_lag_s, where.actuation_lag_s),
          seed(plain.reaction_delay_s, where.reaction_delay_s),
          seed(plain.max_acceleration_mps2, where.max_acceleration_mps2),
          seed(plain.max_deceleration_mps2, where.max_deceleration_mps2),
          seed(plain.sensor_time_offset_s, where.sensor_time_offset_s),
          seed(plain.time_gap_speed_slope_s2_per_m, where.time_gap_speed_slope_s2_per_m),
          seed(plain.set_speed_mps, where.set_speed_mps),
          seed(plain.cruise_gain_per_s, where.cruise_gain_per_s),
          seed(plain.leader_acceleration_gain, where.leader_acceleration_gain),
          seed(plain.short_gap_gain_ratio, where.short_gap_gain_ratio),
          seed(plain.closing_gain_ratio, where.closing_gain_ratio),
          seed(plain.gain_speed_slope_s_per_m, where.gain_speed_slope_s_per_m),
          seed(plain.kinematic_braking_ratio, where.kinematic_braking_ratio),
          seed(plain.leader_braking_gain, where.leader_braking_gain)};
}

template <std::size_t N>
FollowerSpeedSensitivities sensitivitiesWithCapacity(const std::vector<EffectKind>& kinds,
                                                     const std::vector<double>& x, const CarFollowingRun& run)
{
  FollowerSpeedSensitivities out;
  out.dimension = x.size();
  const std::size_t n = run.size();
  out.speed_mps.assign(n, 0.0);
  out.speed_derivatives.assign(n * x.size(), 0.0);
  if (n == 0)
  {
    return out;
  }
  const ModelScalars<ForwardDual<N>> m = seededScalars<N>(kinds, x);
  const std::size_t reached = runWithLeader(m, run, [&](std::size_t k, const ForwardDual<N>& speed, const auto&) {
    out.speed_mps[k] = speed.value;
    std::copy(speed.derivative.begin(), speed.derivative.begin() + static_cast<long>(x.size()),
              out.speed_derivatives.begin() + static_cast<long>(k * x.size()));
  });
  out.diverged = reached < n;
  out.diverged_at_index = reached;
  return out;
}
}  // namespace

SimulatedFollower scorable(SimulatedFollower simulated)
{
  if (simulated.diverged)
  {
    constexpr double kNotSimulated = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = simulated.diverged_at_index; k < simulated.speed_mps.size(); ++k)
      simulated.speed_mps[k] = simulated.space_gap_m[k] = kNotSimulated;
  }
  return simulated;
}

SimulatedFollower simulateFollower(const AccParameters& p, const EffectSettings& e, const CarFollowingRun& run)
{
  const std::size_t n = run.size();
  SimulatedFollower sim;
  sim.speed_mps.resize(n);
  sim.space_gap_m.resize(n);
  if (n == 0)
  {
    return sim;
  }
  const ModelScalars<double> m = plainScalars(p, e);
  const double offset = e.sensor_time_offset_s;
  // The gap is what the recorder would show: the true gap minus delta u (recorded leader at t_k + delta).
  const std::vector<double> shifted = offset != 0.0 ? shiftedLeaderSpeed(run, offset) : std::vector<double>{};
  const std::vector<double>& leader = offset != 0.0 ? shifted : run.leader_speed_mps;
  double last_speed = 0.0;
  double last_gap = 0.0;
  const std::size_t reached = runRecursion(m, run, leader, [&](std::size_t k, double speed, double gap) {
    sim.speed_mps[k] = speed;
    sim.space_gap_m[k] = k == 0 ? run.space_gap_m[0] : gap - offset * leader[k];
    last_speed = speed;
    last_gap = gap;
  });
  if (reached < n)
  {
    sim.diverged = true;
    sim.diverged_at_index = reached;
    for (std::size_t rest = reached; rest < n; ++rest)
    {
      sim.speed_mps[rest] = last_speed;
      sim.space_gap_m[rest] = last_gap - offset * leader[rest];
    }
  }
  return sim;
}

FollowerSpeedSensitivities simulateFollowerSensitivities(const std::vector<EffectKind>& effects,
                                                         const std::vector<double>& x, const CarFollowingRun& run)
{
  if (x.size() < 4)
  {
    throw std::invalid_argument("simulateFollowerSensitivities: x needs k1, k2, tau_e and eta");
  }
  // The smallest capacity that holds x: every dual operation costs its capacity.
  if (x.size() <= 4)
  {
    return sensitivitiesWithCapacity<4>(effects, x, run);
  }
  if (x.size() <= 6)
  {
    return sensitivitiesWithCapacity<6>(effects, x, run);
  }
  if (x.size() <= 8)
  {
    return sensitivitiesWithCapacity<8>(effects, x, run);
  }
  if (x.size() <= 16)
  {
    return sensitivitiesWithCapacity<16>(effects, x, run);
  }
  throw std::invalid_argument("simulateFollowerSensitivities: more than 16 parameters");
}

std::string describeBreakdown(const SimulatedFollower& simulated, const std::vector<double>& time_s, bool* collision)
{
  bool collided = false;
  std::string breakdown;
  const std::size_t end = simulated.diverged ? simulated.diverged_at_index : simulated.speed_mps.size();
  for (std::size_t i = 0; i < end && i < time_s.size() && breakdown.empty(); ++i)
  {
    collided = simulated.space_gap_m[i] <= 0.0;
    if (collided)
      breakdown = printfText("its gap reaches %.1f m (a collision) at t = %.1f s", simulated.space_gap_m[i], time_s[i]);
    else if (simulated.speed_mps[i] < 0.0)
      breakdown = printfText("its speed reaches %.2f m/s (driving backwards) at t = %.1f s", simulated.speed_mps[i],
                             time_s[i]);
  }
  if (collision != nullptr)
    *collision = collided;
  return breakdown;
}

}  // namespace acc
