#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace acc
{
/// One row of an OpenACC two-vehicle file (JRC OpenACC database, CC BY 4.0): vehicle 1 is the
/// leader, vehicle 2 the follower. Index [0] is vehicle 1, [1] vehicle 2.
struct OpenAccRow
{
  std::size_t line = 0;            ///< line number in the file (1-based), for messages
  double time_of_day_s = 0.0;      ///< the file's Time column: seconds since UTC midnight
  double speed_mps[2] = {0, 0};    ///< Doppler speed
  double latitude_rad[2] = {0, 0}; ///< OpenACC positions are in radians
  double longitude_rad[2] = {0, 0};
  double altitude_m[2] = {0, 0};   ///< NaN when the file has no AltN column (the leader here)
  double east_m[2] = {0, 0};       ///< local ENU plane of the file
  double north_m[2] = {0, 0};
  double ivs_m = 0.0;              ///< the database's bumper-to-bumper gap IVS1
};

/// An OpenACC two-vehicle CSV: 5 metadata lines (Date,DD,MM,YYYY first), a header, the rows.
/// Columns are found by name, so extra or reordered columns are fine.
struct OpenAccTrajectories
{
  int year = 0, month = 0, day = 0;
  std::vector<std::string> vehicle_order;  ///< leader first
  std::vector<OpenAccRow> rows;            ///< in file order
  std::vector<std::string> rejected_rows;  ///< "line N: why", one per row not read
  std::string error;                       ///< non-empty when the file cannot be used at all

  /// UTC midnight of the Date line, seconds since the Unix epoch.
  double dayStartUnixS() const;
};

OpenAccTrajectories readOpenAccTrajectories(const std::string& path);

}  // namespace acc
