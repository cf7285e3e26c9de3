// Wakes and calm areas seen from space (issue 9; docs/wakes.md): every wave is below a pixel, so
// they change only the Ross BRDF's slope variance (eq. 4 with w_r = 1): the sea's total times
// s^2 inside a calm area (the same rule as the projected grid's tails, so nothing pops at the
// switch: ocean::calm_tail_variance_bound), plus the variance of the wakes' two branches.
#ifndef THALASSA_PLANET_SPACE_LOCAL_FEATURES_GLSL
#define THALASSA_PLANET_SPACE_LOCAL_FEATURES_GLSL

#ifdef CALM_AREAS
#include "ocean/calm_area.glsl"
#endif
#ifdef KELVIN_WAKES
#include "ocean/local_waves.glsl"
#endif

// p: the point's nadir-frame (x, y), m; sea: every wave's variance along and across the
// wind; downwind: unit, nadir frame.
vec2 SpaceLocalSlopeVariance(vec2 p, vec2 sea, vec2 downwind) {
  vec2 variance = sea;
#ifdef CALM_AREAS
  const float s = CalmAmplitudeScale(p);
  variance *= s * s;
#endif
#ifdef KELVIN_WAKES
  variance += LocalWavesVariance(p, downwind);
#endif
  return variance;
}

#endif  // THALASSA_PLANET_SPACE_LOCAL_FEATURES_GLSL
