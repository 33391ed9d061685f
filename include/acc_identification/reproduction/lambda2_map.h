#pragma once

#include <cstddef>
#include <vector>

namespace acc
{
/// One cell of the paper's Fig. 1: lambda2 at (k1, k2) for one effective time gap.
struct Lambda2MapSample
{
  double tau_e_s = 0.0;
  double k1_per_s2 = 0.0;
  double k2_per_s = 0.0;
  double lambda2 = 0.0;
  bool string_stable = false;  ///< from the transfer function (analyzeStringStability)
};

/// A regular (k1, k2) grid, repeated for each tau_e. Bounds are inclusive; points >= 2.
struct Lambda2MapGrid
{
  std::vector<double> tau_e_s{0.5, 1.0, 1.5, 2.0, 3.0};
  double k1_min_per_s2 = 0.01;  ///< k1 = 0 is degenerate (no spacing feedback, lambda2 = 0)
  double k1_max_per_s2 = 1.0;
  double k2_min_per_s = 0.0;
  double k2_max_per_s = 1.0;
  std::size_t k1_points = 100;
  std::size_t k2_points = 100;
};

/// lambda2 and the stability verdict on every grid point, tau_e outermost, then k1, then k2.
/// Throws std::invalid_argument for a grid with fewer than two points or inverted bounds.
std::vector<Lambda2MapSample> lambda2Map(const Lambda2MapGrid& grid);

/// The stable region in closed form (MATH.md): k1 tau_e^2 + 2 k2 tau_e >= 2 (eta plays no part).
bool inClosedFormStableRegion(double k1_per_s2, double k2_per_s, double tau_e_s);

/// Samples whose transfer-function verdict differs from the closed form: 0 when the map and
/// MATH.md agree (a check printed with Fig. 1).
std::size_t closedFormDisagreements(const std::vector<Lambda2MapSample>& map);

/// Fraction of the samples with the given tau_e that are string stable (0 when there are none).
double stableFraction(const std::vector<Lambda2MapSample>& map, double tau_e_s);

}  // namespace acc
