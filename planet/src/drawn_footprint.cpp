// thalassa — the projected grid's cell at a point, as SeaState::at's footprint
// (planet/sea_state.hpp, drawn_footprint).
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "thalassa/ocean/gl/ocean_node.hpp"
#include "thalassa/ocean/projected_grid.hpp"
#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/planet/renderer.hpp"
#include "thalassa/planet/sea_state.hpp"

namespace thalassa {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
// Bisections for the horizon's point between two image points (the grid's vertex moved onto the
// horizon): 2^-60 of a cell's step is below any rounding of the image plane.
constexpr int kHorizonBisections = 60;

}  // namespace

std::optional<double> drawn_footprint(const Scene& scene, double lat, double lon) {
  if (!(lat >= -90.0 && lat <= 90.0) || !std::isfinite(lon)) {
    std::ostringstream message;
    message.precision(17);
    message << "thalassa::drawn_footprint: expected lat in [-90, 90] and a finite lon, got (" << lat
            << ", " << lon << ")";
    throw std::invalid_argument(message.str());
  }
  // As the renderer: under the sea no grid, from kSpaceModeHeight the view from space.
  if (!(scene.camera.height >= 0.0) || scene.camera.height >= kSpaceModeHeight) return std::nullopt;
  const double scale = ocean::resolved_wave_scale(scene.camera.height);
  if (!(scale > 0.0)) return std::nullopt;

  const Planet planet(scene.planet);
  const NadirFrame frame = make_nadir_frame(planet, scene.camera);
  const CameraBasis basis =
      camera_basis(scene.camera.heading, scene.camera.pitch, scene.camera.roll);
  const double height = std::max(scene.camera.height, kSurfaceCameraHeight);
  const ocean::GridCamera camera = ocean::make_grid_camera(
      basis.right, basis.up, basis.forward, std::tan(0.5 * scene.camera.fov_y * kDegree), height,
      scene.image.width, scene.image.height, frame.sea_surface);

  // The point on the sea at rest (the ellipsoid, or the sphere), in the nadir frame, and its
  // image point. The sea at rest is convex: the camera sees the point when it is on the outer
  // side of the tangent plane there (a test that holds for a camera 1 mm up, where a ray met with
  // the quadric near its horizon would carry the point's rounding, 1e-9 m, into 1e-6 of the
  // distance). Points between the horizon and the grid's last row, a relative 4.5e-5 of the
  // distance short of it (ocean::kHorizonMargin), have no grid waves either.
  const LocalFrame nadir = planet.local_frame(frame.nadir.lat, frame.nadir.lon, 0.0);
  const glm::dvec3 point = nadir.offset(lat, lon, 0.0);
  const glm::dvec3 eye(0.0, 0.0, height);
  const glm::dvec3 d = point - eye;
  const double along = glm::dot(d, camera.forward);
  if (!(along > 0.0) || !(glm::dot(ocean::sea_surface_normal(frame.sea_surface, point), -d) > 0.0))
    return std::nullopt;
  const glm::dvec2 image(
      glm::dot(d, camera.right) / (along * camera.tan_half_fov_y * camera.aspect),
      glm::dot(d, camera.up) / (along * camera.tan_half_fov_y));
  const auto kept = [&](glm::dvec2 at) {
    return ocean::grid_horizon_clearance(camera, ocean::grid_ray(camera, at)) >= 0.0;
  };
  if (!kept(image)) return std::nullopt;

  // The grid's cell there: to the next vertex along a row and along a column. Where the next
  // one's ray passes the horizon, the grid has moved that vertex onto it (its cell is then the
  // distance to the horizon): here, the horizon's point between the two image points. The grid
  // moves it across the horizon's line in the image, so the two points part where that line is
  // tilted in the image, by little against their distance.
  const double cell_px = scene.ocean.grid_cell;
  const glm::dvec2 steps[2] = {{2.0 * cell_px / scene.image.width, 0.0},
                               {0.0, 2.0 * cell_px / scene.image.height}};
  double cell = 0.0;
  for (const glm::dvec2& step : steps) {
    glm::dvec2 next = image + step;
    if (!kept(next)) {
      double inside = 0.0, outside = 1.0;  // fractions of the step
      for (int n = 0; n < kHorizonBisections; ++n) {
        const double middle = 0.5 * (inside + outside);
        (kept(image + middle * step) ? inside : outside) = middle;
      }
      next = image + inside * step;
    }
    glm::dvec3 next_point;
    if (!ocean::sea_point(camera, next, next_point)) return std::nullopt;
    cell = std::max(cell, glm::length(next_point - point));
  }
  return cell / scale;
}

}  // namespace thalassa
