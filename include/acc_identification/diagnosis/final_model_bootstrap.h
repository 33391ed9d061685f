#pragma once

#include <functional>
#include <vector>

#include "acc_identification/calibration/refit_bootstrap.h"
#include "acc_identification/diagnosis/augmented_calibration.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// A model's refit on one replicate drive.
using AugmentedRefit = std::function<AugmentedFit(const std::vector<CarFollowingRun>& replicate)>;

/// The refitting bootstrap (calibration/refit_bootstrap.h) of a diagnosed model: intervals for its
/// base parameters and its effects' sizes that hold on short data, where the sandwich standard
/// errors run short (on a minute of data value +- t se covers 72-88 % for the base law,
/// docs/RESULTS.md), and that carry the fit's bias and skew.
///
/// The replicates are drives the model `fit` could have given on `training` (its own simulation,
/// with its effects, plus the residuals resampled in blocks of its batch-means length, the start
/// gap moved by its noise). Each is refitted by `refit`, which must fit it as the data were fitted,
/// with `fit`'s effects (std::logic_error otherwise); when empty, as the diagnosis fits them
/// (refitAsDiagnosed). The selection of the effects is not
/// repeated: the intervals are those of the sizes given the effects named.
/// Quantities: the parameters by their JSON names (augmentedParameterNames). A parameter at a
/// bound of the diagnosis's box, or within 1.96 standard errors of one, gets no interval and makes
/// the others approximate (Andrews 2000).
/// Not made (RefitBootstrap::note says why) for a fit of the gap or the speed-and-gap objective:
/// the replicates redraw speeds only. options.starts and options.bounds are the base
/// calibration's and not used.
RefitBootstrap bootstrapDiagnosedModel(const AugmentedFit& fit, const std::vector<CarFollowingRun>& training,
                                       const AugmentedCalibrationOptions& calibration,
                                       const RefitBootstrapOptions& options, const AugmentedRefit& refit = {});

/// How `diagnose` fits a model with `fit`'s effects to a replicate: the base model from cold starts,
/// then the effects added one at a time, each fit warm-started from the last (calibrateAugmentedSet
/// with `calibration`); and beside that chain a fit warm-started at `fit` itself, the better of the
/// two on the replicate kept (betterFit).
AugmentedRefit refitAsDiagnosed(const AugmentedFit& fit, const AugmentedCalibrationOptions& calibration);

}  // namespace acc
