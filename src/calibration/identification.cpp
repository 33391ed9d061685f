#include "acc_identification/calibration/identification.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace acc
{
std::string describeInsufficientExcitation(const std::vector<CarFollowingRun>& segments,
                                           const IdentifiabilityCriteria& criteria)
{
  double duration_s = 0.0, sum = 0.0, sum_sq = 0.0;
  std::size_t samples = 0;
  for (const CarFollowingRun& run : segments)
  {
    duration_s += run.durationS();
    for (double v : run.follower_speed_mps)
    {
      sum += v;
      sum_sq += v * v;
    }
    samples += run.size();
  }
  std::ostringstream why;
  if (samples < criteria.min_samples || duration_s < criteria.min_duration_s)
  {
    why << "too little data: " << samples << " samples over " << duration_s << " s (need "
        << criteria.min_samples << " samples and " << criteria.min_duration_s << " s)";
    return why.str();
  }
  const double mean = sum / static_cast<double>(samples);
  const double speed_std = std::sqrt(std::max(0.0, sum_sq / static_cast<double>(samples) - mean * mean));
  if (speed_std < criteria.min_speed_std_mps)
  {
    why << "steady speed (follower speed std " << speed_std << " m/s < " << criteria.min_speed_std_mps
        << " m/s): the data pin only eta + tau_e v, not k1, k2, tau_e and eta apart";
    return why.str();
  }
  return "";
}

std::string describeUndeterminedParameters(const IdentifiableQuantities& quantities)
{
  std::string why;
  for (const char* name : {"k1", "k2", "tau_e", "eta"})
  {
    const QuantityEstimate* q = quantities.find(name);
    if (q == nullptr)
      why += std::string(why.empty() ? "" : "; ") + name + " was not assessed";
    else if (!q->determined)
      why += (why.empty() ? "" : "; ") + q->reason;
  }
  return why;
}

Identification identifyAcc(const std::vector<CarFollowingRun>& segments, const IdentificationOptions& options,
                           const std::vector<AccParameters>& warm_starts)
{
  Identification result;
  result.segments = segments.size();
  for (const CarFollowingRun& run : segments)
  {
    result.samples += run.size();
  }
  result.note = describeInsufficientExcitation(segments, options.criteria);
  if (!result.note.empty())
  {
    return result;
  }
  try
  {
    const CalibrationObjective objective(segments, options.bounds);
    result.calibration = calibrateMultistart(objective, options.multistart, warm_starts);
  }
  catch (const std::invalid_argument& error)
  {
    result.note = error.what();
    return result;
  }
  result.solved = true;
  if (result.calibration.diverged)
  {
    result.note = "every start diverged: no parameter set within the bounds simulates this data";
    return result;
  }
  const AccParameters& p = result.calibration.parameters;
  result.fit = evaluateFit(p, segments);
  result.uncertainty = estimateUncertainty(p, segments);
  result.stability = analyzeStringStability(p);
  result.quantities = assessQuantities(p, result.uncertainty, segments, options.bounds, options.criteria.quantities);
  result.note = describeUndeterminedParameters(*result.quantities);
  result.identifiable = result.note.empty();
  return result;
}

}  // namespace acc
