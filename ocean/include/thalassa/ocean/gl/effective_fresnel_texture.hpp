// thalassa — the effective Fresnel table on the GPU (GL layer, not installed): eq. 24 of Bruneton,
// Neyret & Holzschuch 2010 tabulated in double (ocean/effective_fresnel.hpp) as a float texture
// that shaders/ocean/effective_fresnel.glsl reads with EFFECTIVE_FRESNEL_TABLE or
// SKY_LOBE_FRESNEL_WEIGHTED defined (scenes with ocean.effective_fresnel = "table" or
// ocean.sky_lobe_centre = "fresnel_weighted"; the others create none of it). Shared by the
// surface's ocean node and the view from space's, which read it alike.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/engine/scene.hpp"

namespace thalassa::ocean {

// Texture unit of the table (shaders/ocean/effective_fresnel.glsl's binding), clear of the sky
// provider's units (4 to 11), the calm-area chart's (12) and the reference's depth (14).
inline constexpr unsigned kEffectiveFresnelUnit = 13;

class EffectiveFresnelTexture {
 public:
  // The table where `settings` use it in a lighting pass: eq. 24's F-bar
  // (ocean.effective_fresnel = "table") where a term reads F-bar (reads_fresnel: the sky or the
  // refracted light), the sky's lobe centre (ocean.sky_lobe_centre = "fresnel_weighted") where the
  // reflected sky is drawn (reflects_sky; every ocean.sky_filter moves its lobe to it); null where
  // neither. Uploads the table (computing it on the process's first use).
  static std::unique_ptr<EffectiveFresnelTexture> make_if_used(const OceanSettings& settings,
                                                               bool reads_fresnel,
                                                               bool reflects_sky);

  // EFFECTIVE_FRESNEL_TABLE and SKY_LOBE_FRESNEL_WEIGHTED, as used.
  void add_defines(gl::Defines& defines) const;
  // ocean.effective_fresnel.table and ocean.sky_lobe_centre.fresnel_weighted, as used.
  std::vector<std::string> built() const;
  void bind() const;

 private:
  EffectiveFresnelTexture(bool table, bool sky_lobe);

  bool table_ = false;     // F-bar from eq. 24
  bool sky_lobe_ = false;  // the sky's lobe centred on the facets
  gl::Texture texture_;
};

}  // namespace thalassa::ocean
