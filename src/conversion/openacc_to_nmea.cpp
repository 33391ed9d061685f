#include <acc_identification/conversion/openacc_to_nmea.h>

#include <acc_identification/gnss/nmea_writer.h>

#include <GeographicLib/Geodesic.hpp>

#include <cmath>
#include <fstream>

namespace acc
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;
// Rows further apart than this are not neighbours (the database removed tolls and tunnels).
constexpr double kMaxNeighbourSpacing_s = 0.25;
constexpr double kMinCourseSpeed_mps = 0.5;
constexpr double kMinCourseMotion_m = 0.05;

bool neighbours(const OpenAccRow& a, const OpenAccRow& b)
{
  double step = b.time_of_day_s - a.time_of_day_s;
  return step > 0.0 && step <= kMaxNeighbourSpacing_s;
}

/// Course over ground at row i [rad, clockwise from true north], NaN when not meaningful.
double courseAt(const std::vector<OpenAccRow>& rows, std::size_t i, int v)
{
  std::size_t from = (i > 0 && neighbours(rows[i - 1], rows[i])) ? i - 1 : i;
  std::size_t to = (i + 1 < rows.size() && neighbours(rows[i], rows[i + 1])) ? i + 1 : i;
  if (from == to || rows[i].speed_mps[v] < kMinCourseSpeed_mps)
    return std::nan("");
  double distance = 0, azimuth1 = 0, azimuth2 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(rows[from].latitude_rad[v] * kRadToDeg, rows[from].longitude_rad[v] * kRadToDeg,
                                           rows[to].latitude_rad[v] * kRadToDeg, rows[to].longitude_rad[v] * kRadToDeg,
                                           distance, azimuth1, azimuth2);
  if (distance < kMinCourseMotion_m)
    return std::nan("");
  // A central difference over 0.2 s (at most 9 m) is straight: the azimuth at its start will do.
  double azimuth_deg = to == i ? azimuth2 : azimuth1;
  return std::fmod(azimuth_deg / kRadToDeg + 2.0 * kPi, 2.0 * kPi);
}
}  // namespace

std::vector<GnssFix> openAccFixes(const OpenAccTrajectories& file, int vehicle)
{
  const int v = vehicle == 1 ? 0 : 1;
  std::vector<GnssFix> fixes;
  fixes.reserve(file.rows.size());
  const double day_start_s = file.dayStartUnixS();
  for (std::size_t i = 0; i < file.rows.size(); ++i)
  {
    const OpenAccRow& row = file.rows[i];
    GnssFix fix;
    fix.gnss_time_s = day_start_s + row.time_of_day_s;
    fix.has_date = true;
    fix.receive_time_s = fix.gnss_time_s;
    fix.latitude_deg = row.latitude_rad[v] * kRadToDeg;
    fix.longitude_deg = row.longitude_rad[v] * kRadToDeg;
    fix.speed_over_ground_mps = row.speed_mps[v];
    fix.course_rad = courseAt(file.rows, i, v);
    fix.fix_quality = 1;
    fix.valid_fields = GnssFix::kValidPosition | GnssFix::kValidSpeed | GnssFix::kValidDate;
    if (std::isfinite(fix.course_rad))
      fix.valid_fields |= GnssFix::kValidCourse;
    if (std::isfinite(row.altitude_m[v]))
    {
      fix.altitude_m = row.altitude_m[v];
      fix.valid_fields |= GnssFix::kValidAltitude;
    }
    fixes.push_back(fix);
  }
  return fixes;
}

bool writeNmeaLog(const std::string& path, const std::vector<GnssFix>& fixes, const std::string& talker,
                  std::string& error)
{
  std::ofstream out(path, std::ios::binary);
  if (!out)
  {
    error = "cannot write " + path;
    return false;
  }
  for (const GnssFix& fix : fixes)
    out << formatGga(fix, talker) << "\r\n" << formatRmc(fix, talker) << "\r\n";
  out.flush();
  if (!out)
  {
    error = "write error on " + path;
    return false;
  }
  return true;
}

}  // namespace acc
