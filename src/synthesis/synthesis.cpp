#include "acc_identification/synthesis/synthesis.h"

#include <GeographicLib/LocalCartesian.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "acc_identification/gnss/utc_date.h"
#include "acc_identification/reproduction/lead_profiles.h"
#include "acc_identification/synthesis/road_centreline.h"

namespace acc
{
namespace
{
constexpr double kTwoPi = 6.283185307179586476925;
// Where the follower's front bumper starts along the road: room for its antenna behind it.
constexpr double kFollowerStart_m = 20.0;
// Below this speed a receiver sends no course (its direction of motion is noise), as u-blox do.
constexpr double kMinCourseSpeed_mps = 0.5;
// Noise streams of streamSeed(): one per receiver.
constexpr std::uint64_t kLeaderStream = 1;
constexpr std::uint64_t kFollowerStream = 2;

struct AntennaPath
{
  std::vector<double> distance_m;  ///< along the road
  std::vector<double> speed_mps;
};

/// One receiver's fixes from its antenna's path, with its own error sequence.
std::vector<GnssFix> receiverFixes(const AntennaPath& path, const RoadCentreline& road,
                                   const GeographicLib::LocalCartesian& plane, const SynthesisOptions& options,
                                   std::uint64_t stream)
{
  GnssErrorModel errors(options.errors, streamSeed(options.seed, stream));
  std::vector<GnssFix> fixes(path.distance_m.size());
  for (std::size_t k = 0; k < fixes.size(); ++k)
  {
    const RoadPoint point = road.at(path.distance_m[k]);
    const GnssEpochError error = errors.next(options.epoch_step_s);
    GnssFix& fix = fixes[k];
    fix.gnss_time_s = options.start_time_unix_s + static_cast<double>(k) * options.epoch_step_s;
    fix.has_date = true;
    fix.receive_time_s = fix.gnss_time_s;
    double height_m = 0.0;
    plane.Reverse(point.east_m + error.east_m, point.north_m + error.north_m, 0.0, fix.latitude_deg,
                  fix.longitude_deg, height_m);
    // The road is level: altitude is the start's (the tangent plane's rise over a few km is not
    // a height change of the road) plus the receiver's vertical error.
    fix.altitude_m = options.start_altitude_m + error.up_m;
    const double speed_mps = path.speed_mps[k];
    fix.speed_over_ground_mps = std::max(0.0, speed_mps + error.along_track_speed_mps);
    fix.fix_quality = 1;
    fix.satellites_used = static_cast<std::uint16_t>(options.satellites_used);
    fix.hdop = options.hdop;
    fix.valid_fields = GnssFix::kValidPosition | GnssFix::kValidAltitude | GnssFix::kValidSpeed |
                       GnssFix::kValidDate | GnssFix::kValidHdop | GnssFix::kValidSatellites;
    if (fix.speed_over_ground_mps >= kMinCourseSpeed_mps)
    {
      const double course = point.heading_rad + std::atan2(error.cross_track_speed_mps, std::max(speed_mps, 1e-3));
      fix.course_rad = std::fmod(std::fmod(course, kTwoPi) + kTwoPi, kTwoPi);
      fix.valid_fields |= GnssFix::kValidCourse;
    }
  }
  return fixes;
}

double geodesicAntennaGap(const RoadCentreline& road, const GeographicLib::LocalCartesian& plane, double leader_m,
                          double follower_m, const VehicleGeometry& geometry)
{
  double lat[2], lon[2], h = 0.0;
  const RoadPoint leader = road.at(leader_m);
  const RoadPoint follower = road.at(follower_m);
  plane.Reverse(leader.east_m, leader.north_m, 0.0, lat[0], lon[0], h);
  plane.Reverse(follower.east_m, follower.north_m, 0.0, lat[1], lon[1], h);
  return geodesicDistance(lat[0], lon[0], lat[1], lon[1]) - geometry.combinedOffset();
}
}  // namespace

SynthesizedDrive synthesizeDrive(const SynthesisOptions& options)
{
  SynthesizedDrive drive;
  std::vector<double> lead = leadProfile(options.profile, options.epoch_step_s);
  if (options.duration_s > 0.0)
  {
    const auto epochs = static_cast<std::size_t>(std::floor(options.duration_s / options.epoch_step_s + 1e-9)) + 1;
    if (epochs < 2)
      throw std::invalid_argument("the duration must cover at least two epochs");
    lead.resize(std::min(lead.size(), epochs));
  }
  drive.truth = simulateDriveTruth(lead, options.epoch_step_s, options.parameters, options.effects, kFollowerStart_m);
  const DriveTruth& truth = drive.truth;

  AntennaPath leader, follower;
  leader.speed_mps = truth.run.leader_speed_mps;
  follower.speed_mps = truth.run.follower_speed_mps;
  for (std::size_t k = 0; k < truth.run.size(); ++k)
  {
    leader.distance_m.push_back(truth.leader_rear_bumper_m[k] + options.geometry.leader_antenna_to_rear_bumper_m);
    follower.distance_m.push_back(truth.follower_front_bumper_m[k] - options.geometry.follower_antenna_to_front_bumper_m);
  }
  const double road_length_m = *std::max_element(leader.distance_m.begin(), leader.distance_m.end()) + 100.0;
  const RoadCentreline road(plausibleRoadPattern(), road_length_m, options.start_heading_rad);
  const GeographicLib::LocalCartesian plane(options.start_latitude_deg, options.start_longitude_deg,
                                            options.start_altitude_m);

  drive.leader_fixes = receiverFixes(leader, road, plane, options, kLeaderStream);
  drive.follower_fixes = receiverFixes(follower, road, plane, options, kFollowerStream);
  for (std::size_t k = 0; k < truth.run.size(); ++k)
    drive.straight_line_gap_m.push_back(
        geodesicAntennaGap(road, plane, leader.distance_m[k], follower.distance_m[k], options.geometry));
  return drive;
}

bool parseUtcTime(const std::string& text, double* unix_s)
{
  int year = 0, month = 0, day = 0, hour = 0, minute = 0, consumed = 0;
  double second = 0.0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%lf%n", &year, &month, &day, &hour, &minute, &second,
                  &consumed) != 6)
    return false;
  const std::string rest = text.substr(static_cast<std::size_t>(consumed));
  if (!(rest.empty() || rest == "Z") || month < 1 || day < 1 || !isValidDate(year, month, day) || hour < 0 ||
      hour > 23 || minute < 0 || minute > 59 || !(second >= 0.0 && second < 60.0))
    return false;
  *unix_s = static_cast<double>(daysFromCivil(year, month, day)) * kSecondsPerDay + hour * 3600.0 + minute * 60.0 +
            second;
  return true;
}

bool fitsNmeaYears(double unix_s)
{
  const double first_s = static_cast<double>(daysFromCivil(kNmeaFirstYear, 1, 1)) * kSecondsPerDay;
  const double end_s = static_cast<double>(daysFromCivil(kNmeaFirstYear + 100, 1, 1)) * kSecondsPerDay;
  return unix_s >= first_s && unix_s < end_s;
}

std::string readStartTime(const std::string& text, double* unix_s)
{
  if (!parseUtcTime(text, unix_s))
    return "--start-time '" + text + "' is not YYYY-MM-DDThh:mm:ss[Z] (UTC)";
  if (!fitsNmeaYears(*unix_s))
    return "--start-time '" + text + "' is outside " + std::to_string(kNmeaFirstYear) + "-" +
           std::to_string(kNmeaFirstYear + 99) +
           ": NMEA writes two-digit years, which readers take as the GPS era's, so the logs and the bag would be " +
           "stamped a century off";
  return "";
}

}  // namespace acc
