// The sea's effective Fresnel reflectance F-bar (Bruneton, Neyret & Holzschuch 2010, sec. 5.2) as
// the scene chose it (ocean.effective_fresnel): the paper's fit eq. 26 (OceanEffectiveFresnel,
// ocean/ross_brdf.glsl) of sigma_v^2 (eq. 25) by default, or with EFFECTIVE_FRESNEL_TABLE eq. 24
// itself, integrated in double on the CPU (ocean/effective_fresnel.hpp) and read bilinearly from
// a table, of the slope variances along and across the view (docs/ocean_fresnel.md has both
// errors). With SKY_LOBE_FRESNEL_WEIGHTED (ocean.sky_lobe_centre = "fresnel_weighted") the same
// table gives the slope on which the reflected sky's lobe is centred. Needs ocean/ross_brdf.glsl.
#ifndef THALASSA_OCEAN_EFFECTIVE_FRESNEL_GLSL
#define THALASSA_OCEAN_EFFECTIVE_FRESNEL_GLSL

#if defined(EFFECTIVE_FRESNEL_TABLE) || defined(SKY_LOBE_FRESNEL_WEIGHTED)
// Texture unit of the table (ocean::kEffectiveFresnelUnit): the visible facets' mean Schlick
// factor I, dI/d(variance across the view), their mean slope toward the view and the same
// weighted by the Schlick factor (dimensionless), at the samples of
// OceanEffectiveFresnelTablePosition.
layout(binding = 13) uniform sampler2D effective_fresnel_table;

vec4 OceanEffectiveFresnelTableSample(float cos_theta_v, float along) {
  const vec2 size = vec2(OCEAN_EFFECTIVE_FRESNEL_TABLE_COS_SIZE,
                         OCEAN_EFFECTIVE_FRESNEL_TABLE_SIGMA_SIZE);
  const vec2 uv = (OceanEffectiveFresnelTablePosition(cos_theta_v, along) + 0.5) / size;
  return textureLod(effective_fresnel_table, uv, 0.0);
}
#endif

// F-bar (dimensionless) for the unit view v_t (toward the eye, tangent frame: x along the wind),
// the slope variances (along, across the wind) and Schlick's R = fresnel_r; and in lobe_centre the
// slope (tangent frame) on which the reflected sky's lobe is centred: 0 (eq. 27: the mirror
// direction of the mean normal), or with SKY_LOBE_FRESNEL_WEIGHTED the visible facets'
// Fresnel-weighted mean slope (OceanFresnelWeightedMeanSlope) along the view's azimuth. Both from
// one eq. 25 and one fetch of the table.
float OceanSceneEffectiveFresnel(vec3 v_t, vec2 slope_variance, float fresnel_r,
                                 out vec2 lobe_centre) {
  const float along = OceanSlopeVarianceToward(v_t, slope_variance);
  lobe_centre = vec2(0.0);
#if defined(EFFECTIVE_FRESNEL_TABLE) || defined(SKY_LOBE_FRESNEL_WEIGHTED)
  const vec4 table = OceanEffectiveFresnelTableSample(v_t.z, along);
#endif
#ifdef SKY_LOBE_FRESNEL_WEIGHTED
  const float horizontal = length(vec2(v_t.x, v_t.y));
  if (horizontal > 0.0) {
    lobe_centre = OceanFresnelWeightedMeanSlope(table, horizontal, fresnel_r) *
                  vec2(v_t.x, v_t.y) / horizontal;
  }
#endif
#ifdef EFFECTIVE_FRESNEL_TABLE
  const vec2 s2 = OceanClampedSlopeVariance(slope_variance);
  const float across = max(s2.x + s2.y - along, 0.0);  // eq. 25's complement
  return OceanEffectiveFresnelFromTable(table.xy, along, across, fresnel_r);
#else
  return OceanEffectiveFresnel(v_t.z, along, fresnel_r);
#endif
}

#endif  // THALASSA_OCEAN_EFFECTIVE_FRESNEL_GLSL
