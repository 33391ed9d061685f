#pragma once

#include <acc_identification/gnss/gnss_fix.h>

#include <cmath>
#include <cstddef>
#include <deque>
#include <limits>
#include <optional>
#include <string>

namespace acc
{
/// Where the GNSS antennas sit on the two cars, for the bumper-to-bumper gap [m].
/// Either the two offsets, or one combined offset in leader_antenna_to_rear_bumper_m with the
/// other 0 (the OpenACC Casale cars: 5.60 m combined).
/// An antenna offset beyond this is no car's [m]: the bound of every reader of the geometry.
constexpr double kMaxAntennaOffsetM = 1e3;

struct VehicleGeometry
{
  double leader_antenna_to_rear_bumper_m = 0.0;
  double follower_antenna_to_front_bumper_m = 0.0;

  double combinedOffset() const { return leader_antenna_to_rear_bumper_m + follower_antenna_to_front_bumper_m; }
};

/// The antennas' place as a user gives it (a node's parameters, a tool's options): the combined
/// offset (antenna to antenna minus bumper to bumper), or the two antenna-to-bumper offsets [m].
/// NaN is "not given".
struct AntennaOffsets
{
  double combined_m = NAN;
  double leader_antenna_to_rear_bumper_m = NAN;
  double follower_antenna_to_front_bumper_m = NAN;

  bool anyGiven() const
  {
    return !std::isnan(combined_m) || !std::isnan(leader_antenna_to_rear_bumper_m) ||
           !std::isnan(follower_antenna_to_front_bumper_m);
  }
};

/// The one rule for the antennas' place, for every reader of it: the combined offset alone, or the
/// two antenna-to-bumper offsets together, each within kMaxAntennaOffsetM. Empty when geometry is
/// set; otherwise what is missing, given twice or out of bounds. The gap, and so eta, moves by any
/// error in them, so there is no default to fall back on.
std::string geometryFromOffsets(const AntennaOffsets& offsets, VehicleGeometry& geometry);

/// Geodesic distance on WGS84 between two points [deg] (GeographicLib, accurate to nanometres).
double geodesicDistance(double latitude1_deg, double longitude1_deg, double latitude2_deg, double longitude2_deg);

/// The straight-line bumper-to-bumper gap: antenna-to-antenna geodesic distance less the
/// geometry. This is what the paper and OpenACC use.
double straightLineGap(const GnssFix& leader, const GnssFix& follower, const VehicleGeometry& geometry);

/// 1-sigma of the antenna-to-antenna distance from the fixes' GST sigmas, projected on the line
/// of sight between the antennas; NaN when either fix has no sigmas.
double gapSigma(const GnssFix& leader, const GnssFix& follower);

/// The leader's recent path, for the gap measured along the road on curves. Points are kept
/// at least min_spacing_m apart so that receiver noise at low speed does not add path length.
/// Fixes more than max_fix_gap_s apart start the path anew: where the leader drove unseen, a
/// straight segment across the hole is no road (ZalaZone's handling course: a 103 s hole in a
/// curve gave along-track gaps 4 m off, marked valid).
class LeaderTrack
{
public:
  LeaderTrack(double min_spacing_m = 2.0, double max_length_m = 500.0, double max_lateral_offset_m = 5.0,
              double max_fix_gap_s = std::numeric_limits<double>::infinity());

  /// Appends the leader's fix (in time order; an older fix than the newest is ignored).
  void add(const GnssFix& leader);
  void clear();
  std::size_t size() const { return points_.size(); }

  /// Antenna-to-antenna distance along the leader's path from the follower's position to the
  /// leader's position at the pair's time. nullopt, with the reason in why_not, when the path
  /// does not reach back to the follower or the follower is further than max_lateral_offset_m
  /// from it (a lane change, a different road).
  std::optional<double> alongTrackDistance(const GnssFix& leader_now, const GnssFix& follower,
                                           std::string* why_not = nullptr) const;

private:
  struct Point
  {
    double time_s;
    double latitude_deg;
    double longitude_deg;
  };
  void trim();

  double min_spacing_m_;
  double max_length_m_;
  double max_lateral_offset_m_;
  double max_fix_gap_s_;
  double newest_fix_s_ = std::numeric_limits<double>::quiet_NaN();  ///< the newest fix offered, kept or not
  std::deque<Point> points_;
  double length_m_ = 0.0;
};

}  // namespace acc
