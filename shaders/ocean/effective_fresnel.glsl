// The sea's effective Fresnel reflectance F-bar (Bruneton, Neyret & Holzschuch 2010, sec. 5.2) as
// the scene chose it (ocean.effective_fresnel): the paper's fit eq. 26 (OceanEffectiveFresnel,
// ocean/ross_brdf.glsl) of sigma_v^2 (eq. 25) by default, or with EFFECTIVE_FRESNEL_TABLE eq. 24
// itself, integrated in double on the CPU (ocean/effective_fresnel.hpp) and read bilinearly from
// a table, of the slope variances along and across the view (docs/ocean_fresnel.md has both
// errors). Needs ocean/ross_brdf.glsl.
#ifndef THALASSA_OCEAN_EFFECTIVE_FRESNEL_GLSL
#define THALASSA_OCEAN_EFFECTIVE_FRESNEL_GLSL

#ifdef EFFECTIVE_FRESNEL_TABLE
// Texture unit of the table (ocean::kEffectiveFresnelUnit): rg, the visible facets' mean Schlick
// factor I and dI/d(variance across the view), dimensionless, at the samples of
// OceanEffectiveFresnelTablePosition.
layout(binding = 13) uniform sampler2D effective_fresnel_table;
#endif

// F-bar (dimensionless) for the unit view v_t (toward the eye, tangent frame: x along the wind),
// the slope variances (along, across the wind) and Schlick's R = fresnel_r.
float OceanSceneEffectiveFresnel(vec3 v_t, vec2 slope_variance, float fresnel_r) {
  const float along = OceanSlopeVarianceToward(v_t, slope_variance);
#ifdef EFFECTIVE_FRESNEL_TABLE
  const vec2 s2 = OceanClampedSlopeVariance(slope_variance);
  const float across = max(s2.x + s2.y - along, 0.0);  // eq. 25's complement
  const vec2 size = vec2(OCEAN_EFFECTIVE_FRESNEL_TABLE_COS_SIZE,
                         OCEAN_EFFECTIVE_FRESNEL_TABLE_SIGMA_SIZE);
  const vec2 uv = (OceanEffectiveFresnelTablePosition(v_t.z, along) + 0.5) / size;
  return OceanEffectiveFresnelFromTable(textureLod(effective_fresnel_table, uv, 0.0).rg, along,
                                        across, fresnel_r);
#else
  return OceanEffectiveFresnel(v_t.z, along, fresnel_r);
#endif
}

#endif  // THALASSA_OCEAN_EFFECTIVE_FRESNEL_GLSL
