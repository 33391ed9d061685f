#pragma once

#include <nlohmann/json.hpp>

#include "acc_identification/reproduction/figure_request.h"

namespace acc
{
/// The figures of Gunter et al. made from measured runs (--run RUN.csv, canonical or OpenACC):
/// each writes its data to request.csv_path, prints its key numbers and returns them as JSON.
/// A run file that cannot be read, or no --run, throws FigureUsageError.

/// Fig. 5: space gap against speed, steady samples, equilibrium lines per run and pooled.
nlohmann::json equilibriumFigure(const FigureRequest& request);
/// Figs. 3 and 4: measured against simulated speed and gap of one run (its longest piece), split
/// into train and test parts.
nlohmann::json timeseriesFigure(const FigureRequest& request);

}  // namespace acc
