#pragma once

#include <cstdint>
#include <limits>

namespace acc
{
/// One GNSS epoch as the library sees it (ROS-free twin of msg/GnssFix.msg). The driver
/// assembles it from one epoch's NMEA sentences; the relative-state pairing consumes it.
struct GnssFix
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  /// GNSS (UTC) time of the epoch [s]: seconds since the Unix epoch when has_date, else seconds
  /// since the UTC midnight of an unknown day (the day of the stream's first undated epoch: past
  /// a midnight it goes on above 86400 s, UtcDateTracker::undatedTimeS).
  double gnss_time_s = kNaN;
  bool has_date = false;
  double receive_time_s = kNaN;  ///< host clock when the epoch was completed [s]

  double latitude_deg = kNaN;
  double longitude_deg = kNaN;
  double altitude_m = kNaN;      ///< above mean sea level
  double speed_over_ground_mps = kNaN;
  double course_rad = kNaN;      ///< clockwise from true north, [0, 2 pi)

  std::uint8_t fix_quality = 0;  ///< GGA quality indicator (0 = invalid)
  std::uint16_t satellites_used = 0;
  double hdop = kNaN;
  double latitude_sigma_m = kNaN;   ///< 1-sigma from GST
  double longitude_sigma_m = kNaN;
  double altitude_sigma_m = kNaN;
  /// Geoid separation from GGA [m] (NaN when not sent): ellipsoid height = altitude_m + this.
  double geoid_separation_m = kNaN;

  /// Which fields hold data: the VALID_* bits of msg/GnssFix.msg, mirrored here.
  std::uint32_t valid_fields = 0;
  static constexpr std::uint32_t kValidPosition = 1;
  static constexpr std::uint32_t kValidAltitude = 2;
  static constexpr std::uint32_t kValidSpeed = 4;
  static constexpr std::uint32_t kValidCourse = 8;
  static constexpr std::uint32_t kValidDate = 16;
  static constexpr std::uint32_t kValidHdop = 32;
  static constexpr std::uint32_t kValidPositionSigma = 64;
  static constexpr std::uint32_t kValidSatellites = 128;

  bool has(std::uint32_t field) const { return (valid_fields & field) == field; }
};

}  // namespace acc
