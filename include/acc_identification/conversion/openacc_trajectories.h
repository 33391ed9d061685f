#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace acc
{
/// One row of a leader-follower pair of an OpenACC file (JRC OpenACC database, CC BY 4.0).
/// Index [0] is the pair's leader, [1] its follower (vehicles 1 and 2 of a two-vehicle file).
struct OpenAccRow
{
  std::size_t line = 0;            ///< line number in the file (1-based), for messages
  double time_of_day_s = 0.0;      ///< the file's Time column: seconds since UTC midnight
  double speed_mps[2] = {0, 0};    ///< Doppler speed
  double latitude_rad[2] = {0, 0}; ///< radians, whatever unit the file used (see angle_unit_note)
  double longitude_rad[2] = {0, 0};
  double altitude_m[2] = {0, 0};   ///< NaN when the file has no AltN column (the leader here)
  double east_m[2] = {0, 0};       ///< local ENU plane of the file
  double north_m[2] = {0, 0};
  double ivs_m = 0.0;              ///< the database's bumper-to-bumper gap IVSk of the pair (k: the leader)
};

/// Which pair of a platoon file to read: the follower by its name in Vehicle_order
/// (case-insensitive, e.g. "BMW_I3") or by its position (1-based, e.g. "3"); empty: the first
/// pair the file holds. The leader is always the car directly ahead of the follower.
struct OpenAccPairSelection
{
  std::string follower;
};

/// One leader-follower pair of an OpenACC CSV, two-vehicle (Casale, Cherasco) or platoon
/// (ZalaZone, ...): 5 metadata lines (Date,DD,MM,YYYY first, Vehicle_order, ...), a header, the
/// rows. Columns are found by name (Time; per vehicle k Speedk, Latk, Lonk, Altk, Ek, Nk; IVSk
/// the gap behind vehicle k), so extra, missing or reordered columns are fine.
struct OpenAccTrajectories
{
  int year = 0, month = 0, day = 0;
  std::vector<std::string> vehicle_order;  ///< every car of the test, leader first
  int leader_position = 0;                 ///< 1-based positions in vehicle_order of the pair read
  int follower_position = 0;
  std::vector<int> available_followers;    ///< positions whose pair the file holds (both cars and IVS)
  /// Latitude and longitude are radians by the database's notes, but some files (ZalaZone) hold
  /// degrees: detected per file, converted to radians, and said here with the reason.
  bool positions_were_degrees = false;
  std::string angle_unit_note;
  std::vector<OpenAccRow> rows;            ///< in file order
  std::vector<std::string> rejected_rows;  ///< "line N: why", one per row not read
  std::string error;                       ///< non-empty when the file cannot be used at all

  /// UTC midnight of the Date line, seconds since the Unix epoch.
  double dayStartUnixS() const;
  /// "BMW_I3 (2) behind SMART_TARGET (1)".
  std::string pairName() const;
};

OpenAccTrajectories readOpenAccTrajectories(const std::string& path, const OpenAccPairSelection& selection = {});

}  // namespace acc
