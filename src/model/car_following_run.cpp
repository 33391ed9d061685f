#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/plain_text.h"
#include "acc_identification/model/sample_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace acc
{
namespace
{
std::string firstNonFinite(const std::vector<double>& column, const char* column_name)
{
  for (std::size_t i = 0; i < column.size(); ++i)
  {
    if (!std::isfinite(column[i]))
    {
      std::ostringstream why;
      why << column_name << " is not finite at sample " << i;
      return why.str();
    }
  }
  return "";
}
}  // namespace

std::vector<double> sliceRows(const std::vector<double>& column, std::size_t first, std::size_t end)
{
  if (first > end || end > column.size())
  {
    throw std::out_of_range("rows [" + std::to_string(first) + ", " + std::to_string(end) + ") of a column of " +
                            std::to_string(column.size()));
  }
  return std::vector<double>(column.begin() + static_cast<std::ptrdiff_t>(first),
                             column.begin() + static_cast<std::ptrdiff_t>(end));
}

double gapChangeBySpeedsM(const CarFollowingRun& run, std::size_t k)
{
  const double relative_before = run.leader_speed_mps[k - 1] - run.follower_speed_mps[k - 1];
  const double relative_after = run.leader_speed_mps[k] - run.follower_speed_mps[k];
  return 0.5 * (relative_before + relative_after) * (run.time_s[k] - run.time_s[k - 1]);
}

double gapSampleNoiseM(const CarFollowingRun& run)
{
  if (run.size() < 11)
    return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> mismatches;
  for (std::size_t k = 1; k < run.size(); ++k)
    mismatches.push_back(run.space_gap_m[k] - run.space_gap_m[k - 1] - gapChangeBySpeedsM(run, k));
  const double median = interpolatedQuantile(mismatches, 0.5);
  for (double& m : mismatches)
    m = std::abs(m - median);
  constexpr double kMadToStandardDeviation = 1.4826;  // for normal noise
  return kMadToStandardDeviation * interpolatedQuantile(mismatches, 0.5) / std::sqrt(2.0);
}

double medianStepS(const std::vector<CarFollowingRun>& runs)
{
  std::vector<double> steps;
  for (const CarFollowingRun& run : runs)
    for (std::size_t k = 1; k < run.size(); ++k)
      steps.push_back(run.time_s[k] - run.time_s[k - 1]);
  return steps.empty() ? std::numeric_limits<double>::quiet_NaN() : interpolatedQuantile(steps, 0.5);
}

CarFollowingRun CarFollowingRun::slice(std::size_t first, std::size_t end, const std::string& name_suffix) const
{
  CarFollowingRun part;
  part.name = name + name_suffix;
  part.time_s = sliceRows(time_s, first, end);
  part.space_gap_m = sliceRows(space_gap_m, first, end);
  part.follower_speed_mps = sliceRows(follower_speed_mps, first, end);
  part.leader_speed_mps = sliceRows(leader_speed_mps, first, end);
  return part;
}

std::pair<CarFollowingRun, CarFollowingRun> splitRunInHalf(const CarFollowingRun& run)
{
  const std::size_t half = run.size() / 2;
  return {run.slice(0, half, " (train)"), run.slice(half, run.size(), " (test)")};
}

std::string describeRunProblem(const CarFollowingRun& run)
{
  const std::size_t n = run.time_s.size();
  if (run.space_gap_m.size() != n || run.follower_speed_mps.size() != n ||
      run.leader_speed_mps.size() != n)
  {
    return "columns have different lengths";
  }
  if (n < 2)
  {
    return "fewer than two samples";
  }
  for (const auto& [column, column_name] :
       {std::pair{&run.time_s, "time_s"}, std::pair{&run.space_gap_m, "space_gap_m"},
        std::pair{&run.follower_speed_mps, "follower_speed_mps"},
        std::pair{&run.leader_speed_mps, "leader_speed_mps"}})
  {
    std::string problem = firstNonFinite(*column, column_name);
    if (!problem.empty())
    {
      return problem;
    }
  }
  for (std::size_t i = 1; i < n; ++i)
  {
    if (!(run.time_s[i] > run.time_s[i - 1]))
    {
      std::ostringstream why;
      why << "time does not increase at sample " << i << " (" << run.time_s[i - 1] << " s then "
          << run.time_s[i] << " s)";
      return why.str();
    }
  }
  return "";
}

std::size_t sampleCount(const std::vector<CarFollowingRun>& runs)
{
  std::size_t n = 0;
  for (const CarFollowingRun& run : runs)
    n += run.size();
  return n;
}

double totalDurationS(const std::vector<CarFollowingRun>& runs)
{
  double duration_s = 0.0;
  for (const CarFollowingRun& run : runs)
    duration_s += run.durationS();
  return duration_s;
}

std::vector<CarFollowingRun> inNaturalNameOrder(std::vector<CarFollowingRun> runs)
{
  return inNaturalOrder(std::move(runs), [](const CarFollowingRun& run) -> const std::string& { return run.name; });
}

}  // namespace acc
