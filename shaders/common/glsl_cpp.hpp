// Shared GLSL / C++ subset: the C++ side.
//
// Lets the shader library's .glsl files (written in the subset described at the top of
// common/definitions.glsl) compile as C++ in double precision, for CPU references and tests.
// Usage, with shaders/ on the include path:
//
//   #include "common/glsl_cpp.hpp"           // at global scope, before any .glsl file
//   #pragma GCC diagnostic push
//   #pragma GCC diagnostic ignored "-Wunused-function"
//   namespace thalassa::glsl {
//   namespace {
//   #include "ocean/ross_brdf.glsl"         // its own #include lines resolve through -I shaders
//   }  // namespace
//   }  // namespace thalassa::glsl
//   #pragma GCC diagnostic pop
//
// as ocean/src/ross_brdf_reference.hpp does (use such a header rather than repeating
// this). This header must be included at global scope (it includes <cmath> and GLM), and the
// .glsl files always inside thalassa::glsl's anonymous namespace: the types and built-ins below
// live in thalassa::glsl; the anonymous namespace gives the (non-inline) .glsl functions internal
// linkage, so several translation units of one program can include them; and each .glsl file has
// an include guard, so a file included once in another namespace is not seen again in that
// translation unit.
//
// What it provides:
// - THALASSA_CPP, which makes common/definitions.glsl skip its GLSL-only macros;
// - Number = double, vec2/3/4 = glm::dvec2/3/4, mat2/3/4 = glm::dmat2/3/4, in thalassa::glsl;
// - the parameter macros IN(T) = const T&, OUT(T) = T&, INOUT(T) = T& (global macros, as every
//   macro is: a file including this header cannot use IN, OUT or INOUT as names);
// - the GLSL built-ins the shared code uses, as plain (non-template) overloads for Number and
//   vec2/3/4 in thalassa::glsl. Being non-templates declared in the namespace of the calling
//   code, they hide ::exp and friends from <math.h> and win overload resolution against the
//   glm templates that argument-dependent lookup brings in, so `max(x, 0.0)` or `exp(v)` is never
//   ambiguous. As in GLSL, both arguments of a scalar built-in must be Number: `max(x, 0)` with
//   an int literal does not compile in C++ (and is bad style in GLSL too).
//
// Built-ins: componentwise abs sign floor ceil fract exp exp2 log log2 sqrt inversesqrt sin cos
// tan asin acos atan radians degrees; pow atan(y, x) mod min max step; clamp mix smoothstep;
// geometric dot length distance normalize cross reflect refract.

#ifndef THALASSA_SHADERS_COMMON_GLSL_CPP_HPP_
#define THALASSA_SHADERS_COMMON_GLSL_CPP_HPP_

#define THALASSA_CPP 1

#include <cmath>

#include <glm/glm.hpp>

#define IN(x) const x&
#define OUT(x) x&
#define INOUT(x) x&
// GLSL's `precise` (the same operations in the same order wherever an expression is computed);
// C++ without -ffast-math already keeps them.
#define PRECISE

namespace thalassa::glsl {

using Number = double;
using vec2 = glm::dvec2;
using vec3 = glm::dvec3;
using vec4 = glm::dvec4;
using mat2 = glm::dmat2;
using mat3 = glm::dmat3;
using mat4 = glm::dmat4;

// Componentwise unary built-ins: `scalar` is the Number version (x is its argument), the vector
// versions forward to glm.
#define THALASSA_GLSL_UNARY(name, scalar)                          \
  inline Number name(Number x) { return scalar; }                  \
  inline vec2 name(const vec2& x) { return glm::name(x); }         \
  inline vec3 name(const vec3& x) { return glm::name(x); }         \
  inline vec4 name(const vec4& x) { return glm::name(x); }

THALASSA_GLSL_UNARY(abs, std::abs(x))
THALASSA_GLSL_UNARY(sign, Number((x > 0.0) - (x < 0.0)))
THALASSA_GLSL_UNARY(floor, std::floor(x))
THALASSA_GLSL_UNARY(ceil, std::ceil(x))
THALASSA_GLSL_UNARY(fract, x - std::floor(x))
THALASSA_GLSL_UNARY(exp, std::exp(x))
THALASSA_GLSL_UNARY(exp2, std::exp2(x))
THALASSA_GLSL_UNARY(log, std::log(x))
THALASSA_GLSL_UNARY(log2, std::log2(x))
THALASSA_GLSL_UNARY(sqrt, std::sqrt(x))
THALASSA_GLSL_UNARY(inversesqrt, 1.0 / std::sqrt(x))
THALASSA_GLSL_UNARY(sin, std::sin(x))
THALASSA_GLSL_UNARY(cos, std::cos(x))
THALASSA_GLSL_UNARY(tan, std::tan(x))
THALASSA_GLSL_UNARY(asin, std::asin(x))
THALASSA_GLSL_UNARY(acos, std::acos(x))
THALASSA_GLSL_UNARY(atan, std::atan(x))
THALASSA_GLSL_UNARY(radians, glm::radians(x))
THALASSA_GLSL_UNARY(degrees, glm::degrees(x))

#undef THALASSA_GLSL_UNARY

// Componentwise binary built-ins with both arguments of the same type (x, y).
#define THALASSA_GLSL_BINARY(name, scalar)                                                    \
  inline Number name(Number x, Number y) { return scalar; }                                   \
  inline vec2 name(const vec2& x, const vec2& y) { return glm::name(x, y); }                  \
  inline vec3 name(const vec3& x, const vec3& y) { return glm::name(x, y); }                  \
  inline vec4 name(const vec4& x, const vec4& y) { return glm::name(x, y); }

THALASSA_GLSL_BINARY(pow, std::pow(x, y))
THALASSA_GLSL_BINARY(atan, std::atan2(x, y))  // GLSL atan(y, x): the first argument is y.
THALASSA_GLSL_BINARY(mod, x - y * std::floor(x / y))  // GLSL's mod, not std::fmod.
THALASSA_GLSL_BINARY(min, y < x ? y : x)              // GLSL: min(x, y) = y < x ? y : x.
THALASSA_GLSL_BINARY(max, x < y ? y : x)              // GLSL: max(x, y) = x < y ? y : x.
THALASSA_GLSL_BINARY(step, y < x ? 0.0 : 1.0)         // GLSL step(edge, x): 0 if x < edge.

#undef THALASSA_GLSL_BINARY

// Vector-scalar forms of the binary built-ins that GLSL overloads that way.
#define THALASSA_GLSL_VEC_SCALAR(vec)                                                  \
  inline vec mod(const vec& x, Number y) { return glm::mod(x, y); }                    \
  inline vec min(const vec& x, Number y) { return glm::min(x, y); }                    \
  inline vec max(const vec& x, Number y) { return glm::max(x, y); }                    \
  inline vec step(Number edge, const vec& x) { return glm::step(edge, x); }            \
  inline vec clamp(const vec& x, Number lo, Number hi) { return glm::clamp(x, lo, hi); } \
  inline vec clamp(const vec& x, const vec& lo, const vec& hi) {                       \
    return glm::clamp(x, lo, hi);                                                      \
  }                                                                                    \
  inline vec mix(const vec& x, const vec& y, Number a) { return glm::mix(x, y, a); }   \
  inline vec mix(const vec& x, const vec& y, const vec& a) { return glm::mix(x, y, a); } \
  inline vec smoothstep(Number e0, Number e1, const vec& x) {                          \
    return glm::smoothstep(e0, e1, x);                                                 \
  }                                                                                    \
  inline vec smoothstep(const vec& e0, const vec& e1, const vec& x) {                  \
    return glm::smoothstep(e0, e1, x);                                                 \
  }                                                                                    \
  inline Number dot(const vec& x, const vec& y) { return glm::dot(x, y); }             \
  inline Number length(const vec& x) { return glm::length(x); }                        \
  inline Number distance(const vec& x, const vec& y) { return glm::distance(x, y); }   \
  inline vec normalize(const vec& x) { return glm::normalize(x); }                     \
  inline vec reflect(const vec& i, const vec& n) { return glm::reflect(i, n); }        \
  inline vec refract(const vec& i, const vec& n, Number eta) {                        \
    return glm::refract(i, n, eta);                                                    \
  }

THALASSA_GLSL_VEC_SCALAR(vec2)
THALASSA_GLSL_VEC_SCALAR(vec3)
THALASSA_GLSL_VEC_SCALAR(vec4)

#undef THALASSA_GLSL_VEC_SCALAR

inline Number clamp(Number x, Number lo, Number hi) { return min(max(x, lo), hi); }
inline Number mix(Number x, Number y, Number a) { return x * (1.0 - a) + y * a; }
inline Number smoothstep(Number e0, Number e1, Number x) {
  const Number t = clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}
inline Number length(Number x) { return std::abs(x); }
inline vec3 cross(const vec3& x, const vec3& y) { return glm::cross(x, y); }

}  // namespace thalassa::glsl

#endif  // THALASSA_SHADERS_COMMON_GLSL_CPP_HPP_
