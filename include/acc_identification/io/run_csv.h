#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "acc_identification/car_following_run.h"

namespace acc_identification
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
  std::size_t data_rows = 0;      ///< rows after the header
  std::size_t rejected_rows = 0;  ///< malformed rows (each one listed in problems)
  std::size_t acc_off_rows = 0;   ///< OpenACC rows where the follower was not on ACC (split points)
  std::vector<std::string> problems;  ///< "path:line: why", one per rejected row or short piece
};

/// Reads a canonical run CSV (header time_s,space_gap_m,follower_speed_mps,leader_speed_mps, in
/// any column order) or an OpenACC two-vehicle CSV (metadata lines, then a header with Time,
/// IVS1, Speed2, Speed1 and Driver2). A malformed row (wrong field count, not a number, not
/// finite, time not increasing) is rejected, listed with its line number, and splits the run,
/// so that no simulation ever integrates across it. OpenACC rows with Driver2 != ACC split the
/// run too. Pieces with fewer than two samples are listed in problems. Runs are named after the
/// file ("part3"), with "#2", "#3"... for later pieces.
/// Throws RunReadError when the file cannot be opened or has no recognisable header.
RunFileContents readRunFile(const std::string& path);

/// readRunFile() for tools: returns the runs, and writes every problem (and a count) to stderr,
/// so nothing is dropped silently. Throws RunReadError as readRunFile, and when no run is usable.
std::vector<CarFollowingRun> readRuns(const std::string& path);

/// Writes one run as a canonical CSV (full double precision). Throws RunReadError on I/O failure.
void writeRunCsv(const std::string& path, const CarFollowingRun& run);

}  // namespace acc_identification
