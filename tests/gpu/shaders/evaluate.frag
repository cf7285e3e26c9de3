// Evaluates one shared GLSL function per pixel, for comparison with its double-precision C++
// reference (tests/gpu/reference_test.cpp). Inputs come from a float texture, exactly as the
// CPU sees them: texel (x, y) holds the unit view direction (xyz) for that pixel.
#include "common/definitions.glsl"
#include "atmosphere/analytic_sky.glsl"
#include "ocean/flat_sea.glsl"
#include "ocean/ross_brdf.glsl"

layout(binding = 0) uniform sampler2D inputs;
uniform vec3 sun_dir;      // unit, east-north-up
uniform float wind_speed;  // m/s
uniform vec3 deep_reflectance;
uniform vec3 horizontal_irradiance;
uniform vec2 slope_variance;  // (sigma_x^2, sigma_y^2), tangent frame
layout(location = 0) out vec4 result;

void main() {
  const vec3 v = texelFetch(inputs, ivec2(gl_FragCoord.xy), 0).xyz;
#if FUNCTION == 1
  result = vec4(AnalyticSkyRadiance(v, sun_dir), 1.0);
#elif FUNCTION == 2
  result = vec4(AnalyticSunDiscRadiance(v, sun_dir), 1.0);
#elif FUNCTION == 3
  result = vec4(FlatSeaGlintFactor(v, sun_dir, FlatSeaSlopeVariance(wind_speed)),
                FlatSeaFresnel(v.z), 0.0, 1.0);
#elif FUNCTION == 5
  // The Ross BRDF's sun term (eq. 15), the effective Fresnel (eq. 26) and Smith's Lambda.
  result = vec4(OceanReflectedSun(v, sun_dir, slope_variance, 0.02),
                OceanEffectiveFresnel(v.z, OceanSlopeVarianceToward(v, slope_variance), 0.02),
                OceanSmithLambdaToward(v, slope_variance), 1.0);
#elif FUNCTION == 4
  result = vec4(FlatSeaRadianceWithIrradiance(v, sun_dir, wind_speed, deep_reflectance,
                                              horizontal_irradiance), 1.0);
#endif
}
