#pragma once

#include <acc_identification/gnss/gnss_fix.h>
#include <acc_identification/io/openacc_file.h>

#include <cstddef>
#include <string>
#include <vector>

namespace acc
{
/// One row of a leader-follower pair of an OpenACC file (JRC OpenACC database, CC BY 4.0), as the
/// NMEA conversion uses it. Index [0] is the pair's leader, [1] its follower.
struct OpenAccRow
{
  std::size_t line = 0;              ///< line number in the file (1-based), for messages
  double time_of_day_s = 0.0;        ///< the file's Time column: seconds since UTC midnight
  double speed_mps[2] = {0, 0};      ///< Doppler speed
  double latitude_deg[2] = {0, 0};   ///< degrees, whatever unit the file used (OpenAccFile::angle_unit)
  double longitude_deg[2] = {0, 0};
  double altitude_m[2] = {0, 0};     ///< NaN where the file has no AltN value (Casale's leader)
  double east_m[2] = {0, 0};         ///< local ENU plane of the file; NaN where absent
  double north_m[2] = {0, 0};
  double ivs_m = 0.0;                ///< the database's bumper-to-bumper gap IVSk of the pair (k: the leader)
};

/// The rows of one pair of an OpenACC file read by readOpenAccFile: a view on that one reader, no
/// parsing of its own. A row is used when Time, both cars' Speed, Lat and Lon and their gap IVS are
/// numbers; other cars' cells do not matter, and Alt/E/N are optional (NaN where empty).
struct OpenAccPairTrack
{
  OpenAccPair pair;
  int year = 0, month = 0, day = 0;      ///< the file's Date line
  std::string angle_unit_note;           ///< the unit Lat/Lon were found in and why
  std::vector<OpenAccRow> rows;          ///< in file order
  std::vector<std::string> skipped_rows; ///< "path:line: why", one per row not used
  std::vector<std::string> notes;        ///< the file's notes and how the pair was chosen
  std::string error;                     ///< non-empty when the file or the pair cannot be used at all

  /// UTC midnight of the Date line, seconds since the Unix epoch.
  double dayStartUnixS() const;
  /// "BMW_I3 (2) behind SMART_TARGET (1)".
  std::string pairName() const;
};

/// The rows of this pair (one of availablePairs(file)); error set when a car has no Lat/Lon columns,
/// when fewer than two rows are usable (skipped_rows say why each is not), or when Time steps as no
/// receiver does (milliseconds), so that no empty or misdated log is written.
OpenAccPairTrack openAccPairTrack(const OpenAccFile& file, const OpenAccPair& pair);

/// readOpenAccFile + selectOpenAccPairs (one pair: the first by default, or a follower) +
/// openAccPairTrack; error set when the file or the pair cannot be read.
OpenAccPairTrack readOpenAccPairTrack(const std::string& path,
                                      const OpenAccPairSelector& selector = OpenAccPairSelector::first());

/// The fixes a receiver on one car of the pair (1 = leader, 2 = follower) would have sent:
/// - time: the file's Date plus its Time column (the common clock of both vehicles);
/// - position: Lat/Lon in degrees, altitude where the file has one;
/// - speed: the Doppler speed column;
/// - course: the geodesic azimuth between the neighbouring rows' Lat/Lon (central difference,
///   one-sided at the ends of a contiguous stretch). Lat/Lon rather than the file's E/N, since
///   the ENU plane's north drifts from true north away from its centre (0.2 deg 20 km east of
///   it at 45 deg N). Below 0.5 m/s, or under 5 cm of motion, no course is sent, as the
///   direction of motion is noise there;
/// - quality: 1 (autonomous GNSS): the file does not say; satellites, HDOP and sigmas unknown,
///   so not sent.
std::vector<GnssFix> openAccFixes(const OpenAccPairTrack& track, int vehicle);

/// Writes GGA + RMC per fix, CR LF terminated, at u-blox precision (see nmea_writer.h).
/// Returns false and sets error when the file cannot be written.
bool writeNmeaLog(const std::string& path, const std::vector<GnssFix>& fixes, const std::string& talker,
                  std::string& error);

}  // namespace acc
