#pragma once

#include <cstdint>
#include <limits>
#include <optional>

namespace acc
{
/// The sentence types the parser understands.
enum class NmeaSentenceType : std::uint8_t
{
  kGga,     ///< position, altitude, fix quality, satellites, HDOP
  kRmc,     ///< position, speed, course, date
  kVtg,     ///< speed and course (no time)
  kGst,     ///< position error statistics
  kZda,     ///< time and date
  kPubx00,  ///< u-blox proprietary position / velocity / accuracy
  kGns,     ///< position, altitude, per-constellation mode, satellites, HDOP (multi-GNSS GGA)
  kGll,     ///< position, time, status
};

const char* toString(NmeaSentenceType type);

/// What one sentence said, in SI units. NaN / nullopt: the sentence did not carry that field (or
/// carried it empty, or flagged it invalid).
struct NmeaSentence
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  NmeaSentenceType type = NmeaSentenceType::kGga;
  char talker[2] = {'G', 'P'};   ///< "PU" for PUBX

  double time_of_day_s = kNaN;   ///< UTC seconds since midnight
  std::optional<std::int64_t> day;  ///< UTC days since 1970-01-01 (RMC, ZDA)

  double latitude_deg = kNaN;
  double longitude_deg = kNaN;
  double altitude_m = kNaN;          ///< above mean sea level
  double geoid_separation_m = kNaN;  ///< ellipsoid height = altitude + separation
  double speed_mps = kNaN;
  double course_rad = kNaN;          ///< clockwise from true north, [0, 2 pi)

  int fix_quality = -1;              ///< GGA scale (0..8); -1 when the sentence does not say
  int satellites = -1;
  double hdop = kNaN;
  double latitude_sigma_m = kNaN;
  double longitude_sigma_m = kNaN;
  double altitude_sigma_m = kNaN;
};

}  // namespace acc
