// The ocean's second pass (Bruneton, Neyret & Holzschuch 2010, sec. 4-5, Algorithm 5.1; the
// paper's sec. 7.3 times it as "lighting"): from the G-buffer of ocean_geometry.frag (normal,
// unresolved slope variance), the sun (eq. 15), the sky (eq. 21 with the effective Fresnel of
// eq. 26) and the refracted light (eq. 28). SUN_GLINT, SKY_TERM and SEA_TERM select the terms
// (validation renders them one by one). With UNDERWATER (a camera below the surface) the water
// body's light fills the view and no G-buffer is read.
//
// Until the sky-map provider exists (issue 4), the sky term reads the analytic sky in the mirror
// direction of the mean normal, unfiltered (eq. 27's filtered fetch needs the map).
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "atmosphere/analytic_sky.glsl"
#include "ocean/ross_brdf.glsl"

layout(location = 0) out vec4 radiance;  // W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm

layout(binding = 0) uniform sampler2D normals;    // xyz normal, w coverage (ocean_geometry)
layout(binding = 1) uniform sampler2D variances;  // xy slope variance along, across the wind
uniform vec2 downwind;                // unit, east-north-up
uniform float fresnel_r;              // R of Schlick's Fresnel (eq. 14)
uniform vec3 deep_reflectance;        // irradiance reflectance of the water body, per channel
uniform vec3 horizontal_irradiance;   // sun + sky on a horizontal surface, W m^-2 nm^-1

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
  const vec2 slope_variance = vec2(variance.x, variance.y);
  const vec3 ray = FrameViewRay(gl_FragCoord.xy);
  const vec3 v = -ray;  // toward the eye
  const vec3 wind = vec3(downwind, 0.0);
  const vec3 t_x = normalize(wind - dot(wind, n) * n);
  const vec3 t_y = cross(n, t_x);
  const vec3 v_t = OceanToTangentFrame(v, t_x, t_y, n);
  const vec3 sun = FrameSunDirection();

  // Sky (eq. 21, 26) and refracted light (eq. 28).
  const float fresnel = OceanEffectiveFresnel(v_t.z, OceanSlopeVarianceToward(v_t, slope_variance),
                                              fresnel_r);
  vec3 mirror = reflect(ray, n);
  if (mirror.z < 0.0) mirror = normalize(vec3(mirror.x, mirror.y, 1e-6));
  vec3 sea = vec3(0.0);
#ifdef SKY_TERM
  sea += fresnel * AnalyticSkyRadiance(mirror, sun);
#endif
#ifdef SEA_TERM
  sea += (1.0 - fresnel) * OceanDeepRadiance(deep_reflectance, horizontal_irradiance);
#endif
#ifdef SUN_GLINT
  // Sun (eq. 15): L_sun Omega_sun is the transmitted sun's irradiance on a surface facing it.
  sea += AnalyticSunTransmittedIrradiance(sun) *
         OceanReflectedSun(v_t, OceanToTangentFrame(sun, t_x, t_y, n), slope_variance, fresnel_r);
#endif
  radiance = vec4(sea, 1.0);
#endif
}
