#include "acc_identification/reproduction/lambda2_map.h"

#include <cmath>
#include <stdexcept>

#include "acc_identification/model/string_stability.h"

namespace acc
{
namespace
{
double gridValue(double min, double max, std::size_t points, std::size_t index)
{
  return min + (max - min) * static_cast<double>(index) / static_cast<double>(points - 1);
}

void checkGrid(const Lambda2MapGrid& grid)
{
  if (grid.k1_points < 2 || grid.k2_points < 2 || grid.tau_e_s.empty())
  {
    throw std::invalid_argument("lambda2 map needs at least 2 points per gain and one tau_e");
  }
  if (!(grid.k1_min_per_s2 < grid.k1_max_per_s2) || !(grid.k2_min_per_s < grid.k2_max_per_s) ||
      grid.k1_min_per_s2 < 0.0 || grid.k2_min_per_s < 0.0)
  {
    throw std::invalid_argument("lambda2 map gain bounds must be non-negative with min < max");
  }
  for (double tau : grid.tau_e_s)
  {
    if (!(tau >= 0.0) || !std::isfinite(tau))
    {
      throw std::invalid_argument("lambda2 map tau_e values must be finite and non-negative");
    }
  }
}
}  // namespace

std::vector<Lambda2MapSample> lambda2Map(const Lambda2MapGrid& grid)
{
  checkGrid(grid);
  std::vector<Lambda2MapSample> map;
  map.reserve(grid.tau_e_s.size() * grid.k1_points * grid.k2_points);
  for (double tau : grid.tau_e_s)
  {
    for (std::size_t i = 0; i < grid.k1_points; ++i)
    {
      for (std::size_t j = 0; j < grid.k2_points; ++j)
      {
        Lambda2MapSample sample;
        sample.tau_e_s = tau;
        sample.k1_per_s2 = gridValue(grid.k1_min_per_s2, grid.k1_max_per_s2, grid.k1_points, i);
        sample.k2_per_s = gridValue(grid.k2_min_per_s, grid.k2_max_per_s, grid.k2_points, j);
        const AccParameters p{sample.k1_per_s2, sample.k2_per_s, tau, 0.0};
        const StringStabilityReport report = analyzeStringStability(p);
        sample.lambda2 = report.lambda2;
        sample.string_stable = report.string_stable;
        map.push_back(sample);
      }
    }
  }
  return map;
}

bool inClosedFormStableRegion(double k1_per_s2, double k2_per_s, double tau_e_s)
{
  return k1_per_s2 * tau_e_s * tau_e_s + 2.0 * k2_per_s * tau_e_s >= 2.0;
}

double stableFraction(const std::vector<Lambda2MapSample>& map, double tau_e_s)
{
  std::size_t total = 0;
  std::size_t stable = 0;
  for (const Lambda2MapSample& sample : map)
  {
    if (sample.tau_e_s == tau_e_s)
    {
      ++total;
      stable += sample.string_stable ? 1 : 0;
    }
  }
  return total == 0 ? 0.0 : static_cast<double>(stable) / static_cast<double>(total);
}

std::size_t closedFormDisagreements(const std::vector<Lambda2MapSample>& map)
{
  std::size_t disagreements = 0;
  for (const Lambda2MapSample& s : map)
  {
    disagreements += s.string_stable != inClosedFormStableRegion(s.k1_per_s2, s.k2_per_s, s.tau_e_s);
  }
  return disagreements;
}

}  // namespace acc
