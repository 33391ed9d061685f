#include "acc_identification/diagnosis/final_model_bootstrap.h"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/diagnosis/augmented_fit_json.h"
#include "acc_identification/diagnosis/augmented_standard_errors.h"

namespace acc
{
namespace
{
/// The parameters of a fit in its box's x order.
std::vector<double> pointOf(const AugmentedFit& fit)
{
  std::vector<double> x{fit.base.k1_per_s2, fit.base.k2_per_s, fit.base.tau_e_s, fit.base.eta_m};
  x.insert(x.end(), fit.effect_values.begin(), fit.effect_values.end());
  return x;
}

/// A fit's quantities as the bootstrap sees them: a parameter within the model adequacy's bound
/// fraction of its box's edge is held there, and its standard error is not used.
BootstrapDraw drawOf(const AugmentedFit& fit, const AugmentedParameterBox& box)
{
  BootstrapDraw draw;
  draw.value = pointOf(fit);
  const std::vector<std::string> names = augmentedParameterNames(box.effects);
  const double fraction = ModelAdequacyOptions{}.bound_fraction;
  for (std::size_t i = 0; i < draw.value.size(); ++i)
  {
    draw.held_by_bound.push_back(atBoundText(names[i], draw.value[i], box.lower[i], box.upper[i], fraction));
    const double se = i < fit.standard_errors.size() ? fit.standard_errors[i] : std::nan("");
    draw.standard_error.push_back(draw.held_by_bound.back().empty() ? se : std::nan(""));
  }
  return draw;
}

/// The diagnosis's chain on a replicate: the base from cold starts, then the effects one at a
/// time, each warm-started from the last.
AugmentedFit chainAsDiagnosed(const std::vector<EffectKind>& effects, const std::vector<CarFollowingRun>& replicate,
                              const AugmentedCalibrationOptions& calibration)
{
  AugmentedFit fit = calibrateAugmentedSet({}, replicate, calibration);
  for (std::size_t k = 1; k <= effects.size() && !fit.diverged; ++k)
  {
    const AugmentedFit warm = fit;
    fit = calibrateAugmentedSet(std::vector<EffectKind>(effects.begin(), effects.begin() + k), replicate, calibration,
                                &warm);
  }
  return fit;
}

/// The fit's speed residuals, run after run.
std::vector<double> speedResiduals(const std::vector<CarFollowingRun>& training,
                                   const std::vector<std::vector<double>>& simulated_speed_mps)
{
  std::vector<double> residuals;
  for (std::size_t r = 0; r < training.size(); ++r)
    for (std::size_t k = 0; k < training[r].size(); ++k)
      residuals.push_back(training[r].follower_speed_mps[k] - simulated_speed_mps[r][k]);
  return residuals;
}
}  // namespace

AugmentedRefit refitAsDiagnosed(const AugmentedFit& fit, const AugmentedCalibrationOptions& calibration)
{
  return [fit, calibration](const std::vector<CarFollowingRun>& replicate) {
    const std::vector<EffectKind> effects = effectsOf(fit);
    AugmentedFit best = chainAsDiagnosed(effects, replicate, calibration);
    if (!effects.empty())
    {
      const AugmentedFit from_fit = calibrateAugmentedSet(effects, replicate, calibration, &fit);
      if (betterFit(from_fit, best))
        best = from_fit;
    }
    return best;
  };
}

RefitBootstrap bootstrapDiagnosedModel(const AugmentedFit& fit, const std::vector<CarFollowingRun>& training,
                                       const AugmentedCalibrationOptions& calibration,
                                       const RefitBootstrapOptions& options, const AugmentedRefit& refit)
{
  const std::vector<EffectKind> effects = effectsOf(fit);
  const AugmentedParameterBox box(effects, calibration);
  FittedDrives fitted;
  fitted.quantity_names = augmentedParameterNames(effects);
  fitted.parameter_count = fitted.quantity_names.size();
  fitted.at_fit = drawOf(fit, box);
  fitted.lower_bound = box.lower;
  fitted.upper_bound = box.upper;
  // The replicates resample speed residuals over the measured gaps: a fit that weighs the gap's
  // own error would refit gaps the replicates do not redraw.
  const bool weighs_gap = calibration.objective == FitObjective::gap || calibration.objective == FitObjective::speed_and_gap;
  const std::string not_made =
      fit.diverged  ? "the fit diverged"
      : weighs_gap ? "the bootstrap redraws speeds only, and the " + objectiveName(calibration.objective) +
                          " objective weighs the gap's error"
                    : simulateFittedDrives(fit.base, fit.settings, training, fitted);
  if (!not_made.empty())
    return RefitBootstrap::notMade(options.replicates, not_made);
  fitted.block_length_s = speedResidualBlockLengthS(training, speedResiduals(training, fitted.simulated_speed_mps));
  const AugmentedRefit refit_replicate = refit ? refit : refitAsDiagnosed(fit, calibration);
  const ReplicateRefit draw_of_refit = [&](const std::vector<CarFollowingRun>& replicate) -> std::optional<BootstrapDraw> {
    const AugmentedFit refitted = refit_replicate(replicate);
    if (refitted.diverged)
      return std::nullopt;
    if (effectsOf(refitted) != effects)  // a caller's procedure that fits another model
      throw std::logic_error("bootstrapDiagnosedModel: a refit has effects " + combinedEffectName(effectsOf(refitted)) +
                             ", the model " + combinedEffectName(effects));
    return drawOf(refitted, box);
  };
  return bootstrapFittedDrives(fitted, training, draw_of_refit, options);
}

}  // namespace acc
