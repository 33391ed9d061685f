#include "acc_identification/io/run_plausibility.h"

#include <sstream>

namespace acc
{
namespace
{
/// Written so that NaN is outside too (every comparison with NaN is false).
bool isWithin(double value, double min_value, double max_value)
{
  return min_value <= value && value <= max_value;
}

std::string describeOutside(const char* column, double value, double min_value, double max_value,
                            const char* unit)
{
  std::ostringstream why;
  why << column << " " << value << " outside [" << min_value << ", " << max_value << "] " << unit;
  return why.str();
}
}  // namespace

std::string describeBoundsProblem(const RunPlausibilityBounds& bounds)
{
  if (!(bounds.min_speed_mps < bounds.max_speed_mps))
  {
    return "min_speed_mps must be below max_speed_mps";
  }
  if (!(bounds.min_space_gap_m < bounds.max_space_gap_m))
  {
    return "min_space_gap_m must be below max_space_gap_m";
  }
  if (!(bounds.max_time_step_s > 0.0))
  {
    return "max_time_step_s must be positive";
  }
  return "";
}

std::string describeImplausibleValue(double space_gap_m, double follower_speed_mps, double leader_speed_mps,
                                     const RunPlausibilityBounds& bounds)
{
  if (!isWithin(space_gap_m, bounds.min_space_gap_m, bounds.max_space_gap_m))
  {
    return describeOutside("space_gap_m", space_gap_m, bounds.min_space_gap_m, bounds.max_space_gap_m, "m");
  }
  if (!isWithin(follower_speed_mps, bounds.min_speed_mps, bounds.max_speed_mps))
  {
    return describeOutside("follower_speed_mps", follower_speed_mps, bounds.min_speed_mps, bounds.max_speed_mps,
                           "m/s");
  }
  if (!isWithin(leader_speed_mps, bounds.min_speed_mps, bounds.max_speed_mps))
  {
    return describeOutside("leader_speed_mps", leader_speed_mps, bounds.min_speed_mps, bounds.max_speed_mps,
                           "m/s");
  }
  return "";
}

std::string describeTimeHole(double previous_time_s, double time_s, const RunPlausibilityBounds& bounds)
{
  const double step_s = time_s - previous_time_s;
  if (!(step_s > bounds.max_time_step_s))
  {
    return "";
  }
  std::ostringstream why;
  why << "hole of " << step_s << " s before this row (max " << bounds.max_time_step_s << " s)";
  return why.str();
}

}  // namespace acc
