#include "thalassa/planet/camera_frame.hpp"

#include <cmath>

namespace thalassa {
namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;
}

CameraBasis camera_basis(double heading_deg, double pitch_deg, double roll_deg) {
  const double h = heading_deg * kDegree, p = pitch_deg * kDegree, r = roll_deg * kDegree;
  const glm::dvec3 forward(std::sin(h) * std::cos(p), std::cos(h) * std::cos(p), std::sin(p));
  // The horizontal right vector depends on the heading only, so straight up and down views
  // keep a well-defined basis (no gimbal singularity).
  const glm::dvec3 right0(std::cos(h), -std::sin(h), 0.0);
  const glm::dvec3 up0 = glm::cross(right0, forward);
  CameraBasis basis;
  basis.forward = forward;
  basis.right = std::cos(r) * right0 - std::sin(r) * up0;
  basis.up = std::sin(r) * right0 + std::cos(r) * up0;
  return basis;
}

glm::dvec3 sun_direction(double zenith_deg, double azimuth_deg) {
  const double z = zenith_deg * kDegree, a = azimuth_deg * kDegree;
  return {std::sin(z) * std::sin(a), std::sin(z) * std::cos(a), std::cos(z)};
}

glm::dvec3 view_ray(const CameraBasis& basis, double tan_half_fov_y, double aspect, double u,
                    double v) {
  return basis.forward + (u * tan_half_fov_y * aspect) * basis.right +
         (v * tan_half_fov_y) * basis.up;
}

}  // namespace thalassa
