#include "acc_identification/diagnosis/determined_effects.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/sample_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace acc
{
double neutralValue(EffectKind kind)
{
  switch (kind)
  {
    case EffectKind::actuation_lag:
    case EffectKind::reaction_delay:
    case EffectKind::sensor_time_offset:
    case EffectKind::speed_dependent_time_gap:
    case EffectKind::speed_dependent_gains:
    case EffectKind::leader_acceleration_feedforward:
    case EffectKind::quadratic_closing_response:
    case EffectKind::leader_braking_anticipation: return 0.0;
    case EffectKind::asymmetric_response: return 1.0;
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

double determinedThreshold(double alpha, std::size_t count)
{
  return twoSidedNormalQuantile(alpha / static_cast<double>(std::max<std::size_t>(1, count)));
}

double determinedThreshold(double alpha, const std::vector<EffectKind>& candidates)
{
  const auto tests = std::count_if(candidates.begin(), candidates.end(),
                                   [](EffectKind kind) { return std::isfinite(neutralValue(kind)); });
  return determinedThreshold(alpha, static_cast<std::size_t>(tests));
}

namespace
{
bool atBound(const EffectParameterSpec& spec, double value)
{
  return boundSide(value, spec.lower, spec.upper, ModelAdequacyOptions{}.bound_fraction) != BoundSide::inside;
}
}  // namespace

EffectSize effectSizeIn(const AugmentedFit& fit, EffectKind kind, double threshold)
{
  EffectSize size;
  // The effect's parameters follow the base ones, in the order of the fit's effects.
  std::size_t offset = 0;
  const std::vector<EffectKind> effects = effectsOf(fit);
  const auto own = std::find(effects.begin(), effects.end(), kind);
  if (own == effects.end() || fit.diverged)
  {
    return size;
  }
  for (auto it = effects.begin(); it != own; ++it)
  {
    offset += candidateEffect(*it).parameters.size();
  }
  if (offset >= fit.effect_values.size())
  {
    return size;
  }
  size.value = fit.effect_values[offset];
  const std::size_t se_index = AugmentedParameterBox::kBaseDimension + offset;
  size.standard_error = se_index < fit.standard_errors.size() ? fit.standard_errors[se_index] : size.standard_error;
  size.at_bound = atBound(candidateEffect(kind).parameters.front(), size.value);
  const double neutral = neutralValue(kind);
  if (std::isfinite(neutral) && std::isfinite(size.standard_error) && size.standard_error > 0.0)
  {
    size.z = std::abs(size.value - neutral) / size.standard_error;
    size.determined = size.z > threshold && !size.at_bound;
  }
  return size;
}

void judgeByBootstrap(EffectKind kind, const RefitBootstrap& bootstrap, EffectSize* size)
{
  const double neutral = neutralValue(kind);
  const BootstrapQuantity* q = bootstrap.find(candidateEffect(kind).parameters.front().name);
  if (q == nullptr || !std::isfinite(neutral) || !q->hasInterval())
    return;
  size->bootstrap_interval_holds_none = q->interval_95_low <= neutral && neutral <= q->interval_95_high;
}

std::string bootstrapVerdictText(const EffectSize& size)
{
  return size.bootstrap_interval_holds_none.value_or(false) ? "; its bootstrap interval holds none" : "";
}

std::vector<DeterminedEffect> determinedEffects(const AugmentedFit& base_fit, const std::vector<AugmentedFit>& effect_fits,
                                                double sample_period_s, double alpha)
{
  std::vector<EffectKind> tested;
  for (const AugmentedFit& fit : effect_fits)
  {
    tested.push_back(fit.effect);
  }
  const double threshold = determinedThreshold(alpha, tested);
  std::vector<DeterminedEffect> out;
  for (const AugmentedFit& fit : effect_fits)
  {
    const EffectSize size = effectSizeIn(fit, fit.effect, threshold);
    if (size.determined && isResolvable(fit.effect, fit.effect_values, sample_period_s))
    {
      out.push_back({fit.effect, size.value, size.standard_error, size.z, base_fit.base, fit.base});
    }
  }
  std::sort(out.begin(), out.end(), [](const DeterminedEffect& a, const DeterminedEffect& b) { return a.z > b.z; });
  return out;
}

std::string describeDeterminedEffect(const DeterminedEffect& e)
{
  char text[320];
  std::snprintf(text, sizeof text,
                "%s %.3g +- %.2g (%.1f standard errors from none); with it tau_e %.3g s, k1 %.3g, k2 %.3g "
                "(without: %.3g s, %.3g, %.3g)",
                effectName(e.effect).c_str(), e.value, e.standard_error, e.z, e.base_with.tau_e_s, e.base_with.k1_per_s2,
                e.base_with.k2_per_s, e.base_without.tau_e_s, e.base_without.k1_per_s2, e.base_without.k2_per_s);
  return text;
}

namespace
{
/// A single-effect fit at its none value that gives no standard error there.
bool atNoneWithoutInformation(const AugmentedFit& fit)
{
  if (fit.diverged || fit.effect == EffectKind::none || fit.effect_values.size() != 1)
    return false;
  const EffectParameterSpec& spec = candidateEffect(fit.effect).parameters.front();
  const double neutral = neutralValue(fit.effect);
  return std::isfinite(neutral) && std::abs(fit.effect_values.front() - neutral) <= 1e-3 * (spec.upper - spec.lower) &&
         !std::isfinite(effectSizeIn(fit, fit.effect, 0.0).standard_error);
}
}  // namespace

std::vector<UnmeasuredEffect> unmeasuredEffects(const AugmentedFit& base_fit, const std::vector<AugmentedFit>& effect_fits,
                                                const std::vector<CarFollowingRun>& train,
                                                const AugmentedCalibrationOptions& options, double threshold)
{
  std::vector<UnmeasuredEffect> out;
  for (const AugmentedFit& fit : effect_fits)
  {
    if (!atNoneWithoutInformation(fit))
      continue;
    const EffectParameterSpec& spec = candidateEffect(fit.effect).parameters.front();
    UnmeasuredEffect e;
    e.effect = fit.effect;
    e.held_value = 0.5 * (spec.start_lower + spec.start_upper);
    const EffectSize size =
        effectSizeIn(calibrateWithEffectHeld(fit.effect, {e.held_value}, train, options, &base_fit), fit.effect, threshold);
    e.standard_error = size.standard_error;
    e.z = size.z;
    e.would_be_determined = size.determined;
    out.push_back(e);
  }
  return out;
}

std::string describeUnmeasuredEffect(const UnmeasuredEffect& e)
{
  if (!std::isfinite(e.standard_error))  // a steady drive: the speeds do not move with it at all
    return effectName(e.effect) + ": its fit sits at none, where it carries no information; held at " +
           significant(e.held_value, 3) + " these data carry none either (no standard error): an effect that size "
           "would not be seen";
  char text[320];
  std::snprintf(text, sizeof text,
                "%s: its fit sits at none, where it carries no information; held at %.3g these data pin it to +- "
                "%.2g (%.1f standard errors from none): an effect that size would %s",
                effectName(e.effect).c_str(), e.held_value, e.standard_error, e.z,
                e.would_be_determined ? "be determined" : "not be seen");
  return text;
}

}  // namespace acc
