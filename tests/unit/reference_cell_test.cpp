// Identity tests of the reference's sun lattice geometry (shaders/ocean/reference_cell.glsl,
// issue 6, point 1) through its double-precision CPU reference: the rest height lies on the
// sea's quadric, a facet's frame slope inverts its normal, the glint's coordinates reach the
// mirror slope, the bilinear patch passes
// through its corners, and the cells' solid angles tile a disc of the sea into the disc's own.

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "ross_brdf_reference.hpp"

namespace thalassa::glsl {
namespace {

constexpr double kEarthRadius = 6371000.0;  // m

// The quadric's residual z + 1/2 p^T C p at the rest point over xy.
double QuadricResidual(const mat3& curvature, const vec2& xy) {
  const vec3 p(xy.x, xy.y, ReferenceRestHeight(curvature, xy));
  return p.z + 0.5 * glm::dot(p, curvature * p);
}

TEST(ReferenceCell, RestHeightLiesOnTheQuadric) {
  // The sphere through the nadir, an anisotropic quadric with cross terms (an ellipsoid's C at
  // mid latitude, of the order of 1/R) and the flat sea.
  const mat3 sphere(1.0 / kEarthRadius);
  mat3 ellipsoid(1.0 / 6378137.0);
  ellipsoid[1][1] = 1.0 / 6335439.0;
  ellipsoid[0][1] = ellipsoid[1][0] = 2e-9;
  ellipsoid[1][2] = ellipsoid[2][1] = 1e-9;
  for (const mat3& c : {sphere, ellipsoid})
    for (double r : {0.01, 1.0, 100.0, 1e4, 1e5, 1e6})
      for (double angle : {0.0, 0.7, 2.0, 4.0}) {
        const vec2 xy(r * std::cos(angle), r * std::sin(angle));
        const double z = ReferenceRestHeight(c, xy);
        // The sag is about -r^2 / 2R: the residual is a rounding of it.
        EXPECT_LE(std::abs(QuadricResidual(c, xy)), 1e-14 * (std::abs(z) + 1e-300)) << r;
        EXPECT_LT(z, 0.0);
      }
  // On the sphere the near root is -R + sqrt(R^2 - r^2) = -r^2 / (R + sqrt(R^2 - r^2)).
  const double r = 35000.0;  // the horizon from 100 m
  EXPECT_NEAR(ReferenceRestHeight(sphere, vec2(r, 0.0)),
              -r * r / (kEarthRadius + std::sqrt(kEarthRadius * kEarthRadius - r * r)), 1e-9);
  EXPECT_EQ(ReferenceRestHeight(mat3(0.0), vec2(1e5, -3e4)), 0.0);
  // Past the sphere's silhouette: clamped, finite.
  EXPECT_TRUE(std::isfinite(ReferenceRestHeight(sphere, vec2(2.0 * kEarthRadius, 0.0))));
}

// A facet of slopes zeta in a rotated tangent frame, f = -zeta_x t_x - zeta_y t_y + n at any
// length, gives back zeta; a facet at 90 degrees is held finite.
TEST(ReferenceCell, FrameSlopeInvertsTheFacetNormal) {
  const vec3 n = glm::normalize(vec3(0.1, -0.2, 1.0));
  const vec3 t_x = glm::normalize(glm::cross(vec3(0.0, 1.0, 0.0), n));
  const vec3 t_y = glm::cross(n, t_x);
  for (const vec2 zeta : {vec2(0.0), vec2(0.3, -0.1), vec2(-2.0, 5.0)}) {
    const vec3 f = 3.7 * (-zeta.x * t_x - zeta.y * t_y + n);
    const vec2 found = ReferenceCellFrameSlope(f, t_x, t_y, n);
    EXPECT_NEAR(found.x, zeta.x, 1e-14 * (1.0 + std::abs(zeta.x)));
    EXPECT_NEAR(found.y, zeta.y, 1e-14 * (1.0 + std::abs(zeta.y)));
  }
  const vec2 edge_on = ReferenceCellFrameSlope(t_x, t_x, t_y, n);
  EXPECT_TRUE(std::isfinite(edge_on.x) && std::isfinite(edge_on.y));
  EXPECT_NEAR(edge_on.x, -1e6, 1.0);
}

TEST(ReferenceCell, GlintCoordinatesReachTheMirrorSlope) {
  std::mt19937 random(6);
  std::uniform_real_distribution<double> slope(-0.05, 0.05);
  std::uniform_real_distribution<double> inside(-0.5, 0.5);
  for (int trial = 0; trial < 1000; ++trial) {
    const vec2 c(slope(random), slope(random));
    const vec2 d_u(slope(random), slope(random)), d_v(slope(random), slope(random));
    if (std::abs(d_u.x * d_v.y - d_u.y * d_v.x) < 1e-4 * glm::length(d_u) * glm::length(d_v))
      continue;  // nearly degenerate: the clamp and the centre are tested below
    const vec2 uv(inside(random), inside(random));
    const vec2 m = c + uv.x * d_u + uv.y * d_v;
    const vec2 found = ReferenceGlintCoordinates(c, d_u, d_v, m);
    EXPECT_NEAR(found.x, uv.x, 1e-9);
    EXPECT_NEAR(found.y, uv.y, 1e-9);
    // A mirror slope outside the parallelogram is clamped to its nearest coordinates.
    const vec2 far = ReferenceGlintCoordinates(c, d_u, d_v, c + 3.0 * d_u - 5.0 * d_v);
    EXPECT_DOUBLE_EQ(far.x, 0.5);
    EXPECT_DOUBLE_EQ(far.y, -0.5);
  }
  // A flat cell and a cell whose edges are parallel: the centre.
  EXPECT_EQ(ReferenceGlintCoordinates(vec2(0.01), vec2(0.0), vec2(0.0), vec2(0.02)), vec2(0.0));
  EXPECT_EQ(ReferenceGlintCoordinates(vec2(0.0), vec2(0.01, 0.01), vec2(0.02, 0.02), vec2(0.01)),
            vec2(0.0));
}

TEST(ReferenceCell, BilinearPatchPassesThroughItsCorners) {
  const vec3 p00(0.0, 0.0, 0.1), p10(1.0, 0.1, -0.2), p01(0.2, 1.0, 0.3), p11(1.3, 1.1, 0.0);
  EXPECT_EQ(ReferenceBilinear(p00, p10, p01, p11, vec2(-0.5, -0.5)), p00);
  EXPECT_EQ(ReferenceBilinear(p00, p10, p01, p11, vec2(0.5, -0.5)), p10);
  EXPECT_EQ(ReferenceBilinear(p00, p10, p01, p11, vec2(-0.5, 0.5)), p01);
  EXPECT_EQ(ReferenceBilinear(p00, p10, p01, p11, vec2(0.5, 0.5)), p11);
  const vec3 centre = ReferenceBilinear(p00, p10, p01, p11, vec2(0.0));
  const vec3 mean = 0.25 * (p00 + p10 + p01 + p11);
  EXPECT_NEAR(glm::length(centre - mean), 0.0, 1e-15);
}

// The cells of a flat sea tile the disc of radius rho under an eye at height h into its solid
// angle seen from the axis, 2 pi (1 - h / sqrt(h^2 + rho^2)); a cell facing away adds nothing.
TEST(ReferenceCell, CellSolidAnglesTileADisc) {
  const double h = 4.0, rho = 30.0;
  const vec3 eye(0.0, 0.0, h);
  const int n = 600;  // cells per side of the disc's bounding square: 10 cm cells
  const double side = 2.0 * rho / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      // Cells are counted whole or not at all by their centre: the disc's edge adds a
      // discretisation error of about the edge cells' solid angle times their fraction.
      const vec3 centre(-rho + (i + 0.5) * side, -rho + (j + 0.5) * side, 0.0);
      if (centre.x * centre.x + centre.y * centre.y > rho * rho) continue;
      sum += ReferenceCellSolidAngle(vec3(0.0, 0.0, 1.0), side * side, eye - centre);
    }
  const double exact = 2.0 * PI * (1.0 - h / std::sqrt(h * h + rho * rho));
  EXPECT_NEAR(sum / exact, 1.0, 2e-4);
  // A cell's area vector facing away from the eye, and an eye on the cell.
  EXPECT_EQ(ReferenceCellSolidAngle(vec3(0.0, 0.0, -1.0), 1.0, eye), 0.0);
  EXPECT_EQ(ReferenceCellSolidAngle(vec3(0.0, 0.0, 1.0), 1.0, vec3(0.0)), 0.0);
  // Straight below the eye: A / h^2.
  EXPECT_NEAR(ReferenceCellSolidAngle(vec3(0.0, 0.0, 1.0), 0.01, eye), 0.01 / (h * h), 1e-18);
}

}  // namespace
}  // namespace thalassa::glsl
