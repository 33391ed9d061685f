#include "acc_identification/synthesis/road_centreline.h"
#include "acc_identification/model/angles.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace acc
{
namespace
{
// Below this curvature an arc is computed as a straight (radius beyond 10,000 km).
constexpr double kStraightCurvature_per_m = 1e-10;
}  // namespace

RoadCentreline::RoadCentreline(const std::vector<RoadSegment>& pattern, double length_m, double start_heading_rad)
{
  if (pattern.empty())
    throw std::invalid_argument("road pattern is empty");
  for (const RoadSegment& segment : pattern)
    if (!(segment.length_m > 0.0) || !std::isfinite(segment.curvature_per_m))
      throw std::invalid_argument("road segment with a length that is not positive or a non-finite curvature");
  RoadPoint point{0.0, 0.0, start_heading_rad};
  double distance_m = 0.0;
  std::size_t i = 0;
  do
  {
    const RoadSegment& segment = pattern[i++ % pattern.size()];
    segments_.push_back({distance_m, segment, point});
    point = advance(point, segment, segment.length_m);
    distance_m += segment.length_m;
  } while (distance_m < length_m);
  // A last straight so that at() beyond the end continues along the final heading.
  segments_.push_back({distance_m, RoadSegment{1.0, 0.0}, point});
}

RoadPoint RoadCentreline::advance(const RoadPoint& start, const RoadSegment& segment, double distance_m)
{
  const double kappa = segment.curvature_per_m;
  const double heading = start.heading_rad + kappa * distance_m;
  RoadPoint end{start.east_m, start.north_m, heading};
  if (std::abs(kappa) < kStraightCurvature_per_m)
  {
    end.east_m += distance_m * std::sin(start.heading_rad);
    end.north_m += distance_m * std::cos(start.heading_rad);
    return end;
  }
  // d(east)/ds = sin(heading), d(north)/ds = cos(heading), heading = h0 + kappa s.
  end.east_m += (std::cos(start.heading_rad) - std::cos(heading)) / kappa;
  end.north_m += (std::sin(heading) - std::sin(start.heading_rad)) / kappa;
  return end;
}

RoadPoint RoadCentreline::at(double distance_m) const
{
  if (distance_m < 0.0)
    return advance(segments_.front().start, RoadSegment{1.0, 0.0}, distance_m);
  auto after = std::upper_bound(segments_.begin(), segments_.end(), distance_m,
                                [](double d, const Placed& placed) { return d < placed.start_distance_m; });
  const Placed& placed = *(after - 1);
  const bool last = after == segments_.end();
  const RoadSegment segment = last ? RoadSegment{1.0, 0.0} : placed.segment;
  return advance(placed.start, segment, distance_m - placed.start_distance_m);
}

double RoadCentreline::lengthM() const
{
  return segments_.back().start_distance_m;
}

std::vector<RoadSegment> plausibleRoadPattern()
{
  // Net turn 0 (right 35, left 50, right 15 degrees): the road meanders but goes somewhere.
  auto arc = [](double radius_m, double turn_deg) {
    return RoadSegment{radius_m * std::abs(turn_deg) * kDegToRad, (turn_deg > 0 ? 1.0 : -1.0) / radius_m};
  };
  return {RoadSegment{500.0, 0.0}, arc(700.0, 35.0), RoadSegment{300.0, 0.0}, arc(500.0, -50.0),
          RoadSegment{600.0, 0.0}, arc(900.0, 15.0)};
}

}  // namespace acc
