#pragma once

#include <cstdio>
#include <string>

#include "acc_identification/reproduction/figure_options.h"

namespace acc
{
/// Where a figure writes its text: the key numbers (stdout for the tool) and the notes and
/// warnings about its input (stderr).
struct FigureStreams
{
  std::FILE* numbers = stdout;
  std::FILE* notes = stderr;
};

/// One figure to make: its options, the CSV of its data, the Euler step of every simulation.
struct FigureRequest
{
  FigureOptions options;
  std::string csv_path;
  double time_step_s = 0.1;
  FigureStreams streams;
};

}  // namespace acc
