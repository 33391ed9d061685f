#include "acc_identification/reproduction/equilibrium_regression.h"

#include <cmath>
#include <stdexcept>

#include "acc_identification/model/acc_model.h"

namespace acc
{
namespace
{
/// The line through the given samples and each parameter set's distance from them.
EquilibriumRegression regressOn(const CarFollowingRun& run, std::vector<std::size_t> samples,
                                const std::vector<AccParameters>& settings)
{
  EquilibriumRegression regression;
  regression.steady = std::move(samples);
  try
  {
    regression.line = fitGapSpeedLine(run, regression.steady);
  }
  catch (const std::invalid_argument& error)
  {
    regression.no_line_reason = error.what();
  }
  for (const AccParameters& p : settings)
  {
    regression.rms_from_line_m.push_back(rmsFromEquilibriumLine(p, run, regression.steady));
  }
  return regression;
}
}  // namespace

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

EquilibriumRegression regressEquilibrium(const CarFollowingRun& run, const std::vector<AccParameters>& settings,
                                         double max_relative_speed_mps, double max_acceleration_mps2)
{
  return regressOn(run, steadyFollowingSamples(run, max_relative_speed_mps, max_acceleration_mps2), settings);
}

CarFollowingRun pooledSteadySamples(const std::vector<CarFollowingRun>& runs, double max_relative_speed_mps,
                                    double max_acceleration_mps2)
{
  CarFollowingRun pooled;
  pooled.name = "all runs";
  for (const CarFollowingRun& run : runs)
  {
    for (std::size_t k : steadyFollowingSamples(run, max_relative_speed_mps, max_acceleration_mps2))
    {
      pooled.time_s.push_back(static_cast<double>(pooled.time_s.size()));
      pooled.follower_speed_mps.push_back(run.follower_speed_mps[k]);
      pooled.space_gap_m.push_back(run.space_gap_m[k]);
      pooled.leader_speed_mps.push_back(run.leader_speed_mps[k]);
    }
  }
  return pooled;
}

EquilibriumRegression regressPooledEquilibrium(const std::vector<CarFollowingRun>& runs,
                                               const std::vector<AccParameters>& settings,
                                               double max_relative_speed_mps, double max_acceleration_mps2)
{
  const CarFollowingRun pooled = pooledSteadySamples(runs, max_relative_speed_mps, max_acceleration_mps2);
  std::vector<std::size_t> all(pooled.size());
  for (std::size_t k = 0; k < all.size(); ++k)
  {
    all[k] = k;
  }
  return regressOn(pooled, std::move(all), settings);
}

}  // namespace acc
