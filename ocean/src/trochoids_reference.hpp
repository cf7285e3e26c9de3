// Double-precision CPU reference of one trochoid wave train of the Bruneton et al. 2010 ocean: the
// functions of shaders/ocean/trochoids.glsl (and of shaders/ocean/parallax.glsl, the parallax of
// the waves drawn in the normals alone) compiled as C++ (Number = double, vec2/vec3 =
// glm::dvec2/dvec3) in namespace thalassa::glsl, e.g. thalassa::glsl::TrochoidDisplacement(
// direction, amplitude, argument). Frames, units and sources are documented in the .glsl file.
// Header-only; needs shaders/ on the include path. Like every user of common/glsl_cpp.hpp, a file
// including this header cannot use IN, OUT or INOUT as names (they are macros of the shared
// GLSL / C++ subset).

#ifndef THALASSA_OCEAN_SRC_TROCHOIDS_REFERENCE_HPP_
#define THALASSA_OCEAN_SRC_TROCHOIDS_REFERENCE_HPP_

#include "common/glsl_cpp.hpp"

// Anonymous namespace: the .glsl functions are not `inline` in C++, so each translation unit gets
// its own internal-linkage copy (no duplicate symbols when several files of one program include
// this header), and the ones a file does not use are not reported as unused.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace thalassa::glsl {
namespace {
#include "ocean/parallax.glsl"
#include "ocean/trochoids.glsl"
}  // namespace
}  // namespace thalassa::glsl
#pragma GCC diagnostic pop

#endif  // THALASSA_OCEAN_SRC_TROCHOIDS_REFERENCE_HPP_
