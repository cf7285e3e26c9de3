#include "thalassa/ocean/sea_surface.hpp"

#include <cmath>

namespace thalassa::ocean {

SeaSurface flat_sea_surface() { return {}; }

SeaSurface spherical_sea_surface(double radius_m) {
  SeaSurface surface;
  surface.curvature = glm::dmat3(1.0 / radius_m);
  return surface;
}

double sea_surface_value(const SeaSurface& surface, const glm::dvec3& x) {
  return x.z + 0.5 * glm::dot(x, surface.curvature * x);
}

glm::dvec3 sea_surface_normal(const SeaSurface& surface, const glm::dvec3& x) {
  return glm::normalize(glm::dvec3(0.0, 0.0, 1.0) + surface.curvature * x);
}

glm::dvec3 sea_surface_ray_coefficients(const SeaSurface& surface, double height,
                                        const glm::dvec3& ray) {
  const glm::dmat3& c = surface.curvature;
  const glm::dvec3 c_z = c[2];  // C z-hat (C is symmetric)
  return {0.5 * glm::dot(ray, c * ray), ray.z + height * glm::dot(c_z, ray),
          height * (1.0 + 0.5 * height * c_z.z)};
}

std::optional<double> sea_surface_distance(const SeaSurface& surface, double height,
                                           const glm::dvec3& ray) {
  if (!(height > 0.0)) return std::nullopt;
  const glm::dvec3 q = sea_surface_ray_coefficients(surface, height, ray);
  if (!(q.y < 0.0)) return std::nullopt;  // moving away from (or along) the surface
  const double discriminant = q.y * q.y - 4.0 * q.x * q.z;
  if (!(discriminant >= 0.0)) return std::nullopt;
  return 2.0 * q.z / (-q.y + std::sqrt(discriminant));
}

}  // namespace thalassa::ocean
