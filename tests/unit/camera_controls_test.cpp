// planet/camera_controls.hpp: the free-flying camera of `thalassa view`. Its moves are checked
// against GeographicLib's inverse problem (the distance and azimuth it flew), its climb against
// the exponential it composes, and its edges (the poles, the antimeridian, the pitch's limits,
// bad input).
#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "thalassa/planet/camera_controls.hpp"

namespace thalassa {
namespace {

struct Flown {
  double distance = 0.0;  // m
  double azimuth = 0.0;   // degrees at the start
};

Flown flown(const CameraSettings& from, const CameraSettings& to) {
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  Flown f;
  double azimuth_end = 0.0;
  wgs84.Inverse(from.lat, from.lon, to.lat, to.lon, f.distance, f.azimuth, azimuth_end);
  return f;
}

double angle_difference(double a, double b) { return std::remainder(a - b, 360.0); }

CameraSettings camera_at(double height) {
  CameraSettings camera;
  camera.lat = 20.0;
  camera.lon = -150.0;
  camera.height = height;
  camera.heading = 30.0;
  camera.pitch = -5.0;
  return camera;
}

TEST(CameraControls, MovesHalfItsHeightASecondAlongItsHeading) {
  const Planet planet;
  for (const double height : {4.0, 100.0, 8000.0, 400000.0}) {
    const CameraSettings camera = camera_at(height);
    const CameraSettings ahead = move_camera(planet, camera, {.forward = 1.0}, 1.0);
    const Flown f = flown(camera, ahead);
    EXPECT_NEAR(f.distance, std::max(0.5 * height, 1.0), 1e-6 * height) << height;
    EXPECT_NEAR(angle_difference(f.azimuth, camera.heading), 0.0, 1e-6) << height;
    EXPECT_EQ(ahead.height, camera.height);
    EXPECT_EQ(ahead.pitch, camera.pitch);
    // Sideways: a quarter turn right of the heading, and the heading kept along the way.
    const CameraSettings right = move_camera(planet, camera, {.right = 1.0}, 2.0);
    const Flown r = flown(camera, right);
    EXPECT_NEAR(r.distance, 2.0 * std::max(0.5 * height, 1.0), 1e-6 * height) << height;
    EXPECT_NEAR(angle_difference(r.azimuth, camera.heading + 90.0), 0.0, 1e-6) << height;
    // A diagonal is no faster; backwards is the way back.
    const Flown d = flown(camera, move_camera(planet, camera, {.forward = 1.0, .right = 1.0}, 1.0));
    EXPECT_NEAR(d.distance, f.distance, 1e-6 * height) << height;
    EXPECT_NEAR(angle_difference(d.azimuth, camera.heading + 45.0), 0.0, 1e-6) << height;
    const CameraSettings back = move_camera(planet, ahead, {.forward = -1.0}, 1.0);
    EXPECT_NEAR(flown(camera, back).distance, 0.0, 1e-6 * height) << height;
  }
  // A camera at the sea still moves at the floor's speed.
  EXPECT_NEAR(
      flown(camera_at(0.0), move_camera(planet, camera_at(0.0), {.forward = 1.0}, 3.0)).distance,
      3.0, 1e-9);
}

TEST(CameraControls, ClimbDoublesTheHeightEachSecondAndComposes) {
  const Planet planet;
  const CameraSettings camera = camera_at(100.0);
  const CameraSettings up = move_camera(planet, camera, {.climb = 1.0}, 1.0);
  EXPECT_NEAR(up.height, 200.0, 1e-9);
  // Steps compose: ten steps of 0.1 s are one step of 1 s; a boost of 5 is 5 s.
  CameraSettings steps = camera;
  for (int i = 0; i < 10; ++i) steps = move_camera(planet, steps, {.climb = 1.0}, 0.1);
  EXPECT_NEAR(steps.height, up.height, 1e-9);
  EXPECT_NEAR(move_camera(planet, camera, {.climb = 1.0, .boost = 5.0}, 1.0).height, 3200.0, 1e-6);
  // Down by the same factor, to the floor and no lower; up to the ceiling and no higher.
  EXPECT_NEAR(move_camera(planet, camera, {.climb = -1.0}, 1.0).height, 50.0, 1e-9);
  EXPECT_EQ(move_camera(planet, camera, {.climb = -1.0}, 60.0).height, 0.5);
  EXPECT_EQ(move_camera(planet, camera, {.climb = 1.0}, 60.0).height, 1e9);
  // A scene's camera below the floor (1 cm over the sea) is not lifted by a descent, and a
  // climb starts from the floor.
  const CameraSettings low = camera_at(0.01);
  EXPECT_EQ(move_camera(planet, low, {.climb = -1.0}, 1.0).height, 0.01);
  EXPECT_NEAR(move_camera(planet, low, {.climb = 1.0}, 1.0).height, 1.0, 1e-12);
  // No motion: the camera as it was, to the bit.
  const CameraSettings same = move_camera(planet, camera, {}, 1.0);
  EXPECT_EQ(same.lat, camera.lat);
  EXPECT_EQ(same.lon, camera.lon);
  EXPECT_EQ(same.height, camera.height);
  EXPECT_EQ(same.heading, camera.heading);
}

TEST(CameraControls, CrossesThePoleAndTheAntimeridian) {
  const Planet planet;
  // 20 km north from 10 km short of the pole: over it, now heading south, 180 degrees of
  // longitude further.
  CameraSettings polar = camera_at(40000.0);
  polar.lat = 89.91;
  polar.lon = 10.0;
  polar.heading = 0.0;
  const CameraSettings over = move_camera(planet, polar, {.forward = 1.0}, 1.0);
  EXPECT_GT(over.lat, 89.8);
  EXPECT_LT(over.lat, 90.0);
  EXPECT_NEAR(angle_difference(over.lon, -170.0), 0.0, 1e-6);
  EXPECT_NEAR(angle_difference(over.heading, 180.0), 0.0, 1e-6);
  EXPECT_NEAR(flown(polar, over).distance, 20000.0, 1e-3);
  // East across 180 degrees: the longitude in [-180, 180].
  CameraSettings east = camera_at(1000.0);
  east.lat = 0.0;
  east.lon = 179.999;
  east.heading = 90.0;
  const CameraSettings across = move_camera(planet, east, {.forward = 1.0}, 1.0);
  EXPECT_GE(across.lon, -180.0);
  EXPECT_LT(across.lon, -179.99);
  EXPECT_NEAR(flown(east, across).distance, 500.0, 1e-6);
}

TEST(CameraControls, TurnsWrapTheHeadingAndHoldThePitch) {
  const Planet planet;
  CameraSettings camera = camera_at(10.0);
  camera.heading = 350.0;
  const CameraSettings turned =
      move_camera(planet, camera, {.turn_deg = 20.0, .pitch_deg = -100.0}, 0.0);
  EXPECT_NEAR(turned.heading, 10.0, 1e-12);
  EXPECT_EQ(turned.pitch, -90.0);
  EXPECT_NEAR(move_camera(planet, camera, {.turn_deg = -710.0}, 0.0).heading, 0.0, 1e-9);
  EXPECT_EQ(move_camera(planet, camera, {.pitch_deg = 120.0}, 0.0).pitch, 90.0);
  // A turn and a move in one step move along the new heading.
  const CameraSettings moved = move_camera(planet, camera, {.forward = 1.0, .turn_deg = 40.0}, 1.0);
  EXPECT_NEAR(angle_difference(flown(camera, moved).azimuth, 30.0), 0.0, 1e-6);
}

TEST(CameraControls, RefusesInputThatIsNotFinite) {
  const Planet planet;
  const CameraSettings camera = camera_at(10.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(move_camera(planet, camera, {.forward = 1.0}, nan), std::invalid_argument);
  EXPECT_THROW(move_camera(planet, camera, {.forward = 1.0}, -0.1), std::invalid_argument);
  EXPECT_THROW(move_camera(planet, camera, {.forward = nan}, 0.1), std::invalid_argument);
  EXPECT_THROW(move_camera(planet, camera, {.turn_deg = inf}, 0.1), std::invalid_argument);
  EXPECT_THROW(move_camera(planet, camera, {.boost = 0.0}, 0.1), std::invalid_argument);
  // Far outside [-1, 1] is full speed, no more.
  EXPECT_NEAR(flown(camera, move_camera(planet, camera, {.forward = 1e6}, 1.0)).distance, 5.0,
              1e-9);
}

}  // namespace
}  // namespace thalassa
