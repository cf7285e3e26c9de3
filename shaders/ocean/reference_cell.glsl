// The geometry of one cell of the reference's sun lattice (issue 6, point 1;
// ocean/reference_sun_scatter.comp), in the shared GLSL / C++ subset so that the CPU tests check
// it in double (tests/unit/reference_cell_test.cpp).
#include "common/definitions.glsl"

#ifndef THALASSA_OCEAN_REFERENCE_CELL_GLSL
#define THALASSA_OCEAN_REFERENCE_CELL_GLSL

// The height z (m) of the sea at rest above the rest point's horizontal position xy (m, nadir
// frame): the root near 0 of the frame's quadric z + 1/2 p^T C p = 0, p = (x, y, z), C the
// symmetric curvature (1/m; common/frame.glsl). As a quadratic in z, a z^2 + b z + c = 0 with
// a = C_zz / 2, b = 1 + C_xz x + C_yz y, c = (C_xx x^2 + 2 C_xy x y + C_yy y^2) / 2; the root
// 2c / (-b - sqrt(b^2 - 4ac)) is free of cancellation (c and z are small near the nadir, where
// the printed -b + sqrt(...) would lose them). Beyond the quadric's silhouette (b^2 < 4ac: past
// the planet's limb, 6,400 km for the Earth) the discriminant is clamped at 0.
Number ReferenceRestHeight(IN(mat3) curvature, IN(vec2) xy) {
  Number a = 0.5 * curvature[2][2];
  Number b = 1.0 + curvature[0][2] * xy.x + curvature[1][2] * xy.y;
  Number c = 0.5 * (curvature[0][0] * xy.x * xy.x + 2.0 * curvature[1][0] * xy.x * xy.y +
                    curvature[1][1] * xy.y * xy.y);
  Number discriminant = max(b * b - 4.0 * a * c, 0.0);
  return -2.0 * c / (b + sqrt(discriminant));
}

// The slopes zeta (dimensionless) in the tangent frame (t_x, t_y, n) of a facet of normal f
// (any length, same frame as the axes): f = (-zeta, 1) up to its length. A corner tilted 90
// degrees or more from the cell's mean normal (not a small cell of a resolved sea) is held at
// 1e6.
vec2 ReferenceCellFrameSlope(IN(vec3) f, IN(vec3) t_x, IN(vec3) t_y, IN(vec3) n) {
  return -vec2(dot(f, t_x), dot(f, t_y)) / max(dot(f, n), 1e-6 * length(f));
}

// Where in its cell the glint lies: the cell's slopes (dimensionless, in its tangent frame) are
// c + u d_u + v d_v for (u, v) in [-1/2, 1/2]^2 (the parallelogram of
// ocean/cell_slope_density.glsl), and the mirror slope m (the slope of the half vector) is
// reached at the (u, v) that solves the 2 x 2 system [d_u d_v] (u, v) = m - c. The solution is
// clamped to the cell: a cell whose slopes miss m reflects only the tail of the sun's disc, from
// its nearest edge. A degenerate parallelogram (|det| below 1e-6 of the product of its edges' lengths,
// or both edges 0: a flat cell) gives the cell's centre (0, 0).
vec2 ReferenceGlintCoordinates(IN(vec2) c, IN(vec2) d_u, IN(vec2) d_v, IN(vec2) m) {
  Number det = d_u.x * d_v.y - d_u.y * d_v.x;
  Number scale = dot(d_u, d_u) * dot(d_v, d_v);
  if (!(abs(det) > 1e-6 * sqrt(scale)) || !(scale > 0.0)) return vec2(0.0, 0.0);
  vec2 r = m - c;
  vec2 uv = vec2(r.x * d_v.y - r.y * d_v.x, d_u.x * r.y - d_u.y * r.x) / det;
  return clamp(uv, vec2(-0.5, -0.5), vec2(0.5, 0.5));
}

// The point (any units, any frame) of the bilinear patch through the cell's corners p00, p10,
// p01, p11 at (u, v) in [-1/2, 1/2]^2 (u from p00 to p10, v from p00 to p01).
vec3 ReferenceBilinear(IN(vec3) p00, IN(vec3) p10, IN(vec3) p01, IN(vec3) p11, IN(vec2) uv) {
  Number s = uv.x + 0.5;
  Number t = uv.y + 0.5;
  return (1.0 - t) * ((1.0 - s) * p00 + s * p10) + t * ((1.0 - s) * p01 + s * p11);
}

// The solid angle (sr) the cell subtends seen from the eye, with its facets' visible projection:
// area the mean of its corners' displaced area vectors per unit rest area (d_dx x d_dy, nadir
// frame; dimensionless), rest_area the cell's area on the sea at rest (m^2), to_eye from the
// cell to the eye (m, nadir frame; not unit). A cell facing away from the eye is hidden: 0.
Number ReferenceCellSolidAngle(IN(vec3) area, Number rest_area, IN(vec3) to_eye) {
  Number distance = length(to_eye);
  if (!(distance > 0.0)) return 0.0;
  return max(dot(area, to_eye), 0.0) * rest_area / (distance * distance * distance);
}

#endif  // THALASSA_OCEAN_REFERENCE_CELL_GLSL
