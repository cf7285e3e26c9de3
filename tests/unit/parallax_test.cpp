// Identity tests of the parallax of the waves drawn in the normals alone
// (shaders/ocean/parallax.glsl, ocean.parallax_iterations) through its double-precision CPU
// reference: the shifted point lies on the pixel's ray; pixels spread uniformly over the mesh
// then see the facets of the normal-mapped waves in proportion to their projected area toward
// the eye, the visible-area weight the reference gives its samples
// (shaders/ocean/visible_area_weight.glsl), so that the image's mean of any function of the
// normal is that weighted mean and not the plain one; the shader's few fixed-point steps come
// close to it; the shift fades out where the waves begin to fold the view; and it stays finite
// (zero) for a mesh seen edge-on, from behind or degenerate. Frame: the sea's rest tangent frame (x
// east, y north, z up), metres.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "ross_brdf_reference.hpp"
#include "trochoids_reference.hpp"

namespace thalassa::glsl {
namespace {

constexpr double kPi = std::numbers::pi;

struct Wave {
  vec2 direction;  // unit
  double k;        // rad/m
  double h;        // m
  double phase;    // rad
};

// A sea periodic on the square of side kPeriod: each wave vector is 2 pi / kPeriod times an
// integer pair, so that a uniform grid over the square is an exact quadrature for the means
// below (periodic, smooth integrands). Steepnesses k h 0.10, 0.08 and 0.05: the largest slope is
// below 0.23, and the fixed point contracts wherever that times the grazing angle's cotangent
// stays below 1 (2.75 at 20 degrees grazing, the most grazing view below).
constexpr double kPeriod = 10.0;
std::vector<Wave> PeriodicSea() {
  std::vector<Wave> sea;
  const double lattice = 2.0 * kPi / kPeriod;
  const struct {
    int m, n;
    double steepness, phase;
  } waves[] = {{3, 0, 0.10, 0.3}, {1, 2, 0.08, 2.1}, {-2, 5, 0.05, 4.4}};
  for (const auto& w : waves) {
    const vec2 m(w.m, w.n);
    const double k = lattice * length(m);
    sea.push_back({m / length(m), k, w.steepness / k, w.phase});
  }
  return sea;
}

vec3 Displacement(const std::vector<Wave>& sea, const vec2& x) {
  vec3 d(0.0);
  for (const Wave& w : sea)
    d += TrochoidDisplacement(w.direction, w.h, TrochoidArgument(w.k * w.direction, w.phase, x));
  return d;
}

// N = d_dx x d_dy of the mesh plus the waves at x (per unit rest area, unnormalised; eq. 3).
vec3 SurfaceArea(const std::vector<Wave>& sea, const vec3& mesh_dx, const vec3& mesh_dy,
                 const vec2& x) {
  vec3 d_dx = mesh_dx, d_dy = mesh_dy;
  for (const Wave& w : sea) {
    vec3 wave_dx, wave_dy;
    TrochoidDisplacementDerivatives(
        w.direction, w.k, w.h, TrochoidArgument(w.k * w.direction, w.phase, x), wave_dx, wave_dy);
    d_dx += wave_dx;
    d_dy += wave_dy;
  }
  return cross(d_dx, d_dy);
}

// The rest position x' the pixel at mesh point x sees, after `steps` fixed-point steps from x
// (the shader's loop).
vec2 Parallax(const std::vector<Wave>& sea, const vec3& mesh_dx, const vec3& mesh_dy,
              const vec3& ray, const vec2& x, int steps) {
  vec2 shift(0.0);
  for (int i = 0; i < steps; ++i)
    shift = OceanParallaxShift(mesh_dx, mesh_dy, ray, Displacement(sea, x + shift));
  return x + shift;
}

vec3 UnitView(double theta_deg, double phi_deg) {
  const double t = theta_deg * kPi / 180.0, p = phi_deg * kPi / 180.0;
  return vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
}

struct Mesh {
  vec3 dx, dy;  // tangents, m per m of rest position
};
// The sea at rest, and a plane tilted by geometry waves (slopes 0.06 east, -0.04 north).
const Mesh kMeshes[] = {{vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)},
                        {vec3(1.0, 0.0, 0.06), vec3(0.0, 1.0, -0.04)}};

TEST(OceanParallax, ADisplacementAlongTheRayOrSeenFromAboveShiftsAsItMovesThePoint) {
  const vec3 down(0.0, 0.0, -1.0);
  const vec3 dx(1.0, 0.0, 0.0), dy(0.0, 1.0, 0.0);
  // Straight down: a vertical displacement stays on the ray; a horizontal one of d is undone by
  // a shift of -d.
  EXPECT_EQ(OceanParallaxShift(dx, dy, down, vec3(0.0, 0.0, 0.7)), vec2(0.0));
  const vec2 s = OceanParallaxShift(dx, dy, down, vec3(0.3, -0.2, 0.5));
  EXPECT_NEAR(s.x, -0.3, 1e-15);
  EXPECT_NEAR(s.y, 0.2, 1e-15);
  // At 30 degrees grazing, the ray meets a point raised by 0.1 m 0.1 cot 30 degrees nearer the
  // eye (horizontally, toward its azimuth of 40 degrees) than it meets the mesh.
  const vec3 ray = -UnitView(60.0, 40.0);
  const vec2 t = OceanParallaxShift(dx, dy, ray, vec3(0.0, 0.0, 0.1));
  const double expected = 0.1 / std::tan(30.0 * kPi / 180.0);
  EXPECT_NEAR(t.x, expected * std::cos(40.0 * kPi / 180.0), 1e-15);
  EXPECT_NEAR(t.y, expected * std::sin(40.0 * kPi / 180.0), 1e-15);
}

TEST(OceanParallax, TheFixedPointPutsTheDisplacedPointOnThePixelsRay) {
  const std::vector<Wave> sea = PeriodicSea();
  double worst = 0.0;
  for (const Mesh& mesh : kMeshes)
    for (double theta : {0.0, 50.0, 65.0, 70.0})
      for (double phi : {0.0, 120.0, 250.0}) {
        const vec3 ray = -UnitView(theta, phi);
        for (int i = 0; i < 50; ++i) {
          const vec2 x(0.37 * i, 0.21 * i * i - 3.0);
          const vec2 x_seen = Parallax(sea, mesh.dx, mesh.dy, ray, x, 80);
          const vec3 mesh_point = x.x * mesh.dx + x.y * mesh.dy;
          const vec3 seen = x_seen.x * mesh.dx + x_seen.y * mesh.dy + Displacement(sea, x_seen);
          worst = std::max(worst, length(cross(seen - mesh_point, ray)));
        }
      }
  std::printf("largest distance of the seen point from the ray: %.2e m\n", worst);
  EXPECT_LT(worst, 1e-12);
}

// The mean over the image (pixels uniform on the mesh) of Fresnel's factor of the normal each
// pixel sees is the mean over the rest area weighted by the visible-area weight N.v / (N_mesh.v)
// (OceanReferenceVisibleWeight, whose mean is 1 here: no facet faces away), to quadrature
// accuracy; the plain mean over the rest area, what the pixels see without parallax, is
// larger (by 0.8 % at 40 degrees grazing to 12.6 % at 20 degrees here).
TEST(OceanParallax, PixelsSeeTheFacetsInProportionToTheirProjectedArea) {
  const std::vector<Wave> sea = PeriodicSea();
  constexpr int kGrid = 96;  // per side of the period
  constexpr double kFresnelR = 0.02;
  for (const Mesh& mesh : kMeshes)
    for (double theta : {50.0, 65.0, 70.0})
      for (double phi : {0.0, 35.0, 160.0}) {
        const vec3 v = UnitView(theta, phi);
        const vec3 mesh_area = cross(mesh.dx, mesh.dy);
        double seen = 0.0, weighted = 0.0, weight = 0.0, plain = 0.0;
        for (int j = 0; j < kGrid; ++j)
          for (int i = 0; i < kGrid; ++i) {
            const vec2 x = kPeriod * vec2((i + 0.5) / kGrid, (j + 0.5) / kGrid);
            const vec3 n_at_x = SurfaceArea(sea, mesh.dx, mesh.dy, x);
            const double f_at_x = OceanSchlickFresnel(dot(normalize(n_at_x), v), kFresnelR);
            const double w = OceanReferenceVisibleWeight(n_at_x, vec3(0.0, 0.0, 1.0), mesh_area, v);
            ASSERT_GT(dot(n_at_x, v), 0.0);  // the premise: no facet faces away
            plain += f_at_x;
            weighted += w * f_at_x;
            weight += w;
            const vec2 x_seen = Parallax(sea, mesh.dx, mesh.dy, -v, x, 80);
            seen += OceanSchlickFresnel(
                dot(normalize(SurfaceArea(sea, mesh.dx, mesh.dy, x_seen)), v), kFresnelR);
          }
        const double n = double(kGrid) * kGrid;
        seen /= n;
        weighted /= n;
        plain /= n;
        weight /= n;
        // The rest-area weight is the mesh's area per unit rest area: the mean of w over the
        // period is 1 (the waves' derivative terms integrate to 0 over it).
        EXPECT_NEAR(weight, 1.0, 1e-12) << theta << " " << phi;
        EXPECT_NEAR(seen / weighted, 1.0, 1e-9) << theta << " " << phi;
        EXPECT_GT(plain / weighted - 1.0, 0.005) << theta << " " << phi;
        if (phi == 0.0)
          std::printf("theta_v %.0f, mesh tilt %.2f: plain mean of F %.5f, seen %.5f (+%.1f %%)\n",
                      theta, mesh.dx.z, plain, seen, 100.0 * (plain / seen - 1.0));
      }
}

// The shader takes a few fixed-point steps (ocean.parallax_iterations): the error of the
// image's mean of F after k steps, against the fixed point's, falls with k; at 20 degrees
// grazing, with the contraction 0.63 of this sea, two steps leave under a quarter of the plain
// mean's error.
TEST(OceanParallax, AFewFixedPointStepsTakeMostOfTheWay) {
  const std::vector<Wave> sea = PeriodicSea();
  constexpr int kGrid = 64;
  const Mesh& mesh = kMeshes[0];
  for (double theta : {50.0, 70.0}) {
    const vec3 v = UnitView(theta, 20.0);
    std::vector<double> mean(6, 0.0);  // after 0, 1, 2, 3, 4 steps, and converged (80)
    const int steps[] = {0, 1, 2, 3, 4, 80};
    for (int j = 0; j < kGrid; ++j)
      for (int i = 0; i < kGrid; ++i) {
        const vec2 x = kPeriod * vec2((i + 0.5) / kGrid, (j + 0.5) / kGrid);
        for (int s = 0; s < 6; ++s) {
          const vec2 x_seen = Parallax(sea, mesh.dx, mesh.dy, -v, x, steps[s]);
          mean[s] += OceanSchlickFresnel(
              dot(normalize(SurfaceArea(sea, mesh.dx, mesh.dy, x_seen)), v), 0.02);
        }
      }
    std::printf("theta_v %.0f: relative error of the mean of F after 0-4 steps:", theta);
    for (int s = 0; s < 5; ++s) std::printf(" %+.4f", mean[s] / mean[5] - 1.0);
    std::printf("\n");
    for (int s = 1; s < 5; ++s)
      EXPECT_LT(std::abs(mean[s] / mean[5] - 1.0), std::abs(mean[s - 1] / mean[5] - 1.0))
          << theta << " " << s;
    EXPECT_LT(std::abs(mean[2] / mean[5] - 1.0), 0.25 * std::abs(mean[0] / mean[5] - 1.0)) << theta;
  }
}

// The fade of q = sigma_v cot(grazing): 1 up to 0.4, 0 from 0.8, linear between; the sea of the
// tests above is wholly inside the unfaded range at every view they take (q <= 0.21 at 20
// degrees grazing).
TEST(OceanParallax, TheShiftFadesWhereTheWavesBeginToFoldTheView) {
  const vec3 up(0.0, 0.0, 1.0);
  for (double grazing : {5.0, 20.0, 45.0, 80.0}) {
    const double g = grazing * kPi / 180.0;
    const vec3 ray(-std::cos(g), 0.0, -std::sin(g));
    const double cot = 1.0 / std::tan(g);
    auto fade_at = [&](double q) { return OceanParallaxFade((q / cot) * (q / cot), up, ray); };
    EXPECT_NEAR(fade_at(0.0), 1.0, 1e-15) << grazing;
    EXPECT_NEAR(fade_at(0.4), 1.0, 1e-12) << grazing;
    EXPECT_NEAR(fade_at(0.5), 0.75, 1e-12) << grazing;
    EXPECT_NEAR(fade_at(0.6), 0.5, 1e-12) << grazing;
    EXPECT_NEAR(fade_at(0.8), 0.0, 1e-12) << grazing;
    EXPECT_EQ(fade_at(3.0), 0.0) << grazing;
    double last = 1.0;
    for (double q = 0.0; q < 1.0; q += 0.01) {
      EXPECT_LE(fade_at(q), last) << grazing << " " << q;
      last = fade_at(q);
    }
  }
  // The mesh's area vector of any length and tilt: q takes the grazing angle over the mesh.
  const vec3 tilted = 3.0 * cross(kMeshes[1].dx, kMeshes[1].dy);
  const vec3 ray = -UnitView(70.0, 0.0);
  const double sin_grazing = -dot(ray, normalize(tilted));
  const double cot = std::sqrt(1.0 - sin_grazing * sin_grazing) / sin_grazing;
  EXPECT_NEAR(OceanParallaxFade((0.6 / cot) * (0.6 / cot), tilted, ray), 0.5, 1e-12);
  // The identities' sea: its largest slope variance along any azimuth is below 0.0061
  // (0.10^2 / 2 + 0.08^2 / 2 + 0.05^2 / 2, every wave along it), q below 0.215 at 20 degrees.
  const double most = (0.10 * 0.10 + 0.08 * 0.08 + 0.05 * 0.05) / 2.0;
  EXPECT_EQ(OceanParallaxFade(most, vec3(0.0, 0.0, 1.0), -UnitView(70.0, 0.0)), 1.0);
  // Seen edge-on, from below, degenerate, or NaN: no shift.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(OceanParallaxFade(0.01, up, vec3(1.0, 0.0, 0.0)), 0.0);
  EXPECT_EQ(OceanParallaxFade(0.01, up, vec3(0.0, 0.0, 1.0)), 0.0);
  EXPECT_EQ(OceanParallaxFade(0.01, vec3(0.0), vec3(0.0, 0.0, -1.0)), 0.0);
  EXPECT_EQ(OceanParallaxFade(nan, up, vec3(0.0, 0.0, -1.0)), 0.0);
  EXPECT_EQ(OceanParallaxFade(0.0, up, vec3(0.0, 0.0, -1.0)), 1.0);   // straight down, any sea
  EXPECT_EQ(OceanParallaxFade(-1.0, up, -UnitView(30.0, 0.0)), 1.0);  // no variance
}

TEST(OceanParallax, AMeshSeenEdgeOnFromBehindOrDegenerateKeepsItsRestPosition) {
  const vec3 dx(1.0, 0.0, 0.0), dy(0.0, 1.0, 0.0);
  const vec3 d(0.2, -0.1, 0.3);
  EXPECT_EQ(OceanParallaxShift(dx, dy, vec3(1.0, 0.0, 0.0), d), vec2(0.0));   // edge-on
  EXPECT_EQ(OceanParallaxShift(dx, dy, -UnitView(89.9, 0.0), d), vec2(0.0));  // within 0.6 deg
  EXPECT_EQ(OceanParallaxShift(dx, dy, UnitView(30.0, 0.0), d), vec2(0.0));   // from below
  EXPECT_EQ(OceanParallaxShift(vec3(0.0), dy, vec3(0.0, 0.0, -1.0), d), vec2(0.0));
  EXPECT_EQ(OceanParallaxShift(dx, dx, vec3(0.0, 0.0, -1.0), d), vec2(0.0));
  // Just inside the limit the shift is finite, at most |d| / cos of the limit's angle.
  const vec2 s = OceanParallaxShift(dx, dy, -UnitView(89.4, 0.0), d);
  EXPECT_TRUE(std::isfinite(s.x) && std::isfinite(s.y));
  EXPECT_LT(length(s), 2.0 * length(d) / OCEAN_PARALLAX_MIN_MESH_COS);
  // A NaN displacement: what the caller passed; a NaN ray is refused (the comparison fails).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(OceanParallaxShift(dx, dy, vec3(nan, 0.0, -1.0), d), vec2(0.0));
}

}  // namespace
}  // namespace thalassa::glsl
