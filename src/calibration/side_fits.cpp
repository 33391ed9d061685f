#include "acc_identification/calibration/side_fits.h"

#include <algorithm>
#include <cmath>

#include "acc_identification/model/follower_simulation.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
SideFits fitBothSides(const CalibrationObjective& objective, const MultistartOptions& multistart,
                      const ConstrainedFitOptions& constrained, const std::vector<AccParameters>& warm_starts,
                      const std::vector<AccParameters>& other_side_warm_starts)
{
  SideFits fits;
  const MultistartResult unconstrained = calibrateMultistart(objective, multistart, warm_starts);
  fits.unconstrained_evaluations = unconstrained.evaluations;
  if (unconstrained.diverged)
  {
    fits.failure = "every start of the unconstrained fit diverged";
    return fits;
  }
  const AccParameters& u = unconstrained.parameters;
  fits.unconstrained = u;
  const double u_margin = stabilityMargin(u);
  fits.unconstrained_stable = u_margin >= 0.0;
  SideFit u_side;
  u_side.found = true;
  u_side.parameters = u;
  u_side.margin = u_margin;
  u_side.unconstrained_optimum = true;
  u_side.status = unconstrained.status;
  std::vector<AccParameters> other_warm{u};
  other_warm.insert(other_warm.end(), other_side_warm_starts.begin(), other_side_warm_starts.end());
  const ConstrainedFitResult other = fitWithMarginConstraint(
      objective, fits.unconstrained_stable ? MarginSide::AtMost : MarginSide::AtLeast, 0.0, constrained, other_warm);
  fits.constrained_evaluations = other.evaluations;
  SideFit other_side;
  other_side.found = other.found;
  other_side.parameters = other.parameters;
  other_side.margin = other.margin;
  other_side.status = other.status;
  fits.stable = fits.unconstrained_stable ? u_side : other_side;
  fits.unstable = fits.unconstrained_stable ? other_side : u_side;
  if (!fits.stable.found || !fits.unstable.found)
  {
    fits.failure = std::string("no ") + (fits.stable.found ? "string-unstable" : "string-stable") +
                   " model within the parameter bounds fits the training data";
  }
  return fits;
}

HeldOutErrors heldOutErrors(const AccParameters& p, const std::vector<CarFollowingRun>& held_out, double score_from_s)
{
  return heldOutErrors(p, EffectSettings{}, held_out, score_from_s);
}

HeldOutErrors heldOutErrors(const AccParameters& p, const EffectSettings& effects,
                            const std::vector<CarFollowingRun>& held_out, double score_from_s)
{
  HeldOutErrors result;
  for (const CarFollowingRun& run : held_out)
  {
    const SimulatedFollower sim = simulateFollower(p, effects, run);
    result.diverged = result.diverged || sim.diverged;
    for (std::size_t k = 1; k < run.size(); ++k)
    {
      if (run.time_s[k] < score_from_s)
      {
        continue;
      }
      result.error.push_back(run.follower_speed_mps[k] - sim.speed_mps[k]);
    }
  }
  return result;
}

std::string heldOutDivergence(const HeldOutErrors& stable, const HeldOutErrors& unstable,
                              const std::string& model_name)
{
  if (!stable.diverged && !unstable.diverged)
    return "";
  return std::string("the best ") + (stable.diverged ? "stable " : "unstable ") +
         (model_name.empty() ? "" : model_name + " ") + "model's simulation diverges on the held-out data";
}

double followerSpeedStdMps(const std::vector<CarFollowingRun>& runs)
{
  double sum = 0.0, sum_sq = 0.0;
  std::size_t n = 0;
  for (const CarFollowingRun& run : runs)
  {
    for (double v : run.follower_speed_mps)
    {
      sum += v;
      sum_sq += v * v;
      ++n;
    }
  }
  if (n == 0)
  {
    return 0.0;
  }
  const double m = sum / static_cast<double>(n);
  return std::sqrt(std::max(0.0, sum_sq / static_cast<double>(n) - m * m));
}

double lag1AutocorrelationWithinSegments(const std::vector<double>& x, const std::vector<std::size_t>& segment_lengths)
{
  double m = 0.0;
  for (double value : x)
  {
    m += value;
  }
  m = x.empty() ? 0.0 : m / static_cast<double>(x.size());
  double variance = 0.0, lagged = 0.0;
  std::size_t offset = 0;
  for (std::size_t length : segment_lengths)
  {
    for (std::size_t k = 0; k < length; ++k)
    {
      const double a = x[offset + k] - m;
      variance += a * a;
      if (k > 0)
      {
        lagged += a * (x[offset + k - 1] - m);
      }
    }
    offset += length;
  }
  return variance > 0.0 ? lagged / variance : 0.0;
}

double correlationBlockLengthS(const std::vector<double>& x, const std::vector<std::size_t>& segment_lengths,
                               double mean_step_s, double correlation_times, double min_s, double max_s)
{
  const double rho = std::clamp(lag1AutocorrelationWithinSegments(x, segment_lengths), 1e-6, 0.9999);
  const double correlation_time_s = -mean_step_s / std::log(rho);
  return std::clamp(correlation_times * correlation_time_s, min_s, max_s);
}

}  // namespace acc
