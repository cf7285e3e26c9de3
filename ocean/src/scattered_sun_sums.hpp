// thalassa — whether the reference's scattered sun holds what a scatter can write.
//
// The scatter (shaders/ocean/reference_sun_scatter.comp) leaves four sums per pixel: sum omega
// sun, sum omega, the part of sum omega from footprints past the cell cap (unresolved) and the
// solid angle hidden behind the grid's crests (sr). Every deposit is finite and non-negative and
// each cell's unresolved share is its omega or 0, so a buffer the scatter wrote has all four
// finite, non-negative, unresolved <= sum omega (to the float additions' rounding) and solid
// angles no larger than the sphere's.
//
// Why it is checked (stop 40). On the H200 three references of the default suite at 2048^2
// cells per footprint drew a sun that was not finite in 8-10 % of their pixels, in both of that
// stop's calls, and the sums read back were, as bytes, GLSL source text ("Tail(IN(Number) ",
// "tion w (tangent "): all of the buffer held memory that neither its clear nor the scatter had
// written. Each was a renderer's first scatter, into a buffer just made, of 8-17 s; the same
// lattice as a later scatter into buffers used before was sound; llvmpipe never showed it. Why
// is not known. Such text passes as floats of 1e-19 to 1e35: the tests below catch a buffer of
// it with near certainty (a pixel's four words pass together only where their last bytes are
// spaces, digits or punctuation). Since the fault may as well leave zeros, or what the clear
// wrote, the cells' solid angle is checked against the sea's in the image too
// (scattered_sun_coverage_fault), and new storage starts as NaN, which only a clear and a
// scatter that reached the buffer replace. A lattice that fails is scattered again (ocean_node.cpp,
// scatter_checked).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <span>
#include <string>

namespace thalassa::ocean {

// sr: no solid angle exceeds the sphere's (a pixel's is far smaller).
inline constexpr double kScatteredSunMostSolidAngle = 4.0 * 3.14159265358979323846;
// The relative slack on unresolved <= sum omega: the two sums add the same omegas, but the float
// atomics add a pixel's partial sums (one per invocation's run of cells) in orders that may
// differ between the two (float's 6e-8 per addition; 1e-3 leaves room for thousands).
inline constexpr double kScatteredSunUnresolvedSlack = 1e-3;

// Empty when every pixel's sums are what a scatter can write; else what the first pixel that is
// not holds (x, y: window coordinates, y from the bottom row, as the buffer's rows). `sums`: 4
// floats per pixel, width x height pixels, row-major from the bottom row.
inline std::string scattered_sun_sums_fault(std::span<const float> sums, int width, int height) {
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  if (width < 1 || height < 1 || sums.size() != 4 * pixels)
    return "expected 4 x " + std::to_string(width) + " x " + std::to_string(height) +
           " floats, got " + std::to_string(sums.size());
  for (std::size_t i = 0; i < pixels; ++i) {
    const float* s = &sums[4 * i];
    const char* why = nullptr;
    if (!(std::isfinite(s[0]) && std::isfinite(s[1]) && std::isfinite(s[2]) && std::isfinite(s[3])))
      why = "a sum that is not finite";
    else if (s[0] < 0.0f || s[1] < 0.0f || s[2] < 0.0f || s[3] < 0.0f)
      why = "a negative sum";
    else if (s[1] > kScatteredSunMostSolidAngle || s[2] > kScatteredSunMostSolidAngle ||
             s[3] > kScatteredSunMostSolidAngle)
      why = "a solid angle larger than the sphere's";
    else if (double(s[2]) > double(s[1]) * (1.0 + kScatteredSunUnresolvedSlack))
      why = "more unresolved solid angle than solid angle";
    else if (s[1] > 0.0f && !std::isfinite(s[0] / s[1]))
      why = "a sun factor (sum omega sun / sum omega) past a float's range";
    if (!why) continue;
    char values[160];
    std::snprintf(values, sizeof values, "%.9g, %.9g, %.9g, %.9g", s[0], s[1], s[2], s[3]);
    return std::string(why) + " at window pixel (" + std::to_string(i % std::size_t(width)) + ", " +
           std::to_string(i / std::size_t(width)) +
           ") (sum omega sun, sum omega, unresolved, hidden; sr): " + values;
  }
  return {};
}

// The least fraction of the sea's solid angle in the image (at rest) that a lattice's cells cover,
// visible (sum omega) and hidden (behind the grid's crests) together: the cells tile the sea in
// view (the cells' solid angles are the pixels' on a calm sea to 4e-6: tests/gpu/method_test.cpp,
// ScatteredSunsSolidAnglesAreThePixels); only the facets that face away from the eye are in
// neither, a small part of any view. Measured (stop 40, llvmpipe): 1.00-1.19 of the sea's on the
// default suite's views, from 8 km over the 10 m/s sea to 4 m over the 20 m/s (the displaced
// sea's folds and the margins' cells seen in the image add to it); 1.3-1.5 from 1 and 4 m over
// the 20 m/s sea pitched 2-8 degrees up, and 2-8 where the image holds only the last 1-2.5
// degrees below the horizon (crests rise above the sea at rest's horizon): never below 1.
inline constexpr double kScatteredSunLeastCoverage = 0.5;

// Empty when the sums' solid angle, visible and hidden, is at least kScatteredSunLeastCoverage of
// sea_solid_angle (sr, the sea at rest's in the image; 0: nothing to check); else what it is.
inline std::string scattered_sun_coverage_fault(std::span<const float> sums,
                                                double sea_solid_angle) {
  if (!(sea_solid_angle > 0.0)) return {};
  double covered = 0.0;
  for (std::size_t i = 0; i + 3 < sums.size(); i += 4) covered += double(sums[i + 1]) + sums[i + 3];
  if (covered >= kScatteredSunLeastCoverage * sea_solid_angle) return {};
  char text[200];
  std::snprintf(text, sizeof text,
                "the cells' solid angle, %.6g sr visible and hidden, is under %g of the sea's in "
                "the image, %.6g sr",
                covered, kScatteredSunLeastCoverage, sea_solid_angle);
  return text;
}

}  // namespace thalassa::ocean
