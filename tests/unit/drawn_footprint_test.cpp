// drawn_footprint (planet/sea_state.hpp): at the rest point of each vertex of the grid the
// renderer makes for a scene (ocean::make_projected_grid with the scene's camera, cell and sea at
// rest), the footprint is that vertex's cell size (over the hand-over's scale between 10 and
// 20 km), from 2 m to 15 km up, on the WGS84 ellipsoid and a sphere, looking down and at the
// horizon; and it is absent where the grid draws no waves.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "thalassa/ocean/gl/ocean_node.hpp"
#include "thalassa/ocean/projected_grid.hpp"
#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/planet/renderer.hpp"
#include "thalassa/planet/sea_state.hpp"

namespace thalassa {
namespace {

Scene scene_at(double height, double pitch, double roll, PlanetShape shape) {
  Scene scene;
  scene.image.width = 96;
  scene.image.height = 64;
  scene.camera.lat = 43.7;
  scene.camera.lon = 7.4;
  scene.camera.height = height;
  scene.camera.heading = 123.0;
  scene.camera.pitch = pitch;
  scene.camera.roll = roll;
  scene.planet.shape = shape;
  scene.ocean.grid_cell = 8.0;
  return scene;
}

// Beside the horizon, relative: the next vertex is the horizon's point reached along the row or
// the column here, across the horizon's line by the grid (measured 3.9e-3; falling back to the
// previous vertex instead was off by factors of 0.03 to 60).
constexpr double kBesideHorizon = 1e-2;

TEST(DrawnFootprint, IsTheGridsCellAtItsVertices) {
  double worst = 0.0, worst_beside = 0.0;
  int compared = 0, compared_beside = 0;
  for (PlanetShape shape : {PlanetShape::Wgs84, PlanetShape::Sphere})
    for (double height : {2.0, 100.0, 5000.0, 15000.0})
      for (double pitch : {-90.0, -30.0, -3.0, 5.0})
        for (double roll : {0.0, 30.0}) {
          const Scene scene = scene_at(height, pitch, roll, shape);
          const Planet planet(scene.planet);
          const NadirFrame frame = make_nadir_frame(planet, scene.camera);
          const CameraBasis b = camera_basis(scene.camera.heading, pitch, roll);
          const ocean::GridCamera camera = ocean::make_grid_camera(
              b.right, b.up, b.forward, std::tan(0.5 * scene.camera.fov_y * M_PI / 180.0), height,
              scene.image.width, scene.image.height, frame.sea_surface);
          const ocean::ProjectedGrid grid =
              ocean::make_projected_grid(camera, scene.ocean.grid_cell, 0);
          const LocalFrame nadir = planet.local_frame(frame.nadir.lat, frame.nadir.lon, 0.0);
          const double scale = ocean::resolved_wave_scale(height);
          const glm::dvec2 step(2.0 * scene.ocean.grid_cell / scene.image.width,
                                2.0 * scene.ocean.grid_cell / scene.image.height);
          const std::string where = std::string(shape == PlanetShape::Sphere ? "sphere" : "wgs84") +
                                    " h " + std::to_string(height) + " pitch " +
                                    std::to_string(pitch) + " roll " + std::to_string(roll);
          for (int j = 0; j + 1 < grid.rows; ++j)
            for (int i = 0; i + 1 < grid.columns; ++i) {
              const std::size_t k = static_cast<std::size_t>(j) * grid.columns + i;
              // Vertices on the lattice (not moved onto the horizon, where the cell is the
              // distance from the nadir); their next ones along the row and the column may be.
              const glm::dvec2 lattice = glm::dvec2(-1.0) + glm::dvec2(i, j) * step;
              const auto on_lattice = [&](std::size_t v, glm::dvec2 at) {
                return glm::length(grid.image[v] - at) < 1e-12;
              };
              if (!on_lattice(k, lattice)) continue;
              const bool beside_horizon =
                  !on_lattice(k + 1, lattice + glm::dvec2(step.x, 0)) ||
                  !on_lattice(k + grid.columns, lattice + glm::dvec2(0, step.y));
              const Geodetic g = planet.geodetic(nadir.to_ecef(grid.rest[k]));
              const std::optional<double> footprint = drawn_footprint(scene, g.lat, g.lon);
              ASSERT_TRUE(footprint.has_value()) << where << " vertex " << k;
              const double error = std::abs(*footprint * scale / grid.cell_size[k] - 1.0);
              if (beside_horizon) {
                // The next vertex on the horizon, reached along the row or the column here, across
                // the horizon's line by the grid.
                EXPECT_LT(error, kBesideHorizon) << where << " vertex " << k;
                worst_beside = std::max(worst_beside, error);
                ++compared_beside;
                continue;
              }
              ASSERT_LT(error, 1e-6) << where << " vertex " << k << ": " << *footprint << " m";
              worst = std::max(worst, error);
              ++compared;
            }
        }
  std::printf(
      "%d vertices: the footprint is their cell size to %.1e (relative); %d beside the "
      "horizon, to %.1e\n",
      compared, worst, compared_beside, worst_beside);
  EXPECT_GT(compared_beside, 100);
  EXPECT_GT(compared, 3000);  // 4,164
}

TEST(DrawnFootprint, AbsentWhereTheGridDrawsNoWaves) {
  const Scene down = scene_at(100.0, -90.0, 0.0, PlanetShape::Wgs84);
  ASSERT_TRUE(drawn_footprint(down, down.camera.lat, down.camera.lon).has_value());
  // Behind a camera looking at the horizon (heading 123): 50 m the other way.
  const Scene level = scene_at(4.0, -5.0, 0.0, PlanetShape::Wgs84);
  const double north = 50.0 / 111e3;  // degrees, 50 m; heading 123 looks south-east
  EXPECT_FALSE(drawn_footprint(level, level.camera.lat + north, level.camera.lon).has_value());
  // Ahead, 1 km away, it is there; 100 km away (the horizon from 4 m is 7 km) it is hidden.
  const double east = 1.0 / (111.0 * std::cos(level.camera.lat * M_PI / 180.0));  // degrees/km
  const double south = 1.0 / 111.0;
  EXPECT_TRUE(
      drawn_footprint(level, level.camera.lat - 0.54 * south, level.camera.lon + 0.84 * east)
          .has_value());
  EXPECT_FALSE(drawn_footprint(level, level.camera.lat - 54 * south, level.camera.lon + 84 * east)
                   .has_value());
  // Under the sea, and in space mode.
  Scene under = down;
  under.camera.height = -2.0;
  EXPECT_FALSE(drawn_footprint(under, down.camera.lat, down.camera.lon).has_value());
  Scene space = down;
  space.camera.height = kSpaceModeHeight;
  EXPECT_FALSE(drawn_footprint(space, down.camera.lat, down.camera.lon).has_value());
  // On the sea (height 0) the renderer looks from kSurfaceCameraHeight.
  Scene on = level;
  on.camera.height = 0.0;
  EXPECT_TRUE(
      drawn_footprint(on, level.camera.lat - 0.001 * south, level.camera.lon + 0.0016 * east)
          .has_value());
  EXPECT_THROW(drawn_footprint(down, 90.5, 0.0), std::invalid_argument);
  EXPECT_THROW(drawn_footprint(down, 0.0, NAN), std::invalid_argument);
}

// A camera on the sea (height 0, drawn from kSurfaceCameraHeight) sees every point ahead of it
// from 5 cm to 100 m, and none past its horizon (113 m from 1 mm up): a horizon test by the ray's
// meeting the quadric refused 1 in 10 of the first (its grazing rays carry the point's rounding,
// 1e-9 m, into 1e-6 of the distance).
TEST(DrawnFootprint, ACameraOnTheSeaSeesTheSeaAheadToItsHorizon) {
  Scene scene = scene_at(0.0, -5.0, 0.0, PlanetShape::Wgs84);
  scene.camera.heading = 0.0;  // north
  const Planet planet(scene.planet);
  const LocalFrame nadir = planet.local_frame(scene.camera.lat, scene.camera.lon, 0.0);
  const auto seen = [&](double distance) {
    const Geodetic p = planet.geodetic(nadir.to_ecef({0.0, distance, 0.0}));
    return drawn_footprint(scene, p.lat, scene.camera.lon).has_value();
  };
  int visible = 0, points = 0;
  for (double distance = 0.05; distance < 100.0; distance *= 1.01, ++points)
    visible += seen(distance) ? 1 : 0;
  EXPECT_EQ(visible, points);
  for (double distance = 120.0; distance < 1000.0; distance *= 1.1)
    EXPECT_FALSE(seen(distance)) << distance << " m";
}

// Between 10 and 20 km the grid hands its waves to the view from space: the footprint grows
// as their scale falls (it doubles at 15 km, where the scale is a half).
TEST(DrawnFootprint, GrowsThroughTheHandOverToSpace) {
  Scene scene = scene_at(15000.0, -90.0, 0.0, PlanetShape::Wgs84);
  const double at_15km = *drawn_footprint(scene, scene.camera.lat, scene.camera.lon);
  EXPECT_DOUBLE_EQ(ocean::resolved_wave_scale(15000.0), 0.5);
  // Straight down, the cell is the height times 2 tan(fov / 2) cell_px / image height.
  const double cell = 15000.0 * 2.0 * std::tan(22.5 * M_PI / 180.0) * 8.0 / 64.0;
  EXPECT_NEAR(at_15km / (2.0 * cell), 1.0, 1e-3);
}

}  // namespace
}  // namespace thalassa
