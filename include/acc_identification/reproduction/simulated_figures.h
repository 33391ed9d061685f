#pragma once

#include <nlohmann/json.hpp>

#include "acc_identification/reproduction/figure_request.h"

namespace acc
{
/// The figures of Gunter et al. made by simulation: each writes its data to request.csv_path,
/// prints its key numbers and returns them as JSON (the "summary" of the platoon tool). Options
/// and defaults: paperFiguresHelp() (paper_figures.h). Bad options throw FigureUsageError.

/// Fig. 1: lambda2 over (k1, k2) for several tau_e, and where it disagrees with the closed form.
nlohmann::json lambda2MapFigure(const FigureRequest& request);
/// Fig. 2: a platoon behind a lead speed step down and back up.
nlohmann::json stepFigure(const FigureRequest& request);
/// Fig. 6: |Gamma(jw)| in dB, exact and of the Euler recursion.
nlohmann::json bodeFigure(const FigureRequest& request);
/// Fig. 7: a platoon behind a sinusoidal lead, amplitudes fitted over the last periods.
nlohmann::json sinusoidFigure(const FigureRequest& request);
/// Fig. 8: a platoon behind one of the lead profiles A..I of Sec. III, long and short.
nlohmann::json leadProfileFigure(const FigureRequest& request);

}  // namespace acc
