#include "thalassa/ocean/projected_grid.hpp"

#include <algorithm>
#include <cmath>

namespace thalassa::ocean {
GridCamera make_grid_camera(const glm::dvec3& right, const glm::dvec3& up,
                            const glm::dvec3& forward, double tan_half_fov_y, double height,
                            int width_px, int height_px) {
  GridCamera camera;
  camera.right = right;
  camera.up = up;
  camera.forward = forward;
  camera.tan_half_fov_y = tan_half_fov_y;
  camera.aspect = double(width_px) / double(height_px);
  camera.height = height;
  camera.width = width_px;
  camera.height_px = height_px;
  return camera;
}

glm::dvec3 grid_ray(const GridCamera& c, glm::dvec2 image) {
  return c.forward + (image.x * c.tan_half_fov_y * c.aspect) * c.right +
         (image.y * c.tan_half_fov_y) * c.up;
}

bool sea_point(const GridCamera& camera, glm::dvec2 image, glm::dvec2& point) {
  const glm::dvec3 ray = grid_ray(camera, image);
  if (ray.z >= 0.0 || !(camera.height > 0.0)) return false;
  point = glm::dvec2(ray.x, ray.y) * (camera.height / -ray.z);
  return true;
}

ProjectedGrid make_projected_grid(const GridCamera& camera, double cell_px, int margin_cells) {
  ProjectedGrid grid;
  if (!(camera.height > 0.0) || camera.width < 1 || camera.height_px < 1 || !(cell_px > 0.0))
    return grid;
  // ray.z(u, v) = z0 + gu u + gv v: the horizon is the line ray.z = 0 in the image plane.
  const double z0 = camera.forward.z;
  const glm::dvec2 gradient(camera.tan_half_fov_y * camera.aspect * camera.right.z,
                            camera.tan_half_fov_y * camera.up.z);
  const int margin = std::max(margin_cells, 0);
  const int cells_x = static_cast<int>(std::ceil(camera.width / cell_px)) + 2 * margin;
  const int cells_y = static_cast<int>(std::ceil(camera.height_px / cell_px)) + 2 * margin;
  // Image units per cell: 2 / width per pixel horizontally, 2 / height vertically.
  const glm::dvec2 step(2.0 * cell_px / camera.width, 2.0 * cell_px / camera.height_px);
  const glm::dvec2 origin = glm::dvec2(-1.0, -1.0) - double(margin) * step;

  // Is any of the (extended) image below the horizon? ray.z is linear: test the corners.
  bool sees_sea = false;
  for (double u : {origin.x, origin.x + cells_x * step.x})
    for (double v : {origin.y, origin.y + cells_y * step.y})
      sees_sea = sees_sea || z0 + gradient.x * u + gradient.y * v < -kHorizonDepression;
  if (!sees_sea) return grid;

  grid.columns = cells_x + 1;
  grid.rows = cells_y + 1;
  const std::size_t count = static_cast<std::size_t>(grid.columns) * grid.rows;
  grid.rest.resize(count);
  grid.cell_size.resize(count);
  grid.image.resize(count);
  const double gradient2 = glm::dot(gradient, gradient);
  std::vector<bool> moved(count, false);
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      glm::dvec2 image = origin + glm::dvec2(i, j) * step;
      const double z = z0 + glm::dot(gradient, image);
      if (z > -kHorizonDepression && gradient2 > 0.0) {
        // Onto the line ray.z = -kHorizonDepression, along the gradient (the shortest move).
        image -= ((z + kHorizonDepression) / gradient2) * gradient;
        ++grid.moved_to_horizon;
        moved[static_cast<std::size_t>(j) * grid.columns + i] = true;
      }
      const glm::dvec3 ray = grid_ray(camera, image);
      // ray.z <= -kHorizonDepression < 0 here; its forward component is 1 (in front).
      const double t = camera.height / std::max(-ray.z, kHorizonDepression);
      const std::size_t k = static_cast<std::size_t>(j) * grid.columns + i;
      grid.image[k] = image;
      grid.rest[k] = glm::dvec2(ray.x, ray.y) * t;
    }
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * grid.columns + i;
      // The next vertex along the row and along the column (the previous one on the last).
      const std::size_t right = i + 1 < grid.columns ? k + 1 : k - 1;
      const std::size_t above = j + 1 < grid.rows ? k + grid.columns : k - grid.columns;
      grid.cell_size[k] = std::max(glm::length(grid.rest[right] - grid.rest[k]),
                                   glm::length(grid.rest[above] - grid.rest[k]));
      // Vertices moved onto the horizon crowd together along it, so their neighbours say
      // nothing of the footprint, which is unbounded there: take their distance from the nadir
      // (at least 1e5 times any wave it could hold), so that no wave displaces them. (With a
      // small cell the shader would evaluate short waves at ~1e6 m, where float arguments of
      // 1e9 rad make sin() meaningless, NaN on some drivers.)
      if (moved[k]) grid.cell_size[k] = std::max(grid.cell_size[k], glm::length(grid.rest[k]));
    }
  grid.indices.reserve(static_cast<std::size_t>(cells_x) * cells_y * 6);
  // A triangle whose three vertices were all moved onto the horizon is degenerate by
  // construction (they lie on one line of the image): leaving it out keeps rasterisers from
  // dividing by its zero area (llvmpipe then interpolates NaN).
  auto add_triangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (moved[a] && moved[b] && moved[c]) return;
    grid.indices.insert(grid.indices.end(), {a, b, c});
  };
  for (int j = 0; j < cells_y; ++j)
    for (int i = 0; i < cells_x; ++i) {
      const std::uint32_t a = j * grid.columns + i, b = a + 1, c = a + grid.columns, d = c + 1;
      add_triangle(a, b, d);
      add_triangle(a, d, c);
    }
  return grid;
}

}  // namespace thalassa::ocean
