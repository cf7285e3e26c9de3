// Identity tests of the weight of the reference method's sea samples
// (shaders/ocean/visible_area_weight.glsl, issue 6, point 1) through its double-precision CPU
// reference: a flat sea drawn flat weighs every sample 1; averaged over a Gaussian sea drawn flat
// the weight is Smith's facing area over cos theta_v, 1 + Lambda(v) (smith.glsl), so that the
// weighted average is over the facets' visible projected area; a periodic sea drawn as its own
// mesh weighs its samples 1 on average (the projected area of a surface over a period is its
// base's); and the weight stays finite and non-negative for degenerate input.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "ross_brdf_reference.hpp"

namespace thalassa::glsl {
namespace {

vec3 UnitView(double theta_deg, double phi_deg) {
  const double t = theta_deg * PI / 180.0, p = phi_deg * PI / 180.0;
  return vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

TEST(VisibleAreaWeight, AFlatSeaDrawnFlatWeighsEverySampleOne) {
  // Pixels of any shape and size on the plane z = 0 (m^2 per pixel), their area vector of
  // either sign (the screen's handedness), seen from any direction above it.
  const vec3 pixels[] = {vec3(0.0, 0.0, 0.25), vec3(0.0, 0.0, -3.0e4), vec3(0.0, 0.0, 7.0e-6)};
  for (const vec3& pixel : pixels)
    for (double theta : {0.0, 30.0, 60.0, 85.0, 89.9})
      for (double phi : {0.0, 45.0, 200.0}) {
        const vec3 v = UnitView(theta, phi);
        EXPECT_NEAR(OceanReferenceVisibleWeight(vec3(0.0, 0.0, 1.0), pixel, pixel, v), 1.0, 1e-12)
            << theta << " " << phi;
      }
}

// E_p[max(N.v, 0)] over the Gaussian slopes p (eq. 7) with N = (-zeta, 1) per unit rest area:
// the facing area cos theta_v (1 + Lambda(v)) (Smith; the 1 + Lambda of eq. 15's denominator).
// Midpoint rule over +-9 sigma; the kink where N.v = 0 costs O(h^2) there.
TEST(VisibleAreaWeight, AGaussianSeaDrawnFlatAveragesToOnePlusLambda) {
  const vec3 pixel(0.0, 0.0, 0.5);  // m^2: the sea at rest drawn as the mesh
  const vec2 variances[] = {vec2(0.0153, 0.0145), vec2(0.09, 0.05), vec2(0.004, 0.002)};
  double worst = 0.0;
  for (const vec2& variance : variances)
    for (double theta : {0.0, 60.0, 80.0, 86.0, 89.0})
      for (double phi : {0.0, 30.0, 90.0}) {
        const vec3 v = UnitView(theta, phi);
        const int n = 1200;
        const double sx = std::sqrt(variance.x), sy = std::sqrt(variance.y);
        const double hx = 18.0 * sx / n, hy = 18.0 * sy / n;
        double mean = 0.0;
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            const vec2 zeta(-9.0 * sx + (i + 0.5) * hx, -9.0 * sy + (j + 0.5) * hy);
            mean += OceanSlopePdf(zeta, variance) * hx * hy *
                    OceanReferenceVisibleWeight(vec3(-zeta.x, -zeta.y, 1.0), pixel, pixel, v);
          }
        const double expected = OceanSmithFacingAreaToward(v, variance) / v.z;
        worst = std::max(worst, std::abs(mean / expected - 1.0));
        // Measured: worst 1.1e-5 (at 89 degrees, where smith.glsl's erfc approximation and the
        // quadrature of the kink both count).
        EXPECT_NEAR(mean / expected, 1.0, 3e-5) << variance.x << " " << theta << " " << phi;
        // Near the horizon the back-facing facets the weight hides matter: 1 + Lambda > 1.
        if (theta >= 86.0 && variance.x >= 0.0153) {
          EXPECT_GT(mean, 1.05);
        }
      }
  std::printf("mean weight over a Gaussian sea / (1 + Lambda): worst |ratio - 1| %.2g\n", worst);
}

// A sea of one sine wave z = a sin(k x), drawn as a mesh that follows it exactly (the mesh's
// area vector per pixel N dA, as a pixel of rest area dA sees it), weighs every sample 1; drawn
// flat, the weights average to 1 over a period where no facet faces away (projected area is
// conserved: the integral of N.v over a period is v_z), and to more than 1 where some do.
TEST(VisibleAreaWeight, ASineSeaConservesProjectedArea) {
  const double k = 2.0 * PI / 10.0;  // rad/m: a 10 m wave
  const vec3 rest(0.0, 0.0, 0.01);   // m^2 per pixel
  for (double a : {0.1, 0.5})        // m: slopes up to 0.063 and 0.31
    for (double theta : {40.0, 80.0, 88.0}) {
      const vec3 v = UnitView(theta, 0.0);
      const int n = 4096;
      double flat = 0.0;
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) * (2.0 * PI / k) / n;
        const vec3 normal(-a * k * std::cos(k * x), 0.0, 1.0);  // per unit rest area
        // 1, except where the facet is seen within OCEAN_REFERENCE_MIN_MESH_COS of edge-on.
        const double cos_mesh = dot(normal, v) / length(normal);
        EXPECT_NEAR(OceanReferenceVisibleWeight(normal, rest, rest.z * normal, v),
                    cos_mesh > 0.0 ? std::min(1.0, cos_mesh / OCEAN_REFERENCE_MIN_MESH_COS) : 0.0,
                    1e-12);
        flat += OceanReferenceVisibleWeight(normal, rest, rest, v) / n;
      }
      const bool facing_away = a * k > 1.0 / std::tan(theta * PI / 180.0);
      if (facing_away) {
        EXPECT_GT(flat, 1.0 + 1e-3) << a << " " << theta;
      } else {
        EXPECT_NEAR(flat, 1.0, 1e-9) << a << " " << theta;
      }
    }
}

TEST(VisibleAreaWeight, DegenerateInputGivesAFiniteNonNegativeWeight) {
  const vec3 v = UnitView(70.0, 10.0);
  const vec3 up(0.0, 0.0, 1.0), pixel(0.0, 0.0, 1.0);
  // A degenerate triangle (no area) has no pixel: 0, not a division by 0.
  EXPECT_EQ(OceanReferenceVisibleWeight(up, pixel, vec3(0.0), v), 0.0);
  // A triangle seen edge-on is weighted as one seen at OCEAN_REFERENCE_MIN_MESH_COS.
  const vec3 edge_on = cross(v, vec3(0.0, 1.0, 0.0));
  const double w = OceanReferenceVisibleWeight(up, pixel, edge_on, v);
  EXPECT_TRUE(std::isfinite(w));
  EXPECT_NEAR(w, v.z / (OCEAN_REFERENCE_MIN_MESH_COS * length(edge_on)), 1e-9);
  // A facet facing away from the eye is hidden.
  EXPECT_EQ(OceanReferenceVisibleWeight(-up, pixel, pixel, v), 0.0);
  // A folded triangle seen from behind weighs as seen from the front.
  EXPECT_EQ(OceanReferenceVisibleWeight(up, pixel, -pixel, v),
            OceanReferenceVisibleWeight(up, pixel, pixel, v));
}

}  // namespace
}  // namespace thalassa::glsl
