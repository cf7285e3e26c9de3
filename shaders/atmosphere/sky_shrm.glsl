// The sky prefiltered in frequency space for rough seas seen from afar (Ramamoorthi & Hanrahan
// 2002, sec. 3-4, appendix C; issue 8, point 6): maps of the ocean's eq. 22, L-bar(C) = ∫ k_s(C,
// w) L_sky(w) dw, for the mirror direction C of the mean normal and an isotropic Gaussian slope
// density of per-axis variance s, one layer per s (GlossySkyMaps in
// atmosphere/include/thalassa/atmosphere/gl/sky_shrm.hpp, the CPU side in sky_sh.hpp). Read with
// the reflected direction of the mean normal instead of eq. 27's anisotropic footprint.
//
// Frames and units: directions are unit vectors in the east-north-up frame (x east, y north,
// z up); radiance in W m^-2 sr^-1 nm^-1 (RGB at 680, 550, 440 nm), like sky_provider.glsl.
#ifndef THALASSA_ATMOSPHERE_SKY_SHRM_GLSL
#define THALASSA_ATMOSPHERE_SKY_SHRM_GLSL

#include "common/definitions.glsl"

// Mirrors thalassa::atmosphere::kSkyShrmUnit.
#define SKY_SHRM_BINDING 10

// Layer k: lat-long over the whole sphere, s = azimuth / 2 pi counter-clockwise from east, t =
// zenith angle / pi (t = 0 at the zenith), texel centres at the toolkit's lat-long centres.
layout(binding = SKY_SHRM_BINDING) uniform sampler2DArray sky_shrm_maps;
// (ln s_0, 1 / ln(s_1 / s_0)): layer k holds the per-axis slope variance s_0 (s_1 / s_0)^k.
uniform vec2 sky_shrm_levels;

// The prefiltered sky radiance reflected into the mirror direction c (unit, ENU) by slopes of
// per-axis variance `slope_variance` (dimensionless): the maps' layers interpolated linearly in
// ln s (the geometric spacing), clamped to the first and last layers (smaller variances read the
// sharpest map, over-blurred; larger ones the roughest).
vec3 SkyShrmRadiance(vec3 c, float slope_variance) {
  const float last = float(textureSize(sky_shrm_maps, 0).z - 1);
  const float layer =
      clamp((log(max(slope_variance, 1e-30)) - sky_shrm_levels.x) * sky_shrm_levels.y, 0.0, last);
  const float s = fract(atan(c.y, c.x) / (2.0 * PI) + 1.0);
  const float t = acos(clamp(c.z, -1.0, 1.0)) / PI;
  const float k = floor(layer);
  // Explicit level 0: the maps have no mip chain, and s jumps from 1 to 0 across the azimuth seam
  // (implicit derivatives there would be meaningless).
  const vec3 a = textureLod(sky_shrm_maps, vec3(s, t, k), 0.0).rgb;
  const vec3 b = textureLod(sky_shrm_maps, vec3(s, t, min(k + 1.0, last)), 0.0).rgb;
  return max(mix(a, b, layer - k), vec3(0.0));
}

#endif  // THALASSA_ATMOSPHERE_SKY_SHRM_GLSL
