// The paper's ocean per pixel (Bruneton, Neyret & Holzschuch 2010, sec. 3.2-5), on the projected
// grid of ocean.vert (the sea displaced by the waves longer than a grid cell) in the local
// east-north-up frame at the camera's nadir: each pixel's normal sums the waves longer than the
// pixel at the pixel's rest position (eq. 3 with w_n; not from the filtered positions), the
// shorter ones widen the Ross BRDF (eq. 4, w_r = 1 - w_n), and the sun (eq. 15), the sky (eq. 21
// with the effective Fresnel of eq. 26) and the refracted light (eq. 28) are added as in
// Algorithm 5.1. SUN_GLINT, SKY_TERM and SEA_TERM select the light terms drawn (validation
// renders them one by one). With UNDERWATER (a camera below the surface, full-screen) the water body's light
// fills the view.
//
// Until the sky-map provider exists (issue 4), the sky term reads the analytic sky in the mirror
// direction of the mean normal, unfiltered (eq. 27's filtered fetch needs the map).
#include "common/definitions.glsl"
#include "common/frame.glsl"
#include "atmosphere/analytic_sky.glsl"
#include "ocean/flat_sea.glsl"
#include "ocean/ross_brdf.glsl"
#include "ocean/trochoids.glsl"

layout(location = 0) out vec4 radiance;  // W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm
#ifndef UNDERWATER
in vec2 rest_position;  // m east and north of the camera's nadir (ocean.vert)
#endif

// Two vec4 per wave, longest first: (direction east, direction north, |k| rad/m, h m) and
// (wrapped phase rad, wavelength m, unused, unused). See ocean/src/ocean_node.cpp.
layout(std430, binding = 1) readonly buffer Waves { vec4 waves[]; };
// tails[i] = slope variance (along, across the wind) of the waves j >= i (Appendix A, eq. 4
// with w_r = 1), wave_count + 1 entries, summed on the CPU in double.
layout(std430, binding = 2) readonly buffer Tails { vec2 tails[]; };

uniform int wave_count;
uniform vec2 downwind;                // unit, east-north-up
uniform float n_min;                  // N_min of w_n (sec. 3.2)
uniform float n_max;                  // N_max
uniform float fresnel_r;              // R of Schlick's Fresnel (eq. 14)
uniform vec3 deep_reflectance;        // irradiance reflectance of the water body, per channel
uniform vec3 horizontal_irradiance;   // sun + sky on a horizontal surface, W m^-2 nm^-1

void main() {
#ifdef UNDERWATER
#ifdef SEA_TERM
  radiance = vec4(FlatSeaDeepRadiance(deep_reflectance, horizontal_irradiance), 1.0);
#else
  radiance = vec4(0.0, 0.0, 0.0, 1.0);
#endif
#else
  const vec3 ray = FrameViewRay(gl_FragCoord.xy);
  const vec2 x = rest_position;
  // The pixel's footprint on the sea (m): its larger side, so that no resolved wave aliases.
  const float footprint = max(max(length(dFdx(x)), length(dFdy(x))), 1e-6);

  // Eq. 3 with w_n, and the unresolved variance of eq. 4 with w_r = 1 - w_n: waves are sorted
  // longest first, so w_n falls with the index and the loop ends at the first unresolved wave.
  const vec2 crosswind = vec2(-downwind.y, downwind.x);
  vec3 d_dx = vec3(1.0, 0.0, 0.0);
  vec3 d_dy = vec3(0.0, 1.0, 0.0);
  vec2 partial_variance = vec2(0.0);
  int first_unresolved = wave_count;
  for (int i = 0; i < wave_count; ++i) {
    const vec4 a = waves[2 * i];
    const vec4 b = waves[2 * i + 1];
    const float w_n = WaveFilterWeight(n_min, n_max, b.y / footprint);
    if (w_n <= 0.0) {
      first_unresolved = i;
      break;
    }
    const vec2 direction = vec2(a.x, a.y);
    vec3 wave_dx, wave_dy;
    TrochoidDisplacementDerivatives(direction, a.z, a.w,
                                    TrochoidArgument(a.z * direction, b.x, x), wave_dx, wave_dy);
    d_dx += w_n * wave_dx;
    d_dy += w_n * wave_dy;
    if (w_n < 1.0) {
      const float variance = TrochoidSlopeVariance(a.z * (1.0 - w_n) * a.w);
      const float along = dot(direction, downwind);
      const float across = dot(direction, crosswind);
      partial_variance += variance * vec2(along * along, across * across);
    }
  }
  const vec2 slope_variance = tails[first_unresolved] + partial_variance;

  const vec3 v = -ray;  // toward the eye
  vec3 n = normalize(cross(d_dx, d_dy));
  // Sec. 3.2: a normal facing away from the viewer is reflected back toward it.
  if (dot(n, v) < 0.0) n = normalize(n - 2.0 * dot(n, v) * v);
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
  sea += (1.0 - fresnel) * FlatSeaDeepRadiance(deep_reflectance, horizontal_irradiance);
#endif
#ifdef SUN_GLINT
  // Sun (eq. 15): L_sun Omega_sun is the transmitted sun's irradiance on a surface facing it.
  sea += AnalyticSunTransmittedIrradiance(sun) *
         OceanReflectedSun(v_t, OceanToTangentFrame(sun, t_x, t_y, n), slope_variance, fresnel_r);
#endif
  radiance = vec4(sea, 1.0);
#endif
}
