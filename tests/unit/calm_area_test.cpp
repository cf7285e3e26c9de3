// Tests of calm areas (planet/include/thalassa/planet/calm_area.hpp) and geodetic bounds
// (geo_bounds.hpp): containment of points known inside and outside, holes, a polygon across the
// antimeridian and one around each pole, independence from the ring's orientation, the signed
// distance against a brute-force minimum of GeographicLib's geodesic distances along the edges,
// the fade (1 outside, the factor inside, monotone and C1 across the edge), conservative bounds.

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "thalassa/planet/calm_area.hpp"

namespace thalassa {
namespace {

CalmAreaSettings Area(std::vector<GeoPoint> ring, double scale = 0.2, double fade = 100.0) {
  CalmAreaSettings s;
  s.name = "test";
  s.exterior = std::move(ring);
  s.scale = scale;
  s.fade = fade;
  return s;
}

// A square of +-h degrees around (lat, lon), counterclockwise.
std::vector<GeoPoint> Square(double lat, double lon, double h) {
  return {{lat - h, lon - h}, {lat - h, lon + h}, {lat + h, lon + h}, {lat + h, lon - h}};
}

// The minimum geodesic distance from P to the edge A-B by brute force: 4000 samples along the
// geodesic, then golden-section refinement around the best.
double BruteDistance(const GeographicLib::Geodesic& g, GeoPoint a, GeoPoint b, GeoPoint p) {
  const GeographicLib::GeodesicLine line = g.InverseLine(a.lat, a.lon, b.lat, b.lon);
  const double len = line.Distance();
  auto dist = [&](double s) {
    double lat, lon, d;
    line.Position(s, lat, lon);
    g.Inverse(p.lat, p.lon, lat, lon, d);
    return d;
  };
  const int n = 4000;
  int best = 0;
  double best_d = dist(0.0);
  for (int i = 1; i <= n; ++i) {
    const double d = dist(len * i / n);
    if (d < best_d) best_d = d, best = i;
  }
  double lo = len * std::max(0, best - 1) / n, hi = len * std::min(n, best + 1) / n;
  const double r = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 200 && hi - lo > 1e-9; ++it) {
    const double m1 = hi - r * (hi - lo), m2 = lo + r * (hi - lo);
    if (dist(m1) < dist(m2))
      hi = m2;
    else
      lo = m1;
  }
  return std::min(best_d, dist(0.5 * (lo + hi)));
}

double BruteSignedDistance(const GeographicLib::Geodesic& g, const CalmArea& area, GeoPoint p) {
  double best = std::numeric_limits<double>::infinity();
  const auto& ring = area.settings().exterior;
  for (std::size_t i = 0; i < ring.size(); ++i)
    best = std::min(best, BruteDistance(g, ring[i], ring[(i + 1) % ring.size()], p));
  for (const auto& hole : area.settings().holes)
    for (std::size_t i = 0; i < hole.size(); ++i)
      best = std::min(best, BruteDistance(g, hole[i], hole[(i + 1) % hole.size()], p));
  return area.contains(p.lat, p.lon) ? best : -best;
}

TEST(CalmArea, ContainsPointsKnownInsideAndOutside) {
  const Planet planet;
  CalmAreaSettings s = Area(Square(20.0, -150.0, 0.1));
  s.holes.push_back(Square(20.0, -150.0, 0.02));
  const CalmArea area(planet, s);
  EXPECT_TRUE(area.contains(20.05, -150.05));
  EXPECT_TRUE(area.contains(20.0, -149.93));
  EXPECT_FALSE(area.contains(20.0, -150.0));    // in the hole
  EXPECT_FALSE(area.contains(20.011, -150.0));  // in the hole
  EXPECT_FALSE(area.contains(20.2, -150.0));
  EXPECT_FALSE(area.contains(-20.0, 30.0));  // the far side of the globe
  EXPECT_FALSE(area.contains(std::nan(""), 0.0));
  EXPECT_EQ(area.amplitude_scale(20.2, -150.0), 1.0);
  EXPECT_EQ(area.amplitude_scale(20.0, -150.0), 1.0);
  EXPECT_NEAR(area.amplitude_scale(20.05, -150.05), 0.2, 1e-15);  // ~2 km inside, fade 100 m
  // The orientation of the ring does not matter.
  CalmAreaSettings reversed = s;
  std::reverse(reversed.exterior.begin(), reversed.exterior.end());
  const CalmArea other(planet, reversed);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  for (int i = 0; i < 2000; ++i) {
    const double lat = 20.0 + u(rng), lon = -150.0 + u(rng);
    EXPECT_EQ(area.contains(lat, lon), other.contains(lat, lon));
    // Every point the square holds in latitude-longitude (away from its geodesic edges, which
    // bow by < 1e-4 degrees) agrees with the obvious test.
    const bool in_square = std::abs(lat - 20.0) < 0.0999 && std::abs(lon + 150.0) < 0.0999;
    const bool in_hole = std::abs(lat - 20.0) < 0.0201 && std::abs(lon + 150.0) < 0.0201;
    const bool clearly_out = std::abs(lat - 20.0) > 0.1001 || std::abs(lon + 150.0) > 0.1001;
    const bool clearly_in_hole = std::abs(lat - 20.0) < 0.0199 && std::abs(lon + 150.0) < 0.0199;
    if (in_square && !in_hole) {
      EXPECT_TRUE(area.contains(lat, lon)) << lat << " " << lon;
    }
    if (clearly_out || clearly_in_hole) {
      EXPECT_FALSE(area.contains(lat, lon)) << lat << " " << lon;
    }
  }
  EXPECT_FALSE(area.bounds().contains(20.2, -150.0));
  EXPECT_TRUE(area.bounds().contains(20.05, -150.05));
}

TEST(CalmArea, CrossingTheAntimeridian) {
  const Planet planet;
  const CalmArea area(planet, Area({{-0.5, 179.5}, {-0.5, -179.5}, {0.5, -179.5}, {0.5, 179.5}}));
  for (double lon : {179.6, 180.0, -180.0, -179.6}) EXPECT_TRUE(area.contains(0.0, lon)) << lon;
  for (double lon : {179.4, -179.4, 0.0}) EXPECT_FALSE(area.contains(0.0, lon)) << lon;
  EXPECT_NEAR(area.centre().lat, 0.0, 1e-9);
  EXPECT_NEAR(std::abs(area.centre().lon), 180.0, 1e-9);
  const GeoBounds& b = area.bounds();
  EXPECT_GT(b.west, b.east);  // crosses the antimeridian
  EXPECT_NEAR(b.longitude_span(), 1.0, 1e-9);
  EXPECT_TRUE(b.contains(0.0, 180.0));
  EXPECT_TRUE(b.contains(0.0, -180.0));
  EXPECT_FALSE(b.contains(0.0, 0.0));
  // The distance to the edge at lon 179.5 from a point at 179.7 on the equator: 0.2 degrees of
  // the equator (a geodesic there), a * 0.2 pi / 180.
  const double expected = 6378137.0 * 0.2 * std::acos(-1.0) / 180.0;
  EXPECT_NEAR(area.signed_distance(0.0, 179.7), expected, 1e-6);
  EXPECT_NEAR(area.signed_distance(0.0, -179.7), expected, 1e-6);
  EXPECT_NEAR(area.signed_distance(0.0, 179.3), -expected, 1e-6);
}

TEST(CalmArea, AroundEachPole) {
  const Planet planet;
  for (double sign : {1.0, -1.0}) {
    std::vector<GeoPoint> ring;
    for (int i = 0; i < 6; ++i) ring.push_back({sign * 89.0, -180.0 + 60.0 * i});
    const CalmArea area(planet, Area(ring, 0.5, 1000.0));
    EXPECT_TRUE(area.contains(sign * 90.0, 0.0));
    EXPECT_TRUE(area.contains(sign * 89.5, 123.0));
    // The edges are geodesics, which bow toward the pole: between the vertices at longitudes
    // -180 and -120 the edge's middle is at colatitude atan(tan(1 deg) cos(30 deg)) = 0.866
    // deg (on a sphere), so 89.1 at longitude -150 is outside while 89.05 at a vertex's
    // longitude is inside.
    EXPECT_TRUE(area.contains(sign * 89.05, -180.0));
    EXPECT_FALSE(area.contains(sign * 89.1, -150.0));
    EXPECT_TRUE(area.contains(sign * 89.2, -150.0));
    EXPECT_FALSE(area.contains(sign * 88.9, 0.0));
    EXPECT_FALSE(area.contains(sign * 88.9, -180.0));
    EXPECT_FALSE(area.contains(0.0, 0.0));
    EXPECT_NEAR(std::abs(area.centre().lat), 90.0, 1e-9);
    const GeoBounds& b = area.bounds();
    EXPECT_TRUE(b.full_longitude());
    EXPECT_EQ(sign > 0 ? b.north : b.south, sign * 90.0);
    EXPECT_NEAR(sign > 0 ? b.south : -b.north, 89.0, 1e-12);
    EXPECT_EQ(area.amplitude_scale(sign * 90.0, 0.0), 0.5);
    // At the pole the distance to each edge is the same (a regular hexagon of geodesics): the
    // edges' middles at colatitude ~0.866 deg, ~96.7 km away.
    const double d = area.signed_distance(sign * 90.0, 0.0);
    EXPECT_GT(d, 0.96e5);
    EXPECT_LT(d, 0.975e5);
    for (int i = 0; i < 6; ++i)
      EXPECT_NEAR(area.signed_distance(sign * 90.0, -150.0 + 60.0 * i), d, 1e-6);
  }
}

TEST(CalmArea, SignedDistanceMatchesGeodesicBruteForce) {
  const Planet planet;
  const GeographicLib::Geodesic g(planet.equatorial_radius(), planet.flattening());
  std::vector<CalmArea> areas;
  areas.emplace_back(planet, Area({{44.9, 12.1}, {45.02, 12.4}, {45.2, 12.35}, {45.15, 12.0}}));
  areas.emplace_back(planet, Area({{-0.5, 179.5}, {-0.3, -179.4}, {0.5, -179.5}, {0.4, 179.6}}));
  std::vector<GeoPoint> polar;
  for (int i = 0; i < 5; ++i) polar.push_back({-88.5 + 0.2 * (i % 2), -180.0 + 72.0 * i + 10});
  areas.emplace_back(planet, Area(polar));
  areas.emplace_back(planet, Area({{60.0, -10.0}, {61.0, 20.0}, {70.0, 5.0}}));  // long edges
  std::mt19937_64 rng(42);
  double worst = 0.0;
  for (const CalmArea& area : areas) {
    const GeoPoint c = area.centre();
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 25; ++i) {
      // Points around the polygon, inside and outside: up to ~1.5 x its size from the centre.
      const double azimuth = 180.0 * u(rng);
      double size;
      g.Inverse(c.lat, c.lon, area.settings().exterior[0].lat, area.settings().exterior[0].lon,
                size);
      GeoPoint p;
      g.Direct(c.lat, c.lon, azimuth, size * (0.75 + 0.75 * u(rng)), p.lat, p.lon);
      const double d = area.signed_distance(p.lat, p.lon);
      const double brute = BruteSignedDistance(g, area, p);
      worst = std::max(worst, std::abs(d - brute));
      EXPECT_NEAR(d, brute, 1e-6) << area.centre().lat << " " << p.lat << " " << p.lon;
    }
  }
  std::printf("worst |signed distance - brute force| = %.3g m\n", worst);
}

// The gnomonic estimate of the signed distance (CalmArea::estimate_signed_distance) is within
// its stated bound of the exact distance, and the bound is small where the sea's chart uses it:
// a 2 km slick (wake_demo's), 50 km and 400 km squares at 45 N (where the gnomonic's geodesics
// bend most), one with a hole, one around the north pole, one across the antimeridian, and the
// 50 km square on a sphere (no bend at all). Points fall in a box 1.6 times the polygon's and in
// the band 300 m either side of its edges. The exact distance converges to 1e-9 m; 1e-7 m is
// allowed for it.
TEST(CalmArea, DistanceEstimateIsWithinItsBound) {
  struct Case {
    const char* name;
    Planet planet;
    CalmAreaSettings settings;
    // m: the largest bound allowed within 300 m of an edge, about (sigma - 1) 300 m with the
    // centre's distance for S (calm_area.cpp): the slick's is below kChartEstimateTolerance
    // (local_features.cpp, 1 mm), so the chart takes the estimate all along its edge.
    double near_edge_bound;
  };
  const std::vector<GeoPoint> slick = {
      {35.978969, -20.005489}, {35.982374, -20.005797}, {35.986036, -20.005967},
      {35.990584, -20.011585}, {35.994791, -20.017112}, {35.994842, -20.021353},
      {35.995538, -20.025877}, {35.993218, -20.027766}, {35.988250, -20.023631},
      {35.983574, -20.020210}, {35.980435, -20.014388}, {35.978327, -20.009011}};
  CalmAreaSettings holed = Area(Square(45.0, 10.0, 1.8));
  holed.holes = {Square(45.3, 10.2, 0.4)};
  const std::vector<Case> cases = {
      {"slick", Planet(), Area(slick, 0.08, 150.0), 1e-4},
      {"50 km", Planet(), Area(Square(45.0, 10.0, 0.225)), 1e-2},
      {"400 km with a hole", Planet(), holed, 1.0},
      {"north pole", Planet(), Area({{89.8, 0.0}, {89.8, 90.0}, {89.8, 180.0}, {89.8, -90.0}}),
       1e-2},
      {"antimeridian", Planet(),
       Area({{-10.1, 179.9}, {-10.1, -179.9}, {-9.9, -179.9}, {-9.9, 179.9}}), 5e-3},
      {"50 km, sphere", Planet::sphere(6371e3), Area(Square(45.0, 10.0, 0.225)), 1e-2},
  };
  std::mt19937 rng(7);
  for (const Case& c : cases) {
    const CalmArea area(c.planet, c.settings);
    const GeographicLib::Geodesic g(c.planet.equatorial_radius(), c.planet.flattening());
    const GeoBounds& b = area.bounds();
    const double span_lat = b.north - b.south;
    const double span_lon = b.full_longitude() ? 360.0 : b.east - b.west + (b.east < b.west) * 360;
    std::uniform_real_distribution<double> u(-0.8, 0.8), unit(0.0, 1.0), band(-300.0, 300.0);
    double worst_ratio = 0.0, worst_near = 0.0;
    int bounded = 0;
    for (int k = 0; k < 600; ++k) {
      GeoPoint p;
      bool near_edge = k % 2 == 1;
      if (near_edge) {
        // A point `band` metres across an edge, from a point along it.
        const auto& ring = c.settings.exterior;
        const std::size_t e = std::size_t(unit(rng) * ring.size()) % ring.size();
        const GeoPoint& a = ring[e];
        const GeoPoint& z = ring[(e + 1) % ring.size()];
        const GeographicLib::GeodesicLine line = g.InverseLine(a.lat, a.lon, z.lat, z.lon);
        double lat, lon, azi;
        line.Position(unit(rng) * line.Distance(), lat, lon, azi);
        g.Direct(lat, lon, azi + 90.0, band(rng), p.lat, p.lon);
      } else {
        p.lat = std::clamp(0.5 * (b.north + b.south) + u(rng) * span_lat, -90.0, 90.0);
        p.lon = b.full_longitude() ? 360.0 * unit(rng) - 180.0
                                   : std::remainder(b.west + (0.5 + u(rng)) * span_lon, 360.0);
      }
      const CalmArea::DistanceEstimate estimate = area.estimate_signed_distance(p.lat, p.lon);
      if (!std::isfinite(estimate.error)) continue;
      ++bounded;
      const double exact = area.signed_distance(p.lat, p.lon);
      const double difference = std::abs(estimate.distance - exact);
      EXPECT_LE(difference, estimate.error + 1e-7) << c.name << " at " << p.lat << ", " << p.lon
                                                   << ": " << estimate.distance << " vs " << exact;
      if (estimate.error > 1e-6) worst_ratio = std::max(worst_ratio, difference / estimate.error);
      if (near_edge) worst_near = std::max(worst_near, estimate.error);
    }
    EXPECT_GT(bounded, 500) << c.name;
    EXPECT_LE(worst_near, c.near_edge_bound) << c.name;
    std::printf("%s: largest bound within 300 m of an edge %.2g m, error / bound at most %.4f\n",
                c.name, worst_near, worst_ratio);
  }
  // No bound for vertices beyond kCalmEstimateMaxRadius, nor for points not finite.
  const CalmArea wide(Planet(), Area(Square(0.0, 0.0, 12.0)));
  EXPECT_FALSE(std::isfinite(wide.estimate_signed_distance(11.0, 0.0).error));
  EXPECT_GT(wide.estimate_signed_distance(11.0, 0.0).distance, 0.0);
  const CalmArea small(Planet(), Area(Square(0.0, 0.0, 0.1)));
  EXPECT_FALSE(std::isfinite(small.estimate_signed_distance(NAN, 0.0).error));
  EXPECT_LT(small.estimate_signed_distance(NAN, 0.0).distance, 0.0);  // outside, as contains()
}

TEST(CalmArea, FadeIsOneOutsideTheFactorInsideMonotoneAndC1) {
  // The function of the distance.
  const double scale = 0.3, fade = 200.0;
  EXPECT_EQ(calm_fade(-5.0, scale, fade), 1.0);
  EXPECT_EQ(calm_fade(0.0, scale, fade), 1.0);
  EXPECT_EQ(calm_fade(fade, scale, fade), scale);
  EXPECT_EQ(calm_fade(1e9, scale, fade), scale);
  EXPECT_EQ(calm_fade(1.0, scale, 0.0), scale);  // no fade: a step
  const double h = 1e-4;
  for (double d : {0.0, fade}) {  // one-sided derivatives vanish at both ends of the fade
    EXPECT_NEAR((calm_fade(d + h, scale, fade) - calm_fade(d, scale, fade)) / h, 0.0, 1e-5);
    EXPECT_NEAR((calm_fade(d, scale, fade) - calm_fade(d - h, scale, fade)) / h, 0.0, 1e-5);
  }
  // Along a geodesic across an edge of a real area: monotone, with a derivative (per metre)
  // that changes by little between neighbouring samples (no kink), from 1 to the factor.
  const Planet planet;
  const GeographicLib::Geodesic g(planet.equatorial_radius(), planet.flattening());
  const CalmArea area(planet, Area(Square(-33.0, 151.3, 0.05), scale, fade));
  // Start 300 m outside the southern edge's middle, walk north 800 m.
  double lat0, lon0;
  g.Direct(-33.05, 151.3, 180.0, 300.0, lat0, lon0);
  const int n = 1600;
  const double step = 800.0 / n;
  std::vector<double> values;
  for (int i = 0; i <= n; ++i) {
    double lat, lon;
    g.Direct(lat0, lon0, 0.0, step * i, lat, lon);
    values.push_back(area.amplitude_scale(lat, lon));
  }
  EXPECT_EQ(values.front(), 1.0);
  EXPECT_EQ(values.back(), scale);
  double max_jump = 0.0, max_slope = 0.0;
  for (int i = 1; i <= n; ++i) {
    EXPECT_LE(values[i], values[i - 1] + 1e-15);
    const double slope = (values[i] - values[i - 1]) / step;
    max_slope = std::max(max_slope, std::abs(slope));
    if (i > 1) {
      const double previous = (values[i - 1] - values[i - 2]) / step;
      max_jump = std::max(max_jump, std::abs(slope - previous));
    }
  }
  // The smoothstep's slope peaks at 1.5 (1 - scale) / fade; C1: the slope changes by O(step).
  EXPECT_NEAR(max_slope, 1.5 * (1 - scale) / fade, 1e-3 * (1 - scale) / fade);
  EXPECT_LT(max_jump, 6.0 * (1 - scale) / (fade * fade) * step * 1.01);
}

TEST(CalmArea, CompoundsOverlapsAndRefusesBadGeometry) {
  const Planet planet;
  std::vector<CalmArea> areas;
  areas.emplace_back(planet, Area(Square(10.0, 10.0, 0.1), 0.5, 0.0));
  areas.emplace_back(planet, Area(Square(10.05, 10.05, 0.1), 0.4, 0.0));
  EXPECT_NEAR(calm_amplitude_scale(areas, 10.07, 10.07), 0.2, 1e-15);
  EXPECT_NEAR(calm_amplitude_scale(areas, 9.95, 9.95), 0.5, 1e-15);
  EXPECT_EQ(calm_amplitude_scale(areas, 0.0, 0.0), 1.0);
  EXPECT_THROW(CalmArea(planet, Area({{0, 0}, {0, 1}})), std::invalid_argument);
  EXPECT_THROW(CalmArea(planet, Area({{0, 0}, {0, 1}, {0, 1}, {0, 0}})), std::invalid_argument);
  EXPECT_THROW(CalmArea(planet, Area({{0, 0}, {0, 1}, {91, 0}})), std::invalid_argument);
  EXPECT_THROW(CalmArea(planet, Area({{0, 0}, {0, 1}, {std::nan(""), 0}})), std::invalid_argument);
  EXPECT_THROW(CalmArea(planet, Area(Square(0, 0, 1), 1.5)), std::invalid_argument);
  EXPECT_THROW(CalmArea(planet, Area(Square(0, 0, 1), 0.5, -1)), std::invalid_argument);
  EXPECT_THROW(CalmArea(planet, Area({{0, 0}, {0, 120}, {0, -120}})), std::invalid_argument);
  EXPECT_THROW(CalmArea(planet, Area({{-40, -40}, {60, 0}, {-40, 40}})), std::invalid_argument);
}

TEST(GeoBounds, ArcsIntersectionsAndGrowth) {
  const GeoBounds a = GeoBounds::from_arcs(0, 10, {{170.0, 5.0}, {-178.0, 3.0}});
  EXPECT_NEAR(a.west, 170.0, 1e-12);
  EXPECT_NEAR(a.east, -175.0, 1e-12);
  EXPECT_NEAR(a.longitude_span(), 15.0, 1e-12);
  EXPECT_TRUE(a.contains(5, 180.0));
  EXPECT_TRUE(a.contains(5, -176.0));
  EXPECT_FALSE(a.contains(5, -170.0));
  EXPECT_FALSE(a.contains(11, 175.0));
  const GeoBounds b{-5, 1, -176.0, -160.0};
  EXPECT_TRUE(a.intersects(b));
  EXPECT_TRUE(b.intersects(a));
  const GeoBounds c{-5, 1, -170.0, -160.0};
  EXPECT_FALSE(a.intersects(c));
  EXPECT_FALSE(c.intersects(a));
  EXPECT_TRUE(GeoBounds::from_arcs(0, 1, {{-180.0, 360.0}}).full_longitude());
  EXPECT_TRUE(GeoBounds::from_arcs(0, 1, {{0.0, 200.0}, {190.0, 180.0}}).full_longitude());
  EXPECT_TRUE(GeoBounds{}.empty());
  // Growth: 111 km is about 1 degree of latitude; near a pole the region takes every longitude.
  const GeoBounds g = GeoBounds{10, 11, 20, 21}.expanded(111000.0, 6378137.0, 1 / 298.257223563);
  EXPECT_LT(g.south, 9.0);
  EXPECT_GT(g.north, 12.0);
  EXPECT_LT(g.west, 19.0);
  EXPECT_GT(g.east, 22.0);
  EXPECT_GT(g.south, 8.9);
  const GeoBounds polar = GeoBounds{89.5, 89.6, 20, 21}.expanded(60000.0, 6378137.0, 0.0);
  EXPECT_TRUE(polar.full_longitude());
}

}  // namespace
}  // namespace thalassa
