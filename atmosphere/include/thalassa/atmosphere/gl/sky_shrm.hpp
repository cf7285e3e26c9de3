// thalassa — the sky provider's sky in spherical harmonics, GL layer (issue 8, point 6): the SH
// irradiance of any SkyProvider, and the SHRM-prefiltered glossy sky maps the ocean reads for
// rough seas seen from afar (ocean.sky_filter = "shrm"), uploaded as a 2D array texture over
// roughness. The CPU work is thalassa/atmosphere/sky_sh.hpp; shaders/atmosphere/sky_shrm.glsl
// reads the maps. Frames and units as sky_provider.hpp: ENU directions, heights in metres.
//
// Why the sky is projected from the provider's CPU radiance (SkyProvider::sky_radiance on a
// lat-long grid) rather than read back from the GPU's stereographic sky map: the toolkit's
// projection is a lat-long quadrature (exact for band-limited skies, spherical_harmonics.hpp),
// which a stereographic map would first have to be resampled into (an extra interpolation, and
// the map stops 12.7 degrees below the horizon); the CPU answer is double precision, needs no
// context (the irradiance is a per-frame constant like sky_irradiance()), and is the same
// function the GPU map is tested against (sky_provider_test.cpp: within 2.3e-3).
#pragma once

#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/atmosphere/sky_sh.hpp"
#include "thalassa/engine/gl/objects.hpp"

namespace thalassa::atmosphere {

// Texture unit of the glossy sky maps (shaders/atmosphere/sky_shrm.glsl, SKY_SHRM_BINDING): after
// the provider's 4 to 9.
inline constexpr GLuint kSkyShrmUnit = 10;

// The ocean's sky of `provider` seen from `height` with the sun at `sun` (ENU): sky_radiance
// (no sun disc) for d_z >= 0, below_horizon_radiance below, as the stereographic map holds it.
SkyRadianceFunction ocean_sky(const SkyProvider& provider, double height, const glm::dvec3& sun);

// The provider's sky irradiance as order-2 SH (R&H 2001): E(n) for any normal n by
// evaluate_irradiance(). E(up) reproduces provider.sky_irradiance(height, sun) within the order-2
// truncation and the provider's own quadrature (measured: docs/spherical_harmonics.md). The sun
// is not in it: add provider.sun_irradiance() (or L_sun Omega_sun max(n.sun, 0)) analytically.
IrradianceSh sky_irradiance_sh(const SkyProvider& provider, double height, const glm::dvec3& sun,
                               const SkyProjectionGrid& grid = {});

// The glossy sky maps on the GPU: a GL_TEXTURE_2D_ARRAY, RGBA32F, one layer per roughness level
// (glossy_sky()'s maps, layer k at per-axis slope variance glossy_sky_slope_variance(k)), linear
// filtering, repeat in s (azimuth), clamped in t (zenith angle). Needs a current context.
class GlossySkyMaps {
 public:
  explicit GlossySkyMaps(const GlossySkySettings& settings = {});

  // Builds the maps for this sky on the first call and whenever height or sun change (once per
  // sky map, like SkyProvider::sky_map); then marks the pass "sky.shrm" on `timer`, if given.
  const GlossySky& update(const SkyProvider& provider, double height, const glm::dvec3& sun,
                          gl::GpuTimer* timer);
  // Binds the array to kSkyShrmUnit.
  void bind() const;
  // The last build (empty before the first update()).
  const GlossySky& sky() const { return sky_; }
  const GlossySkySettings& settings() const { return settings_; }
  // For `built` in the statistics: "sky.shrm_maps (L levels, F = F_max..F_min)" once built.
  std::vector<std::string> built() const;
  int build_count() const { return build_count_; }  // builds so far
  // Wall-clock ms of the last build (the kernels' coefficients, computed with the first build
  // only, are kernels_ms()).
  double build_ms() const { return build_ms_; }
  double kernels_ms() const { return kernels_ms_; }
  // (ln s_0, 1 / ln(s_1 / s_0)): the fractional layer of a per-axis slope variance s is
  // (ln s - x) y (shaders/atmosphere/sky_shrm.glsl, sky_shrm_levels).
  glm::dvec2 level_mapping() const;

 private:
  GlossySkySettings settings_;
  GlossySkyKernels kernels_;  // computed on the first update(): they do not depend on the sky
  GlossySky sky_;
  gl::Texture texture_;
  bool built_ = false;
  double height_ = 0.0;
  glm::dvec3 sun_{0.0};
  int build_count_ = 0;
  double build_ms_ = 0.0;
  double kernels_ms_ = 0.0;
};

}  // namespace thalassa::atmosphere
