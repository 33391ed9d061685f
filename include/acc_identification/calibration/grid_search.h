#pragma once

#include <array>
#include <cstddef>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/calibration/calibration_objective.h"

namespace acc
{
/// Exhaustive check of a multistart result: the reduced objective (eta in closed form) at every
/// node of a regular grid over (k1, k2, tau_e). Slow by design; it shows that no basin was missed.
struct GridSearchResult
{
  AccParameters best;              ///< grid node with the lowest objective (eta its best eta)
  double best_rmse_speed_mps = 0.0;
  std::size_t nodes = 0;
  std::size_t diverged_nodes = 0;
  std::array<double, 3> spacing{};  ///< grid step in k1, k2, tau_e
};

/// nodes_per_axis >= 2 nodes on each axis, from lower to upper inclusive.
GridSearchResult gridSearch(const CalibrationObjective& objective, const AccParameters& lower,
                            const AccParameters& upper, std::array<std::size_t, 3> nodes_per_axis);

}  // namespace acc
