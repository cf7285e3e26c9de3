// Helpers shared by the tests of the GLSL functions' double-precision references (tests that
// include a *_reference.hpp, i.e. the shared GLSL compiled as C++ in thalassa::glsl).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/glsl_cpp.hpp"
#include "thalassa/planet/camera_frame.hpp"

namespace thalassa::glsl::test {

// Unit direction of a zenith angle and an azimuth (clockwise from north), both in degrees.
inline glm::dvec3 Direction(double zenith_deg, double azimuth_deg) {
  return thalassa::sun_direction(zenith_deg, azimuth_deg);
}

// |a - b| / |b|, with the smallest normal double as the floor of |b|.
inline double RelativeDifference(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(b), std::numeric_limits<double>::min());
}

inline bool IsFiniteNonNegative(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0 &&
         v.y >= 0.0 && v.z >= 0.0;
}

}  // namespace thalassa::glsl::test
