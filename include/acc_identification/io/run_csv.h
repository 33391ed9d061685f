#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "acc_identification/model/car_following_run.h"
#include "acc_identification/io/run_plausibility.h"

namespace acc
{
/// A file that cannot be read as runs at all (missing, no recognisable header, no data).
class RunReadError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Everything read from one run file, with an account of every row that was not used.
struct RunFileContents
{
  std::vector<CarFollowingRun> runs;
  std::size_t data_rows = 0;          ///< rows after the header
  std::size_t rejected_rows = 0;      ///< rows not used (each one listed in problems)
  std::size_t implausible_rows = 0;   ///< of rejected_rows: values outside the plausibility bounds
  std::size_t time_holes = 0;         ///< steps longer than max_time_step_s (split points, no row lost)
  std::size_t acc_off_rows = 0;       ///< OpenACC rows where the follower was not on ACC (split points)
  std::vector<std::string> problems;  ///< "path:line: why", one per rejected row, hole or short piece
};

/// Reads a canonical run CSV (header time_s,space_gap_m,follower_speed_mps,leader_speed_mps, in
/// any column order) or an OpenACC two-vehicle CSV (metadata lines, then a header with Time,
/// IVS1, Speed2, Speed1 and Driver2). A bad row (wrong field count, not a number, not finite,
/// a value outside the plausibility bounds, time not increasing) is rejected, listed with its
/// line number, and splits the run, so that no simulation ever integrates across it. A time step
/// longer than bounds.max_time_step_s splits the run too, keeping both rows, and is listed.
/// OpenACC rows with Driver2 != ACC split the run. Pieces with fewer than two samples are listed
/// in problems. Runs are named after the file ("part3"), with "#2", "#3"... for later pieces.
/// Throws RunReadError when the file cannot be opened or has no recognisable header, and
/// std::invalid_argument when the bounds are unusable (describeBoundsProblem); never for a row.
RunFileContents readRunFile(const std::string& path, const RunPlausibilityBounds& bounds = RunPlausibilityBounds{});

/// readRunFile() for tools: returns the runs, and writes every problem (and the counts of rejected
/// rows and holes) to stderr, so nothing is dropped silently. Throws as readRunFile, and
/// RunReadError when no run is usable.
std::vector<CarFollowingRun> readRuns(const std::string& path,
                                      const RunPlausibilityBounds& bounds = RunPlausibilityBounds{});

/// Writes one run as a canonical CSV (full double precision). Throws RunReadError on I/O failure.
void writeRunCsv(const std::string& path, const CarFollowingRun& run);

}  // namespace acc
