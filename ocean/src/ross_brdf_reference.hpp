// Double-precision CPU reference of the Ross et al. ocean BRDF and its lighting terms: the
// functions of shaders/ocean/ross_brdf.glsl (and, through it, shaders/ocean/smith.glsl) and of
// shaders/ocean/cell_slope_density.glsl (the reference method's per-cell sun) and
// shaders/ocean/visible_area_weight.glsl (the weight of its samples) and
// shaders/ocean/reference_cell.glsl (the geometry of its sun's cells) compiled as C++
// (Number = double, vec2/vec3 = glm::dvec2/dvec3) in namespace thalassa::glsl, e.g.
// thalassa::glsl::OceanRossBrdf(v, l, slope_variance, fresnel_r). Frames (the tangent frame:
// x along the wind, y across, z the mean normal), units and sources are documented in the .glsl
// files. Header-only; needs shaders/ on the include path. Like every user of common/glsl_cpp.hpp,
// a file including this header cannot use IN, OUT or INOUT as names (they are macros of the
// shared GLSL / C++ subset).

#ifndef THALASSA_OCEAN_SRC_ROSS_BRDF_REFERENCE_HPP_
#define THALASSA_OCEAN_SRC_ROSS_BRDF_REFERENCE_HPP_

#include "common/glsl_cpp.hpp"

// Anonymous namespace: the .glsl functions are not `inline` in C++, so each translation unit gets
// its own internal-linkage copy (no duplicate symbols when several files of one program include
// this header), and the ones a file does not use are not reported as unused.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace thalassa::glsl {
namespace {
#include "ocean/ross_brdf.glsl"
#include "ocean/cell_slope_density.glsl"
#include "ocean/visible_area_weight.glsl"
#include "ocean/reference_cell.glsl"
}  // namespace
}  // namespace thalassa::glsl
#pragma GCC diagnostic pop

#endif  // THALASSA_OCEAN_SRC_ROSS_BRDF_REFERENCE_HPP_
