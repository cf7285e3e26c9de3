// Tests of the nearest point of a geodesic segment (planet/src/geodesic_segment.hpp), the search
// behind a ship's track coordinates and a calm area's distances: points built at a known foot and
// distance with GeographicLib come back to it, the geodesic to the point leaves the segment at a
// right angle, and the fixed point stops within a few iterations instead of cycling at the
// rounding's floor.

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "geodesic_segment.hpp"

namespace thalassa::detail {
namespace {

struct Segment {
  double lat, lon, azimuth, length;  // start A, azimuth at A (degrees), m
};

TEST(GeodesicSegment, FeetOfPointsBuiltAtAKnownFoot) {
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  // A ship's 6 km wake track, a long calm-area edge, a segment across the antimeridian and one
  // passing 30 km from a pole.
  const Segment segments[] = {{36.0, -20.0, 225.0, 6000.0},
                              {-41.0, 147.0, 80.0, 600e3},
                              {-12.0, 179.99, 95.0, 3000.0},
                              {89.5, 30.0, 10.0, 90e3}};
  int most_iterations = 0;
  double worst_along = 0.0, worst_distance = 0.0, worst_angle = 0.0, worst_away = 0.0;
  for (const Segment& s : segments) {
    const GeographicLib::GeodesicLine line = g.Line(s.lat, s.lon, s.azimuth);
    double lat_b, lon_b;
    line.Position(s.length, lat_b, lon_b);
    for (double fraction : {0.0017, 0.25, 0.5, 0.5001, 0.75, 0.9983}) {
      for (double y : {-600.0, -60.0, -1.0, 0.0, 1e-3, 1.0, 60.0, 250.0, 600.0}) {
        double lat_f, lon_f, azi_f;
        line.Position(fraction * s.length, lat_f, lon_f, azi_f);
        double lat_p, lon_p, azi_at_p;
        g.Direct(lat_f, lon_f, azi_f - 90.0, y, lat_p, lon_p, azi_at_p);  // y > 0: to the left
        const SegmentFoot foot = nearest_on_segment(g, s.lat, s.lon, lat_b, lon_b, lat_p, lon_p);
        most_iterations = std::max(most_iterations, foot.iterations);
        worst_along = std::max(worst_along, std::abs(foot.along - fraction * s.length));
        worst_distance = std::max(worst_distance, std::abs(foot.distance - std::abs(y)));
        worst_angle = std::max(worst_angle, std::abs(std::remainder(foot.azimuth - azi_f, 360.0)));
        if (std::abs(y) >= 1.0) {
          // The geodesic to the point leaves the segment at a right angle, and arrives at the
          // point with the azimuth of the geodesic built to it (pointing away from the segment).
          const double side = y > 0.0 ? -90.0 : 90.0;
          worst_angle = std::max(
              worst_angle, std::abs(std::remainder(foot.point_azimuth - (azi_f + side), 360.0)));
          worst_away = std::max(
              worst_away,
              std::abs(std::remainder(
                  foot.azimuth_at_point - (y > 0.0 ? azi_at_p : azi_at_p + 180.0), 360.0)));
        }
      }
    }
  }
  std::printf(
      "worst along %.3g m, distance %.3g m, angle %.3g deg, at the point %.3g deg; "
      "at most %d iterations\n",
      worst_along, worst_distance, worst_angle, worst_away, most_iterations);
  EXPECT_LT(worst_along, 1e-6);
  EXPECT_LT(worst_distance, 1e-6);
  EXPECT_LT(worst_angle, 1e-6);
  EXPECT_LT(worst_away, 1e-6);
  // 1-3 from the segment's middle (at most 2 here); when the search went on to steps of 1e-9 m,
  // points 600 m abeam of a 6 km segment cycled at 1.1e-9 m for all kFootMaxIterations.
  EXPECT_LE(most_iterations, 3);
}

TEST(GeodesicSegment, EndsAreTheFeetOfPointsBeyondThem) {
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  const GeographicLib::GeodesicLine line = g.Line(36.0, -20.0, 225.0);
  double lat_b, lon_b, azi_b;
  line.Position(6000.0, lat_b, lon_b, azi_b);
  double lat_p, lon_p;
  g.Direct(lat_b, lon_b, azi_b + 20.0, 300.0, lat_p, lon_p);  // past B
  const SegmentFoot past_b = nearest_on_segment(g, 36.0, -20.0, lat_b, lon_b, lat_p, lon_p);
  EXPECT_NEAR(past_b.along, 6000.0, 1e-6);
  EXPECT_NEAR(past_b.distance, 300.0, 1e-6);
  g.Direct(36.0, -20.0, 225.0 + 180.0 - 35.0, 40.0, lat_p, lon_p);  // before A
  const SegmentFoot before_a = nearest_on_segment(g, 36.0, -20.0, lat_b, lon_b, lat_p, lon_p);
  EXPECT_NEAR(before_a.along, 0.0, 1e-6);
  EXPECT_NEAR(before_a.distance, 40.0, 1e-6);
}

}  // namespace
}  // namespace thalassa::detail
