#pragma once

#include <vector>

namespace acc
{
/// One piece of a road: a straight (curvature 0) or a constant-radius arc.
struct RoadSegment
{
  double length_m = 0.0;
  double curvature_per_m = 0.0;  ///< 1 / radius; > 0 turns right (clockwise seen from above)
};

/// A point of the centreline in a local east-north plane.
struct RoadPoint
{
  double east_m = 0.0;
  double north_m = 0.0;
  double heading_rad = 0.0;  ///< direction of travel, clockwise from north (as a GNSS course)
};

/// A road centreline made of straights and arcs, the pattern repeated until the road is long
/// enough. Positions are exact (closed-form arcs), so a car's position along the road maps to
/// the plane without integration error.
class RoadCentreline
{
public:
  /// Throws std::invalid_argument when the pattern is empty or has a segment of length <= 0.
  RoadCentreline(const std::vector<RoadSegment>& pattern, double length_m, double start_heading_rad);

  /// The point distance_m along the road from its start; beyond either end the road goes on
  /// straight (so antennas behind the start are still placed).
  RoadPoint at(double distance_m) const;
  double lengthM() const;

private:
  struct Placed
  {
    double start_distance_m;
    RoadSegment segment;
    RoadPoint start;
  };
  static RoadPoint advance(const RoadPoint& start, const RoadSegment& segment, double distance_m);

  std::vector<Placed> segments_;
};

/// A plausible rural main road: 300-600 m straights between arcs of 500-900 m radius turning
/// 15-50 degrees, left and right so that the road does not circle back. At 31 m/s (70 mph, the
/// fastest profile) the tightest arc needs about 2 m/s^2 of lateral acceleration.
std::vector<RoadSegment> plausibleRoadPattern();

}  // namespace acc
