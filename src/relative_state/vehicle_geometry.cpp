#include <acc_identification/relative_state/vehicle_geometry.h>
#include <acc_identification/model/angles.h>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace acc
{
namespace
{

struct PlanePoint
{
  double east_m;
  double north_m;
};

double planeDistance(const PlanePoint& a, const PlanePoint& b) { return std::hypot(b.east_m - a.east_m, b.north_m - a.north_m); }
}  // namespace

std::string geometryFromOffsets(const AntennaOffsets& offsets, VehicleGeometry& geometry)
{
  const bool combined = !std::isnan(offsets.combined_m);
  const bool leader = !std::isnan(offsets.leader_antenna_to_rear_bumper_m);
  const bool follower = !std::isnan(offsets.follower_antenna_to_front_bumper_m);
  if (combined && (leader || follower))
    return "give the antennas' place once: the combined antenna offset or the two antenna-to-bumper offsets, not both";
  if (!combined && !(leader && follower))
    return leader || follower ? "the two antenna-to-bumper offsets go together: give both, or the combined offset"
                              : "say where the antennas are, as the combined antenna offset or the two antenna-to-bumper "
                                "offsets: the gap, and so eta, moves by any error in them";
  const std::array<double, 3> given{offsets.combined_m, offsets.leader_antenna_to_rear_bumper_m,
                                    offsets.follower_antenna_to_front_bumper_m};
  for (double offset_m : given)
    if (!std::isnan(offset_m) && !(std::abs(offset_m) <= kMaxAntennaOffsetM))
    {
      std::ostringstream refusal;
      refusal << "an antenna offset of " << offset_m << " m is not between -1000 and 1000 m";
      return refusal.str();
    }
  // The combined offset all on one side: only the sum enters the gap.
  geometry = combined ? VehicleGeometry{offsets.combined_m, 0.0}
                      : VehicleGeometry{offsets.leader_antenna_to_rear_bumper_m, offsets.follower_antenna_to_front_bumper_m};
  return "";
}

double geodesicDistance(double latitude1_deg, double longitude1_deg, double latitude2_deg, double longitude2_deg)
{
  double distance_m = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(latitude1_deg, longitude1_deg, latitude2_deg, longitude2_deg, distance_m);
  return distance_m;
}

double straightLineGap(const GnssFix& leader, const GnssFix& follower, const VehicleGeometry& geometry)
{
  return geodesicDistance(leader.latitude_deg, leader.longitude_deg, follower.latitude_deg, follower.longitude_deg) -
         geometry.combinedOffset();
}

double gapSigma(const GnssFix& leader, const GnssFix& follower)
{
  double distance_m = 0.0, azimuth1_deg = 0.0, azimuth2_deg = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(follower.latitude_deg, follower.longitude_deg, leader.latitude_deg,
                                           leader.longitude_deg, distance_m, azimuth1_deg, azimuth2_deg);
  double c = std::cos(azimuth1_deg * kDegToRad), s = std::sin(azimuth1_deg * kDegToRad);
  auto projected = [c, s](const GnssFix& fix) {
    return c * c * fix.latitude_sigma_m * fix.latitude_sigma_m + s * s * fix.longitude_sigma_m * fix.longitude_sigma_m;
  };
  return std::sqrt(projected(leader) + projected(follower));  // NaN propagates when a sigma is missing
}

LeaderTrack::LeaderTrack(double min_spacing_m, double max_length_m, double max_lateral_offset_m,
                         double max_fix_gap_s)
  : min_spacing_m_(min_spacing_m)
  , max_length_m_(max_length_m)
  , max_lateral_offset_m_(max_lateral_offset_m)
  , max_fix_gap_s_(max_fix_gap_s)
{
}

void LeaderTrack::clear()
{
  points_.clear();
  length_m_ = 0.0;
  newest_fix_s_ = std::numeric_limits<double>::quiet_NaN();
}

void LeaderTrack::add(const GnssFix& leader)
{
  if (leader.gnss_time_s - newest_fix_s_ > max_fix_gap_s_)
    clear();  // a hole in the leader's fixes (false while there is no fix yet: NaN compares false)
  if (!(leader.gnss_time_s <= newest_fix_s_))
    newest_fix_s_ = leader.gnss_time_s;
  Point point{leader.gnss_time_s, leader.latitude_deg, leader.longitude_deg};
  if (points_.empty())
  {
    points_.push_back(point);
    return;
  }
  const Point& last = points_.back();
  if (point.time_s <= last.time_s)
    return;
  double step_m = geodesicDistance(last.latitude_deg, last.longitude_deg, point.latitude_deg, point.longitude_deg);
  if (step_m < min_spacing_m_)
    return;
  points_.push_back(point);
  length_m_ += step_m;
  trim();
}

void LeaderTrack::trim()
{
  while (points_.size() > 2)
  {
    double first_step_m = geodesicDistance(points_[0].latitude_deg, points_[0].longitude_deg, points_[1].latitude_deg,
                                           points_[1].longitude_deg);
    if (length_m_ - first_step_m < max_length_m_)
      break;
    length_m_ -= first_step_m;
    points_.pop_front();
  }
}

// In a local tangent plane at the follower (flat to millimetres over a few hundred metres):
// project the follower on the nearest segment of the path, then walk the path to the leader.
std::optional<double> LeaderTrack::alongTrackDistance(const GnssFix& leader_now, const GnssFix& follower,
                                                      std::string* why_not) const
{
  auto fail = [why_not](const std::string& reason) -> std::optional<double> {
    if (why_not)
      *why_not = reason;
    return std::nullopt;
  };
  GeographicLib::LocalCartesian plane(follower.latitude_deg, follower.longitude_deg, 0.0);
  std::vector<PlanePoint> path;
  for (const Point& point : points_)
  {
    if (point.time_s >= leader_now.gnss_time_s)
      break;
    double east = 0.0, north = 0.0, up = 0.0;
    plane.Forward(point.latitude_deg, point.longitude_deg, 0.0, east, north, up);
    path.push_back({east, north});
  }
  double east = 0.0, north = 0.0, up = 0.0;
  plane.Forward(leader_now.latitude_deg, leader_now.longitude_deg, 0.0, east, north, up);
  path.push_back({east, north});
  if (path.size() < 2)
    return fail("no leader path yet");

  const PlanePoint origin{0.0, 0.0};
  double best_lateral_m = std::numeric_limits<double>::infinity();
  std::size_t best_segment = 0;
  double best_fraction = 0.0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
  {
    double de = path[i + 1].east_m - path[i].east_m, dn = path[i + 1].north_m - path[i].north_m;
    double length2 = de * de + dn * dn;
    double fraction = length2 > 0.0 ? -(path[i].east_m * de + path[i].north_m * dn) / length2 : 0.0;
    fraction = std::min(1.0, std::max(0.0, fraction));
    PlanePoint foot{path[i].east_m + fraction * de, path[i].north_m + fraction * dn};
    double lateral_m = planeDistance(origin, foot);
    if (lateral_m < best_lateral_m)
    {
      best_lateral_m = lateral_m;
      best_segment = i;
      best_fraction = fraction;
    }
  }
  if (best_segment == 0 && best_fraction <= 0.0)
    return fail("the leader's path does not reach back to the follower");
  if (best_lateral_m > max_lateral_offset_m_)
    return fail("the follower is " + std::to_string(best_lateral_m) + " m off the leader's path");
  const PlanePoint& a = path[best_segment];
  const PlanePoint& b = path[best_segment + 1];
  double along_m = (1.0 - best_fraction) * planeDistance(a, b);
  for (std::size_t i = best_segment + 1; i + 1 < path.size(); ++i)
    along_m += planeDistance(path[i], path[i + 1]);
  return along_m;
}

}  // namespace acc
