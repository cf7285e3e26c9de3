// Identity tests of the reference method's per-cell sun (shaders/ocean/cell_slope_density.glsl,
// issue 6, point 1) through its double-precision CPU reference: the cell's slope density
// integrates to 1 for every shape of cell, cells that tile slope space sum to a flat density
// (the property the Gaussian per cell lacked), a flat cell is eq. 15 with the paper's minimum
// variance, and on a sea's slope field the estimate no longer depends on where the cells fall.
// Slopes are dimensionless, in the cell's tangent frame.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "ross_brdf_reference.hpp"

namespace thalassa::glsl {
namespace {

const double kSigma = std::sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE);  // 1.16e-3

double Cross(const vec2& a, const vec2& b) { return a.x * b.y - a.y * b.x; }

struct Cell {
  const char* name;
  vec2 d_u, d_v;
};

// Cells of every regime of OceanCellSlopeDensity: height over the longer edge (in sigma) in
// brackets.
const Cell kCells[] = {
    {"square (17)", vec2(0.02, 0.0), vec2(0.0, 0.02)},
    {"sheared (5.6)", vec2(0.02, 0.004), vec2(0.012, 0.009)},
    {"blend (2.2)", vec2(0.02, 0.0), vec2(0.005, 0.0026)},
    {"sliver (0.69)", vec2(0.02, 0.0), vec2(0.01, 0.0008)},
    {"parallel edges (0)", vec2(0.01, 0.01), vec2(0.005, 0.005)},
    {"tiny (0.17)", vec2(1e-4, 0.0), vec2(0.0, 2e-4)},
    {"flat", vec2(0.0), vec2(0.0)},
};

// Midpoint rule over the parallelogram's bounding box widened by 10 sigma, at sigma / 6.
double Integral(const Cell& cell) {
  const double half_x = 0.5 * (std::abs(cell.d_u.x) + std::abs(cell.d_v.x)) + 10.0 * kSigma;
  const double half_y = 0.5 * (std::abs(cell.d_u.y) + std::abs(cell.d_v.y)) + 10.0 * kSigma;
  const double step = kSigma / 6.0;
  const int nx = int(std::ceil(2.0 * half_x / step));
  const int ny = int(std::ceil(2.0 * half_y / step));
  const double hx = 2.0 * half_x / nx, hy = 2.0 * half_y / ny;
  double sum = 0.0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const vec2 r(-half_x + (i + 0.5) * hx, -half_y + (j + 0.5) * hy);
      sum += OceanCellSlopeDensity(r, cell.d_u, cell.d_v, kSigma);
    }
  return sum * hx * hy;
}

TEST(CellSlopeDensity, IntegratesToOneForEveryShape) {
  for (const Cell& cell : kCells) {
    const double integral = Integral(cell);
    std::printf("%-20s integral %.8f\n", cell.name, integral);
    EXPECT_NEAR(integral, 1.0, 1e-5) << cell.name;
  }
}

// A lattice of cells (every cell's parallelogram a translate by i d_u + j d_v, as the slopes of
// a field whose slope varies linearly tile slope space) sums to 1 / area everywhere. The
// Gaussian of each parallelogram's variance, stop 15's estimator, does not: it is checked too,
// to show what the test would catch.
TEST(CellSlopeDensity, ALatticeOfCellsSumsToAFlatDensity) {
  const Cell lattices[] = {kCells[0], kCells[1], kCells[2], kCells[3]};
  for (const Cell& cell : lattices) {
    const double area = std::abs(Cross(cell.d_u, cell.d_v));
    double worst = 0.0, worst_gaussian = 0.0;
    for (int k = 0; k < 64; ++k) {
      // Points spread over one cell (a 2-D Halton-like sequence in the cell's coordinates).
      const double a = std::fmod(0.5 + k * 0.6180339887, 1.0) - 0.5;
      const double b = std::fmod(0.5 + k * 0.7548776662, 1.0) - 0.5;
      const vec2 r = a * cell.d_u + b * cell.d_v;
      double sum = 0.0, sum_gaussian = 0.0;
      const int n = 40;  // enough that the sliver's lattice covers 20 sigma across
      for (int j = -n; j <= n; ++j)
        for (int i = -n; i <= n; ++i) {
          const vec2 q = r - double(i) * cell.d_u - double(j) * cell.d_v;
          sum += OceanCellSlopeDensity(q, cell.d_u, cell.d_v, kSigma);
          // Stop 15: a Gaussian of (|d_u|^2 + |d_v|^2) / 12 per axis (no covariance), raised
          // to the sun's variance.
          const vec2 variance = max((cell.d_u * cell.d_u + cell.d_v * cell.d_v) / 12.0,
                                    vec2(OCEAN_SUN_MIN_SLOPE_VARIANCE));
          sum_gaussian += OceanSlopePdf(q, variance);
        }
      worst = std::max(worst, std::abs(sum * area - 1.0));
      worst_gaussian = std::max(worst_gaussian, std::abs(sum_gaussian * area - 1.0));
    }
    std::printf("%-20s lattice sum x area - 1: worst %.2e (a Gaussian per cell: %.2e)\n",
                cell.name, worst, worst_gaussian);
    // The box cells are a partition of unity up to rounding; the blend and the sliver up to
    // the neglected correlation and the ripple of Gaussians (sigma_across >= h / 1.5 apart).
    EXPECT_LT(worst, 5e-3) << cell.name;
    // Gaussians of a box's variance ripple by 2 exp(-2 pi^2 / 12) = 0.39 and more; the sliver's
    // are as wide as the sun's, much wider than its lattice's rows, and ripple little.
    if (cell.d_v.y > 0.002) {
      EXPECT_GT(worst_gaussian, 0.2) << cell.name;
    }
  }
}

TEST(CellSlopeDensity, ALargeCellIsItsInverseAreaInsideAndZeroFarOutside) {
  const vec2 d_u(0.05, 0.01), d_v(-0.01, 0.04);
  const double area = std::abs(Cross(d_u, d_v));
  for (const vec2 r : {vec2(0.0), 0.3 * d_u - 0.2 * d_v, -0.35 * d_u + 0.3 * d_v})
    EXPECT_NEAR(OceanCellSlopeDensity(r, d_u, d_v, kSigma) * area, 1.0, 1e-6);
  for (const vec2 r : {0.5 * d_u + 0.5 * d_v + vec2(0.02), -1.0 * d_u, 2.0 * d_v})
    EXPECT_LT(OceanCellSlopeDensity(r, d_u, d_v, kSigma) * area, 1e-12);
  // On an edge (away from corners) half of the inside's.
  EXPECT_NEAR(OceanCellSlopeDensity(0.5 * d_u, d_u, d_v, kSigma) * area, 0.5, 1e-6);
}

// A flat cell is the paper's eq. 15 with the sun's minimum variance (sec. 5.1), bit for bit up
// to rounding: both are the sun's Gaussian in slope space.
TEST(CellSlopeDensity, AFlatCellIsEq15WithTheSunsMinimumVariance) {
  int compared = 0;
  for (double view_zenith : {0.0, 30.0, 60.0, 85.0})
    for (double offset : {0.0, 0.5e-3, 2e-3}) {
      const double theta = view_zenith * DEGREE;
      const vec3 v(std::sin(theta), 0.0, std::cos(theta));
      // The sun mirrored about the vertical, moved by `offset` radians across.
      const vec3 l = normalize(vec3(-v.x, offset, v.z));
      const double expected = OceanReflectedSun(v, l, vec2(0.0), OCEAN_DEFAULT_FRESNEL_R);
      const double cell = OceanCellReflectedSun(v, l, vec2(0.0), vec2(0.0), vec2(0.0),
                                                OCEAN_DEFAULT_FRESNEL_R);
      ASSERT_GT(expected, 0.0);
      EXPECT_NEAR(cell / expected, 1.0, 1e-12) << view_zenith << " " << offset;
      ++compared;
    }
  EXPECT_EQ(compared, 12);
}

// The estimator on a sea: the slope field of three sines (slopes up to ~0.2), cut into cells of
// 1/32 of the shortest wavelength, each cell's parallelogram from its four corners' slopes as
// ocean/reference_sun.glsl builds it. The density of slopes at a mirror slope, averaged over the
// area, is estimated with the cells' grid shifted by 8 fractions of a cell: it must hardly depend
// on the shift (the spread of the 8 estimates) and must agree with 4 times finer cells.
// Measured (docs/validation.md): the spread falls from 2.3 % at 16 cells per wavelength to 0.4,
// 0.12 and 0.02 % at 32, 64 and 128, the Gaussian per cell's from 7.5 % to 4.4, 2.9 and 1.2 %.
struct SlopeField {
  // h = sum A sin(k.x + phase); slope = grad h.
  struct Wave {
    vec2 k;
    double amplitude, phase;
  };
  std::vector<Wave> waves;
  vec2 operator()(const vec2& x) const {
    vec2 slope(0.0);
    for (const Wave& w : waves)
      slope += w.amplitude * std::cos(dot(w.k, x) + w.phase) * w.k;
    return slope;
  }
};

// Mean over the square [0, size]^2 (shifted by `shift` cells) of the cells' density at `mirror`,
// cells of side `cell`; `gaussian` uses stop 15's Gaussian per cell instead.
double MeanDensity(const SlopeField& field, double size, double cell, double shift,
                   const vec2& mirror, bool gaussian) {
  const int n = int(std::round(size / cell));
  std::vector<vec2> previous(n + 1), current(n + 1);
  double sum = 0.0;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i)
      current[i] = field(vec2((i + shift) * cell, (j + shift * 0.61803) * cell));
    if (j > 0)
      for (int i = 1; i <= n; ++i) {
        const vec2 c00 = previous[i - 1], c10 = previous[i], c01 = current[i - 1],
                   c11 = current[i];
        const vec2 centre = 0.25 * (c00 + c10 + c01 + c11);
        const vec2 d_u = 0.5 * ((c10 - c00) + (c11 - c01));
        const vec2 d_v = 0.5 * ((c01 - c00) + (c11 - c10));
        if (gaussian) {
          const vec2 variance =
              max((d_u * d_u + d_v * d_v) / 12.0, vec2(OCEAN_SUN_MIN_SLOPE_VARIANCE));
          sum += OceanSlopePdf(mirror - centre, variance);
        } else {
          sum += OceanCellSlopeDensity(mirror - centre, d_u, d_v, kSigma);
        }
      }
    std::swap(previous, current);
  }
  return sum / (double(n) * n);
}

TEST(CellSlopeDensity, OnASeaTheEstimateDoesNotDependOnWhereTheCellsFall) {
  const double two_pi = 2.0 * PI;
  // Wavelengths 1, 1.7 and 2.9 (the shortest 1), slopes A k of 0.12, 0.1 and 0.08.
  SlopeField field{{{two_pi * vec2(1.0, 0.0), 0.12 / two_pi, 0.3},
                    {two_pi / 1.7 * normalize(vec2(0.8, 0.6)), 0.1 * 1.7 / two_pi, 1.1},
                    {two_pi / 2.9 * normalize(vec2(-0.3, 1.0)), 0.08 * 2.9 / two_pi, 2.0}}};
  const double size = 8.0;
  for (const vec2 mirror : {vec2(0.03, -0.02), vec2(-0.1, 0.05)}) {
    const double fine = MeanDensity(field, size, 1.0 / 128.0, 0.5, mirror, false);
    const double cell = 1.0 / 32.0;
    double spread[2] = {0.0, 0.0}, bias[2] = {0.0, 0.0};
    for (int gaussian = 0; gaussian < 2; ++gaussian) {
      std::vector<double> estimates;
      for (int s = 0; s < 8; ++s)
        estimates.push_back(MeanDensity(field, size, cell, s / 8.0, mirror, gaussian));
      double mean = 0.0;
      for (double e : estimates) mean += e / estimates.size();
      for (double e : estimates)
        spread[gaussian] = std::max(spread[gaussian], std::abs(e / mean - 1.0));
      bias[gaussian] = mean / fine - 1.0;
    }
    std::printf("mirror (%g, %g): density %.4g; 32 cells per wavelength: spread over shifts %.2e "
                "(Gaussian per cell %.2e), against 128 per wavelength %+.2e (Gaussian %+.2e)\n",
                mirror.x, mirror.y, fine, spread[0], spread[1], bias[0], bias[1]);
    EXPECT_LT(spread[0], 0.01);
    EXPECT_GT(spread[1], 2.0 * spread[0]);  // what the partition of unity buys
    EXPECT_LT(std::abs(bias[0]), 0.02);
  }
}

}  // namespace
}  // namespace thalassa::glsl
