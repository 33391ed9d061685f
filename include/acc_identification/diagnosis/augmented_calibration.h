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
/// Search box of the base parameters and how hard the local solver works. The same for the base
/// fit and every augmented fit, so that they differ only by the effect.
struct AugmentedCalibrationOptions
{
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
  int max_evaluations_per_start = 600;
  double relative_x_tolerance = 1e-6;
};

/// The parameters of an augmented model as one vector x = (k1, k2, tau_e, eta, effect values in
/// the catalogue's order), and the unit box every local solver of the diagnosis works in, so that
/// one trust-region radius suits gains of 0.05 and jam distances of 5 m alike.
struct AugmentedParameterBox
{
  static constexpr std::size_t kBaseDimension = 4;
  EffectKind effect;
  std::vector<double> lower;  ///< the options' base bounds, then the catalogue's effect bounds
  std::vector<double> upper;

  AugmentedParameterBox(EffectKind kind, const AugmentedCalibrationOptions& options);
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
  /// The effect settings of a physical x.
  EffectSettings settingsOf(const std::vector<double>& x) const { return makeEffectSettings(effect, effectPart(x)); }
};

/// A calibrated model: base parameters, the effect and its parameters.
struct AugmentedFit
{
  EffectKind effect = EffectKind::none;
  AccParameters base;
  std::vector<double> effect_values;  ///< in the catalogue's order
  EffectSettings settings;            ///< base settings with effect_values applied
  double train_mse_speed = std::numeric_limits<double>::infinity();  ///< mean squared speed error [m^2/s^2]
  bool diverged = false;              ///< no start found a simulation that does not blow up
  std::size_t evaluations = 0;
  /// Standard errors of (k1, k2, tau_e, eta, effect values...): the Gauss-Newton sandwich
  /// (J^T J)^-1 M (J^T J)^-1 with a finite-difference Jacobian J of the simulated speeds and M the
  /// batch-means covariance of the scores J_k r_k (blocks of five residual correlation times, at
  /// least 10 s, within segments), as the calibration component's fit statistics. NaN when the
  /// data do not constrain a parameter (e.g. an acceleration limit that the commands never reach)
  /// or there are fewer than four blocks.
  std::vector<double> standard_errors;
};

/// Mean squared speed error of a model over segments, each simulated from its own start; the
/// value is kDivergedObjective when a simulation diverges. Segments must be valid runs.
double augmentedSpeedMse(const AccParameters& p, const EffectSettings& effects,
                         const std::vector<CarFollowingRun>& segments);

constexpr double kDivergedObjective = 1.0e6;

/// Least-squares fit of the speed (the paper's objective) of the base model plus `effect` over
/// the segments: NLopt LN_BOBYQA on the unit-scaled box from several starts. For effect none the
/// starts are Halton points; otherwise `warm_start` (the base fit) with the effect parameters at
/// low-discrepancy starting values. Throws std::invalid_argument for invalid segments.
AugmentedFit calibrateAugmented(EffectKind effect, const std::vector<CarFollowingRun>& segments,
                                const AugmentedCalibrationOptions& options, const AugmentedFit* warm_start = nullptr);


}  // namespace acc
