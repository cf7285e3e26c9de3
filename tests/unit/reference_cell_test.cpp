// Identity tests of the reference's sun lattice geometry (shaders/ocean/reference_cell.glsl,
// issue 6, point 1) through its double-precision CPU reference: the rest height lies on the
// sea's quadric, a facet's frame slope inverts its normal, the glint's coordinates reach the
// mirror slope, the glint's centroid is the sun's weighted centre of its cell (against quadrature,
// with its truncated Gaussians and scaled erfc) and makes a glint's split across a pixel's edge
// converge as the cells shrink, the bilinear patch passes
// through its corners, and the cells' solid angles tile a disc of the sea into the disc's own.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <utility>

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

// The mean of N(mu, s^2) truncated to [-1/2, 1/2], by the midpoint rule on 20,000 points of the
// interval in double (the Gaussian is resolved for s >= 1e-3; narrower ones are tested by their
// limit, the clamped mean). The density is taken relative to its value at the interval's point
// nearest mu, so that nothing underflows however far mu is.
double TruncatedMeanByQuadrature(double mu, double s) {
  constexpr int kPoints = 20000;
  const double nearest = std::clamp(mu, -0.5, 0.5);
  double weight = 0.0, moment = 0.0;
  for (int i = 0; i < kPoints; ++i) {
    const double x = -0.5 + (i + 0.5) / kPoints;
    const double w =
        std::exp(-0.5 * ((x - mu) * (x - mu) - (nearest - mu) * (nearest - mu)) / (s * s));
    weight += w;
    moment += w * x;
  }
  return weight > 0.0 ? moment / weight : std::clamp(mu, -0.5, 0.5);
}

TEST(ReferenceCell, ScaledErfcMatchesLongDouble) {
  double worst = 0.0;
  for (double x = 0.0; x < 26.0; x += 1e-3) {
    const long double expected = std::erfc((long double)x) * std::exp((long double)x * x);
    worst = std::max(worst, double(std::abs(ReferenceScaledErfc(x) / expected - 1.0L)));
  }
  // Measured: 1.07e-7 (Numerical Recipes' bound for its fit: 1.2e-7).
  EXPECT_LT(worst, 1.2e-7);
  // Far out, the asymptotic series 1 / (x sqrt(pi)) (1 - 1 / (2 x^2)).
  for (double x : {100.0, 1e4})
    EXPECT_NEAR(ReferenceScaledErfc(x) * x * std::sqrt(PI), 1.0 - 0.5 / (x * x), 1e-6);
}

TEST(ReferenceCell, TruncatedGaussianMeanMatchesQuadrature) {
  // Means from far left to far right of the interval, standard deviations from a thousandth of it
  // to a thousand times it: every branch (inside, one-sided, far, tilt).
  double worst = 0.0;
  for (double s : {1e-3, 3e-3, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 3.99, 4.01, 10.0, 100.0, 1000.0})
    for (double mu = -12.0; mu <= 12.0; mu += 0.0625) {
      const double got = ReferenceTruncatedGaussianMean(mu, s);
      worst = std::max(worst, std::abs(got - TruncatedMeanByQuadrature(mu, s)));
      // Mirror symmetry, exactly.
      EXPECT_EQ(ReferenceTruncatedGaussianMean(-mu, s), -got);
      EXPECT_GE(got, -0.5);
      EXPECT_LE(got, 0.5);
    }
  std::printf("truncated Gaussian mean: worst error %.2e of the interval\n", worst);
  // Measured: 1.3e-4, in the tilt (s just above REFERENCE_TILT_SD, the mean 12 away); 2.1e-2
  // with A&S 7.1.26's polynomial for exp(x^2) erfc(x) in the one-sided ratio (6 sigma out). The
  // quadrature's own error, where s is 1e-3 and mu far (the density falls within its spacing),
  // is 2.4e-5.
  EXPECT_LT(worst, 5e-4);
  // Limits: a narrow Gaussian is its clamped mean; s -> infinity gives the centre; s = 0 and
  // s < 0 clamp.
  EXPECT_DOUBLE_EQ(ReferenceTruncatedGaussianMean(0.2, 1e-9), 0.2);
  EXPECT_NEAR(ReferenceTruncatedGaussianMean(3.0, 1e-4), 0.5, 1e-3);
  EXPECT_NEAR(ReferenceTruncatedGaussianMean(0.3, 1e6), 0.0, 1e-12);
  EXPECT_EQ(ReferenceTruncatedGaussianMean(0.7, 0.0), 0.5);
  EXPECT_EQ(ReferenceTruncatedGaussianMean(-0.7, -1.0), -0.5);
}

// The centroid of G(c + u d_u + v d_v - m) over the unit square, by the midpoint rule on n x n.
vec2 CentroidByQuadrature(const vec2& c, const vec2& d_u, const vec2& d_v, const vec2& m,
                          double sigma) {
  constexpr int kPoints = 400;
  double weight = 0.0;
  vec2 moment(0.0);
  for (int j = 0; j < kPoints; ++j)
    for (int i = 0; i < kPoints; ++i) {
      const vec2 uv(-0.5 + (i + 0.5) / kPoints, -0.5 + (j + 0.5) / kPoints);
      const vec2 r = c + uv.x * d_u + uv.y * d_v - m;
      const double w = std::exp(-0.5 * glm::dot(r, r) / (sigma * sigma));
      weight += w;
      moment += w * uv;
    }
  return weight > 1e-200 ? moment / weight : vec2(std::nan(""));
}

TEST(ReferenceCell, GlintCentroidIsTheSunsWeightedCentreOfTheCell) {
  const double sigma = std::sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE);
  std::mt19937 random(32);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Orthogonal edges: the Gaussian is separable on the square and the conditionals are exact.
  // Sheared edges: the conditionals approximate the centroid. Cells from a tenth of the disc's
  // width to twenty times it, mirror slopes inside and up to two cells outside.
  double worst_orthogonal = 0.0, worst_sheared = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const bool orthogonal = trial % 2 == 0;
    const double size = sigma * std::pow(10.0, -1.0 + 2.3 * (0.5 + 0.5 * unit(random)));
    const double angle = 3.14159 * unit(random);
    const vec2 e(std::cos(angle), std::sin(angle));
    const vec2 d_u = size * (1.0 + 0.5 * unit(random)) * e;
    const vec2 d_v = size * (1.0 + 0.5 * unit(random)) *
                     (orthogonal ? vec2(-e.y, e.x) : glm::normalize(vec2(-e.y, e.x) + 0.7 * e));
    const vec2 c(0.01 * unit(random), 0.01 * unit(random));
    const vec2 m = c + 1.5 * unit(random) * d_u + 1.5 * unit(random) * d_v;
    const vec2 expected = CentroidByQuadrature(c, d_u, d_v, m, sigma);
    if (!std::isfinite(expected.x)) continue;  // a weight below 1e-200 everywhere on the cell
    const vec2 got = ReferenceGlintCentroid(c, d_u, d_v, m, sigma);
    const double error = glm::length(got - expected);
    (orthogonal ? worst_orthogonal : worst_sheared) =
        std::max(orthogonal ? worst_orthogonal : worst_sheared, error);
  }
  std::printf("glint centroid: worst error %.2e (orthogonal edges), %.2e (sheared) of the cell\n",
              worst_orthogonal, worst_sheared);
  // Measured: 2.8e-4 (orthogonal: the quadrature's own error), 6.5e-3 (sheared).
  EXPECT_LT(worst_orthogonal, 1e-3);
  EXPECT_LT(worst_sheared, 0.02);
  // A cell much wider than the disc with the mirror slope inside: the glint's own point.
  const vec2 c(0.02, -0.01), d_u(0.03, 0.004), d_v(-0.002, 0.025);
  const vec2 m = c + 0.3 * d_u - 0.2 * d_v;
  const vec2 centroid = ReferenceGlintCentroid(c, d_u, d_v, m, sigma);
  const vec2 point = ReferenceGlintCoordinates(c, d_u, d_v, m);
  EXPECT_NEAR(centroid.x, point.x, 0.01);
  EXPECT_NEAR(centroid.y, point.y, 0.01);
  // A cell much narrower than the disc: its centre.
  const vec2 tiny = ReferenceGlintCentroid(c, 1e-3 * sigma * vec2(1.0, 0.0),
                                           1e-3 * sigma * vec2(0.0, 1.0), c + vec2(sigma), sigma);
  EXPECT_NEAR(tiny.x, 0.0, 1e-3);
  EXPECT_NEAR(tiny.y, 0.0, 1e-3);
  // A flat cell, a cell with one edge flat, parallel edges: finite, inside the cell.
  for (const auto& [u, v] : {std::pair{vec2(0.0), vec2(0.0)}, std::pair{vec2(0.01, 0.0), vec2(0.0)},
                             std::pair{vec2(0.01, 0.01), vec2(0.02, 0.02)}}) {
    const vec2 uv = ReferenceGlintCentroid(c, u, v, c + vec2(0.004, 0.001), sigma);
    EXPECT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y));
    EXPECT_LE(std::abs(uv.x), 0.5);
    EXPECT_LE(std::abs(uv.y), 0.5);
  }
  // An edge with no slope change leaves its coordinate at the centre.
  EXPECT_EQ(ReferenceGlintCentroid(c, vec2(0.01, 0.0), vec2(0.0), c + vec2(0.004, 0.001), sigma).y,
            0.0);
}

// What the centroid is for: how a glint's light divides between the two sides of a pixel's edge
// converges as the cells shrink. A sea of three sines (slopes up to 0.3), the sun's disc widened
// so that a glint spreads over a few hundredths of the domain, the mirror slope that of a point
// on the edge y = 1/2 (the glint straddles it); each cell's light (ocean/cell_slope_density.glsl)
// goes to the side of its centroid, or of its glint's point (ReferenceGlintCoordinates, the rule
// until stop 32). The share above the edge, on lattices of n and 2n cells per side.
TEST(ReferenceCell, GlintCentroidSplitsAGlintAcrossAnEdgeAsTheCellsShrink) {
  const double sigma = 0.01;
  const double k[3][2] = {{6.0, 1.0}, {-2.0, 9.0}, {13.0, 5.0}};  // rad per unit length
  const double a[3] = {0.012, 0.009, 0.004};                      // heights
  const double phase[3] = {0.3, 1.7, 4.1};
  const auto slope = [&](double x, double y) {
    vec2 z(0.0);
    for (int i = 0; i < 3; ++i) {
      const double s = -a[i] * std::sin(k[i][0] * x + k[i][1] * y + phase[i]);
      z += s * vec2(k[i][0], k[i][1]);
    }
    return z;
  };
  const auto share_above = [&](int n, const vec2& mirror, bool centroid) {
    const double h = 1.0 / n;
    double above = 0.0, total = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const vec2 z00 = slope(i * h, j * h), z10 = slope((i + 1) * h, j * h);
        const vec2 z01 = slope(i * h, (j + 1) * h), z11 = slope((i + 1) * h, (j + 1) * h);
        const vec2 c = 0.25 * (z00 + z10 + z01 + z11);
        const vec2 d_u = 0.5 * ((z10 - z00) + (z11 - z01));
        const vec2 d_v = 0.5 * ((z01 - z00) + (z11 - z10));
        const double light = OceanCellSlopeDensity(mirror - c, d_u, d_v, sigma);
        const vec2 uv = centroid ? ReferenceGlintCentroid(c, d_u, d_v, mirror, sigma)
                                 : ReferenceGlintCoordinates(c, d_u, d_v, mirror);
        total += light;
        if ((j + 0.5 + uv.y) * h > 0.5) above += light;
      }
    return above / total;
  };
  double worst_centroid = 0.0, worst_point = 0.0;
  for (double x : {0.21, 0.47, 0.66, 0.83}) {
    const vec2 mirror = slope(x, 0.5);
    for (int n : {192, 384}) {
      const double change_centroid =
          std::abs(share_above(2 * n, mirror, true) / share_above(n, mirror, true) - 1.0);
      const double change_point =
          std::abs(share_above(2 * n, mirror, false) / share_above(n, mirror, false) - 1.0);
      std::printf(
          "glint at x = %.2f, %d -> %d cells: share above changes by %.3f %% (centroid), "
          "%.3f %% (glint's point)\n",
          x, n, 2 * n, 100.0 * change_centroid, 100.0 * change_point);
      worst_centroid = std::max(worst_centroid, change_centroid);
      worst_point = std::max(worst_point, change_point);
    }
  }
  EXPECT_LT(worst_centroid, 2e-3);
  EXPECT_GT(worst_point, 5.0 * worst_centroid);
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
