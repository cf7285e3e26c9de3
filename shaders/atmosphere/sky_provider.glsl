// The sky provider's shader interface: everything the ocean, the planet and the sky pass know
// about sky light. One of two implementations is compiled, chosen by the provider's defines
// (atmosphere/include/thalassa/atmosphere/gl/sky_provider.hpp):
// - SKY_PROVIDER_ATMOSPHERE: the physical model's tables (atmosphere/model.glsl), with the
//   parameters in the ATMOSPHERE define (an AtmosphereParameters constructor);
// - SKY_PROVIDER_ENVIRONMENT: an HDR photograph (equirectangular panorama, sun removed), no
//   atmosphere between the camera and the scene.
// Both provide the stereographic sky map of the ocean's eq. 27 (binding SKY_MAP_BINDING), built
// on the host for the frame's observer and sun.
//
// Frames and units: positions are planet-centred (m) in a frame parallel to the local
// east-north-up frame at the camera's nadir (x east, y north, z up; the nadir is at
// (0, 0, bottom radius)); directions are unit vectors in that frame. Spectral radiance in
// W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm. GLSL only (samplers): the CPU side of each
// function is AtmosphereModel / EnvironmentMap.
#ifndef THALASSA_ATMOSPHERE_SKY_PROVIDER_GLSL
#define THALASSA_ATMOSPHERE_SKY_PROVIDER_GLSL

#include "common/definitions.glsl"

// Texture units of the provider (the ocean's own use units 0 to 3). Mirrors
// thalassa::atmosphere::kSkyMapUnit and friends.
#define SKY_MAP_BINDING 4
#define SKY_TRANSMITTANCE_BINDING 5
#define SKY_SCATTERING_BINDING 6
#define SKY_SINGLE_MIE_BINDING 7
#define SKY_IRRADIANCE_BINDING 8
#define SKY_PANORAMA_BINDING 9

// The stereographic sky map: texel (s, t) in [0, 1]^2 holds the radiance arriving from the
// direction of u = (2 s - 1, 2 t - 1) SKY_MAP_EXTENT, u = (r_x, r_y) / (1 + r_z) in the ENU
// frame of the observer (s east, t north; |u| <= 1 is the sky, |u| > 1 the below-horizon radiance
// of the ocean paper's multiple-reflection extension, sec. 6). Mipmapped, anisotropic.
layout(binding = SKY_MAP_BINDING) uniform sampler2D sky_map;

// Most taps of SkyMapRadianceGrad's anisotropic filter: 16, as the 16x hardware anisotropy the
// paper's texture2DGrad had.
const int SKY_MAP_MAX_TAPS = 16;

// The sky map's radiance at u, filtered over the footprint spanned by the gradients du_dx, du_dy
// (in u units): eq. 27's anisotropic fetch. The anisotropy is done here rather than by the
// texture unit, as EXT_texture_filter_anisotropic describes it: N = min(ceil(P_max / P_min), 16)
// trilinear taps spaced along the longer gradient, at the level of detail log2(P_max / N)
// (P_max, P_min the gradients' lengths in texels). Why not the texture unit: llvmpipe's
// anisotropic filter returns 0 for scattered pixels of this fetch (measured, Mesa 22.3), and an
// explicit filter gives the same result on every driver, so the CPU reference and the golden
// images hold everywhere. The map's own sampler is therefore isotropic.
vec3 SkyMapRadianceGrad(vec2 u, vec2 du_dx, vec2 du_dy) {
  const float scale = 0.5 / SKY_MAP_EXTENT;
  const float size = float(textureSize(sky_map, 0).x);
  const vec2 st = u * scale + 0.5;
  const vec2 g_x = du_dx * scale;
  const vec2 g_y = du_dy * scale;
  const float l_x = length(g_x) * size;  // texels
  const float l_y = length(g_y) * size;
  const vec2 major = l_x >= l_y ? g_x : g_y;
  const float p_max = max(l_x, l_y);
  const float p_min = min(l_x, l_y);
  const int taps = int(clamp(ceil(p_max / max(p_min, 1e-3 * p_max + 1e-9)), 1.0,
                             float(SKY_MAP_MAX_TAPS)));
  const float lod = log2(max(p_max / float(taps), 1e-9));
  vec3 sum = vec3(0.0);
  for (int i = 0; i < taps; ++i) {
    const float offset = (float(i) + 0.5) / float(taps) - 0.5;
    sum += textureLod(sky_map, st + offset * major, lod).rgb;
  }
  return sum / float(taps);
}

vec3 SkyMapRadianceLod(vec2 u, float lod) {
  return textureLod(sky_map, u * (0.5 / SKY_MAP_EXTENT) + 0.5, lod).rgb;
}

#ifdef SKY_PROVIDER_ATMOSPHERE
#include "atmosphere/model.glsl"

layout(binding = SKY_TRANSMITTANCE_BINDING) uniform sampler2D sky_transmittance_texture;
layout(binding = SKY_SCATTERING_BINDING) uniform sampler3D sky_scattering_texture;
layout(binding = SKY_SINGLE_MIE_BINDING) uniform sampler3D sky_single_mie_scattering_texture;
layout(binding = SKY_IRRADIANCE_BINDING) uniform sampler2D sky_irradiance_texture;

// The sky behind the scene along `view` from `camera`, without the sun's disc, and the
// transmittance along the ray (for the disc).
vec3 SkyBackgroundRadiance(vec3 camera, vec3 view, vec3 sun_direction, out vec3 transmittance) {
  return GetSkyRadiance(ATMOSPHERE, sky_transmittance_texture, sky_scattering_texture,
                        sky_single_mie_scattering_texture, camera, view, sun_direction,
                        transmittance);
}

// Aerial perspective between `camera` and `point`: returns the in-scattered radiance; the light
// leaving `point` arrives multiplied by `transmittance`.
vec3 SkyAerialPerspective(vec3 camera, vec3 point, vec3 sun_direction, out vec3 transmittance) {
  return GetSkyRadianceToPoint(ATMOSPHERE, sky_transmittance_texture, sky_scattering_texture,
                               sky_single_mie_scattering_texture, camera, point, sun_direction,
                               transmittance);
}

// Transmittance of the sun's light to `point` (times the visible fraction of its disc).
vec3 SkySunTransmittance(vec3 point, vec3 sun_direction) {
  float r = length(point);
  return GetTransmittanceToSun(ATMOSPHERE, sky_transmittance_texture, ClampRadius(ATMOSPHERE, r),
                               ClampCosine(dot(point, sun_direction) / r));
}

// Sun and sky irradiance on a surface at `point` with unit `normal`.
vec3 SkySunAndSkyIrradiance(vec3 point, vec3 normal, vec3 sun_direction,
                            out vec3 sky_irradiance) {
  return GetSunAndSkyIrradiance(ATMOSPHERE, sky_transmittance_texture, sky_irradiance_texture,
                                point, normal, sun_direction, sky_irradiance);
}

#elif defined(SKY_PROVIDER_ENVIRONMENT)

// The photograph as an equirectangular panorama, sun removed: s = azimuth / 2 pi clockwise from
// north (s = 0 at north), t = 1 at the zenith.
layout(binding = SKY_PANORAMA_BINDING) uniform sampler2D sky_panorama;

vec3 SkyBackgroundRadiance(vec3 camera, vec3 view, vec3 sun_direction, out vec3 transmittance) {
  transmittance = vec3(1.0);
  float azimuth = atan(view.x, view.y);  // clockwise from north
  float s = fract(azimuth / (2.0 * PI) + 1.0);
  float t = 0.5 + asin(clamp(view.z, -1.0, 1.0)) / PI;
  return texture(sky_panorama, vec2(s, t)).rgb;
}

vec3 SkyAerialPerspective(vec3 camera, vec3 point, vec3 sun_direction, out vec3 transmittance) {
  transmittance = vec3(1.0);
  return vec3(0.0);
}

#else
#error "sky_provider.glsl needs SKY_PROVIDER_ATMOSPHERE or SKY_PROVIDER_ENVIRONMENT"
#endif

#endif  // THALASSA_ATMOSPHERE_SKY_PROVIDER_GLSL
