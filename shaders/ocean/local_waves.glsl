// Ships' Kelvin wakes joined to the ocean's hierarchy (issue 9, point 1; paper 000 sec. 3.2 and
// sec. 6 "Local waves"; docs/wakes.md): at a point each wake is two trochoids whose wavelength,
// direction, amplitude and argument ocean/kelvin_wake.glsl gives in closed form, and each is
// filtered exactly like a wave of the set with its own wavelength: displacement with w_p
// (ocean.vert), normals with w_n and the slope variance of eq. 4 with w_r = 1 - w_n
// (ocean_geometry.frag), the variance alone from space (planet/ocean_space.frag).
//
// Frame and units: positions are the nadir frame's (x, y), m (common/frame.glsl); each wake's
// ship frame is laid in that plane by the CPU (ocean/local_features.hpp, WakeInFrame).
#ifndef THALASSA_OCEAN_LOCAL_WAVES_GLSL
#define THALASSA_OCEAN_LOCAL_WAVES_GLSL

#include "common/definitions.glsl"
#include "ocean/kelvin_wake.glsl"
#include "ocean/trochoids.glsl"

// Three vec4 per wake (ocean/src/local_features.cpp): (k0 rad/m, a_ref N m, draft m, length m),
// (half-width m, beyond which the wake is exactly 0 (ocean::kelvin_wake_half_width); index of
// its first track point; point count; 0) and the box (lo x, lo y, hi x, hi y; m) its track grown
// by the half-width covers. The tracks: the ship first, then the past track's points (m).
layout(std430, binding = 3) readonly buffer Wakes { vec4 wakes[]; };
layout(std430, binding = 4) readonly buffer WakeTracks { vec2 wake_tracks[]; };
uniform int wake_count;

// The wake i's ship frame at the nadir-frame point p (m), ShipWake's track-following one: the
// track's point nearest to p (the foot), b the distance along the track from the ship to it, y
// the distance from it (> 0 to port), e the direction of travel there. False where the wake is
// exactly 0. CPU reference: ocean::wake_frame_coordinates.
bool LocalWakeFrame(int i, vec2 p, out float b, out float y, out vec2 e) {
  b = 0.0;
  y = 0.0;
  e = vec2(0.0, 1.0);
  const vec4 box = wakes[3 * i + 2];
  // Away from the wake the pixels pay only this test (issue 9, point 5).
  if (!(p.x >= box.x && p.y >= box.y && p.x <= box.z && p.y <= box.w)) return false;
  const vec4 track = wakes[3 * i + 1];
  const int first = int(track.y), count = int(track.z);
  float best = 1e30, along = 0.0;
  for (int j = 0; j + 1 < count; ++j) {
    const vec2 newer = wake_tracks[first + j], older = wake_tracks[first + j + 1];
    const float len = length(newer - older);
    if (!(len > 0.0)) continue;
    const vec2 travel = (newer - older) / len;
    const float t = clamp(dot(p - older, travel), 0.0, len);
    const vec2 foot = older + t * travel;
    const float d = length(p - foot);
    if (d < best) {
      best = d;
      b = along + (len - t);
      y = dot(p - foot, vec2(-travel.y, travel.x)) < 0.0 ? -d : d;
      e = travel;
    }
    along += len;
  }
  return best <= track.x && b > 0.0 && b < min(wakes[3 * i].w, along);
}

// The wake i's two branches at the nadir-frame point p (m), their wave vectors turned into the
// nadir frame.
void LocalWake(int i, vec2 p, out KelvinWakeWave transverse, out KelvinWakeWave divergent) {
  float b, y;
  vec2 e;
  if (!LocalWakeFrame(i, p, b, y, e)) {
    transverse = KelvinEmptyWave();
    divergent = KelvinEmptyWave();
    return;
  }
  KelvinWake(wakes[3 * i], b, y, transverse, divergent);
  const vec2 n = vec2(-e.y, e.x);  // to port
  transverse.wave_vector = transverse.wave_vector.x * e + transverse.wave_vector.y * n;
  divergent.wave_vector = divergent.wave_vector.x * e + divergent.wave_vector.y * n;
}

// Eq. 2's displacement (m, local east-north-up) of one branch filtered with w_p for the grid
// cell `cell` (m); `scale` is the resolved-wave scale of ocean.vert.
vec3 LocalWaveDisplacement(KelvinWakeWave w, float cell, float n_min, float n_max, float scale) {
  if (w.amplitude <= 0.0) return vec3(0.0);
#ifdef METHOD_REFERENCE
  const float w_p = 1.0;
#else
  const float w_p = WaveFilterWeight(n_min, n_max, scale * 2.0 * PI / w.wavenumber / cell);
#endif
  return w_p * TrochoidDisplacement(w.wave_vector / w.wavenumber, w.amplitude, w.argument);
}

vec3 LocalWavesDisplacement(vec2 p, float cell, float n_min, float n_max, float scale) {
  vec3 displacement = vec3(0.0);
  for (int i = 0; i < wake_count; ++i) {
    KelvinWakeWave transverse, divergent;
    LocalWake(i, p, transverse, divergent);
    displacement += LocalWaveDisplacement(transverse, cell, n_min, n_max, scale);
    displacement += LocalWaveDisplacement(divergent, cell, n_min, n_max, scale);
  }
  return displacement;
}

// One branch into eq. 3 (w_n) and eq. 4 (w_r = 1 - w_n), for the pixel footprint `footprint`
// (m); the variance along and across `downwind` (unit, nadir frame).
void LocalWaveNormal(KelvinWakeWave w, float footprint, float n_min, float n_max, float scale,
                     vec2 downwind, inout vec3 d_dx, inout vec3 d_dy, inout vec2 variance) {
  if (w.amplitude <= 0.0) return;
#ifdef METHOD_REFERENCE
  const float w_n = 1.0;
#else
  const float w_n = WaveFilterWeight(n_min, n_max, scale * 2.0 * PI / w.wavenumber / footprint);
#endif
  const vec2 direction = w.wave_vector / w.wavenumber;
  if (w_n > 0.0) {
    vec3 wave_dx, wave_dy;
    TrochoidDisplacementDerivatives(direction, w.wavenumber, w.amplitude, w.argument, wave_dx,
                                    wave_dy);
    d_dx += w_n * wave_dx;
    d_dy += w_n * wave_dy;
  }
  if (w_n < 1.0) {
    const float v = TrochoidSlopeVariance(w.wavenumber * (1.0 - w_n) * w.amplitude);
    const float along = dot(direction, downwind);
    const float across = dot(direction, vec2(-downwind.y, downwind.x));
    variance += v * vec2(along * along, across * across);
  }
}

void LocalWavesNormals(vec2 p, float footprint, float n_min, float n_max, float scale,
                       vec2 downwind, inout vec3 d_dx, inout vec3 d_dy, inout vec2 variance) {
  for (int i = 0; i < wake_count; ++i) {
    KelvinWakeWave transverse, divergent;
    LocalWake(i, p, transverse, divergent);
    LocalWaveNormal(transverse, footprint, n_min, n_max, scale, downwind, d_dx, d_dy, variance);
    LocalWaveNormal(divergent, footprint, n_min, n_max, scale, downwind, d_dx, d_dy, variance);
  }
}

// From space every wave is unresolved (w_r = 1): the wakes' slope variance along and across
// `downwind` at p.
vec2 LocalWavesVariance(vec2 p, vec2 downwind) {
  vec3 d_dx = vec3(1.0, 0.0, 0.0), d_dy = vec3(0.0, 1.0, 0.0);
  vec2 variance = vec2(0.0);
  // w_n = 0 for every wave: n_min = n_max = +inf makes the weight a step that is never reached.
  for (int i = 0; i < wake_count; ++i) {
    KelvinWakeWave transverse, divergent;
    LocalWake(i, p, transverse, divergent);
    LocalWaveNormal(transverse, 1.0, 1e30, 1e30, 0.0, downwind, d_dx, d_dy, variance);
    LocalWaveNormal(divergent, 1.0, 1e30, 1e30, 0.0, downwind, d_dx, d_dy, variance);
  }
  return variance;
}

#endif  // THALASSA_OCEAN_LOCAL_WAVES_GLSL
