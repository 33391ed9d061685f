#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "acc_identification/calibration/refit_bootstrap.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// An effect whose size the training data pin away from "no effect", whether or not it predicts
/// the held-out parts better. Why both: on real runs a clock offset or a delay is often absorbed
/// by the base model's time gap (tau_e moves by about the offset, k1 and k2 follow), so the two
/// models predict the held-out parts alike, while the effect's own fit recovers its size to a
/// tenth of a second and leaves the base parameters where the untouched data had them. The
/// held-out rule (effect_selection.h) then names nothing; this says what the data do determine.
struct DeterminedEffect
{
  EffectKind effect = EffectKind::none;
  double value = 0.0;           ///< the effect's first parameter in its single-effect fit
  double standard_error = 0.0;  ///< its sandwich standard error (AugmentedFit::standard_errors)
  double z = 0.0;               ///< |value - neutral| / standard_error
  AccParameters base_without;   ///< the base model's parameters without the effect
  AccParameters base_with;      ///< and with it: what the effect moves
};

/// The value at which an effect vanishes (lag, delay, clock offset: 0 s; gap slope: 0), or NaN
/// for effects without one inside their range (acceleration limits and a set speed vanish only at
/// infinity: the held-out rule decides them).
double neutralValue(EffectKind kind);

/// The two-sided normal quantile for level alpha over count tests (Bonferroni): the z an effect's
/// size must exceed to be determined.
double determinedThreshold(double alpha, std::size_t count);

/// determinedThreshold over the candidates that have a neutral value: the z the determined rule
/// asks of each when these effects are tested together.
double determinedThreshold(double alpha, const std::vector<EffectKind>& candidates);

/// How precisely a fit pins one of its effects' size: the effect's first parameter against its
/// "none" value. A step of the forward selection can be named by the held-out rule while the
/// training data leave its size open (on Casale part6 the first step's gain slope is -0.010 +-
/// 0.022): the held-out gain then lies in the model as a whole, not in a measured effect.
struct EffectSize
{
  double value = std::numeric_limits<double>::quiet_NaN();  ///< the effect's first parameter in the fit
  double standard_error = std::numeric_limits<double>::quiet_NaN();
  /// |value - neutral| / standard_error; NaN where the effect has no none value (limits, set
  /// speed) or the fit no finite standard error.
  double z = std::numeric_limits<double>::quiet_NaN();
  bool at_bound = false;    ///< at a bound of its range: the search's limit, not the data's answer
  bool determined = false;  ///< z above the threshold and not at a bound
  /// On short data, where the fit's refitting bootstrap gave the first parameter a 95 % interval:
  /// whether that interval holds the none value (unset without one). "determined" stays the
  /// standard error's decision; where the two disagree (TOYOTA_RAV4 at L: z 2.4, interval [0, 3] s)
  /// the data's own standard error is large against the refits', and the size is not pinned
  /// (docs/PLATOON_DIAGNOSIS.md, "How sure each car's sizes are").
  std::optional<bool> bootstrap_interval_holds_none;
};

/// kind's size in fit (kind among effectsOf(fit); otherwise every field NaN and not determined).
EffectSize effectSizeIn(const AugmentedFit& fit, EffectKind kind, double threshold);

/// Sets size->bootstrap_interval_holds_none from bootstrap, the refitting bootstrap of the fit
/// size was taken from (final_model_bootstrap.h), where it gives kind's first parameter an interval
/// and kind has a none value.
void judgeByBootstrap(EffectKind kind, const RefitBootstrap& bootstrap, EffectSize* size);

/// "; its bootstrap interval holds none" where that is set, else "": printed after a size's verdict.
std::string bootstrapVerdictText(const EffectSize& size);

/// Every single-effect fit whose first parameter is determined: finite standard error, resolvable
/// (timing effects at least sample_period_s), not at a bound of its range (a value at a bound is
/// the search's limit, not the data's answer), and |value - neutral| / standard_error above
/// determinedThreshold(alpha, the fits' effects). Sorted by z, largest first.
std::vector<DeterminedEffect> determinedEffects(const AugmentedFit& base_fit, const std::vector<AugmentedFit>& effect_fits,
                                                double sample_period_s, double alpha);

/// One line per determined effect, for the summary and the report.
std::string describeDeterminedEffect(const DeterminedEffect& effect);

/// An effect whose own fit sits at its none value where the model carries no information about it
/// (a lag of 0: the realised acceleration moves by exp(-dt / T), flat to every order at T = 0), so
/// its fit has no standard error and "not determined" would say nothing about how well these data
/// could measure it. Held at a typical size (the middle of its start range) with the base model
/// refitted around it (calibrateWithEffectHeld): its standard error there, and whether an effect
/// of that size would be determined. Where it would not, these data cannot tell whether the car
/// has it.
struct UnmeasuredEffect
{
  EffectKind effect = EffectKind::none;
  double held_value = 0.0;      ///< the size asked about
  double standard_error = 0.0;  ///< the effect's sandwich standard error at that size
  double z = 0.0;               ///< |held_value - neutral| / standard_error
  bool would_be_determined = false;  ///< z above the determined threshold
};

/// Every one-parameter single-effect fit that sits at its none value with no finite standard
/// error, asked at its typical size on the training data. threshold: determinedThreshold over
/// the candidates.
std::vector<UnmeasuredEffect> unmeasuredEffects(const AugmentedFit& base_fit, const std::vector<AugmentedFit>& effect_fits,
                                                const std::vector<CarFollowingRun>& train,
                                                const AugmentedCalibrationOptions& options, double threshold);

/// "actuation_lag: its fit sits at none, where it carries no information; held at 0.8 these data
/// pin it to +- 1.5 (z 0.5): an effect that size would not be seen".
std::string describeUnmeasuredEffect(const UnmeasuredEffect& effect);

}  // namespace acc
