#include "thalassa/ocean/sea_surface.hpp"

#include <algorithm>
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

double sea_surface_sag(const SeaSurface& surface, const glm::dvec2& xy) {
  const glm::dmat3& c = surface.curvature;
  const double c_zz = c[2][2];
  const double b = 1.0 + c[2][0] * xy.x + c[2][1] * xy.y;
  const double q =
      0.5 * (c[0][0] * xy.x * xy.x + 2.0 * c[1][0] * xy.x * xy.y + c[1][1] * xy.y * xy.y);
  if (q == 0.0) return 0.0;  // the nadir, or the flat sea
  const double discriminant = b * b - 2.0 * c_zz * q;
  if (!(discriminant >= 0.0)) return c_zz > 0.0 ? -b / c_zz : 0.0;
  const double denominator = b + std::copysign(std::sqrt(discriminant), b);
  return denominator != 0.0 ? -2.0 * q / denominator : 0.0;
}

double sea_surface_horizon_dip(const SeaSurface& surface, double height,
                               const glm::dvec2& azimuth) {
  if (!(height > 0.0)) return 0.0;
  const glm::dmat3& c = surface.curvature;
  const glm::dvec3 h_dir(azimuth, 0.0);
  const double m = glm::dot(h_dir, c * h_dir);
  // An infinitely far camera sees a curved sea's horizon straight down (inf * 0 would be NaN).
  if (std::isinf(height)) return m > 0.0 ? height : 0.0;
  const double k = glm::dot(glm::dvec3(c[2]), h_dir);
  const double c_zz = c[2][2];
  const double two_cm = 2.0 * height * (1.0 + 0.5 * height * c_zz) * m;
  if (!(two_cm > 0.0)) return std::max(-height * k, 0.0);
  const double root = std::sqrt(two_cm);
  if (std::isinf(root)) return root;  // h^2 / r^2 overflowed: straight down, as far as double says
  const double hk = height * k;
  if (hk <= 0.0) return root - hk;
  // 2 c m - h^2 k^2 = 2 h m + h^2 (m C_zz - k^2), both terms >= 0 for C positive semidefinite.
  return (2.0 * height * m + height * height * std::max(m * c_zz - k * k, 0.0)) / (root + hk);
}

}  // namespace thalassa::ocean
