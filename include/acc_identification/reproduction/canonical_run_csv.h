#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "acc_identification/car_following_run.h"

namespace acc_identification
{
/// A canonical run CSV as read for the figures, with an account of every row not used.
struct CanonicalRunCsv
{
  CarFollowingRun run;
  std::size_t rejected_rows = 0;
  std::vector<std::string> problems;  ///< "path:line: why", one per rejected row
};

/// Reads time_s,space_gap_m,follower_speed_mps,leader_speed_mps (header required, any column
/// order, extra columns ignored). A row with a wrong field count, a field that is not a finite
/// number, or a time not after the previous row is rejected and listed, never used. Throws
/// std::runtime_error when the file cannot be opened, lacks a column, or leaves < 2 rows.
/// (A stand-in until the package's run reader, io/run_csv.h, is available to this component.)
CanonicalRunCsv readCanonicalRunCsv(const std::string& path);

}  // namespace acc_identification
