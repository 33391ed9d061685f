#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace acc
{
/// One measured car-following record: the four canonical columns of a run, sampled together.
/// Time must be strictly increasing; the step need not be uniform.
struct CarFollowingRun
{
  std::string name;                          ///< where it came from, for reports
  std::vector<double> time_s;
  std::vector<double> space_gap_m;           ///< leader rear bumper to follower front bumper
  std::vector<double> follower_speed_mps;
  std::vector<double> leader_speed_mps;

  std::size_t size() const { return time_s.size(); }
  double durationS() const { return time_s.empty() ? 0.0 : time_s.back() - time_s.front(); }
};

/// Checks the run's invariants (equal column lengths, at least two samples, strictly increasing
/// time, finite values). Returns an empty string when the run is usable, else why it is not.
std::string describeRunProblem(const CarFollowingRun& run);

}  // namespace acc
