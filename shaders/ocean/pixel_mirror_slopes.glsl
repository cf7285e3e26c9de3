// The sun's mirror slopes at the edges of a pixel, for OceanReflectedSunOverPixel
// (ocean/ross_brdf.glsl): eq. 15 averaged over the pixel. Used by the lighting pass of every
// method but the reference (ocean/ocean_lighting.frag) and by the view from space
// (planet/ocean_space.frag), so that the two agree at the hand-over. GLSL only (common/frame.glsl); the CPU tests give
// OceanReflectedSunOverPixel the same edges' slopes through OceanHalfVectorSlopes.
//
// Frames and units: the nadir frame of common/frame.glsl; slopes dimensionless, in the tangent
// frame (t_x, t_y, n) of the pixel's centre (Algorithm 5.1's).
#ifndef THALASSA_OCEAN_PIXEL_MIRROR_SLOPES_GLSL
#define THALASSA_OCEAN_PIXEL_MIRROR_SLOPES_GLSL

// The slopes of the facet that mirrors `l` (unit, toward the sun, tangent frame) into the eye
// along the view ray through frag_coord (pixels), relative to the sea at rest where that ray meets
// it: OceanHalfVectorSlopes of the ray's reversed direction and l, less the slopes of the rest
// surface's normal there, to first order in the angle between that normal and the centre's (the planet's curvature turns
// it across a far pixel's footprint: 1.6e-4 rad a kilometre). A ray that misses the sea (the
// horizon's pixel, the limb) takes the centre's rest normal `up`.
vec2 OceanEdgeMirrorSlopes(vec2 frag_coord, vec3 t_x, vec3 t_y, vec3 n, vec3 up, vec3 l) {
  const vec3 ray = FrameViewRay(frag_coord);
  const float distance = FrameSeaDistance(ray);
  const vec3 rest_up =
      distance >= 0.0 ? FrameSeaNormal(FrameCameraPosition() + distance * ray) : up;
  const vec3 u = OceanToTangentFrame(rest_up, t_x, t_y, n);
  return OceanHalfVectorSlopes(OceanToTangentFrame(-ray, t_x, t_y, n), l) +
         vec2(u.x, u.y) / max(u.z, OCEAN_MIN_FACET_COS);
}

// OceanReflectedSunOverPixel for the pixel whose centre is frag_coord (gl_FragCoord.xy), v and
// l the directions toward the eye through the centre and toward the sun, in the tangent frame
// (t_x, t_y, n). The mirror slopes' changes across the pixel are
// taken between the middles of its opposite edges from exact directions (FrameViewRay), not
// screen-space derivatives, which a deferred pass cannot take across the sea's edge.
Number OceanSunOverPixel(vec2 frag_coord, vec3 t_x, vec3 t_y, vec3 n, vec3 up, vec3 v, vec3 l,
                         vec2 slope_variance, float fresnel_r) {
  const vec2 zeta_dx = OceanEdgeMirrorSlopes(frag_coord + vec2(0.5, 0.0), t_x, t_y, n, up, l) -
                       OceanEdgeMirrorSlopes(frag_coord - vec2(0.5, 0.0), t_x, t_y, n, up, l);
  const vec2 zeta_dy = OceanEdgeMirrorSlopes(frag_coord + vec2(0.0, 0.5), t_x, t_y, n, up, l) -
                       OceanEdgeMirrorSlopes(frag_coord - vec2(0.0, 0.5), t_x, t_y, n, up, l);
  return OceanReflectedSunOverPixel(v, l, slope_variance, fresnel_r, zeta_dx, zeta_dy);
}

#endif  // THALASSA_OCEAN_PIXEL_MIRROR_SLOPES_GLSL
