#include "acc_identification/diagnosis/augmented_stability.h"

#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>
#include <vector>

#include "acc_identification/model/angles.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
namespace
{
double linearisedTimeGap(const AccParameters& p, const EffectSettings& e, double operating_speed_mps)
{
  return p.tau_e_s + 2.0 * e.time_gap_speed_slope_s2_per_m * operating_speed_mps;
}

/// The gains of one branch's small-signal law (the branch's own r_s and r_c: branchesOf), scheduled
/// at the operating speed (the schedule's own derivative multiplies a spacing error and relative
/// speed that are 0 at equilibrium).
AccParameters linearisedGains(const AccParameters& p, const EffectSettings& e, double operating_speed_mps)
{
  AccParameters out = p;
  const double schedule = e.gain_speed_slope_s_per_m != 0.0
                              ? std::exp(e.gain_speed_slope_s_per_m * (operating_speed_mps - kGainReferenceSpeedMps))
                              : 1.0;
  out.k1_per_s2 = p.k1_per_s2 * schedule * e.short_gap_gain_ratio;
  out.k2_per_s = p.k2_per_s * schedule * e.closing_gain_ratio;
  out.tau_e_s = linearisedTimeGap(p, e, operating_speed_mps);
  return out;
}

/// The linear laws a law with branches switches between at equilibrium, where its gap error and
/// relative speed change sign: an asymmetric law's four, (k1 or k1 r_s) x (k2 or k2 r_c), and the
/// anticipation of the leader's braking with and without its k_b. A small disturbance meets every
/// one of them (a braking leader the short-gap and closing branch first, then the others on the
/// way back), so the law is held to all of them: string stable only where every branch is. A law
/// without branches has one, itself. At most eight, in a fixed array: the side search evaluates
/// this thousands of times per fit.
struct Branches
{
  std::array<EffectSettings, 8> laws;
  std::size_t count = 0;
};

/// Whether the law switches gains at equilibrium (branchesOf gives more than the law itself).
bool hasBranches(const EffectSettings& e)
{
  return e.short_gap_gain_ratio != 1.0 || e.closing_gain_ratio != 1.0 || e.leader_braking_gain != 0.0;
}

Branches branchesOf(const EffectSettings& e)
{
  Branches out;
  out.laws[out.count++] = e;
  const auto split = [&out](auto to_other_branch) {
    const std::size_t n = out.count;
    for (std::size_t i = 0; i < n; ++i)
    {
      out.laws[out.count] = out.laws[i];
      to_other_branch(out.laws[out.count++]);
    }
  };
  if (e.short_gap_gain_ratio != 1.0)
    split([](EffectSettings& b) { b.short_gap_gain_ratio = 1.0; });
  if (e.closing_gain_ratio != 1.0)
    split([](EffectSettings& b) { b.closing_gain_ratio = 1.0; });
  if (e.leader_braking_gain != 0.0)
    split([](EffectSettings& b) { b.leader_braking_gain = 0.0; });
  return out;
}

std::string localInstabilityNote(const AugmentedStability& s)
{
  if (!std::isfinite(s.phase_margin_deg))
    return "NOT LOCALLY STABLE: no feedback from the gap or the leader's speed";
  return printfText("NOT LOCALLY STABLE: the car's own loop has phase margin %.1f deg at %.3f rad/s, so one car "
                    "oscillates with growing amplitude behind a steady leader and |Gamma| does not describe it",
                    s.phase_margin_deg, s.crossover_rad_s);
}

std::string smallSignalNote(EffectKind effect)
{
  switch (effect)
  {
    case EffectKind::none: return "base model, paper eq. 9";
    case EffectKind::actuation_lag: return "lag adds (T s + 1) to the s^2 term of the denominator";
    case EffectKind::reaction_delay: return "dead time multiplies the feedback by exp(-s d)";
    case EffectKind::acceleration_limits:
      return "limits do not act on small disturbances: small-signal Gamma equals the base one";
    case EffectKind::sensor_time_offset:
      return "a clock offset changes the record, not the vehicle: Gamma equals the base one";
    case EffectKind::speed_dependent_time_gap: return "time gap linearised at the operating speed: tau_e + 2 c v0";
    case EffectKind::leader_acceleration_feedforward: return "feedforward adds k_a s (1 - exp(-s W)) / W to the numerator (W its window)";
    case EffectKind::asymmetric_response:
      return "no single transfer function: held to each of its four branches ((k1 or k1 r_s) x (k2 or k2 r_c)), "
             "the largest |Gamma| at each frequency";
    case EffectKind::speed_dependent_gains:
      return printfText("gains scheduled at the operating speed: k exp(g (v0 - %g m/s))", kGainReferenceSpeedMps);
    case EffectKind::quadratic_closing_response:
      return "a quadratic term has no slope at equilibrium: small-signal Gamma equals the base one";
    case EffectKind::leader_braking_anticipation:
      return "no single transfer function: held to both branches, the leader braking (the feedforward adds "
             "k_b s (1 - exp(-s W)) / W to the numerator) and not, the larger |Gamma| at each frequency";
    case EffectKind::set_speed_cruise:
      return "cruise mode is inactive while following below the set speed: small-signal Gamma equals the base one";
  }
  return "";
}
/// The frequency where |L(j w)| = 1 (L as in localLoopStability), by bisection on log w: the
/// log-log slope of |L| is below -1 everywhere, so there is exactly one.
double loopCrossoverRadS(double k1, double b, double lag_s)
{
  auto excess = [&](double w) {  // ln |L(j w)|^2
    return std::log(k1 * k1 + b * b * w * w) - 4.0 * std::log(w) - std::log1p(lag_s * lag_s * w * w);
  };
  double lo = std::log(1e-9), hi = std::log(1e6);
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (excess(std::exp(mid)) > 0.0 ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}
}  // namespace

void localLoopStability(const AccParameters& g, double actuation_lag_s, double reaction_delay_s,
                        AugmentedStability* out)
{
  const double k1 = g.k1_per_s2;
  const double b = g.k2_per_s + g.k1_per_s2 * g.tau_e_s;
  if (!(k1 > 0.0 || b != 0.0))
  {
    out->locally_stable = false;  // no feedback from the gap or the leader's speed: nothing to follow with
    out->phase_margin_deg = out->crossover_rad_s = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const double w = loopCrossoverRadS(k1, b, actuation_lag_s);
  const double margin_rad = std::atan2(b * w, k1) - std::atan(actuation_lag_s * w) - w * reaction_delay_s;
  out->crossover_rad_s = w;
  out->phase_margin_deg = margin_rad * kRadToDeg;
  out->locally_stable = margin_rad > 0.0;
}

bool locallyStableAt(const AccParameters& p, const EffectSettings& e, const std::vector<double>& operating_speeds_mps)
{
  // Called at every point a fit evaluates, so the two shortcuts: the linearised law is the same at
  // every speed unless an effect schedules it on speed, and without delay or lag the phase margin
  // atan2(b w_c, k1) has the sign of atan2(b, k1), with no crossover to search.
  const bool depends_on_speed = e.gain_speed_slope_s_per_m != 0.0 || e.time_gap_speed_slope_s2_per_m != 0.0;
  const bool timed = e.actuation_lag_s != 0.0 || e.reaction_delay_s != 0.0;
  const Branches branches = branchesOf(e);
  for (const double speed : operating_speeds_mps)
  {
    for (std::size_t b = 0; b < branches.count; ++b)
    {
      const AccParameters g = linearisedGains(p, branches.laws[b], speed);
      AugmentedStability loop;
      if (timed)
        localLoopStability(g, e.actuation_lag_s, e.reaction_delay_s, &loop);
      else
        loop.locally_stable = std::atan2(g.k2_per_s + g.k1_per_s2 * g.tau_e_s, g.k1_per_s2) > 0.0;
      if (!loop.locally_stable)
        return false;
    }
    if (!depends_on_speed)
      break;
  }
  return true;
}

namespace
{
/// |Gamma(j w)|^2 of one branch's linear law.
double branchGainSquared(const AccParameters& p, const EffectSettings& e, double operating_speed_mps,
                         double frequency_rad_s)
{
  const std::complex<double> s(0.0, frequency_rad_s);
  const AccParameters g = linearisedGains(p, e, operating_speed_mps);
  const double tau = g.tau_e_s;
  // exp(0) is 1 exactly: skip the complex exponential when there is no delay (most models).
  const std::complex<double> delay =
      e.reaction_delay_s != 0.0 ? std::exp(-s * e.reaction_delay_s) : std::complex<double>(1.0, 0.0);
  // The anticipation reads the leader's acceleration over a window W: s (1 - e^{-s W}) / W.
  const double anticipation_gain = e.leader_acceleration_gain + e.leader_braking_gain;
  const std::complex<double> anticipated =
      anticipation_gain != 0.0
          ? anticipation_gain * s * (1.0 - std::exp(-s * kLeaderAccelerationWindowS)) / kLeaderAccelerationWindowS
          : std::complex<double>(0.0, 0.0);
  const std::complex<double> numerator = delay * (anticipated + g.k2_per_s * s + g.k1_per_s2);
  const std::complex<double> denominator =
      (e.actuation_lag_s * s + 1.0) * s * s + delay * ((g.k2_per_s + g.k1_per_s2 * tau) * s + g.k1_per_s2);
  // |N|^2 / |D|^2: no complex division and no hypot, which the side search's index (thousands of
  // evaluations of 2,001 frequencies) would otherwise spend most of its time in.
  const double denominator_squared = std::norm(denominator);
  if (denominator_squared == 0.0)
  {
    return std::norm(numerator) == 0.0 ? 1.0 : INFINITY;
  }
  return std::norm(numerator) / denominator_squared;
}
}  // namespace

double augmentedTransferGainSquared(const AccParameters& p, const EffectSettings& e, double operating_speed_mps,
                                    double frequency_rad_s)
{
  // The side search's index calls this for 2,001 frequencies at every point it tries: a law
  // without branches skips building them.
  if (!hasBranches(e))
    return branchGainSquared(p, e, operating_speed_mps, frequency_rad_s);
  const Branches branches = branchesOf(e);
  double largest = 0.0;
  for (std::size_t b = 0; b < branches.count; ++b)
    largest = std::max(largest, branchGainSquared(p, branches.laws[b], operating_speed_mps, frequency_rad_s));
  return largest;
}

double augmentedTransferGain(const AccParameters& p, const EffectSettings& e, double operating_speed_mps,
                             double frequency_rad_s)
{
  return std::sqrt(augmentedTransferGainSquared(p, e, operating_speed_mps, frequency_rad_s));
}

namespace
{
/// The grid's peak of |Gamma|, the car's own loop, and `note` (how the effects enter), with why
/// the model is not string stable when its loop is not.
AugmentedStability analyzeSmallSignal(const AccParameters& p, std::string note, const EffectSettings& e,
                                      double operating_speed_mps)
{
  AugmentedStability out;
  out.note = std::move(note);
  // The grid, plus the closed-form peak of each branch's delay- and lag-free law.
  const Branches branches = branchesOf(e);
  std::vector<double> frequencies_rad_s;
  const int points = 4000;
  const double w_lo = 1e-4;
  const double w_hi = 20.0;
  for (int i = 0; i <= points; ++i)
    frequencies_rad_s.push_back(w_lo * std::pow(w_hi / w_lo, static_cast<double>(i) / points));
  out.lambda2 = -std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < branches.count; ++b)
  {
    const AccParameters linear = linearisedGains(p, branches.laws[b], operating_speed_mps);
    frequencies_rad_s.push_back(peakFrequencyRadS(linear));
    out.lambda2 = std::max(out.lambda2, lambda2(linear));  // the least stable branch's
    AugmentedStability loop;
    localLoopStability(linear, e.actuation_lag_s, e.reaction_delay_s, &loop);
    // The least stable branch's loop: the first unstable one, else the least margin.
    const bool less_stable =
        b == 0 || (out.locally_stable && (!loop.locally_stable || loop.phase_margin_deg < out.phase_margin_deg));
    if (less_stable)
    {
      out.locally_stable = loop.locally_stable;
      out.phase_margin_deg = loop.phase_margin_deg;
      out.crossover_rad_s = loop.crossover_rad_s;
    }
  }
  double best_gain = augmentedTransferGain(p, e, operating_speed_mps, 0.0);
  double best_w = 0.0;
  for (const double w : frequencies_rad_s)
  {
    const double gain = augmentedTransferGain(p, e, operating_speed_mps, w);
    if (gain > best_gain)
    {
      best_gain = gain;
      best_w = w;
    }
  }
  out.peak_gain_db = 20.0 * std::log10(best_gain);
  out.peak_frequency_rad_s = best_w;
  out.string_stable = out.locally_stable && best_gain <= 1.0 + 1e-12;
  if (!out.locally_stable)
    out.note += "; " + localInstabilityNote(out);
  const double time_gap_s = linearisedTimeGap(p, e, operating_speed_mps);
  if (time_gap_s < 0.0)
    out.note += printfText("; the linearised time gap tau_e + 2 c v0 is %.2f s at %.1f m/s, below 0: a spacing "
                           "policy that wants a shorter gap the faster it goes, outside the paper's conditions on "
                           "the law's derivatives, so read its |Gamma| with that",
                           time_gap_s, operating_speed_mps);
  return out;
}
}  // namespace

AugmentedStability analyzeAugmentedStability(const AccParameters& p, EffectKind effect, const EffectSettings& e,
                                             double operating_speed_mps)
{
  return analyzeSmallSignal(p, smallSignalNote(effect), e, operating_speed_mps);
}

AugmentedStability analyzeAugmentedStability(const AccParameters& p, const std::vector<EffectKind>& kinds,
                                             const EffectSettings& e, double operating_speed_mps)
{
  std::string note = smallSignalNote(kinds.empty() ? EffectKind::none : kinds.front());
  for (std::size_t i = 1; i < kinds.size(); ++i)
    note += "; " + smallSignalNote(kinds[i]);
  return analyzeSmallSignal(p, note, e, operating_speed_mps);
}

}  // namespace acc
