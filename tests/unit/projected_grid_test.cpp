// The projected grid (issue 3, point 2): for any heading, pitch and roll, the camera looking
// above the horizon included, the grid covers every pixel that sees the sea, no triangle folds
// over or degenerates, every vertex is in front of the camera and finite, and the vertices on
// the sky's side sit on the horizon line.
#include <gtest/gtest.h>

#include <cmath>

#include "thalassa/ocean/projected_grid.hpp"
#include "thalassa/planet/camera_frame.hpp"

namespace thalassa::ocean {
namespace {

GridCamera make_camera(double heading, double pitch, double roll, int width, int height,
                       double camera_height = 4.0, double fov_y = 45.0) {
  const CameraBasis b = camera_basis(heading, pitch, roll);
  return make_grid_camera(b.right, b.up, b.forward, std::tan(0.5 * fov_y * M_PI / 180.0),
                          camera_height, width, height);
}

double ray_z(const GridCamera& c, glm::dvec2 image) { return grid_ray(c, image).z; }

// Twice the signed area of triangle (a, b, c) in the image plane.
double signed_area(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool inside(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  const double tolerance = -1e-12;
  return signed_area(a, b, p) >= tolerance && signed_area(b, c, p) >= tolerance &&
         signed_area(c, a, p) >= tolerance;
}

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr double kCell = 8.0;

TEST(ProjectedGrid, CoversTheSeaForAnyOrientation) {
  int cameras = 0, with_horizon = 0;
  for (double heading : {0.0, 37.0, 180.0, 300.0})
    for (double pitch : {-90.0, -45.0, -10.0, -1.0, 0.0, 3.0, 15.0, 21.0})
      for (double roll : {-180.0, -90.0, -30.0, 0.0, 10.0, 90.0, 135.0}) {
        const GridCamera c = make_camera(heading, pitch, roll, kWidth, kHeight);
        const ProjectedGrid g = make_projected_grid(c, kCell, 2);
        // Does any pixel centre see the sea?
        bool any_sea = false;
        for (int y = 0; y < kHeight; ++y)
          for (int x = 0; x < kWidth; ++x)
            any_sea = any_sea || ray_z(c, {2.0 * (x + 0.5) / kWidth - 1.0,
                                           1.0 - 2.0 * (y + 0.5) / kHeight}) < 0.0;
        if (!any_sea) continue;  // e.g. looking up: the sky pass covers it all
        ASSERT_GT(g.rows, 0) << heading << " " << pitch << " " << roll;
        ++cameras;
        if (g.moved_to_horizon > 0) ++with_horizon;
        for (std::size_t k = 0; k < g.rest.size(); ++k) {
          ASSERT_TRUE(std::isfinite(g.rest[k].x) && std::isfinite(g.rest[k].y));
          ASSERT_TRUE(std::isfinite(g.cell_size[k]) && g.cell_size[k] > 0.0);
          // In front of the camera: the rest point seen from the camera has a positive
          // component along the view axis.
          const glm::dvec3 d(g.rest[k].x, g.rest[k].y, -c.height);
          ASSERT_GT(glm::dot(d, c.forward), 0.0);
          ASSERT_LE(ray_z(c, g.image[k]), -kHorizonDepression * (1.0 - 1e-9));
        }
        // No fold-over and no degenerate triangle: all counterclockwise with positive area.
        for (std::size_t t = 0; t < g.indices.size(); t += 3) {
          const double area = signed_area(g.image[g.indices[t]], g.image[g.indices[t + 1]],
                                          g.image[g.indices[t + 2]]);
          ASSERT_GT(area, 0.0) << heading << " " << pitch << " " << roll << " triangle " << t;
        }
        // Coverage: every pixel centre that sees the sea (a hair below the horizon) is inside
        // some triangle.
        for (int y = 0; y < kHeight; ++y)
          for (int x = 0; x < kWidth; ++x) {
            const glm::dvec2 p(2.0 * (x + 0.5) / kWidth - 1.0, 1.0 - 2.0 * (y + 0.5) / kHeight);
            if (ray_z(c, p) >= -2.0 * kHorizonDepression) continue;
            bool covered = false;
            for (std::size_t t = 0; t < g.indices.size() && !covered; t += 3)
              covered = inside(p, g.image[g.indices[t]], g.image[g.indices[t + 1]],
                               g.image[g.indices[t + 2]]);
            ASSERT_TRUE(covered) << "pixel " << x << "," << y << " of camera " << heading << " "
                                 << pitch << " " << roll;
          }
      }
  EXPECT_GT(cameras, 100);
  EXPECT_GT(with_horizon, 50);  // the horizon case was exercised
}

TEST(ProjectedGrid, NoGridWithoutSeaOrBelowTheSurface) {
  EXPECT_EQ(make_projected_grid(make_camera(0, 60, 0, kWidth, kHeight), kCell, 2).rows, 0);
  EXPECT_EQ(make_projected_grid(make_camera(0, -10, 0, kWidth, kHeight, -1.0), kCell, 2).rows, 0);
  EXPECT_EQ(make_projected_grid(make_camera(0, -10, 0, kWidth, kHeight, 0.0), kCell, 2).rows, 0);
}

TEST(ProjectedGrid, RestPositionsAreTheRayPlaneIntersections) {
  // Looking straight down from 100 m with a 90 degree field: the image's corners see the sea
  // 100 m away along each axis (times the aspect horizontally), the centre right below.
  const GridCamera c = make_camera(0, -90, 0, 64, 64, 100.0, 90.0);
  const ProjectedGrid g = make_projected_grid(c, 8.0, 0);
  ASSERT_EQ(g.columns, 9);
  EXPECT_EQ(g.moved_to_horizon, 0);
  const std::size_t centre = 4 * 9 + 4, corner = 0;
  EXPECT_NEAR(glm::length(g.rest[centre]), 0.0, 1e-9);
  // Image corner (-1, -1): right = east, up = north when looking down with heading 0.
  EXPECT_NEAR(g.rest[corner].x, -100.0, 1e-9);
  EXPECT_NEAR(g.rest[corner].y, -100.0, 1e-9);
  EXPECT_NEAR(g.cell_size[centre], 25.0, 1e-9);  // 8 of 64 pixels over 200 m
}

}  // namespace
}  // namespace thalassa::ocean
