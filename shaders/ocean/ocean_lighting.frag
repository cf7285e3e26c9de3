// The ocean's second pass (Bruneton, Neyret & Holzschuch 2010, sec. 4-5, Algorithm 5.1; the
// paper's sec. 7.3 times it as "lighting"): from the G-buffer of ocean_geometry.frag (normal,
// unresolved slope variance), the sun (eq. 15), the sky (eq. 21 with the effective Fresnel of
// eq. 26 and the filtered sky-map fetch of eq. 27) and the refracted light (eq. 28), all from
// the sky provider (atmosphere/sky_provider.glsl), then the aerial perspective between the
// camera and the sea. SUN_GLINT, SKY_TERM, SEA_TERM and AIR_TERM (the in-scattered light) select
// the terms (validation renders them one by one); SKY_NINE_SAMPLES replaces eq. 27's single
// anisotropic fetch with the average of nine samples inside the filter's support that the paper
// mentions (sec. 7.2); SKY_SHRM replaces it with a lookup in sky maps prefiltered in frequency
// space (Ramamoorthi & Hanrahan 2002; atmosphere/sky_shrm.glsl). EFFECTIVE_FRESNEL_TABLE reads
// eq. 24 from a table for eq. 26, SKY_LOBE_FRESNEL_WEIGHTED centres eq. 27's lobe on the visible
// facets' Fresnel-weighted mean slope (ocean/effective_fresnel.glsl). With UNDERWATER
// (a camera below the surface) the water body's light fills the view and no G-buffer is read.
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "atmosphere/sky_provider.glsl"
#include "ocean/ross_brdf.glsl"
#include "ocean/effective_fresnel.glsl"
#include "ocean/sea_point_light.glsl"
#include "ocean/pixel_mirror_slopes.glsl"
#ifdef SKY_SHRM
#include "atmosphere/sky_shrm.glsl"
#endif
#ifdef SKY_MAP_ARRAY
#include "ocean/sky_array_reflection.glsl"
// Weight of the sky from the sun-zenith array against the nadir's single map, 0 to 1 as the
// camera rises through the hand-over to the view from space (1 - resolved_wave_scale,
// ocean/gl/ocean_node.hpp): at 20 km the grid reflects the sky exactly as the view from space.
uniform float sky_array_weight;
#endif

layout(location = 0) out vec4 radiance;  // W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm

layout(binding = 0) uniform sampler2D normals;    // xyz normal, w coverage (ocean_geometry)
// xy slope variance along, across the wind (METHOD_REFERENCE: see ocean_geometry.frag)
layout(binding = 1) uniform sampler2D variances;
#ifdef METHOD_REFERENCE
// The reference's sea samples write |alpha| = this + their weight >= 0; every other pass writes
// alpha 1 (planet/src/renderer.cpp, kReferenceSeaAlpha, reads it).
const float REFERENCE_SEA_ALPHA = 2.0;
#endif
#ifdef REFERENCE_SUN_SCATTER
// The reference's scattered sun, 4 floats per pixel (row-major from the bottom row) summed over
// the sea's lattice by ocean/reference_sun_scatter.comp: sum omega sun, sum omega, the
// unresolved part of sum omega, the hidden solid angle.
layout(std430, binding = 7) readonly buffer ReferenceSunSums { float reference_sun[]; };
#endif
uniform vec2 downwind;                // unit, east-north-up
uniform float fresnel_r;              // R of Schlick's Fresnel (eq. 14)
uniform vec3 deep_reflectance;        // irradiance reflectance of the water body, per channel
// Sun + sky on a horizontal surface at sea level under the nadir: the water body's light seen
// from below the surface, and with SKY_SHRM the irradiance of its SH sky (elsewhere each point
// has its own, ocean/sea_point_light.glsl).
uniform vec3 horizontal_irradiance;
uniform float horizon_distance;       // m: the sea's horizon, for rays that miss its rest shape

// Eq. 22 by a 3 x 3 Gauss-Hermite rule in slope space: p is a Gaussian of standard deviations
// sigma_x, sigma_y, and the 3-point rule (nodes 0, +-sqrt(3) sigma; weights 2/3, 1/6, 1/6) is
// exact for its average of polynomials up to degree 5. Each node reads the map at its exact
// u(v, zeta) (OceanSkyMapCoordinates, not the linearisation eq. 27 assumes) with a footprint of
// one sigma, so that the nodes' footprints together cover the kernel.
vec3 SkyNineSamples(vec3 v, vec3 t_x, vec3 t_y, vec3 n, vec2 centre, vec2 sigma, vec2 du_x,
                    vec2 du_y) {
  const float node = sqrt(3.0);
  const float weights[3] = float[3](1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0);
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      vec2 zeta = centre + vec2(float(i - 1), float(j - 1)) * node * sigma;
      vec2 u = OceanSkyMapCoordinates(v, t_x, t_y, n, zeta);
      sum += weights[i] * weights[j] * SkyMapRadianceGrad(u, sigma.x * du_x, sigma.y * du_y);
    }
  }
  return sum;
}

void main() {
#ifdef UNDERWATER
#ifdef SEA_TERM
  radiance = vec4(OceanDeepRadiance(deep_reflectance, horizontal_irradiance), 1.0);
#else
  radiance = vec4(0.0, 0.0, 0.0, 1.0);
#endif
#else
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 normal = texelFetch(normals, pixel, 0);
  if (normal.w == 0.0) discard;  // not the sea: the sky pass's pixel
  const vec3 n = vec3(normal.x, normal.y, normal.z);
  const vec4 variance = texelFetch(variances, pixel, 0);
#ifdef METHOD_REFERENCE
  // A mirror; the channels hold the sample's weight, the sun and whether it was resolved
  // (ocean_geometry.frag).
  const vec2 slope_variance = vec2(0.0);
#else
  const vec2 slope_variance = vec2(variance.x, variance.y);
#endif
  const vec3 ray = FrameViewRay(gl_FragCoord.xy);
  const vec3 v = -ray;  // toward the eye
  const vec3 wind = vec3(downwind, 0.0);
  const vec3 t_x = normalize(wind - dot(wind, n) * n);
  const vec3 t_y = cross(n, t_x);
  const vec3 v_t = OceanToTangentFrame(v, t_x, t_y, n);
  const vec3 sun = FrameSunDirection();

  // The pixel's point of the sea at rest (a ray over a crest that misses it: the horizon's
  // distance), moved radially onto the atmosphere's sphere for its lookups (the planet's quadric
  // and that sphere part by at most ~0.1 km within a surface view's horizon).
  const float rest_distance = FrameSeaDistance(ray);
  const vec3 point = FrameCameraPosition() +
                     (rest_distance >= 0.0 ? rest_distance : horizon_distance) * ray;
  // The sun, the irradiance and the atmosphere at the point itself: across a view from 20 km the
  // local sun zenith changes by up to 9 degrees, as it does from one pixel to the next in the
  // view from space.
  const vec3 up = FrameSeaNormal(point);
  OceanPointLight light = OceanLightAtPoint(point, up, sun);
#ifdef SKY_SHRM
  // The SH sky's own irradiance, so that the reflected and the refracted sky are one sky; through
  // the hand-over to the view from space, toward the point's own as the sky's reflection goes to
  // the array's (below).
#ifdef SKY_MAP_ARRAY
  light.irradiance = mix(horizontal_irradiance, light.irradiance, sky_array_weight);
#else
  light.irradiance = horizontal_irradiance;
#endif
#endif

  // Sky (eq. 21, 26 or 24, 27) and refracted light (eq. 28); the sky lobe's centre in slope
  // space: 0 (eq. 27), or with ocean.sky_lobe_centre = "fresnel_weighted" the visible facets'
  // Fresnel-weighted mean slope.
  vec2 centre;
  const float fresnel = OceanSceneEffectiveFresnel(v_t, slope_variance, fresnel_r, centre);
  vec3 sea = vec3(0.0);
#ifdef SKY_TERM
  const vec2 clamped_variance = OceanClampedSlopeVariance(slope_variance);
  const vec2 sigma = sqrt(clamped_variance);
#ifdef SKY_SHRM
  // Eq. 21 with L-bar (eq. 22) from the SHRM-prefiltered maps, read by the mirror direction of
  // the mean normal. Two approximations (docs/spherical_harmonics.md): the slope density is made
  // isotropic with the geometric mean of the two variances (the same p(0) and ellipse area), and
  // the kernel is eq. 22's at normal view, radially symmetric about the mirror direction (P = 0),
  // so the narrowing of the lobe across the plane of incidence at grazing views (by cos theta_v)
  // is not represented. Fresnel stays outside, as eq. 26's effective Fresnel: a Fresnel-weighted
  // Ross BRDF needs a high view order P in SH (sh_brdf_test.cpp). The lobe's centre moves as
  // eq. 27's does: to the mirror direction of the facet whose slope is the centre (tangent frame;
  // the normal of slope zeta is n - zeta_x t_x - zeta_y t_y before normalising, the derivative
  // that OceanSkyMapGradients takes), exactly rather than to first order in the map.
#ifdef SKY_LOBE_FRESNEL_WEIGHTED
  const vec3 lobe_normal = normalize(n - centre.x * t_x - centre.y * t_y);
#else
  const vec3 lobe_normal = n;
#endif
  vec3 sky =
      SkyShrmRadiance(reflect(ray, lobe_normal), sqrt(clamped_variance.x * clamped_variance.y));
#else
  vec2 u0, du_x, du_y;
  OceanSkyMapGradients(v, t_x, t_y, n, u0, du_x, du_y);
#ifdef SKY_LOBE_FRESNEL_WEIGHTED
  u0 += centre.x * du_x + centre.y * du_y;
#endif
#ifdef SKY_NINE_SAMPLES
  vec3 sky = SkyNineSamples(v, t_x, t_y, n, centre, sigma, du_x, du_y);
#else
  vec3 sky = SkyMapRadianceGrad(u0, 2.0 * sigma.x * du_x, 2.0 * sigma.y * du_y);
#endif
#endif  // SKY_SHRM
#ifdef SKY_MAP_ARRAY
  // The hand-over to the view from space, whatever the filter: from 20 km the grid reflects the
  // sky as the view from space does (shrm kept its maps to the switch until stop 39, and the sky's
  // rows jumped by up to 28 % there).
  sky = mix(sky, OceanSkyArrayReflection(up, v, t_x, t_y, n, centre, sigma, sun),
            sky_array_weight);
#endif
  sea += fresnel * sky;
#endif
#ifdef SEA_TERM
  sea += (1.0 - fresnel) * OceanDeepRadiance(deep_reflectance, light.irradiance);
#endif
#ifdef SUN_GLINT
  // Sun (eq. 15): L_sun Omega_sun is the transmitted sun's irradiance on a surface facing it.
#if defined(REFERENCE_SUN_SCATTER)
  // The reference's scattered sun: the solid-angle weighted mean over the sea the pixel sees
  // (ocean/reference_sun_scatter.comp), the same for all the pixel's samples.
  const int sun_index = 4 * (pixel.y * int(frame_viewport.x) + pixel.x);
  const float sun_omega = reference_sun[sun_index + 1];
  sea += light.sun_irradiance * (sun_omega > 0.0 ? reference_sun[sun_index] / sun_omega : 0.0);
  // Resolved where at most half the pixel's sea came from footprints over the cell cap; a pixel
  // no cell landed in is not.
  const bool sun_resolved = sun_omega > 0.0 && reference_sun[sun_index + 2] <= 0.5 * sun_omega;
#elif defined(REFERENCE_SUN)
  // The reference's gathered sun: integrated over the sample's stratum by the first pass
  // (ocean/reference_sun.glsl).
  sea += light.sun_irradiance * variance.z;
#else
  // Eq. 15 averaged over the pixel (ocean/pixel_mirror_slopes.glsl): the lobe of a calm sea, and
  // the mirror's sun disc, can be narrower than the motion of the mirror slope across a pixel.
  // Every method draws its sun so: they differ in the waves they resolve, not in how a pixel
  // integrates its light.
  sea += light.sun_irradiance * OceanSunOverPixel(gl_FragCoord.xy, t_x, t_y, n, up, v_t,
                                                  OceanToTangentFrame(sun, t_x, t_y, n),
                                                  slope_variance, fresnel_r);
#endif
#endif

  // Aerial perspective to the point.
  vec3 transmittance;
  vec3 in_scattered = SkyAerialPerspective(light.camera, light.ground, sun, transmittance);
#ifndef AIR_TERM
  in_scattered = vec3(0.0);
#endif
#ifdef METHOD_REFERENCE
  // Alpha tells the reference's sea samples from the sky's (alpha 1): |alpha| = 2 + the sample's
  // visible-area weight, negative where the reference's sun did not resolve every wave. The
  // Renderer's draw_reference averages each pixel's sea samples with these weights, turns the
  // signs into each row's resolved fraction and restores alpha to 1.
  const float sample_code = REFERENCE_SEA_ALPHA + variance.x;
#ifdef REFERENCE_SUN_SCATTER
  const bool resolved = sun_resolved;
#else
  const bool resolved = variance.y > 0.5;
#endif
  radiance = vec4(sea * transmittance + in_scattered, resolved ? sample_code : -sample_code);
#else
  radiance = vec4(sea * transmittance + in_scattered, 1.0);
#endif
#endif
}
