// Evaluates the ocean's shared GLSL functions in float over the stiff sweeps of
// tests/gpu/numerics_test.cpp, one input per pixel, for comparison with their double-precision
// C++ references (the same source compiled as C++). Texel (x, y) of `inputs` holds the four
// inputs of the pixel (exactly the floats the CPU reference is given); uniforms hold what is
// common to a sweep (a light direction, slope variances, a tangent frame), also as floats.
#include "common/definitions.glsl"
#include "ocean/ross_brdf.glsl"
#if FUNCTION == 12
#define EFFECTIVE_FRESNEL_TABLE 1
#define SKY_LOBE_FRESNEL_WEIGHTED 1
#endif
#include "ocean/effective_fresnel.glsl"
#include "ocean/trochoids.glsl"
#include "atmosphere/model.glsl"

layout(binding = 0) uniform sampler2D inputs;
uniform vec3 light;           // unit, tangent frame (FUNCTION 4)
uniform vec2 slope_variance;  // (sigma_x^2, sigma_y^2), tangent frame (FUNCTION 4)
uniform vec3 frame_x;         // t_x, t_y, n: the tangent frame in the sky map's frame
uniform vec3 frame_y;         // (FUNCTION 7 and 8)
uniform vec3 frame_n;
uniform vec3 dr;              // a direction derivative (FUNCTION 6)
uniform vec2 radii;           // bottom and top radius of the atmosphere, m (FUNCTION 9, 10)
uniform vec2 wave_vector;     // rad/m, one wave's k (FUNCTION 11)
uniform float wave_phase;     // rad, its wrapped phase (FUNCTION 11)
uniform vec2 step;            // m, an offset between two nearby points (FUNCTION 11)
layout(location = 0) out vec4 result;

void main() {
  const vec4 p = texelFetch(inputs, ivec2(gl_FragCoord.xy), 0);
#if FUNCTION == 1
  // Smith's Lambda(a), a = p.x.
  result = vec4(OceanSmithLambda(p.x), 0.0, 0.0, 0.0);
#elif FUNCTION == 2
  // cos theta Lambda and the facing area, cos theta = p.x, sigma_sin = p.y.
  result = vec4(OceanSmithCosLambda(p.x, p.y), OceanSmithFacingArea(p.x, p.y), 0.0, 0.0);
#elif FUNCTION == 3
  // The trochoid's slope variance 1 - sqrt(1 - s^2), s = p.x.
  result = vec4(TrochoidSlopeVariance(p.x), 0.0, 0.0, 0.0);
#elif FUNCTION == 4
  // The reflected sun (eq. 15) and the BRDF (eq. 13), v = p.xyz.
  const vec3 v = vec3(p.x, p.y, p.z);
  result = vec4(OceanReflectedSun(v, light, slope_variance, 0.02),
                OceanRossBrdf(v, light, slope_variance, 0.02), 0.0, 0.0);
#elif FUNCTION == 5
  // The effective Fresnel (eq. 26) and Schlick's (eq. 14), cos theta_v = p.x, sigma_v^2 = p.y.
  result = vec4(OceanEffectiveFresnel(p.x, p.y, 0.02), OceanSchlickFresnel(p.x, 0.02), 0.0, 0.0);
#elif FUNCTION == 6
  // The stereographic mapping and its derivative along dr, r = p.xyz.
  const vec3 r = vec3(p.x, p.y, p.z);
  const vec2 u = OceanStereographic(r);
  const vec2 du = OceanStereographicDerivative(r, dr);
  result = vec4(u.x, u.y, du.x, du.y);
#elif FUNCTION == 7 || FUNCTION == 8
  // Algorithm 5.1's sky-map coordinates u0 and their derivatives (7: u0 and du/dzeta_x, 8:
  // du/dzeta_y), v = p.xyz, the reflected ray computed in float.
  const vec3 v = vec3(p.x, p.y, p.z);
  vec2 u0;
  vec2 du_x;
  vec2 du_y;
  OceanSkyMapGradients(v, frame_x, frame_y, frame_n, u0, du_x, du_y);
#if FUNCTION == 7
  result = vec4(u0.x, u0.y, du_x.x, du_x.y);
#else
  result = vec4(du_y.x, du_y.y, 0.0, 0.0);
#endif
#elif FUNCTION == 9 || FUNCTION == 10
  // The atmosphere's ray-sphere distances (m) from radius r = p.x (m) along cosine mu = p.y.
  AtmosphereParameters atmosphere;
  atmosphere.bottom_radius = radii.x;
  atmosphere.top_radius = radii.y;
  const float r = p.x;
  const float mu = p.y;
#if FUNCTION == 9
  // model.glsl's: distance to the top, to the ground, the transmittance table's u, and whether
  // the ray hits the ground (1 or 0).
  result = vec4(DistanceToTopAtmosphereBoundary(atmosphere, r, mu),
                DistanceToBottomAtmosphereBoundary(atmosphere, r, mu),
                GetTransmittanceTextureUvFromRMu(atmosphere, r, mu).x,
                RayIntersectsGround(atmosphere, r, mu) ? 1.0 : 0.0);
#else
  // The forms before the product-of-roots rewrite, for comparison: -r mu +- sqrt(disc).
  result = vec4(max(-r * mu + SafeSqrt(SphereDiscriminant(r, mu, radii.y)), 0.0),
                max(-r * mu - SafeSqrt(SphereDiscriminant(r, mu, radii.x)), 0.0), 0.0, 0.0);
#endif
#elif FUNCTION == 11
  // sin of one wave's argument at origin o = p.xy plus local l = p.zw and at l + step:
  // TrochoidArgumentFrom's (the reference's lattice) and TrochoidArgument's at o + l in float.
  const vec2 o = vec2(p.x, p.y);
  const vec2 l = vec2(p.z, p.w);
  result = vec4(sin(TrochoidArgumentFrom(wave_vector, wave_phase, o, l)),
                sin(TrochoidArgumentFrom(wave_vector, wave_phase, o, l + step)),
                sin(TrochoidArgument(wave_vector, wave_phase, o + l)),
                sin(TrochoidArgument(wave_vector, wave_phase, o + l + step)));
#elif FUNCTION == 12
  // F-bar from eq. 24's table (ocean.effective_fresnel = "table"), v = (sqrt(1 - p.x^2), 0, p.x)
  // in the tangent frame (toward the wind: along = p.y, across = p.z).
  const vec3 v = vec3(sqrt(max(1.0 - p.x * p.x, 0.0)), 0.0, p.x);
  vec2 lobe_centre;
  const float fresnel = OceanSceneEffectiveFresnel(v, vec2(p.y, p.z), 0.02, lobe_centre);
  result = vec4(fresnel, lobe_centre, 0.0);
#endif
}
