#include "openacc_text.h"

#include "acc_identification/model/angles.h"
#include "acc_identification/model/number_text.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <cstdlib>
#include <sstream>
#include <tuple>

namespace acc
{
namespace openacc
{
namespace
{
constexpr double kEarthRadiusM = 6371000.0;
// Fixes further apart than this are not consecutive (holes, cuts) for the unit check.
constexpr double kMaxConsecutiveStepS = 1.0;
// Below this much motion by E/N, the unit check cannot tell radians from degrees.
constexpr double kMinMotionForUnitCheckM = 1.0;

/// The small-distance length of the step between two fixes, the angles read in the given unit.
double stepLengthM(double lat0, double lon0, double lat1, double lon1, double to_radians)
{
  const double dlat = (lat1 - lat0) * to_radians;
  const double dlon = (lon1 - lon0) * to_radians * std::cos(lat0 * to_radians);
  return kEarthRadiusM * std::hypot(dlat, dlon);
}

/// Whether a fix can be in radians: |Lat| <= pi/2 and |Lon| <= pi (it then fits both units).
bool fitsRadians(double latitude, double longitude)
{
  return std::abs(latitude) <= kPi / 2.0 && std::abs(longitude) <= kPi;
}

/// The largest |Lat| and |Lon| over the finite fixes of the cars with Lat/Lon columns, and how
/// many of those fixes cannot be radians.
struct LatLonRange
{
  double max_latitude = 0.0, max_longitude = 0.0;
  std::size_t values = 0, columns = 0, beyond_radians = 0;

  std::string describe() const
  {
    std::string text = "|Lat| up to " + significant(max_latitude, 6) + ", |Lon| up to " + significant(max_longitude, 6);
    if (beyond_radians > 0 && beyond_radians < values)
      text += "; " + std::to_string(beyond_radians) + " of " + std::to_string(values) + " fixes beyond radians";
    return text;
  }
};

LatLonRange latLonRange(const OpenAccFile& file)
{
  LatLonRange range;
  for (const OpenAccVehicle& vehicle : file.vehicles)
  {
    if (!vehicle.has_lat_lon)
    {
      continue;
    }
    ++range.columns;
    for (std::size_t i = 0; i < file.rows(); ++i)
    {
      if (std::isfinite(vehicle.latitude_deg[i]) && std::isfinite(vehicle.longitude_deg[i]))
      {
        ++range.values;
        range.max_latitude = std::max(range.max_latitude, std::abs(vehicle.latitude_deg[i]));
        range.max_longitude = std::max(range.max_longitude, std::abs(vehicle.longitude_deg[i]));
        range.beyond_radians += fitsRadians(vehicle.latitude_deg[i], vehicle.longitude_deg[i]) ? 0 : 1;
      }
    }
  }
  return range;
}

/// How far the cars move over consecutive fixes: by E/N, and by Lat/Lon read either way.
struct ConsecutiveMotion
{
  double en_m = 0.0, as_radians_m = 0.0, as_degrees_m = 0.0;
  std::size_t steps = 0;
};

/// Whether fixes i-1 and i of the car are consecutive (close in time) with every value finite and
/// both fixes fitting both units (a stray cell beyond radians would outweigh every true step).
bool isCheckableStep(const OpenAccFile& file, const OpenAccVehicle& vehicle, std::size_t i)
{
  const double dt = file.time_s[i] - file.time_s[i - 1];
  const double values_of_step[] = {vehicle.latitude_deg[i - 1], vehicle.longitude_deg[i - 1],
                                   vehicle.latitude_deg[i],     vehicle.longitude_deg[i],
                                   vehicle.east_m[i - 1],       vehicle.north_m[i - 1],
                                   vehicle.east_m[i],           vehicle.north_m[i]};
  return dt > 0.0 && dt <= kMaxConsecutiveStepS &&
         std::all_of(std::begin(values_of_step), std::end(values_of_step), [](double v) { return std::isfinite(v); }) &&
         fitsRadians(vehicle.latitude_deg[i - 1], vehicle.longitude_deg[i - 1]) &&
         fitsRadians(vehicle.latitude_deg[i], vehicle.longitude_deg[i]);
}

ConsecutiveMotion consecutiveMotion(const OpenAccFile& file)
{
  ConsecutiveMotion motion;
  for (const OpenAccVehicle& v : file.vehicles)
  {
    if (!v.has_lat_lon || !v.has_east_north)
    {
      continue;
    }
    for (std::size_t i = 1; i < file.rows(); ++i)
    {
      if (!isCheckableStep(file, v, i))
      {
        continue;
      }
      ++motion.steps;
      motion.en_m += std::hypot(v.east_m[i] - v.east_m[i - 1], v.north_m[i] - v.north_m[i - 1]);
      motion.as_radians_m +=
          stepLengthM(v.latitude_deg[i - 1], v.longitude_deg[i - 1], v.latitude_deg[i], v.longitude_deg[i], 1.0);
      motion.as_degrees_m += stepLengthM(v.latitude_deg[i - 1], v.longitude_deg[i - 1], v.latitude_deg[i],
                                         v.longitude_deg[i], kPi / 180.0);
    }
  }
  return motion;
}

/// Values that fit both units: the unit in which the fixes move as far as E/N says, and why.
void chooseUnitByMotion(OpenAccFile& file, const std::string& range)
{
  const ConsecutiveMotion motion = consecutiveMotion(file);
  file.angle_unit = OpenAccAngleUnit::kRadians;
  if (motion.steps == 0)
  {
    file.angle_unit_reason = "Lat/Lon in radians, the database's unit: the values fit both units (" + range +
                             ") and there are no consecutive fixes with E/N to check them against";
    return;
  }
  if (motion.en_m < kMinMotionForUnitCheckM)
  {
    file.angle_unit_reason = "Lat/Lon in radians, the database's unit: the values fit both units (" + range +
                             ") and the cars move only " + significant(motion.en_m, 3) +
                             " m by E/N, too little to check them";
    return;
  }
  const bool degrees = std::abs(std::log(motion.as_degrees_m / motion.en_m)) <
                       std::abs(std::log(motion.as_radians_m / motion.en_m));
  file.angle_unit = degrees ? OpenAccAngleUnit::kDegrees : OpenAccAngleUnit::kRadians;
  const double chosen_m = degrees ? motion.as_degrees_m : motion.as_radians_m;
  std::ostringstream reason;
  reason << "Lat/Lon in " << (degrees ? "degrees" : "radians") << ": the values fit both units (" << range
         << "); over " << motion.steps << " consecutive fixes the cars move " << significant(motion.en_m, 6)
         << " m by their E/N columns, " << significant(motion.as_radians_m, 6) << " m by Lat/Lon read as radians, "
         << significant(motion.as_degrees_m, 6) << " m read as degrees";
  if (chosen_m > 2.0 * motion.en_m || chosen_m < 0.5 * motion.en_m)
  {
    reason << " (neither unit matches E/N within a factor 2: check the file)";
  }
  file.angle_unit_reason = reason.str();
}

void convertRadiansToDegrees(OpenAccFile& file)
{
  for (OpenAccVehicle& vehicle : file.vehicles)
  {
    for (std::vector<double>* angles : {&vehicle.latitude_deg, &vehicle.longitude_deg})
    {
      for (double& value : *angles)
      {
        value *= kRadToDeg;
      }
    }
  }
}

/// One impossible angle (in degrees by now) as a bad cell, described in the file's unit.
OpenAccBadCell impossibleAngle(const OpenAccFile& file, std::size_t row, const std::string& column, double value_deg)
{
  const bool radians = file.angle_unit == OpenAccAngleUnit::kRadians;
  const double as_written = radians ? value_deg / kRadToDeg : value_deg;
  const std::string what = column.compare(0, 3, "Lat") == 0 ? "a latitude" : "a longitude";
  return {row, file.line[row], column, significant(as_written, 10),
          "not " + what + " in " + (radians ? "radians" : "degrees") + ", the file's unit"};
}

/// The line number a problem entry ("path:line: why") names; problems are in line order.
std::size_t problemLine(const OpenAccFile& file, const std::string& problem)
{
  return std::strtoul(problem.c_str() + file.path.size() + 1, nullptr, 10);
}

/// Lists new bad cells (in row order) where the reader lists its own: each row's cells in its one
/// problem line (a row that already had one gets them appended), bad_cells kept in row order. One
/// pass over each list, so a file of many bad angles costs no more than its reading.
void listBadCells(OpenAccFile& file, const std::vector<OpenAccBadCell>& found)
{
  std::vector<OpenAccBadCell> cells;
  cells.reserve(file.bad_cells.size() + found.size());
  std::merge(file.bad_cells.begin(), file.bad_cells.end(), found.begin(), found.end(), std::back_inserter(cells),
             [](const OpenAccBadCell& a, const OpenAccBadCell& b) { return a.row < b.row; });
  std::vector<std::string> problems;
  problems.reserve(file.problems.size() + found.size());
  auto listed = file.problems.begin();
  for (auto cell = found.begin(); cell != found.end();)
  {
    const auto row_end = std::find_if(cell, found.end(), [&](const OpenAccBadCell& c) { return c.row != cell->row; });
    std::vector<std::string> described;
    for (auto c = cell; c != row_end; ++c)
    {
      described.push_back(c->describe() + " (NaN)");
      ++file.bad_cells_by_column[c->column];
    }
    for (; listed != file.problems.end() && problemLine(file, *listed) < cell->line; ++listed)
      problems.push_back(*listed);
    const bool row_listed = listed != file.problems.end() && problemLine(file, *listed) == cell->line;
    file.bad_rows += row_listed ? 0 : 1;  // a listed row is already counted
    if (row_listed)
      problems.push_back(*listed++ + "; " + join(described, "; "));
    else
      problems.push_back(file.path + ":" + std::to_string(cell->line) + ": " + join(described, "; "));
    cell = row_end;
  }
  problems.insert(problems.end(), listed, file.problems.end());
  file.problems = std::move(problems);
  file.bad_cells = std::move(cells);
}

}  // namespace

void setAsideImpossibleAngles(OpenAccFile& file)
{
  std::vector<OpenAccBadCell> found;
  for (OpenAccVehicle& vehicle : file.vehicles)
  {
    if (!vehicle.has_lat_lon)
      continue;
    const std::string n = std::to_string(vehicle.position);
    const std::string lat = "Lat" + n;
    const std::string lon = "Lon" + n;
    for (std::size_t i = 0; i < file.rows(); ++i)
    {
      for (auto [column, value, limit_deg] : {std::make_tuple(&lat, &vehicle.latitude_deg[i], 90.0),
                                              std::make_tuple(&lon, &vehicle.longitude_deg[i], 180.0)})
      {
        if (std::abs(*value) > limit_deg)
        {
          found.push_back(impossibleAngle(file, i, *column, *value));
          *value = std::numeric_limits<double>::quiet_NaN();
        }
      }
    }
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const OpenAccBadCell& a, const OpenAccBadCell& b) { return a.row < b.row; });
  listBadCells(file, found);
}

void detectAngleUnit(OpenAccFile& file)
{
  const LatLonRange range = latLonRange(file);
  if (range.columns == 0 || range.values == 0)
  {
    file.angle_unit = OpenAccAngleUnit::kRadians;
    file.angle_unit_reason = std::string("Lat/Lon: ") +
                             (range.columns == 0 ? "no Lat/Lon columns" : "no Lat/Lon values") +
                             " (radians assumed, the database's unit; nothing to convert)";
  }
  else if (2 * range.beyond_radians > range.values)
  {
    // Most fixes, not the largest value: one corrupt cell must not decide the unit of every fix.
    file.angle_unit = OpenAccAngleUnit::kDegrees;
    file.angle_unit_reason = "Lat/Lon in degrees: " + range.describe() + ", " +
                             (range.beyond_radians == range.values ? "every fix" : "most fixes") +
                             " beyond radians (|Lat| <= pi/2, |Lon| <= pi), although the database's notes say radians";
  }
  else
  {
    chooseUnitByMotion(file, range.describe());
  }
  if (file.angle_unit == OpenAccAngleUnit::kRadians)
  {
    convertRadiansToDegrees(file);
  }
}


}  // namespace openacc
}  // namespace acc
