#include "acc_identification/calibration/grid_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace acc
{
GridSearchResult gridSearch(const CalibrationObjective& objective, const AccParameters& lower,
                            const AccParameters& upper, std::array<std::size_t, 3> nodes_per_axis)
{
  for (auto& n : nodes_per_axis)
  {
    n = std::max<std::size_t>(2, n);
  }
  const std::array<double, 3> low{lower.k1_per_s2, lower.k2_per_s, lower.tau_e_s};
  const std::array<double, 3> high{upper.k1_per_s2, upper.k2_per_s, upper.tau_e_s};
  GridSearchResult result;
  for (int i = 0; i < 3; ++i)
  {
    result.spacing[i] = (high[i] - low[i]) / static_cast<double>(nodes_per_axis[i] - 1);
  }
  double best_mse = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < nodes_per_axis[0]; ++a)
  {
    for (std::size_t b = 0; b < nodes_per_axis[1]; ++b)
    {
      for (std::size_t c = 0; c < nodes_per_axis[2]; ++c)
      {
        const double k1 = low[0] + static_cast<double>(a) * result.spacing[0];
        const double k2 = low[1] + static_cast<double>(b) * result.spacing[1];
        const double tau = low[2] + static_cast<double>(c) * result.spacing[2];
        const ReducedObjectiveValue value = objective.evaluate(k1, k2, tau, false);
        ++result.nodes;
        if (value.diverged)
        {
          ++result.diverged_nodes;
        }
        else if (value.mse_speed_mps2 < best_mse)
        {
          best_mse = value.mse_speed_mps2;
          result.best = AccParameters{k1, k2, tau, value.eta_m};
        }
      }
    }
  }
  result.best_rmse_speed_mps = std::sqrt(best_mse);
  return result;
}

}  // namespace acc
