// The renderer's frame at the camera's nadir (planet/nadir_frame.hpp): the sea's quadric is the
// planet's surface exactly, its normals are the ellipsoid's, and the waves' chart follows the
// camera to the nanometre while staying fixed to the planet.
#include <gtest/gtest.h>

#include <cmath>

#include "thalassa/planet/nadir_frame.hpp"

namespace thalassa {
namespace {

const double kLatitudes[] = {0.0, 20.0, 45.0, -60.0, 89.9, -89.9};

// Points of the ellipsoid (height 0) at distances from 1 m to 2,000 km from the nadir, put in the
// nadir frame through GeographicLib, lie on the quadric (|f| is the ECEF round-off, ~1e-9 m, plus
// f's own rounding, relative 1e-16 of x^2 / R).
TEST(NadirFrame, SeaQuadricIsThePlanetsSurface) {
  for (const Planet& planet : {Planet::wgs84(), Planet::sphere(6371000.0)})
    for (double lat : kLatitudes) {
      const double lon = 180.0;
      const ocean::SeaSurface surface = planet_sea_surface(planet, lat, lon);
      const LocalFrame frame = planet.local_frame(lat, lon, 0.0);
      double worst = 0.0, worst_normal = 0.0;
      for (double distance : {1.0, 1e3, 1e5, 5e5, 2e6})
        for (double azimuth : {0.0, 45.0, 90.0, 200.0, 300.0}) {
          // A point `distance` away along the surface, roughly: through ECEF from the frame.
          const double a = azimuth * M_PI / 180.0;
          const glm::dvec3 guess(distance * std::sin(a), distance * std::cos(a), 0.0);
          const Geodetic g = planet.geodetic(frame.to_ecef(guess));
          const glm::dvec3 x = frame.offset(g.lat, g.lon, 0.0);
          const double f = ocean::sea_surface_value(surface, x);
          worst = std::max(worst, std::abs(f));
          // The quadric's normal there is the ellipsoid's up, in the nadir's axes.
          const EnuBasis there = planet.enu_basis(g.lat, g.lon);
          const glm::dvec3 up = frame.direction_to_enu(there.up);
          const glm::dvec3 n = ocean::sea_surface_normal(surface, x);
          worst_normal = std::max(worst_normal, glm::length(n - up));
        }
      EXPECT_LT(worst, 1e-7) << lat;
      EXPECT_LT(worst_normal, 1e-12) << lat;
    }
}

// The camera's height is along the normal: the nadir ray meets the quadric at exactly `height`.
TEST(NadirFrame, NadirRayMeetsTheSeaAtTheCameraHeight) {
  for (double lat : kLatitudes) {
    const ocean::SeaSurface surface = planet_sea_surface(Planet::wgs84(), lat, 10.0);
    for (double h : {1e-3, 1.0, 2e4, 3.6e7}) {
      const auto t = ocean::sea_surface_distance(surface, h, {0.0, 0.0, -1.0});
      ASSERT_TRUE(t.has_value());
      EXPECT_NEAR(*t, h, 1e-15 * h + 1e-18) << lat << " " << h;
    }
  }
}

TEST(NadirFrame, WaveAnchorIsTheNearestLatticePoint) {
  const Geodetic a = nearest_wave_anchor(45.1, -179.95);
  EXPECT_DOUBLE_EQ(a.lat, 45.0);
  EXPECT_DOUBLE_EQ(a.lon, 180.0);  // across the antimeridian, in (-180, 180]
  const Geodetic b = nearest_wave_anchor(89.9, 12.4);
  EXPECT_DOUBLE_EQ(b.lat, 90.0);
  EXPECT_DOUBLE_EQ(b.lon, 12.5);
  const Geodetic c = nearest_wave_anchor(-20.13, 33.37);
  EXPECT_DOUBLE_EQ(c.lat, -20.25);
  EXPECT_DOUBLE_EQ(c.lon, 33.25);
}

// A camera keeps its anchor within kWaveAnchorKeepDistance (100 km of chord) and takes the
// lattice point nearest it beyond: 0.8 degree of latitude (89 km) keeps it, 1 degree (111 km)
// does not.
TEST(NadirFrame, KeptWaveAnchorWithinItsDistance) {
  const Planet planet;
  const Geodetic anchor{20.0, -150.0, 0.0};
  const Geodetic kept = kept_wave_anchor(planet, anchor, 20.8, -150.1);
  EXPECT_EQ(kept.lat, 20.0);
  EXPECT_EQ(kept.lon, -150.0);
  const Geodetic moved = kept_wave_anchor(planet, anchor, 21.0, -150.1);
  EXPECT_EQ(moved.lat, 21.0);
  EXPECT_EQ(moved.lon, -150.0);
}

// A 1 mm move of the camera moves the nadir's chart coordinates by 1 mm along the nadir's axes in
// the chart, in double; the axes are a rotation to ~1e-5 within a lattice cell; the same point
// of the planet gets the same chart coordinates from two nadirs (the waves stay put).
TEST(NadirFrame, WaveChartFollowsTheCameraAndStaysOnThePlanet) {
  const Planet planet = Planet::wgs84();
  for (double lat : {0.0, 45.0, 89.9, -89.9}) {
    CameraSettings camera;
    camera.lat = lat;
    camera.lon = 180.0;
    camera.height = 1.0;
    const NadirFrame base = make_nadir_frame(planet, camera);
    const glm::dmat2 j = base.wave_axes;
    EXPECT_NEAR(glm::length(j[0]), 1.0, 1e-5);
    EXPECT_NEAR(glm::length(j[1]), 1.0, 1e-5);
    EXPECT_NEAR(glm::dot(j[0], j[1]), 0.0, 1e-5);
    // 1 mm east and north.
    const LocalFrame here = planet.local_frame(lat, 180.0, 0.0);
    for (const glm::dvec3 step : {glm::dvec3(1e-3, 0, 0), glm::dvec3(0, 1e-3, 0)}) {
      const Geodetic p = planet.geodetic(here.to_ecef(step));
      CameraSettings moved = camera;
      moved.lat = p.lat;
      moved.lon = p.lon;
      const NadirFrame next = make_nadir_frame(planet, moved, base.wave_anchor);
      const glm::dvec2 expected = base.wave_origin + j * glm::dvec2(step.x, step.y);
      EXPECT_LT(glm::length(next.wave_origin - expected), 1e-8) << lat;
    }
    // A point 3 km away has the same chart coordinates seen from this nadir and from a second
    // one 2 km off: the linear chart map of each nadir differs from the tangent plane's by its
    // curvature, ~d^2 / R ~ 1 mm here, far below any wave.
    const glm::dvec3 far(3000.0, -1000.0, 0.0);
    const Geodetic point = planet.geodetic(here.to_ecef(far));
    const Geodetic second = planet.geodetic(here.to_ecef({-1500.0, 1300.0, 0.0}));
    CameraSettings other = camera;
    other.lat = second.lat;
    other.lon = second.lon;
    const NadirFrame b = make_nadir_frame(planet, other, base.wave_anchor);
    const LocalFrame there = planet.local_frame(second.lat, second.lon, 0.0);
    const glm::dvec3 x_a = here.offset(point.lat, point.lon, 0.0);
    const glm::dvec3 x_b = there.offset(point.lat, point.lon, 0.0);
    const glm::dvec2 chart_a = base.wave_origin + base.wave_axes * glm::dvec2(x_a);
    const glm::dvec2 chart_b = b.wave_origin + b.wave_axes * glm::dvec2(x_b);
    EXPECT_LT(glm::length(chart_a - chart_b), 0.01) << lat;
  }
}

}  // namespace
}  // namespace thalassa
