// The reflected sky from the provider's sun-zenith-indexed array (Bruneton et al. 2010, sec. 6:
// "each point is then lit with the 2D map corresponding to the local Sun elevation"): eq. 27's
// filtered fetch in the array's map of the point's own sun zenith, in the frame whose north is
// the sun's azimuth at the point (the layers have the sun at azimuth 0). Shared by the view from
// space (planet/ocean_space.frag) and by the projected grid as it hands over to it
// (ocean/ocean_lighting.frag above kResolvedFadeStart). Needs atmosphere/sky_provider.glsl and
// ocean/ross_brdf.glsl; OceanSkyArrayReflection exists only with SKY_MAP_ARRAY (the array's
// lookup in sky_provider.glsl), so that a shader without the sky term (and without the array,
// which is then not built) can still use OceanTangentToward.
#ifndef THALASSA_OCEAN_SKY_ARRAY_REFLECTION_GLSL
#define THALASSA_OCEAN_SKY_ARRAY_REFLECTION_GLSL

// A unit vector perpendicular to the unit vector n, as close to `preferred` as it can be: the
// component of `preferred` in the plane, or (where `preferred` is along n) one of `fallback`.
vec3 OceanTangentToward(vec3 n, vec3 preferred, vec3 fallback) {
  vec3 t = preferred - dot(preferred, n) * n;
  if (dot(t, t) < 1e-8) t = fallback - dot(fallback, n) * n;
  if (dot(t, t) < 1e-8)
    t = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) - n.x * n : vec3(0.0, 1.0, 0.0) - n.y * n;
  return normalize(t);
}

#ifdef SKY_MAP_ARRAY
// up: the sea's normal at rest at the point (its local vertical); v toward the eye; t_x, t_y, n
// the shading tangent frame (Algorithm 5.1); sigma the slope standard deviations along t_x, t_y;
// sun toward the sun. All unit vectors in one frame (the nadir frame). With
// SKY_LOBE_FRESNEL_WEIGHTED the lobe is centred on the slope `centre` (along t_x, t_y;
// ocean/effective_fresnel.glsl, OceanSceneEffectiveFresnel) instead of the mean normal's mirror
// direction.
vec3 OceanSkyArrayReflection(vec3 up, vec3 v, vec3 t_x, vec3 t_y, vec3 n, vec2 centre, vec2 sigma,
                             vec3 sun) {
  const vec3 map_north = OceanTangentToward(up, sun, t_x);
  const vec3 map_east = cross(map_north, up);
  const mat3 to_map = transpose(mat3(map_east, map_north, up));
  vec2 u0, du_x, du_y;
  OceanSkyMapGradients(to_map * v, to_map * t_x, to_map * t_y, to_map * n, u0, du_x, du_y);
#ifdef SKY_LOBE_FRESNEL_WEIGHTED
  u0 += centre.x * du_x + centre.y * du_y;
#endif
  return SkyMapArrayRadianceGrad(u0, 2.0 * sigma.x * du_x, 2.0 * sigma.y * du_y,
                                 SkyMapArrayLayer(dot(up, sun)));
}
#endif  // SKY_MAP_ARRAY
#endif
