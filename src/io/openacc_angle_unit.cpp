#include "openacc_text.h"

#include "acc_identification/model/angles.h"
#include "acc_identification/model/number_text.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

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

/// The largest |Lat| and |Lon| over the finite fixes of the cars with Lat/Lon columns.
struct LatLonRange
{
  double max_latitude = 0.0, max_longitude = 0.0;
  std::size_t values = 0, columns = 0;

  std::string describe() const
  {
    return "|Lat| up to " + significant(max_latitude, 6) + ", |Lon| up to " + significant(max_longitude, 6);
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

/// Whether fixes i-1 and i of the car are consecutive (close in time) with every value finite.
bool isCheckableStep(const OpenAccFile& file, const OpenAccVehicle& vehicle, std::size_t i)
{
  const double dt = file.time_s[i] - file.time_s[i - 1];
  const double values_of_step[] = {vehicle.latitude_deg[i - 1], vehicle.longitude_deg[i - 1],
                                   vehicle.latitude_deg[i],     vehicle.longitude_deg[i],
                                   vehicle.east_m[i - 1],       vehicle.north_m[i - 1],
                                   vehicle.east_m[i],           vehicle.north_m[i]};
  return dt > 0.0 && dt <= kMaxConsecutiveStepS &&
         std::all_of(std::begin(values_of_step), std::end(values_of_step), [](double v) { return std::isfinite(v); });
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

}  // namespace

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
  else if (range.max_latitude > kPi / 2.0 || range.max_longitude > kPi)
  {
    file.angle_unit = OpenAccAngleUnit::kDegrees;
    file.angle_unit_reason = "Lat/Lon in degrees: " + range.describe() +
                             ", beyond radians (|Lat| <= pi/2, |Lon| <= pi), although the database's notes say radians";
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
