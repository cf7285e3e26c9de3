// thalassa — the sea at rest near the camera, curved with the planet (issue 5, point 3), in
// double precision on the CPU; shaders/ocean/sea_surface.glsl is its float twin.
//
// Frame and units: the east-north-up frame tangent at the camera's nadir (x east, y north, z up
// along the surface normal there), its origin the nadir point on the sea; metres. The camera is
// at (0, 0, h), h its height above the sea. In that frame the sea at rest is the set of x with
//
//   f(x) = z + 1/2 x^T C x = 0,
//
// exact for any quadric tangent to the plane z = 0 at the origin, the WGS84 ellipsoid included:
// an ellipsoid p^T A p = 1 (ECEF) through the nadir N becomes, with p = N + R x (R the ENU axes
// in ECEF), x^T (R^T A R) x + 2 (R^T A N) . x = 0, and R^T A N = |A N| z-hat because A N is
// along the surface normal at N; dividing by 2 |A N| gives C = R^T A R / |A N|. For a sphere of
// radius r, C = I / r; for the flat sea of the ocean issue, C = 0. f is negative below the sea.
//
// Why this form: every quantity is small near the camera (no planet-sized number is ever
// subtracted from another), so a ray's intersection, written cancellation-free below, keeps full
// relative precision in float on the GPU as in double here, from 1 mm to 36,000 km up.
#pragma once

#include <optional>

#include <glm/glm.hpp>

namespace thalassa::ocean {

struct SeaSurface {
  glm::dmat3 curvature{0.0};  // C (symmetric, 1/m); glm is column-major: curvature[col][row]
  bool operator==(const SeaSurface&) const = default;  // exact
};

SeaSurface flat_sea_surface();
SeaSurface spherical_sea_surface(double radius_m);

// f(x) (m): negative below the sea at rest, positive above.
double sea_surface_value(const SeaSurface& surface, const glm::dvec3& x);
// The outward unit normal at a point of the surface, grad f = z-hat + C x normalised.
glm::dvec3 sea_surface_normal(const SeaSurface& surface, const glm::dvec3& x);

// The ray from the camera at (0, 0, height) along the unit direction `ray`: the distance (m) to
// its first point on the sea, or nothing when it misses (or the camera is not above the sea).
// With a = 1/2 d^T C d, b = d_z + h (C z-hat) . d, c = h (1 + 1/2 h C_zz), f(t) = a t^2 + b t + c,
// and the near root is t = 2c / (-b + sqrt(b^2 - 4ac)), free of cancellation (b < 0 when it hits).
std::optional<double> sea_surface_distance(const SeaSurface& surface, double height,
                                           const glm::dvec3& ray);

// The quadratic's coefficients (a, b, c) of the ray, as above; the ray grazes the surface where
// b^2 = 4 a c (the horizon).
glm::dvec3 sea_surface_ray_coefficients(const SeaSurface& surface, double height,
                                        const glm::dvec3& ray);

// The surface's z (m) above or below the horizontal point (x, y) (m, nadir ENU): the sag, the
// root near 0 of f(x, y, z) = 1/2 C_zz z^2 + (1 + C_xz x + C_yz y) z + 1/2 (x, y) C_hh (x, y)^T,
// in the cancellation-free form z = -2 q / (B + sqrt(B^2 - 2 C_zz q)); exactly 0 for the flat
// sea, -(x^2 + y^2) / (2 r) to first order for a sphere. Assumes C positive semidefinite (a
// convex sea); where the vertical line through (x, y) misses the surface (beyond a sphere's
// radius), returns the z of its closest approach, -B / C_zz.
double sea_surface_sag(const SeaSurface& surface, const glm::dvec2& xy);

// The horizon seen from the camera at (0, 0, height) in the horizontal direction `azimuth`
// (unit, x east and y north): tan(delta), delta the dip below the horizontal of the ray
// d = azimuth - tan(delta) z-hat that grazes the surface. Rays of that azimuth meet the surface
// exactly when their tan(dip) is at least this. Closed form: with m = H^T C H, k = (C z-hat) . H
// and c as above, b^2 - 4 a c of d is (tan(delta) + h k)^2 - 2 c m (the tan^2 coefficient
// (1 + h C_zz)^2 - 2 c C_zz is exactly 1), so tan(delta) = sqrt(2 c m) - h k, written without
// cancellation. For a sphere of radius r: sqrt(h (2 r + h)) / r. 0 for the flat sea, and for a
// camera not above the sea (height <= 0). Assumes C positive semidefinite.
double sea_surface_horizon_dip(const SeaSurface& surface, double height, const glm::dvec2& azimuth);

}  // namespace thalassa::ocean
