#include "acc_identification/gnss/nmea_writer.h"
#include "acc_identification/model/angles.h"

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "acc_identification/gnss/nmea_fields.h"
#include "acc_identification/gnss/utc_date.h"

namespace acc
{
namespace
{
constexpr double kMpsToKnot = 3600.0 / 1852.0;

/// hhmmss.ss, rounded to the centisecond as a whole (so 59.996 s carries into the minute).
std::string formatTime(double gnss_time_s)
{
  if (!std::isfinite(gnss_time_s))
    return "";
  double time_of_day = std::fmod(gnss_time_s, kSecondsPerDay);
  if (time_of_day < 0.0)
    time_of_day += kSecondsPerDay;
  const auto centiseconds = static_cast<std::int64_t>(std::llround(time_of_day * 100.0)) % 8640000;
  char text[16];
  std::snprintf(text, sizeof text, "%02d%02d%02d.%02d", static_cast<int>(centiseconds / 360000),
                static_cast<int>(centiseconds / 6000 % 60), static_cast<int>(centiseconds / 100 % 60),
                static_cast<int>(centiseconds % 100));
  return text;
}

/// ddmm.mmmmm,N or dddmm.mmmmm,E, rounded to 1e-5 minute as a whole (no 60.00000 minutes).
std::string formatAngle(double degrees, int degree_digits, char positive, char negative)
{
  const auto units = static_cast<std::int64_t>(std::llround(std::fabs(degrees) * 60.0 * 1e5));  // 1e-5 minute
  const std::int64_t whole_degrees = units / 6000000;
  const std::int64_t minute_units = units % 6000000;
  char text[32];
  std::snprintf(text, sizeof text, "%0*lld%02lld.%05lld,%c", degree_digits, static_cast<long long>(whole_degrees),
                static_cast<long long>(minute_units / 100000), static_cast<long long>(minute_units % 100000),
                degrees < 0.0 ? negative : positive);
  return text;
}

std::string formatNumber(double value, int decimals)
{
  if (!std::isfinite(value))
    return "";
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

/// ddmmyy of the fix's UTC day.
std::string formatDate(const GnssFix& fix)
{
  if (!fix.has_date || !std::isfinite(fix.gnss_time_s))
    return "";
  // Inverse of daysFromCivil (H. Hinnant's civil_from_days).
  const std::int64_t z = static_cast<std::int64_t>(std::floor(fix.gnss_time_s / kSecondsPerDay)) + 719468;
  const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  const std::int64_t day = doy - (153 * mp + 2) / 5 + 1;
  const std::int64_t month = mp < 10 ? mp + 3 : mp - 9;
  const std::int64_t year = yoe + era * 400 + (month <= 2 ? 1 : 0);
  char text[16];
  std::snprintf(text, sizeof text, "%02d%02d%02d", static_cast<int>(day), static_cast<int>(month),
                static_cast<int>(year % 100));
  return text;
}

std::string withChecksum(const std::string& body) { return "$" + body + "*" + nmeaChecksum(body); }

std::string position(const GnssFix& fix)
{
  if (!fix.has(GnssFix::kValidPosition))
    return ",,,";
  return formatAngle(fix.latitude_deg, 2, 'N', 'S') + "," + formatAngle(fix.longitude_deg, 3, 'E', 'W');
}
}  // namespace

std::string nmeaChecksum(std::string_view body)
{
  static constexpr char kHex[] = "0123456789ABCDEF";
  const std::uint8_t sum = nmeaChecksumValue(body);
  return {kHex[sum >> 4], kHex[sum & 0xF]};
}

std::string formatGga(const GnssFix& fix, const std::string& talker)
{
  const bool has_position = fix.has(GnssFix::kValidPosition);
  const int quality = has_position ? (fix.fix_quality > 0 ? fix.fix_quality : 1) : 0;
  const std::string satellites =
      fix.has(GnssFix::kValidSatellites) ? formatNumber(fix.satellites_used, 0) : std::string();
  const bool has_altitude = has_position && fix.has(GnssFix::kValidAltitude);
  const std::string body = talker + "GGA," + formatTime(fix.gnss_time_s) + "," + position(fix) + "," +
                           std::to_string(quality) + "," + (satellites.size() == 1 ? "0" : "") + satellites + "," +
                           (fix.has(GnssFix::kValidHdop) ? formatNumber(fix.hdop, 2) : "") + "," +
                           (has_altitude ? formatNumber(fix.altitude_m, 1) : "") + ",M," +
                           (has_altitude ? formatNumber(fix.geoid_separation_m, 1) : "") + ",M,,";
  return withChecksum(body);
}

std::string formatRmc(const GnssFix& fix, const std::string& talker)
{
  const bool valid = fix.has(GnssFix::kValidPosition);
  // u-blox mode indicator: A autonomous, D differential, R/F RTK fixed/float, E dead reckoning.
  static constexpr char kMode[] = {'N', 'A', 'D', 'A', 'R', 'F', 'E'};
  const char mode = !valid ? 'N' : fix.fix_quality <= 6 ? kMode[fix.fix_quality == 0 ? 1 : fix.fix_quality] : 'A';
  const double course_deg = fix.course_rad * 180.0 / kPi;
  const std::string body =
      talker + "RMC," + formatTime(fix.gnss_time_s) + "," + (valid ? "A" : "V") + "," + position(fix) + "," +
      (valid && fix.has(GnssFix::kValidSpeed) ? formatNumber(fix.speed_over_ground_mps * kMpsToKnot, 3) : "") + "," +
      (valid && fix.has(GnssFix::kValidCourse) ? formatNumber(course_deg, 2) : "") + "," + formatDate(fix) + ",,," +
      mode + ",V";
  return withChecksum(body);
}

}  // namespace acc
