// The sky provider's shader interface: everything the ocean, the planet and the sky pass know
// about sky light. One of two implementations is compiled, chosen by the provider's defines
// (atmosphere/include/thalassa/atmosphere/gl/sky_provider.hpp):
// - SKY_PROVIDER_ATMOSPHERE: the physical model's tables (atmosphere/model.glsl), with the
//   parameters in the ATMOSPHERE define (an AtmosphereParameters constructor);
// - SKY_PROVIDER_ENVIRONMENT: an HDR photograph (equirectangular panorama, sun removed), no
//   atmosphere between the camera and the scene.
// Both provide the stereographic sky map of the ocean's eq. 27 (binding SKY_MAP_BINDING), built
// on the host for the frame's observer and sun, and, where the including shader defines
// SKY_MAP_ARRAY, the sun-zenith-indexed array of such maps for views from space
// (SkyMapArrayRadianceGrad, binding SKY_MAP_ARRAY_BINDING).
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
#define SKY_MAP_ARRAY_BINDING 11  // unit 10 is the glossy sky maps' (sky_shrm.glsl)

// The stereographic sky map: texel (s, t) in [0, 1]^2 holds the radiance arriving from the
// direction of u = (2 s - 1, 2 t - 1) SKY_MAP_EXTENT, u = (r_x, r_y) / (1 + r_z) in the ENU
// frame of the observer (s east, t north; |u| <= 1 is the sky, |u| > 1 the below-horizon radiance
// of the ocean paper's multiple-reflection extension, sec. 6). Mipmapped; its sampler is
// isotropic (the anisotropy is SkyMapFilterFootprint's).
layout(binding = SKY_MAP_BINDING) uniform sampler2D sky_map;

// Most anisotropy of eq. 27's filter: 16, as the 16x hardware anisotropy the paper's
// texture2DGrad had. Its taps are at most 2 floor(15 / 2) + 3 = 17 (SkyMapTapCount).
const float SKY_MAP_MAX_ANISOTROPY = 16.0;

// Eq. 27's footprint, as taps in texture space: the anisotropy is done here rather than by the
// texture unit. Why not the texture unit: llvmpipe's anisotropic filter returns 0 for scattered
// pixels of this fetch (measured, Mesa 22.3), and an explicit filter gives the same result on
// every driver, so the CPU reference and the golden images hold everywhere. The maps' own
// samplers are therefore isotropic. Shared by the single map (SkyMapRadianceGrad) and the
// sun-zenith array (SkyMapArrayRadianceGrad).
//
// The footprint is P_max texels along the longer gradient and P_min across (the gradients'
// lengths), as in EXT_texture_filter_anisotropic. Where the gradients are not perpendicular that
// is wider across than the ellipse they span (whose minor axis is the parallelogram's area over
// P_max). The ocean's are nearly parallel at grazing views off the wind's axis: each slope axis
// then moves the mirror direction mostly in elevation, and P_min spreads the sky's lobe in
// azimuth about as widely as in elevation. That is kept on purpose. The ellipse itself was
// measured farther from the reference (stop 52: `full`'s sky row error, median over the default
// suite, 0.0785 -> 0.0935; over data/suites/crosswind.json 0.0829 -> 0.0908): eq. 27's
// linearisation at the mean normal draws the lobe too narrow in azimuth at grazing views, and the
// reference spreads the sky wider in azimuth than even the visible facets' slopes do (docs/
// validation.md, "The sky map's footprint across the wind").
//
// Each tap is trilinear, w = max(P_min, P_max / 16) texels wide (level of detail
// log2 w), and the taps' centres cover the segment of length l = P_max - w along the longer
// gradient, so that taps and segment together span P_max. The segment is integrated by the
// trapezoid rule from its centre outwards with nodes w apart, and a last, shorter interval to
// each end: h = l / 2w, n = floor(h), nodes at 0, +-1, ..., +-n and +-h steps. Every weight and
// node moves continuously with the gradients: the filter has no seams. EXT_texture_filter_
// anisotropic's N = ceil(P_max / P_min) equal taps at the level of detail log2(P_max / N) jump
// where the ratio crosses an integer (N by one, the level by a whole one just above 1): across the
// horizon circle's step, where the far sea reflects a grazing sky, they drew seams of up to 20 %
// in the sky's reflection along the image's columns (stop 51; tests/gpu/sky_provider_test.cpp).
struct SkyMapFootprint {
  vec2 st;      // the footprint's centre, texture coordinates
  vec2 along;   // from one node to the next along the longer gradient (w), texture coordinates
  float h;      // the segment's half-length, in steps (0: one tap)
  float lod;    // level of detail of each tap
};

// The footprint of u (stereographic, u units) and its screen gradients du_dx, du_dy in a map of
// `size` texels per side covering [-SKY_MAP_EXTENT, SKY_MAP_EXTENT]^2.
SkyMapFootprint SkyMapFilterFootprint(vec2 u, vec2 du_dx, vec2 du_dy, float size) {
  const float scale = 0.5 / SKY_MAP_EXTENT;
  const vec2 g_x = du_dx * scale;
  const vec2 g_y = du_dy * scale;
  // Texels; 1e20 holds an overflowing gradient to the coarsest level rather than inf / inf.
  const float l_x = min(length(g_x) * size, 1e20);
  const float l_y = min(length(g_y) * size, 1e20);
  const float p_max = max(l_x, l_y);
  const float p_min = min(l_x, l_y);
  const float w = max(p_min, p_max / SKY_MAP_MAX_ANISOTROPY);  // texels
  SkyMapFootprint footprint;
  footprint.st = u * scale + 0.5;
  footprint.lod = log2(max(w, 1e-9));
  // Below a millionth of a texel the footprint is a point: one tap (and no 0 / 0).
  const bool point = !(w > 1e-6);
  footprint.h = point ? 0.0 : max(0.5 * (p_max / w - 1.0), 0.0);
  footprint.along = point ? vec2(0.0) : (l_x >= l_y ? g_x : g_y) * (w / p_max);
  return footprint;
}

// The taps of the footprint: the centre, then the pairs of nodes at +-j steps, j = 1 to n, then
// the ends at +-h steps; one for a point. About ceil(P_max / P_min) + 1: EXT's taps, plus the
// ends' pair where the ratio is within 1 above an odd integer (the mean over ratios from 1 to 16,
// 9.5 against 9.0). Anchoring the trapezoid at the ends instead, with the centre blended in,
// keeps EXT's count continuously, but rippled the far sea's sky by 1-2 % along a row, with a
// period of about 25 pixels, as its centre's weight moved to the innermost pair (stop 51).
int SkyMapTapCount(SkyMapFootprint footprint) {
  return footprint.h > 0.0 ? 2 * int(floor(footprint.h)) + 3 : 1;
}

// Tap i's texture coordinates and weight (the weights sum to 1): the trapezoid rule's over the
// nodes 0, 1, ..., n, h of the half-segment (intervals of 1 and, last, e = h - n), mirrored.
vec2 SkyMapTap(SkyMapFootprint footprint, int i, out float weight) {
  const float h = footprint.h;
  if (i == 0) {
    if (!(h > 0.0)) {
      weight = 1.0;
      return footprint.st;
    }
    // Node 0 takes half of each neighbouring interval: 1, or e where it is the only node.
    weight = min(h, 1.0) / (2.0 * h);
    return footprint.st;
  }
  const float n = floor(h);
  const float e = h - n;
  const int j = (i + 1) / 2;  // 1, 1, 2, 2, ...
  const float side = (i % 2 == 1) ? 1.0 : -1.0;
  float node, half_weight;
  if (float(j) <= n) {
    node = float(j);
    half_weight = float(j) < n ? 1.0 : 0.5 * (1.0 + e);
  } else {
    node = h;
    half_weight = 0.5 * e;
  }
  weight = half_weight / (2.0 * h);
  return footprint.st + side * node * footprint.along;
}

// The sky map's radiance at u, filtered over the footprint spanned by the gradients du_dx, du_dy
// (in u units): eq. 27's anisotropic fetch.
vec3 SkyMapRadianceGrad(vec2 u, vec2 du_dx, vec2 du_dy) {
  const SkyMapFootprint footprint =
      SkyMapFilterFootprint(u, du_dx, du_dy, float(textureSize(sky_map, 0).x));
  vec3 sum = vec3(0.0);
  const int taps = SkyMapTapCount(footprint);
  for (int i = 0; i < taps; ++i) {
    float weight;
    const vec2 st = SkyMapTap(footprint, i, weight);
    sum += weight * textureLod(sky_map, st, footprint.lod).rgb;
  }
  return sum;
}

vec3 SkyMapRadianceLod(vec2 u, float lod) {
  return textureLod(sky_map, u * (0.5 / SKY_MAP_EXTENT) + 0.5, lod).rgb;
}

#ifdef SKY_MAP_ARRAY
// The sun-zenith-indexed array of sky maps for views from space (SkyProvider::sky_map_array;
// defined by the shader that reads it, bound by the provider's bind() once built). Bruneton,
// Neyret & Holzschuch 2010, sec. 6 ("planet-scale rendering"): each point of the sea is lit with
// the sky map of its own local sun zenith angle. Layer k holds the map of
// sky_provider.glsl's layout seen from the sea surface with the sun at azimuth 0 (north, +t) and
// the zenith angle of layer k; the layers are spaced piecewise-linearly in sun zenith
// (SkyMapSettings): SKY_MAP_ARRAY_KNEE_LAYER intervals up to SKY_MAP_ARRAY_KNEE_ZENITH, the rest
// up to SKY_MAP_ARRAY_MAX_ZENITH (rad), SKY_MAP_ARRAY_LAYERS layers in all (float literals, from
// the provider's defines()). Mipmapped, isotropic sampler, like sky_map.
layout(binding = SKY_MAP_ARRAY_BINDING) uniform sampler2DArray sky_map_array;

// Radiance (W m^-2 sr^-1 nm^-1) a texel of the array is read as at least, so that the logarithms
// of the geometric interpolation stay finite (no -inf, no NaN) where a texel is 0, as in a black
// photograph. Far below any sky: the darkest texel of the atmosphere's array (the sun 102
// degrees from the zenith) is 1.6e-9, the day's 1e-3 to 0.15 (measured, 64 x 64 layers).
const float SKY_MAP_ARRAY_MIN_RADIANCE = 1e-30;

// The fractional layer, clamped to [0, SKY_MAP_ARRAY_LAYERS - 1], of the sun zenith angle whose
// cosine is cos_sun_zenith (dimensionless; clamped to [-1, 1]): the piecewise-linear mapping of
// sky_map_array_layer() in C++. acos is accurate to about 1e-4 rad on llvmpipe (1.6e-4 at worst,
// measured in tests/gpu/sky_provider_test.cpp): under 0.01 of a 1.1-degree twilight layer, far
// below the interpolation's own error, and enough for a layer index.
float SkyMapArrayLayer(float cos_sun_zenith) {
  const float zenith = acos(clamp(cos_sun_zenith, -1.0, 1.0));  // rad
  const float last = SKY_MAP_ARRAY_LAYERS - 1.0;
  const float layer =
      zenith <= SKY_MAP_ARRAY_KNEE_ZENITH
          ? SKY_MAP_ARRAY_KNEE_LAYER * zenith / SKY_MAP_ARRAY_KNEE_ZENITH
          : SKY_MAP_ARRAY_KNEE_LAYER + (last - SKY_MAP_ARRAY_KNEE_LAYER) *
                                           (zenith - SKY_MAP_ARRAY_KNEE_ZENITH) /
                                           (SKY_MAP_ARRAY_MAX_ZENITH - SKY_MAP_ARRAY_KNEE_ZENITH);
  return clamp(layer, 0.0, last);
}

// Eq. 27's anisotropic fetch (SkyMapFilterFootprint) of one layer of the array.
vec3 SkyMapArrayLayerRadiance(SkyMapFootprint footprint, float layer) {
  vec3 sum = vec3(0.0);
  const int taps = SkyMapTapCount(footprint);
  for (int i = 0; i < taps; ++i) {
    float weight;
    const vec2 st = SkyMapTap(footprint, i, weight);
    sum += weight * textureLod(sky_map_array, vec3(st, layer), footprint.lod).rgb;
  }
  return sum;
}

// The array's radiance at u (stereographic, u = (r_x, r_y) / (1 + r_z) in a frame where the sun
// is at azimuth 0, +y; SKY_MAP_EXTENT scaling as SkyMapRadianceGrad) filtered over the footprint
// of du_dx, du_dy (u units), at the fractional `layer` (SkyMapArrayLayer; clamped to the array).
// Between layers k = floor(layer) and k + 1 the two filtered radiances are interpolated
// geometrically, channel by channel, L_k (L_k+1 / L_k)^f with f = layer - k: the twilight sky
// falls exponentially with the sun's depression, which a linear mix overestimates by up to 5x at
// a 3.3-degree spacing (the error left is in docs/atmosphere.md). What is interpolated is the two
// layers' filtered radiances (one logarithm per layer and channel, not one per tap): where the
// footprint is one texel this is the texel-by-texel interpolation that docs/atmosphere.md
// measures; over a wider footprint it is the geometric mean of two averages, not the average of
// geometric means. Written from the nearer layer, L_k 2^(f d) or L_k+1 2^((f - 1) d) with
// d = log2(L_k+1) - log2(L_k): an integer layer returns its layer's fetch exactly, and the
// exponent stays within half of d (at most 114), so no finite texels can overflow it.
vec3 SkyMapArrayRadianceGrad(vec2 u, vec2 du_dx, vec2 du_dy, float layer) {
  const SkyMapFootprint footprint =
      SkyMapFilterFootprint(u, du_dx, du_dy, float(textureSize(sky_map_array, 0).x));
  const float last = SKY_MAP_ARRAY_LAYERS - 1.0;
  const float clamped = clamp(layer, 0.0, last);
  const float k = floor(clamped);
  const float f = clamped - k;
  const vec3 low = max(SkyMapArrayLayerRadiance(footprint, k), vec3(SKY_MAP_ARRAY_MIN_RADIANCE));
  const vec3 high = max(SkyMapArrayLayerRadiance(footprint, min(k + 1.0, last)),
                        vec3(SKY_MAP_ARRAY_MIN_RADIANCE));
  const vec3 d = log2(high) - log2(low);
  return f <= 0.5 ? low * exp2(f * d) : high * exp2((f - 1.0) * d);
}
#endif  // SKY_MAP_ARRAY

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
vec3 SkySunAndSkyIrradiance(vec3 point, vec3 normal, vec3 sun_direction, out vec3 sky_irradiance) {
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
