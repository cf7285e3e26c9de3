// Camera and sun frames: orthonormality at every angle, the sign conventions of DESIGN
// section 4, and the limits (straight up and down, rolled, azimuths across north).
#include <gtest/gtest.h>

#include <cmath>

#include "thalassa/planet/camera_frame.hpp"

namespace thalassa {
namespace {

constexpr double kTolerance = 1e-12;

void expect_near(const glm::dvec3& a, const glm::dvec3& b) {
  EXPECT_NEAR(a.x, b.x, kTolerance);
  EXPECT_NEAR(a.y, b.y, kTolerance);
  EXPECT_NEAR(a.z, b.z, kTolerance);
}

TEST(CameraFrame, OrthonormalRightHandedEverywhere) {
  for (double heading = -360; heading <= 360; heading += 22.5)
    for (double pitch = -90; pitch <= 90; pitch += 15)
      for (double roll = -180; roll <= 180; roll += 30) {
        const CameraBasis b = camera_basis(heading, pitch, roll);
        EXPECT_NEAR(glm::length(b.right), 1.0, kTolerance);
        EXPECT_NEAR(glm::length(b.up), 1.0, kTolerance);
        EXPECT_NEAR(glm::length(b.forward), 1.0, kTolerance);
        EXPECT_NEAR(glm::dot(b.right, b.up), 0.0, kTolerance);
        EXPECT_NEAR(glm::dot(b.right, b.forward), 0.0, kTolerance);
        EXPECT_NEAR(glm::dot(b.up, b.forward), 0.0, kTolerance);
        expect_near(glm::cross(b.right, b.up), -b.forward);
      }
}

TEST(CameraFrame, HeadingIsClockwiseFromNorth) {
  expect_near(camera_basis(0, 0, 0).forward, {0, 1, 0});   // north
  expect_near(camera_basis(90, 0, 0).forward, {1, 0, 0});  // east
  expect_near(camera_basis(180, 0, 0).forward, {0, -1, 0});
  expect_near(camera_basis(-90, 0, 0).forward, {-1, 0, 0});  // west
  expect_near(camera_basis(0, 0, 0).up, {0, 0, 1});
  expect_near(camera_basis(0, 0, 0).right, {1, 0, 0});
}

TEST(CameraFrame, PitchAboveHorizontalAndVerticalViews) {
  expect_near(camera_basis(0, -90, 0).forward, {0, 0, -1});  // straight down
  expect_near(camera_basis(0, 90, 0).forward, {0, 0, 1});    // straight up
  // Looking down with heading north, the top of the image points north.
  expect_near(camera_basis(0, -90, 0).up, {0, 1, 0});
  const CameraBasis b = camera_basis(30, 45, 0);
  EXPECT_NEAR(std::asin(b.forward.z), 45.0 * M_PI / 180.0, kTolerance);
}

TEST(CameraFrame, PositiveRollBanksRight) {
  // Rolling right, the image's right edge dips below the horizon: right gets a negative z.
  const CameraBasis b = camera_basis(0, 0, 30);
  EXPECT_LT(b.right.z, 0.0);
  EXPECT_NEAR(b.right.z, -0.5, kTolerance);
  expect_near(camera_basis(0, 0, 180).up, {0, 0, -1});  // upside down
  expect_near(camera_basis(0, 0, 90).right, {0, 0, -1});
}

TEST(SunDirection, ZenithAndAzimuth) {
  expect_near(sun_direction(0, 123), {0, 0, 1});
  expect_near(sun_direction(90, 0), {0, 1, 0});
  expect_near(sun_direction(90, 90), {1, 0, 0});
  expect_near(sun_direction(180, 0), {0, 0, -1});
  expect_near(sun_direction(60, 180), {0, -std::sin(M_PI / 3), 0.5});
  expect_near(sun_direction(60, 180), sun_direction(60, -180));
}

TEST(ViewRay, CornersSpanTheFieldOfView) {
  const CameraBasis b = camera_basis(0, 0, 0);
  const double t = std::tan(22.5 * M_PI / 180.0);
  const glm::dvec3 top = glm::normalize(view_ray(b, t, 2.0, 0.0, 1.0));
  EXPECT_NEAR(std::asin(top.z), 22.5 * M_PI / 180.0, kTolerance);  // half of fov_y = 45
  const glm::dvec3 right = glm::normalize(view_ray(b, t, 2.0, 1.0, 0.0));
  EXPECT_NEAR(std::atan2(right.x, right.y), std::atan(2.0 * t), kTolerance);
}

}  // namespace
}  // namespace thalassa
