// A synthetic, real-looking one-channel sky for the prefiltering tests and benchmark
// (tests/unit/sh_prefilter_test.cpp, tests/bench/sh_prefilter_bench.cpp): no HDR photograph is
// needed, and the map is the same on every machine. Lat-long, the toolkit's layout
// (spherical_harmonics.hpp): +z is the zenith, rows top first. Radiance in arbitrary units
// (think W m^-2 sr^-1 of one channel).
//
// What it holds, and why: a sky that brightens toward the horizon (a gradient, the low
// frequencies), a darker ground, a horizon blended over a few degrees (sharp enough to excite
// high orders, smooth enough that a 128-texel map resolves it), a broad circumsolar glow and a
// small bright "sun" region (a Gaussian of 3 degrees, 300 times the zenith sky: the high
// frequencies that make prefiltering worth doing). The real sun is far smaller and brighter; the
// engine handles it analytically (issue 8, point 6), so a resolved bright region is the honest
// test of a map that SH will actually see.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace thalassa::test {

struct SyntheticSky {
  double zenith = 1.0;           // sky radiance at the zenith
  double horizon = 3.0;          // sky radiance at the horizon (gradient in 1 - cos(zenith))
  double ground = 0.3;           // radiance below the horizon
  double horizon_blend = 0.035;  // radians (2 degrees): half-width of the horizon's smoothstep
  double sun_elevation = 0.61;   // radians (35 degrees) above the horizon
  double sun_azimuth = 1.05;     // radians (60 degrees) from +x toward +y
  double sun_radius = 0.052;     // radians (3 degrees): 1/e radius of the bright region
  double sun_peak = 300.0;       // its peak radiance
  double glow_radius = 0.35;     // radians (20 degrees): 1/e radius of the circumsolar glow
  double glow_peak = 4.0;        // its peak radiance

  double radiance(double x, double y, double z) const {
    const double elevation = std::asin(std::clamp(z, -1.0, 1.0));
    const double e = std::clamp(0.5 + 0.5 * elevation / horizon_blend, 0.0, 1.0);
    const double blend = e * e * (3.0 - 2.0 * e);  // smoothstep
    const double sky = zenith + (horizon - zenith) * (1.0 - std::max(z, 0.0));
    const double cos_sun_el = std::cos(sun_elevation);
    const double sx = cos_sun_el * std::cos(sun_azimuth), sy = cos_sun_el * std::sin(sun_azimuth),
                 sz = std::sin(sun_elevation);
    const double angle = std::acos(std::clamp(x * sx + y * sy + z * sz, -1.0, 1.0));
    const double sun = sun_peak * std::exp(-(angle / sun_radius) * (angle / sun_radius)) +
                       glow_peak * std::exp(-(angle / glow_radius) * (angle / glow_radius));
    return blend * (sky + sun) + (1.0 - blend) * ground;
  }

  // The map sampled at texel centres, width x height values, rows top first.
  std::vector<double> lat_long(int width, int height) const {
    std::vector<double> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int row = 0; row < height; ++row) {
      const double theta = (row + 0.5) * std::numbers::pi / height;
      for (int column = 0; column < width; ++column) {
        const double phi = 2.0 * std::numbers::pi * (column + 0.5) / width;
        out[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(column)] =
            radiance(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                     std::cos(theta));
      }
    }
    return out;
  }
};

}  // namespace thalassa::test
