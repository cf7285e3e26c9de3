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
// A point whose image point's ray meets the sea at rest farther than this from it, relative to
// its distance from the camera, is hidden beyond the horizon (the ray met the sea before it).
// The ray's own intersection is exact to about 1e-12 of the distance (projected_grid.hpp).
constexpr double kHiddenTolerance = 1e-6;

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
  // image point.
  const LocalFrame nadir = planet.local_frame(frame.nadir.lat, frame.nadir.lon, 0.0);
  const glm::dvec3 point = nadir.offset(lat, lon, 0.0);
  const glm::dvec3 eye(0.0, 0.0, height);
  const glm::dvec3 d = point - eye;
  const double along = glm::dot(d, camera.forward);
  if (!(along > 0.0)) return std::nullopt;
  const glm::dvec2 image(
      glm::dot(d, camera.right) / (along * camera.tan_half_fov_y * camera.aspect),
      glm::dot(d, camera.up) / (along * camera.tan_half_fov_y));
  glm::dvec3 rest;
  if (!ocean::sea_point(camera, image, rest) ||
      glm::length(rest - point) > kHiddenTolerance * glm::length(d))
    return std::nullopt;

  // The grid's cell there: to the next vertex along a row and along a column, or to the previous
  // one where the next would be beyond the horizon (as the grid's last row and column).
  const double cell_px = scene.ocean.grid_cell;
  const glm::dvec2 steps[2] = {{2.0 * cell_px / scene.image.width, 0.0},
                               {0.0, 2.0 * cell_px / scene.image.height}};
  double cell = 0.0;
  for (const glm::dvec2& step : steps) {
    glm::dvec3 next;
    if (!ocean::sea_point(camera, image + step, next) &&
        !ocean::sea_point(camera, image - step, next))
      return std::nullopt;
    cell = std::max(cell, glm::length(next - rest));
  }
  return cell / scale;
}

}  // namespace thalassa
