// Double-precision CPU reference of the foundation's placeholder sky: the functions of
// shaders/atmosphere/analytic_sky.glsl compiled as C++ (Number = double, vec3 = glm::dvec3) in
// namespace thalassa::glsl, e.g. thalassa::glsl::AnalyticSkyRadiance(view_dir, sun_dir).
// Frames, units and sources are documented in the .glsl file. Header-only; needs shaders/ on the
// include path. Like every user of common/glsl_cpp.hpp, a file including this header cannot use
// IN, OUT or INOUT as names (they are macros of the shared GLSL / C++ subset).

#ifndef THALASSA_ATMOSPHERE_SRC_ANALYTIC_SKY_REFERENCE_HPP_
#define THALASSA_ATMOSPHERE_SRC_ANALYTIC_SKY_REFERENCE_HPP_

#include "common/glsl_cpp.hpp"

// Anonymous namespace: the .glsl functions are not `inline` in C++, so each translation unit gets
// its own internal-linkage copy (no duplicate symbols when several files of one program include
// this header), and the ones a file does not use are not reported as unused.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace thalassa::glsl {
namespace {
#include "atmosphere/analytic_sky.glsl"
}  // namespace
}  // namespace thalassa::glsl
#pragma GCC diagnostic pop

#endif  // THALASSA_ATMOSPHERE_SRC_ANALYTIC_SKY_REFERENCE_HPP_
