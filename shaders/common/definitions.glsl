// Shared GLSL / C++ subset: the GLSL side. Included as #include "common/definitions.glsl".
//
// Shader library files (shaders/**/*.glsl) are written so that the same source compiles as GLSL
// on the GPU and as C++ in double precision for the CPU references and tests, as in Bruneton's
// precomputed_atmospheric_scattering (see DESIGN.md, sections 4 and 8):
//
// - Scalars are `Number`, vectors vec2 / vec3 / vec4. Casts are written `Number(x)`, never
//   `float(x)`. Literals are written `1.0` (float in GLSL, double in C++), never `1.0f` or `1`.
// - Parameters are declared with IN(T), OUT(T) or INOUT(T). PRECISE is GLSL's `precise` (the
//   same operations in the same order wherever the expression is computed), empty in C++.
// - Components are read and written only as .x / .y / .z / .w: no swizzles (glm offers them only
//   with GLM_FORCE_SWIZZLE, which would change the glm types for the whole program).
// - Only the built-ins that common/glsl_cpp.hpp provides (it lists them), no arrays, no uniforms
//   or other interface variables, and every function is defined before use.
//
// How the two sides meet: common/glsl_cpp.hpp (C++ only) defines THALASSA_CPP, Number = double,
// vec* = glm::dvec*, IN/OUT/INOUT as references and the built-ins. When THALASSA_CPP is defined,
// the GLSL-only macro block below is skipped and only the named constants compile, as C++
// constants in the namespace into which the .glsl file was included (thalassa::glsl). So the
// `#include "common/definitions.glsl"` line at the top of every library file works under both
// preprocessors, and the constants have one definition for both languages.
//
// No #version here: the shader library prepends `#version 450 core`.

#ifndef THALASSA_COMMON_DEFINITIONS_GLSL
#define THALASSA_COMMON_DEFINITIONS_GLSL

#ifndef THALASSA_CPP
#define Number float
#define IN(x) const in x
#define OUT(x) out x
#define INOUT(x) inout x
#define PRECISE precise
#endif  // THALASSA_CPP

const Number PI = 3.14159265358979323846;
// rad, pi (3 - sqrt(5)): consecutive points of a sunflower spiral spread evenly over a disc.
const Number GOLDEN_ANGLE = 2.39996322972865332;

// Radians per degree: `30.0 * DEGREE` is 30 degrees in radians.
const Number DEGREE = PI / 180.0;

// Wavelengths (nm) at which the R, G and B channels of every radiance are evaluated: radiance is
// spectral radiance in W m^-2 sr^-1 nm^-1 at these wavelengths (as in Bruneton's 2017 demo).
const vec3 RGB_WAVELENGTHS = vec3(680.0, 550.0, 440.0);

#endif  // THALASSA_COMMON_DEFINITIONS_GLSL
