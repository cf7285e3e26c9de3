// thalassa — the effective Fresnel table on the GPU (GL layer, not installed): eq. 24 of Bruneton,
// Neyret & Holzschuch 2010 tabulated in double (ocean/effective_fresnel.hpp) as a float texture
// that shaders/ocean/effective_fresnel.glsl reads with EFFECTIVE_FRESNEL_TABLE or
// SKY_LOBE_FRESNEL_WEIGHTED defined (scenes with ocean.effective_fresnel = "table" or
// ocean.sky_lobe_centre = "fresnel_weighted"; the others create none of it).
#pragma once

#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/shader_library.hpp"

namespace thalassa::ocean {

// Texture unit of the table (shaders/ocean/effective_fresnel.glsl's binding), clear of the sky
// provider's units (4 to 11), the calm-area chart's (12) and the reference's depth (14).
inline constexpr unsigned kEffectiveFresnelUnit = 13;

class EffectiveFresnelTexture {
 public:
  // Uploads the table (computing it on the process's first use).
  EffectiveFresnelTexture();

  // EFFECTIVE_FRESNEL_TABLE, which makes the lighting read the table instead of eq. 26.
  static void add_defines(gl::Defines& defines);
  void bind() const;

 private:
  gl::Texture texture_;
};

}  // namespace thalassa::ocean
