// What the two sky providers share about their GL textures and shader defines (internal).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include "thalassa/engine/gl/gl.hpp"

namespace thalassa::atmosphere {

// Mip levels of a square texture of `size` texels, down to 1 x 1.
inline int sky_map_mip_levels(int size) {
  return 1 + static_cast<int>(std::floor(std::log2(size)));
}

// Trilinear, clamped: the anisotropy of eq. 27's fetch is done in the shader
// (SkyMapRadianceGrad in shaders/atmosphere/sky_provider.glsl), not by the texture unit.
inline void set_sky_map_sampling(GLuint texture) {
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

// A double as a GLSL float literal with full float precision ("1.0", "2.5e-06").
inline std::string glsl_float_literal(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  std::string s = buffer;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

}  // namespace thalassa::atmosphere
