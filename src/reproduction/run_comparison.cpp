#include "acc_identification/reproduction/run_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>


namespace acc
{
namespace
{
/// RMS of (a - b) over [from, to); NaN for an empty range.
double rms(const std::vector<double>& a, const std::vector<double>& b, std::size_t from, std::size_t to)
{
  if (to <= from)
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  double sum = 0.0;
  for (std::size_t k = from; k < to; ++k)
  {
    sum += (a[k] - b[k]) * (a[k] - b[k]);
  }
  return std::sqrt(sum / static_cast<double>(to - from));
}
}  // namespace

TrainTestErrors trainTestErrors(const CarFollowingRun& run, const SimulatedFollower& sim, double train_fraction)
{
  if (!(train_fraction > 0.0 && train_fraction < 1.0))
  {
    throw std::invalid_argument("train fraction must lie in (0, 1)");
  }
  if (sim.speed_mps.size() != run.size() || sim.space_gap_m.size() != run.size() || run.size() < 2)
  {
    throw std::invalid_argument("simulation and run must have the same number (>= 2) of samples");
  }
  TrainTestErrors errors;
  const std::size_t n = run.size();
  errors.split_index = std::min(n - 1, static_cast<std::size_t>(std::ceil(train_fraction * static_cast<double>(n))));
  errors.split_time_s = run.time_s[errors.split_index];
  errors.diverged = sim.diverged;
  // After a divergence the samples hold a frozen state: score only what came before.
  const std::size_t valid_end = sim.diverged ? sim.diverged_at_index : n;
  const std::size_t split = std::min(errors.split_index, valid_end);
  errors.train_samples = split;
  errors.test_samples = valid_end - split;
  errors.train_speed_rmse_mps = rms(run.follower_speed_mps, sim.speed_mps, 0, split);
  errors.test_speed_rmse_mps = rms(run.follower_speed_mps, sim.speed_mps, split, valid_end);
  errors.train_gap_rmse_m = rms(run.space_gap_m, sim.space_gap_m, 0, split);
  errors.test_gap_rmse_m = rms(run.space_gap_m, sim.space_gap_m, split, valid_end);
  return errors;
}

}  // namespace acc
