// What the two sky providers share about their GL textures and shader defines (internal).
#pragma once

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/gl.hpp"
#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/shader_library.hpp"

namespace thalassa::atmosphere {

// Mip levels of a square texture of `size` texels, down to 1 x 1.
inline int sky_map_mip_levels(int size) {
  return 1 + static_cast<int>(std::floor(std::log2(size)));
}

// Trilinear, clamped: the anisotropy of eq. 27's fetch is done in the shader
// (SkyMapRadianceGrad in shaders/atmosphere/sky_provider.glsl), not by the texture unit.
inline void set_sky_map_sampling(GLuint texture) {
  gl::set_sampling(texture, {.min_filter = GL_LINEAR_MIPMAP_LINEAR});
}

// A double as a GLSL float literal with full float precision ("1.0", "2.5e-06").
inline std::string glsl_float_literal(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  std::string s = buffer;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// Throws std::invalid_argument unless `settings` describe a map and an array both providers can
// build and the array's lookup can index (its layer mapping divides by the knee's zenith and by
// the zenith span beyond it).
inline void check_sky_map_settings(const SkyMapSettings& settings) {
  if (settings.size < 1 || settings.size > 8192)
    throw std::invalid_argument("sky map size must be in [1, 8192]");
  if (settings.array_layers < 3 || settings.array_layers > 256)
    throw std::invalid_argument("sky map array layers must be in [3, 256]");
  if (!(settings.array_knee_layer > 0 && settings.array_knee_layer < settings.array_layers - 1 &&
        settings.array_knee_zenith > 0.0 &&
        settings.array_knee_zenith < settings.array_max_sun_zenith))
    throw std::invalid_argument("sky map array knee must lie strictly inside the array");
}

// The constants of sky_provider.glsl's array lookup (SkyMapArrayLayer), as float literals:
// the layer count and the knee's layer (dimensionless), the knee's and the last layer's sun
// zenith angles (rad).
inline gl::Defines sky_map_array_defines(const SkyMapSettings& settings) {
  return {{"SKY_MAP_ARRAY_LAYERS", glsl_float_literal(settings.array_layers)},
          {"SKY_MAP_ARRAY_KNEE_LAYER", glsl_float_literal(settings.array_knee_layer)},
          {"SKY_MAP_ARRAY_KNEE_ZENITH", glsl_float_literal(settings.array_knee_zenith)},
          {"SKY_MAP_ARRAY_MAX_ZENITH", glsl_float_literal(settings.array_max_sun_zenith)}};
}

}  // namespace thalassa::atmosphere
