#pragma once

#include <cstddef>
#include <string>
#include <utility>
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
  /// The samples [first, end) of every column, named name + name_suffix ("part3 (train)").
  /// Throws std::out_of_range when the rows are not within the run (first <= end <= size()).
  CarFollowingRun slice(std::size_t first, std::size_t end, const std::string& name_suffix = "") const;
};

/// The samples of all runs, summed.
std::size_t sampleCount(const std::vector<CarFollowingRun>& runs);

/// The runs' durations, summed [s] (the holes between runs are not in it).
double totalDurationS(const std::vector<CarFollowingRun>& runs);

/// The first half of a run (samples [0, n/2), named "... (train)") for training and the second
/// ([n/2, n), "... (test)"), simulated from its own measured start, for testing: the paper's
/// protocol (Section V-B). The columns must be of equal length (describeRunProblem).
std::pair<CarFollowingRun, CarFollowingRun> splitRunInHalf(const CarFollowingRun& run);

/// The rows [first, end) of one column: the one slicing of the package, for runs (above) and for
/// the columns of a file read row by row. Throws std::out_of_range unless first <= end <= size.
std::vector<double> sliceRows(const std::vector<double>& column, std::size_t first, std::size_t end);

/// The change of the gap from sample k - 1 to k that the two speeds say: the trapezoid integral
/// of (leader - follower) speed over the step [m]. 1 <= k < run.size().
double gapChangeBySpeedsM(const CarFollowingRun& run, std::size_t k);

/// The sample-to-sample part of the gap's measurement error [m]: the standard deviation of white
/// noise on the gap that would make the steps' mismatch (s_k - s_k-1) - gapChangeBySpeedsM(run, k)
/// as spread as it is: 1.4826 MAD of the mismatches over sqrt(2) (white gap noise of standard
/// deviation sigma puts 2 sigma^2 into each step; the speeds' own noise adds h^2 of theirs, which
/// at 10 Hz is nothing). Robust to the odd jump. What it cannot see is an error that stays over
/// many samples (an antenna offset, slow multipath): to the data that is the gap. NaN with fewer
/// than 10 steps.
double gapSampleNoiseM(const CarFollowingRun& run);

/// The median step between consecutive samples over the runs [s] (the middle two averaged); NaN
/// without a step.
double medianStepS(const std::vector<CarFollowingRun>& runs);

/// The runs by name in natural order (inNaturalOrder in plain_text.h).
std::vector<CarFollowingRun> inNaturalNameOrder(std::vector<CarFollowingRun> runs);

/// Checks the run's invariants (equal column lengths, at least two samples, strictly increasing
/// time, finite values). Returns an empty string when the run is usable, else why it is not.
std::string describeRunProblem(const CarFollowingRun& run);

}  // namespace acc
