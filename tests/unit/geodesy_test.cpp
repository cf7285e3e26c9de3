// Geodesy (planet/include/thalassa/planet/geodesy.hpp): round trips geodetic -> ECEF ->
// geodetic, the ENU frames against finite differences of ecef(), the WGS84 constants and the
// sphere, the camera's pose, the precision of camera-relative offsets (1 mm at latitudes 0, 45,
// 89.9 and 90, longitude +-180) and the errors on bad input.
#include <gtest/gtest.h>

#include <GeographicLib/Constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "thalassa/planet/geodesy.hpp"

namespace thalassa {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;  // radians per degree

const std::vector<double> kLatitudes = {0.0, 45.0, -45.0, 89.9, -89.9, 90.0, -90.0};
const std::vector<double> kLongitudes = {-180.0, 180.0, 0.0, -150.0, 37.5};
const std::vector<double> kHeights = {0.0, 1.0, 20e3, 36e6};  // m

// |a - b| in degrees of longitude, modulo 360.
double lon_difference(double a, double b) {
  const double d = std::remainder(a - b, 360.0);
  return std::abs(d);
}

void expect_orthonormal(const glm::dvec3& x, const glm::dvec3& y, const glm::dvec3& z,
                        double tolerance) {
  EXPECT_NEAR(glm::length(x), 1.0, tolerance);
  EXPECT_NEAR(glm::length(y), 1.0, tolerance);
  EXPECT_NEAR(glm::length(z), 1.0, tolerance);
  EXPECT_NEAR(glm::dot(x, y), 0.0, tolerance);
  EXPECT_NEAR(glm::dot(x, z), 0.0, tolerance);
  EXPECT_NEAR(glm::dot(y, z), 0.0, tolerance);
  EXPECT_NEAR(glm::length(glm::cross(x, y) - z), 0.0, tolerance);  // right-handed
}

void expect_round_trips(const Planet& planet) {
  for (double lat : kLatitudes)
    for (double lon : kLongitudes)
      for (double h : kHeights) {
        SCOPED_TRACE("lat " + std::to_string(lat) + " lon " + std::to_string(lon) + " h " +
                     std::to_string(h));
        const glm::dvec3 p = planet.ecef(lat, lon, h);
        const Geodetic g = planet.geodetic(p);
        EXPECT_NEAR(g.lat, lat, 1e-9);
        if (std::abs(lat) < 90.0) {  // any longitude is right at a pole
          EXPECT_LT(lon_difference(g.lon, lon), 1e-9);
        }
        EXPECT_NEAR(g.height, h, 1e-6);
        EXPECT_LT(glm::length(planet.ecef(g) - p), 1e-6);
      }
}

TEST(Geodesy, Wgs84ConstantsComeFromGeographicLib) {
  const Planet planet;
  EXPECT_EQ(planet.shape(), PlanetShape::Wgs84);
  EXPECT_EQ(planet.equatorial_radius(), GeographicLib::Constants::WGS84_a());
  EXPECT_EQ(planet.flattening(), GeographicLib::Constants::WGS84_f());
  EXPECT_EQ(planet.equatorial_radius(), 6378137.0);
  EXPECT_DOUBLE_EQ(planet.flattening(), 1.0 / 298.257223563);
  const Planet from_scene{PlanetSettings{}};  // the scene's default shape is WGS84
  EXPECT_EQ(from_scene.shape(), PlanetShape::Wgs84);
  EXPECT_EQ(from_scene.equatorial_radius(), 6378137.0);
  // The ellipsoid itself: the equator at a, the poles at b = a (1 - f).
  const double a = 6378137.0, b = a * (1.0 - 1.0 / 298.257223563);
  EXPECT_NEAR(glm::length(planet.ecef(0, 0, 0) - glm::dvec3(a, 0, 0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(planet.ecef(0, 90, 0) - glm::dvec3(0, a, 0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(planet.ecef(90, 0, 0) - glm::dvec3(0, 0, b)), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(planet.ecef(-90, 0, 0) - glm::dvec3(0, 0, -b)), 0.0, 1e-9);
  EXPECT_NEAR(planet.nadir_radius(0), a, 1e-9);
  EXPECT_NEAR(planet.nadir_radius(90), b, 1e-9);
  // Gaussian radius of curvature sqrt(M N): b at the equator, a^2 / b at the poles.
  EXPECT_NEAR(planet.curvature_radius(0), b, 1e-8);
  EXPECT_NEAR(planet.curvature_radius(-90), a * a / b, 1e-8);
}

TEST(Geodesy, Wgs84RoundTrips) { expect_round_trips(Planet::wgs84()); }

TEST(Geodesy, SphereRoundTrips) { expect_round_trips(Planet::sphere(6371000.0)); }

TEST(Geodesy, SphereHasTheSceneRadius) {
  PlanetSettings settings;
  settings.shape = PlanetShape::Sphere;
  settings.radius = 3389500.0;  // m (Mars)
  const Planet planet(settings);
  EXPECT_EQ(planet.shape(), PlanetShape::Sphere);
  EXPECT_EQ(planet.equatorial_radius(), settings.radius);
  EXPECT_EQ(planet.flattening(), 0.0);
  for (double lat : kLatitudes)
    for (double lon : kLongitudes) {
      const double r = settings.radius;
      EXPECT_NEAR(planet.nadir_radius(lat), r, 1e-9 * r);
      EXPECT_NEAR(planet.curvature_radius(lat), r, 1e-9 * r);
      EXPECT_NEAR(glm::length(planet.ecef(lat, lon, 0.0)), r, 1e-9 * r);
      EXPECT_NEAR(glm::length(planet.ecef(lat, lon, 20e3)), r + 20e3, 1e-9 * r);
      // On a sphere the normal is the radial direction.
      const glm::dvec3 up = planet.enu_basis(lat, lon).up;
      EXPECT_NEAR(glm::length(up - glm::normalize(planet.ecef(lat, lon, 0.0))), 0.0, 1e-12);
    }
}

// The ENU basis is orthonormal and right-handed; up is the ellipsoid normal: orthogonal to
// d ecef / d lat and d ecef / d lon (central differences), equal to d ecef / d height, and
// pointing outward. north is along d ecef / d lat, east along d ecef / d lon.
TEST(Geodesy, EnuBasisIsTheEllipsoidNormalFrame) {
  const Planet planet;
  const double step = 1e-5;  // degrees (about 1 m)
  for (double lat : kLatitudes)
    for (double lon : kLongitudes) {
      SCOPED_TRACE("lat " + std::to_string(lat) + " lon " + std::to_string(lon));
      const EnuBasis b = planet.enu_basis(lat, lon);
      expect_orthonormal(b.east, b.north, b.up, 1e-14);
      EXPECT_GT(glm::dot(b.up, planet.ecef(lat, lon, 0.0)), 0.0);
      // d ecef / d height is exactly the unit normal.
      const glm::dvec3 d_h = (planet.ecef(lat, lon, 1.0) - planet.ecef(lat, lon, -1.0)) / 2.0;
      EXPECT_NEAR(glm::length(d_h - b.up), 0.0, 1e-8);
      // d ecef / d lat (one-sided at the poles).
      const double lat0 = std::clamp(lat, -90.0 + step, 90.0 - step);
      const glm::dvec3 d_lat =
          glm::normalize(planet.ecef(lat0 + step, lon, 0.0) - planet.ecef(lat0 - step, lon, 0.0));
      const double tolerance = std::abs(lat) == 90.0 ? 2e-7 : 1e-9;
      EXPECT_NEAR(glm::dot(d_lat, b.up), 0.0, tolerance);
      EXPECT_NEAR(glm::length(d_lat - b.north), 0.0, tolerance);
      if (std::abs(lat) < 90.0) {  // the longitude moves nothing at a pole
        const glm::dvec3 d_lon =
            glm::normalize(planet.ecef(lat, lon + step, 0.0) - planet.ecef(lat, lon - step, 0.0));
        EXPECT_NEAR(glm::dot(d_lon, b.up), 0.0, 1e-9);
        EXPECT_NEAR(glm::length(d_lon - b.east), 0.0, 1e-9);
      }
      // The closed form of the geodetic normal.
      const double phi = lat * kDegree, lambda = lon * kDegree;
      const glm::dvec3 normal(std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda),
                              std::sin(phi));
      EXPECT_NEAR(glm::length(b.up - normal), 0.0, 1e-14);
    }
}

TEST(Geodesy, CameraPoseInEcef) {
  const Planet planet;
  CameraSettings camera;
  camera.lat = 45.0;
  camera.lon = 180.0;
  camera.height = 1000.0;
  for (double heading : {0.0, 90.0, 200.0})
    for (double pitch : {-90.0, -5.0, 0.0, 30.0, 90.0})
      for (double roll : {0.0, 20.0}) {
        camera.heading = heading;
        camera.pitch = pitch;
        camera.roll = roll;
        const CameraPose pose = planet.camera_pose(camera);
        EXPECT_EQ(pose.ecef, planet.ecef(45.0, 180.0, 1000.0));
        EXPECT_EQ(pose.position.height, 1000.0);
        expect_orthonormal(pose.world.right, pose.world.up, -pose.world.forward, 1e-14);
        const CameraBasis local = camera_basis(heading, pitch, roll);
        const EnuBasis& e = pose.enu;
        const glm::dvec3 forward =
            local.forward.x * e.east + local.forward.y * e.north + local.forward.z * e.up;
        EXPECT_NEAR(glm::length(pose.world.forward - forward), 0.0, 1e-14);
        // The pitch is the elevation above the local horizontal (the ellipsoid's tangent plane).
        EXPECT_NEAR(std::asin(glm::dot(pose.world.forward, e.up)) / kDegree, pitch, 1e-6);
      }
  camera.heading = 0.0;
  camera.pitch = 0.0;
  camera.roll = 0.0;
  const CameraPose level = planet.camera_pose(camera);
  EXPECT_NEAR(glm::length(level.world.forward - level.enu.north), 0.0, 1e-14);
  EXPECT_NEAR(glm::length(level.world.up - level.enu.up), 0.0, 1e-14);
  EXPECT_NEAR(level.nadir_radius, glm::length(planet.ecef(45.0, 180.0, 0.0)), 1e-9);
  EXPECT_NEAR(level.curvature_radius, planet.curvature_radius(45.0), 1e-9);
}

// A point 1 mm from the camera (up, east, north, and across the antimeridian) comes out 1 mm
// away in the camera's ENU frame, to < 1e-6 m (measured < 1e-8 m). ECEF differences in double
// carry an absolute error of a few 1e-9 m at the Earth's radius, whatever the distance.
TEST(Geodesy, CameraRelativeOffsetsKeepOneMillimetre) {
  const Planet planet;
  const double d = 1e-3;  // m
  double worst = 0.0;     // m
  const auto check = [&](const LocalFrame& frame, double lat, double lon, double h,
                         const glm::dvec3& expected) {
    const glm::dvec3 offset = frame.offset(lat, lon, h);
    const double error = glm::length(offset - expected);
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-6) << "point " << lat << ", " << lon << ", " << h;
    // The ECEF path gives the same offset.
    const double ecef_error = glm::length(frame.offset(planet.ecef(lat, lon, h)) - expected);
    worst = std::max(worst, ecef_error);
    EXPECT_LT(ecef_error, 1e-6);
  };
  const double a = planet.equatorial_radius(), f = planet.flattening(), e2 = f * (2.0 - f);
  for (double lat : {0.0, 45.0, -45.0, 89.9, -89.9, 90.0})
    for (double lon : {180.0, -180.0})
      for (double h : {0.0, 1.0, 20e3}) {
        SCOPED_TRACE("camera lat " + std::to_string(lat) + " lon " + std::to_string(lon) + " h " +
                     std::to_string(h));
        const LocalFrame frame = planet.local_frame(lat, lon, h);
        EXPECT_EQ(glm::length(frame.offset(lat, lon, h)), 0.0);
        check(frame, lat, lon, h + d, {0.0, 0.0, d});
        check(frame, lat, lon, h - d, {0.0, 0.0, -d});
        // Radii of curvature: meridian M and prime vertical N (m).
        const double s = std::sin(lat * kDegree), w = std::sqrt(1.0 - e2 * s * s);
        const double m = a * (1.0 - e2) / (w * w * w), n = a / w;
        const double dlat = d / (m + h) / kDegree;  // degrees
        if (lat < 90.0) check(frame, lat + dlat, lon, h, {0.0, d, 0.0});
        check(frame, lat - dlat, lon, h, {0.0, -d, 0.0});
        if (std::abs(lat) < 90.0) {
          const double dlon = d / ((n + h) * std::cos(lat * kDegree)) / kDegree;  // degrees
          check(frame, lat, lon + dlon, h, {d, 0.0, 0.0});
          check(frame, lat, lon - dlon, h, {-d, 0.0, 0.0});
          // Across the antimeridian: the same points written on the other side of +-180.
          check(frame, lat, lon + dlon - 360.0, h, {d, 0.0, 0.0});
          check(frame, lat, lon - dlon + 360.0, h, {-d, 0.0, 0.0});
        }
      }
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", worst);
  RecordProperty("worst_offset_error_m", text);
  EXPECT_LT(worst, 1e-8);
  // to_ecef inverts offset.
  const LocalFrame frame = planet.local_frame(45.0, 180.0, 1.0);
  const glm::dvec3 p = planet.ecef(45.001, -179.999, 3.0);
  EXPECT_LT(glm::length(frame.to_ecef(frame.offset(p)) - p), 1e-8);
}

// Far points: the offset is the ECEF difference rotated into the camera's ENU axes.
TEST(Geodesy, CameraRelativeOffsetsOfFarPoints) {
  const Planet planet;
  const LocalFrame frame = planet.local_frame(-30.0, 170.0, 400e3);
  const glm::dvec3 p = planet.ecef(-35.0, -175.0, 0.0);
  const glm::dvec3 offset = frame.offset(-35.0, -175.0, 0.0);
  EXPECT_NEAR(glm::length(offset), glm::length(p - frame.origin_ecef()), 1e-8);
  EXPECT_NEAR(glm::length(frame.direction_to_ecef(offset) - (p - frame.origin_ecef())), 0.0, 1e-8);
  const LocalFrame copy = frame;  // copies keep the origin
  EXPECT_EQ(copy.offset(-35.0, -175.0, 0.0), offset);
}

void expect_invalid(const std::function<void()>& call, const std::string& fragment) {
  try {
    call();
    ADD_FAILURE() << "no std::invalid_argument; expected one mentioning " << fragment;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

TEST(Geodesy, BadInputThrowsWithAMessage) {
  const Planet planet;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_invalid([&] { planet.ecef(91.0, 0.0, 0.0); }, "latitude: expected");
  expect_invalid([&] { planet.ecef(91.0, 0.0, 0.0); }, "got 91");
  expect_invalid([&] { planet.ecef(-90.5, 0.0, 0.0); }, "[-90, 90]");
  expect_invalid([&] { planet.ecef(nan, 0.0, 0.0); }, "latitude");
  expect_invalid([&] { planet.ecef(0.0, inf, 0.0); }, "longitude");
  expect_invalid([&] { planet.ecef(0.0, 0.0, nan); }, "height");
  expect_invalid([&] { planet.geodetic({nan, 0.0, 0.0}); }, "ECEF x");
  expect_invalid([&] { planet.enu_basis(91.0, 0.0); }, "Planet::enu_basis");
  expect_invalid([&] { planet.nadir_radius(inf); }, "latitude");
  expect_invalid([&] { planet.local_frame(0.0, nan, 0.0); }, "LocalFrame");
  const LocalFrame frame = planet.local_frame(0.0, 0.0, 0.0);
  expect_invalid([&] { frame.offset(95.0, 0.0, 0.0); }, "latitude");
  CameraSettings camera;
  camera.lat = 91.0;
  expect_invalid([&] { planet.camera_pose(camera); }, "latitude");
  camera.lat = 0.0;
  camera.pitch = nan;
  expect_invalid([&] { planet.camera_pose(camera); }, "camera.pitch");
  expect_invalid([] { Planet::sphere(0.0); }, "radius");
  expect_invalid([&] { Planet::sphere(nan); }, "radius");
  PlanetSettings settings;
  settings.shape = PlanetShape::Sphere;
  settings.radius = -1.0;
  expect_invalid([&] { Planet{settings}; }, "radius");
}

}  // namespace
}  // namespace thalassa
