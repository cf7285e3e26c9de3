// The seas at rest the unit tests use (ocean/include/thalassa/ocean/sea_surface.hpp): the
// Earth's sphere, an ellipsoid-like C with an off-diagonal term, and the WGS84 ellipsoid's own C
// at a latitude, built from its ECEF quadric in long double.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include "thalassa/ocean/sea_surface.hpp"

namespace thalassa::ocean::testing {

constexpr double kEarthRadius = 6371e3;          // m, the sphere of the tests
constexpr double kWgs84A = 6378137.0;            // m, equatorial radius
constexpr double kWgs84F = 1.0 / 298.257223563;  // flattening

// The WGS84 C in the ENU frame at geodetic latitude lat (degrees, longitude 0): C = R^T A R /
// |A N| (sea_surface.hpp), with A = diag(1/a^2, 1/a^2, 1/b^2), N the nadir point and R the ENU
// axes (east, north, up) in ECEF. Its off-diagonal term couples north and up: sin cos e^2 /
// ((1 - e^2) N) = 5.3e-10 / m at 45 degrees.
struct Wgs84Frame {
  long double nadir[3];    // ECEF, m
  long double axes[3][3];  // axes[i]: east, north, up in ECEF
  SeaSurface surface;
};

inline Wgs84Frame wgs84_frame(double lat_deg) {
  const long double a = kWgs84A, b = a * (1.0L - kWgs84F);
  const long double e2 = 1.0L - (b * b) / (a * a);
  const long double phi = lat_deg * 3.141592653589793238462643383279503L / 180.0L;
  const long double s = std::sin(phi), c = std::cos(phi);
  const long double n = a / std::sqrt(1.0L - e2 * s * s);  // prime vertical radius
  Wgs84Frame frame{
      {n * c, 0.0L, n * (1.0L - e2) * s}, {{0.0L, 1.0L, 0.0L}, {-s, 0.0L, c}, {c, 0.0L, s}}, {}};
  const long double inverse_squares[3] = {1.0L / (a * a), 1.0L / (a * a), 1.0L / (b * b)};
  long double an[3], an_length2 = 0.0L;
  for (int k = 0; k < 3; ++k) {
    an[k] = inverse_squares[k] * frame.nadir[k];
    an_length2 += an[k] * an[k];
  }
  const long double an_length = std::sqrt(an_length2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      long double sum = 0.0L;
      for (int k = 0; k < 3; ++k) sum += frame.axes[i][k] * inverse_squares[k] * frame.axes[j][k];
      frame.surface.curvature[j][i] = static_cast<double>(sum / an_length);
    }
  return frame;
}

// diag(1/6378137, 1/6356752, 1/6371000) (1/m) with an off-diagonal east-up term of the size of
// WGS84's north-up one at 45 degrees: an ellipsoid-like sea whose horizon dip depends on the
// azimuth and whose C z-hat is not vertical.
inline SeaSurface ellipsoid_like_sea() {
  SeaSurface surface;
  surface.curvature = glm::dmat3(0.0);
  surface.curvature[0][0] = 1.0 / 6378137.0;
  surface.curvature[1][1] = 1.0 / 6356752.0;
  surface.curvature[2][2] = 1.0 / 6371000.0;
  surface.curvature[2][0] = surface.curvature[0][2] = 5.3e-10;
  return surface;
}

}  // namespace thalassa::ocean::testing
