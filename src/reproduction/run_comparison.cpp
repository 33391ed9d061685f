#include "acc_identification/reproduction/run_comparison.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "acc_identification/model/acc_model.h"

namespace acc
{
namespace
{
/// RMS of (a - b) over [from, to); 0 for an empty range.
double rms(const std::vector<double>& a, const std::vector<double>& b, std::size_t from, std::size_t to)
{
  if (to <= from)
  {
    return 0.0;
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
  errors.train_speed_rmse_mps = rms(run.follower_speed_mps, sim.speed_mps, 0, split);
  errors.test_speed_rmse_mps = rms(run.follower_speed_mps, sim.speed_mps, split, valid_end);
  errors.train_gap_rmse_m = rms(run.space_gap_m, sim.space_gap_m, 0, split);
  errors.test_gap_rmse_m = rms(run.space_gap_m, sim.space_gap_m, split, valid_end);
  return errors;
}

std::vector<std::size_t> steadyFollowingSamples(const CarFollowingRun& run, double max_relative_speed_mps,
                                                double max_acceleration_mps2)
{
  std::vector<std::size_t> steady;
  for (std::size_t k = 1; k + 1 < run.size(); ++k)
  {
    const double acceleration = (run.follower_speed_mps[k + 1] - run.follower_speed_mps[k - 1]) /
                                (run.time_s[k + 1] - run.time_s[k - 1]);
    if (std::abs(run.leader_speed_mps[k] - run.follower_speed_mps[k]) <= max_relative_speed_mps &&
        std::abs(acceleration) <= max_acceleration_mps2)
    {
      steady.push_back(k);
    }
  }
  return steady;
}

GapSpeedLine fitGapSpeedLine(const CarFollowingRun& run, const std::vector<std::size_t>& samples)
{
  if (samples.size() < 2)
  {
    throw std::invalid_argument("a gap-speed line needs at least two samples");
  }
  double mean_v = 0.0, mean_s = 0.0;
  for (std::size_t k : samples)
  {
    mean_v += run.follower_speed_mps[k];
    mean_s += run.space_gap_m[k];
  }
  const auto count = static_cast<double>(samples.size());
  mean_v /= count;
  mean_s /= count;
  double s_vv = 0.0, s_vs = 0.0;
  for (std::size_t k : samples)
  {
    s_vv += (run.follower_speed_mps[k] - mean_v) * (run.follower_speed_mps[k] - mean_v);
    s_vs += (run.follower_speed_mps[k] - mean_v) * (run.space_gap_m[k] - mean_s);
  }
  if (!(s_vv > 1e-9 * count))
  {
    throw std::invalid_argument("a gap-speed line needs samples at more than one speed");
  }
  GapSpeedLine line;
  line.slope_s = s_vs / s_vv;
  line.intercept_m = mean_s - line.slope_s * mean_v;
  line.samples = samples.size();
  const AccParameters as_model{0.0, 0.0, line.slope_s, line.intercept_m};
  line.rms_residual_m = rmsFromEquilibriumLine(as_model, run, samples);
  return line;
}

double rmsFromEquilibriumLine(const AccParameters& p, const CarFollowingRun& run,
                              const std::vector<std::size_t>& samples)
{
  if (samples.empty())
  {
    return 0.0;
  }
  double sum = 0.0;
  for (std::size_t k : samples)
  {
    const double residual = run.space_gap_m[k] - equilibriumSpaceGapM(p, run.follower_speed_mps[k]);
    sum += residual * residual;
  }
  return std::sqrt(sum / static_cast<double>(samples.size()));
}

}  // namespace acc
