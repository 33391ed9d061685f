#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "acc_identification/model/halton_sequence.h"
#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"

namespace acc
{
/// What a fit minimises over the segments' samples.
enum class FitObjective
{
  speed,          ///< mean squared speed error: the paper's objective
  gap,            ///< mean squared space-gap error: weighs slow, large deviations (a gap integrates speed)
  speed_and_gap,  ///< the two, each divided by the variance of its measured series (Punzo et al.'s
                  ///< normalised mix, as El-Baklish et al. use it)
  /// The speed MSE over every sample plus the speed MSE over the samples inside the leader's
  /// perturbation windows (insidePerturbationWindows): where a whole-run MSE barely sees a
  /// 3-second braking, half the weight goes to the brakings. The speed objective on runs
  /// without a perturbation.
  speed_and_windows,
};

/// "speed", "gap", "speed_and_gap", "speed_and_windows".
std::string objectiveName(FitObjective objective);

/// Search box of the base parameters and how hard the local solver works. The same for the base
/// fit and every augmented fit, so that they differ only by the effect.
struct AugmentedCalibrationOptions
{
  /// The gap objectives (gap, speed_and_gap) need the simulated gap's sensitivities, which a clock offset
  /// (sensor_time_offset) would make depend on the shifted leader: a fit of that effect must use
  /// the speed objective (calibrateAugmentedSet throws otherwise).
  FitObjective objective = FitObjective::speed;
  AccParameters lower{0.0, 0.0, 0.0, 0.0};
  AccParameters upper{1.0, 2.0, 4.0, 40.0};
  /// Base fit: Halton starts for (k1, k2, tau_e) in this box; eta starts at its equilibrium
  /// estimate mean(s - tau_e v) for each.
  AccParameters start_lower{0.01, 0.05, 0.3, 0.0};
  AccParameters start_upper{0.30, 1.00, 2.5, 0.0};
  std::size_t base_starts = 12;
  /// Augmented fit: warm start from the base fit, with the effect's parameters at this many
  /// low-discrepancy points of the catalogue's start range (plus the "almost off" point).
  std::size_t effect_starts = 6;
  /// The local solver (Levenberg-Marquardt with the simulator's exact Jacobian): passes per start,
  /// and it stops when a step moves no unit coordinate by more than relative_x_tolerance or an
  /// accepted step lowers the MSE by less than relative_mse_tolerance of it.
  int max_evaluations_per_start = 600;
  double relative_x_tolerance = 1e-6;
  double relative_mse_tolerance = 1e-10;
  double initial_damping = 1e-3;
};

/// The parameters of an augmented model as one vector x = (k1, k2, tau_e, eta, effect values in
/// the catalogue's order, effect after effect in the order of `effects`), and the unit box every
/// local solver of the diagnosis works in, so that one trust-region radius suits gains of 0.05 and
/// jam distances of 5 m alike.
struct AugmentedParameterBox
{
  static constexpr std::size_t kBaseDimension = 4;
  EffectKind effect;                 ///< the last of effects (none for the base model)
  std::vector<EffectKind> effects;   ///< every effect of the model, in x's order (empty: base model)
  std::vector<double> lower;  ///< the options' base bounds, then the catalogue's effect bounds
  std::vector<double> upper;

  AugmentedParameterBox(EffectKind kind, const AugmentedCalibrationOptions& options);
  /// A model with several effects at once.
  AugmentedParameterBox(const std::vector<EffectKind>& kinds, const AugmentedCalibrationOptions& options);
  std::size_t dimension() const { return lower.size(); }
  /// Unit coordinates (clamped into [0, 1]) to physical values.
  std::vector<double> physical(const std::vector<double>& unit) const;
  /// Physical values to unit coordinates, clamped into the box.
  std::vector<double> unit(const std::vector<double>& x) const;
  static AccParameters baseOf(const std::vector<double>& x) { return AccParameters{x[0], x[1], x[2], x[3]}; }
  static std::vector<double> effectPart(const std::vector<double>& x)
  {
    return std::vector<double>(x.begin() + kBaseDimension, x.end());
  }
  /// The effect settings of a physical x (every effect of the box switched on).
  EffectSettings settingsOf(const std::vector<double>& x) const
  {
    return makeCombinedEffectSettings(effects, effectPart(x));
  }
};

/// A calibrated model: base parameters, the effect(s) and their parameters.
struct AugmentedFit
{
  EffectKind effect = EffectKind::none;  ///< the single effect, or the last one added to a combination
  /// Every effect of the model in the order of effect_values; {effect} for a single-effect fit
  /// made by calibrateAugmented, empty for the base model.
  std::vector<EffectKind> effects;
  AccParameters base;
  std::vector<double> effect_values;  ///< in the catalogue's order, effect after effect
  EffectSettings settings;            ///< base settings with effect_values applied
  double train_mse_speed = std::numeric_limits<double>::infinity();  ///< mean squared speed error [m^2/s^2]
  FitObjective objective = FitObjective::speed;       ///< what the fit minimised
  double train_objective = std::numeric_limits<double>::infinity();  ///< its value (= train_mse_speed for speed)
  bool diverged = false;              ///< no start found a simulation that does not blow up
  /// The fit is held to models whose own loop is stable (locallyStableAt the training data's
  /// loopCheckSpeedsMps), as a production ACC's is: false only when no
  /// start reached one, and the fit is then the best of the unstable models it saw.
  bool locally_stable = true;
  /// A fit the platoon and the link evidence may use: it neither diverged nor left the stable set.
  bool usable() const { return !diverged && locally_stable; }
  std::size_t evaluations = 0;
  /// Standard errors of (k1, k2, tau_e, eta, effect values...): the speed fit's sandwich, start
  /// gaps included (augmentedStandardErrors, augmented_standard_errors.h); NaN where the data do
  /// not constrain a parameter. For a gap objective they are the speed objective's sandwich at the
  /// fitted point: a measure of what the speeds determine there, not of the fit's own spread.
  std::vector<double> standard_errors;
};

/// Mean squared speed error of a model over segments, each simulated from its own start; the
/// value is kDivergedObjective when a simulation diverges. Segments must be valid runs.
double augmentedSpeedMse(const AccParameters& p, const EffectSettings& effects,
                         const std::vector<CarFollowingRun>& segments);

constexpr double kDivergedObjective = 1.0e6;

/// The speeds at which a fitted model's own loop must be stable (locallyStableAt): the lowest,
/// median and highest follower speed of the segments, since the gains and the time gap of the
/// speed-dependent effects change with speed. Empty without samples.
std::vector<double> loopCheckSpeedsMps(const std::vector<CarFollowingRun>& segments);

/// augmentedSpeedMse at the physical point x of the box and its exact gradient with respect to
/// x's unit coordinates in the box (from the simulator's sensitivities), for gradient-based
/// searches; the gradient is empty when a simulation diverges (mse is then kDivergedObjective).
struct MseWithGradient
{
  double mse = kDivergedObjective;
  std::vector<double> unit_gradient;
};
MseWithGradient augmentedSpeedMseWithGradient(const AugmentedParameterBox& box, const std::vector<double>& x,
                                              const std::vector<CarFollowingRun>& segments);

/// Least-squares fit of the speed (the paper's objective) of the base model plus `effect` over
/// the segments: Levenberg-Marquardt with the simulator's exact Jacobian (simulateFollowerSensitivities)
/// on the unit-scaled box from several starts. For effect none the
/// starts are Halton points; otherwise `warm_start` (the base fit) with the effect parameters at
/// low-discrepancy starting values. Throws std::invalid_argument for invalid segments.
AugmentedFit calibrateAugmented(EffectKind effect, const std::vector<CarFollowingRun>& segments,
                                const AugmentedCalibrationOptions& options, const AugmentedFit* warm_start = nullptr);

/// The same fit for a model with several effects at once, x = (k1, k2, tau_e, eta, values of
/// effects[0], values of effects[1], ...). With a warm start (typically the fit of the previous
/// forward-selection step): the warm fit's base parameters and the values of every effect it
/// already has, and the effects it lacks at the catalogue's low-discrepancy starts plus their
/// "almost off" point, so the result is never worse on the training data than the warm fit.
/// calibrateAugmented(kind, ...) is this with {kind} ({} for none), number for number.
AugmentedFit calibrateAugmentedSet(const std::vector<EffectKind>& effects, const std::vector<CarFollowingRun>& segments,
                                   const AugmentedCalibrationOptions& options,
                                   const AugmentedFit* warm_start = nullptr);

/// The base parameters refitted with one effect held at held_values (its catalogue values, clamped
/// into its range): the starts are calibrateAugmented's cold ones (warm_start's base first). Its
/// standard errors are those of the full model at that point, the effect's included: how
/// precisely these data would measure the effect were it that large. Where the effect's own fit
/// sits at a none value that carries no information (a lag of 0: exp(-dt / T) is flat there),
/// this is the only standard error there is. Throws std::invalid_argument for invalid segments or
/// a wrong number of values.
AugmentedFit calibrateWithEffectHeld(EffectKind effect, const std::vector<double>& held_values,
                                     const std::vector<CarFollowingRun>& segments,
                                     const AugmentedCalibrationOptions& options,
                                     const AugmentedFit* warm_start = nullptr);

/// Whether a is the better of two fits of the same data: a usable one first, then the lower
/// training objective.
bool betterFit(const AugmentedFit& a, const AugmentedFit& b);

/// The effects of a fit: fit.effects, or {fit.effect} for a fit made before combinations existed.
std::vector<EffectKind> effectsOf(const AugmentedFit& fit);

/// The point x = (k1, k2, tau_e, eta, effect values) of a model with `effects` that is the nested
/// fit: its base and the values of the effects it has, every other effect at its "almost off"
/// values (the edge of its start range nearest the base model, or its neutral value: a gain ratio
/// of 1), so that a search over the larger model can start where the smaller one ended.
std::vector<double> nestedStart(const std::vector<EffectKind>& effects, const AugmentedFit& nested);

/// "none", an effect's name, or the names joined by " + " (for reports).
std::string combinedEffectName(const std::vector<EffectKind>& effects);

/// Parameter names of the effects in effect_values' order (catalogue names, effect after effect).
std::vector<std::string> effectParameterNames(const std::vector<EffectKind>& effects);

}  // namespace acc
