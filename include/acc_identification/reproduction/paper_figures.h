#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/reproduction/figure_request.h"

namespace acc
{
/// The figures of Gunter et al. by name: what the platoon tool runs (src/tools/platoon_main.cpp).

/// The usage text of the figures: each name, its paper number, its options with their defaults,
/// the parameter-set options and the run formats.
const char* paperFiguresHelp();

/// Every FIGURE a caller may name: the names (lambda2-map, step, ...) and the paper's figure
/// numbers (fig1 to fig8).
std::vector<std::string> acceptedFigures();

/// The value options a figure (named or numbered) reads: its own, the parameter-set options
/// where it draws settings, --time-step where it simulates at a step of its own. Empty for an
/// unknown figure.
std::vector<std::string> figureOptionNames(const std::string& figure);

/// Makes one figure, named or numbered: refuses an option the figure does not read (a typo, or
/// one meant for another figure, would otherwise pass unnoticed), checks --time-step, then runs
/// it. Throws FigureUsageError for an unknown figure or a bad option, std::runtime_error when its
/// CSV cannot be written.
nlohmann::json runPaperFigure(const std::string& figure, const FigureOptions& options, const std::string& csv_path,
                              const FigureStreams& streams = FigureStreams{});

}  // namespace acc
