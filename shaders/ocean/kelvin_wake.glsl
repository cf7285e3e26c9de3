// The Kelvin wake of a ship at a point of its ship frame, in float: the GPU's mirror of
// thalassa::ocean::kelvin_wake_at (ocean/src/kelvin_wake.cpp, the double-precision reference;
// docs/wakes.md derives every line; tests/gpu/local_waves_test.cpp compares the two over a grid
// of points). Issue 9, point 1; paper 000 sec. 6 "Local waves".
//
// Frame and units: the SHIP FRAME of ocean/kelvin_wake.hpp: b (m) astern of the ship, y (m) to
// port; wave vectors in (e, n) components, rad/m; amplitudes m; arguments rad.
//
// Precision: the phase psi = -k0 b sqrt(1 + t^2)(1 - tau t) is homogeneous of degree 1 in
// (b, y), so float computes it with a relative error of a few ulps: about 1e-4 rad at
// k0 b = 1e3 (a 64 m transverse wave 10 km astern), 1e-3 rad at 1e4. The arguments are
// stationary in the ship frame (no omega t), and (b, y) come from the ship's position made
// camera-relative in double on the CPU (ocean/local_features.hpp), so no large number enters.
#ifndef THALASSA_OCEAN_KELVIN_WAKE_GLSL
#define THALASSA_OCEAN_KELVIN_WAKE_GLSL

#include "common/definitions.glsl"

// kelvin_wake.hpp's constants, in float.
const float KELVIN_TAN_HALF_ANGLE = 0.35355339059327379;  // 1 / (2 sqrt 2)
const float KELVIN_AIRY_MAXIMUM = 0.53565665601569;       // max Ai
const float KELVIN_AIRY_FADE_START = 3.0;                  // z, kWakeAiryFadeStart
const float KELVIN_AIRY_CUTOFF = 4.0;                      // z, kWakeAiryCutoff
const float KELVIN_TAIL_FRACTION = 0.2;                    // kWakeTailFraction
const float KELVIN_MAX_STEEPNESS = 0.5;                    // kMaxTrochoidSteepness
// Beyond k0 d t^2 = 80 the source term exp(-k0 d t^2) < 2e-35: the divergent branch is left at
// 0 there (the reference's bound is 700, where double's exp underflows; the values between are
// far below a float's resolution of the sea).
const float KELVIN_MAX_SOURCE_EXPONENT = 80.0;

// One branch: locally a trochoid (paper eq. 2).
struct KelvinWakeWave {
  vec2 wave_vector;  // k, rad/m, ship frame (e, n); 0 when empty
  float wavenumber;  // |k|, rad/m
  float amplitude;   // h, m
  float argument;    // theta_w = -(psi + sign(psi'') pi / 4), wrapped to [0, 2 pi), rad
};

float KelvinSmoothstep(float a, float b, float x) {
  const float u = clamp((x - a) / (b - a), 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

// (psi''^4 + R^4)^(1/4) without overflow (the reference's `regularised`).
float KelvinRegularised(float psi2, float r) {
  const float m = max(abs(psi2), r);
  if (m == 0.0) return 0.0;
  const float u = psi2 / m, v = r / m;
  return m * sqrt(sqrt(u * u * u * u + v * v * v * v));
}

// The branch at t = tan(theta) >= 0 (the lateral sign applied through `side`); `factor`
// multiplies the amplitude (the fades and Airy's tail), `amplitude_factor` is a_ref N (m).
KelvinWakeWave KelvinWakeBranch(float k0, float amplitude_factor, float draft, float t, float b,
                                float y_abs, float side, float offset, float regularisation,
                                float factor) {
  KelvinWakeWave w;
  const float s = sqrt(1.0 + t * t);  // sec(theta)
  w.wavenumber = k0 * s * s;
  w.wave_vector = vec2(k0 * s, side * k0 * s * t);
  const float psi = -k0 * s * (b - y_abs * t);
  const float psi2 = -k0 * (b - 4.0 * y_abs * t) * s * s * s;
  w.amplitude = amplitude_factor * exp(-k0 * draft * t * t) *
                sqrt(2.0 * PI / KelvinRegularised(psi2, regularisation)) * factor;
  const float argument = -(psi + offset);
  w.argument = argument - 2.0 * PI * floor(argument / (2.0 * PI));
  return w;
}

KelvinWakeWave KelvinEmptyWave() {
  KelvinWakeWave w;
  w.wave_vector = vec2(0.0);
  w.wavenumber = 0.0;
  w.amplitude = 0.0;
  w.argument = 0.0;
  return w;
}

// The wake at (b, y) (m, ship frame) for params = (k0 rad/m, a_ref N m, draft m, length m)
// (ocean::kelvin_wake_gpu_params): the transverse and the divergent branch, steepness clamped.
void KelvinWake(vec4 params, float b, float y, out KelvinWakeWave transverse,
                out KelvinWakeWave divergent) {
  transverse = KelvinEmptyWave();
  divergent = KelvinEmptyWave();
  const float k0 = params.x, amplitude_factor = params.y, draft = params.z, len = params.w;
  if (!(k0 > 0.0) || !(amplitude_factor > 0.0) || !(b > 0.0) || b >= len) return;
  const float side = y < 0.0 ? -1.0 : 1.0;
  const float lambda0 = 2.0 * PI / k0;
  const float y_abs = abs(y);
  const float tau = y_abs / b;
  const float fade = KelvinSmoothstep(0.0, lambda0, b) *
                     (1.0 - KelvinSmoothstep((1.0 - KELVIN_TAIL_FRACTION) * len, len, b));
  if (fade == 0.0) return;
  const float third = 1.5 * sqrt(3.0) * k0 * b;  // psi''' at the cusp, rad
  const float regularisation = 2.0 / (PI * KELVIN_AIRY_MAXIMUM * KELVIN_AIRY_MAXIMUM) *
                               pow(0.25 * third * third, 1.0 / 3.0);
  const float offset = PI / 4.0;
  if (tau <= KELVIN_TAN_HALF_ANGLE) {
    // The two roots of y / b = t / (1 + 2 t^2), cancellation-free (kelvin_stationary_roots).
    const float s = sqrt(max(0.0, 1.0 - 8.0 * tau * tau));
    const float t_transverse = 2.0 * tau / (1.0 + s);
    transverse = KelvinWakeBranch(k0, amplitude_factor, draft, t_transverse, b, y_abs, side,
                                  -offset, regularisation, fade);
    // The divergent root (1 + s) / (4 tau), left out where its source term has vanished
    // (k0 d t^2 > KELVIN_MAX_SOURCE_EXPONENT, i.e. 4 tau < (1 + s) sqrt(k0 d / max exponent)).
    if (4.0 * tau * sqrt(KELVIN_MAX_SOURCE_EXPONENT) > (1.0 + s) * sqrt(k0 * draft)) {
      const float t_divergent = (1.0 + s) / (4.0 * tau);
      divergent = KelvinWakeBranch(k0, amplitude_factor, draft, t_divergent, b, y_abs, side,
                                   offset, regularisation, fade);
    }
  } else {
    // Beyond the cusp line: both branches at the cusp, Ai's tail (kelvin_wake_at).
    const float delta = k0 * b * sqrt(1.5) * (2.0 * tau - 1.0 / sqrt(2.0));
    const float z = delta / pow(0.5 * third, 1.0 / 3.0);
    if (z >= KELVIN_AIRY_CUTOFF) return;
    const float airy = exp(-2.0 / 3.0 * z * sqrt(z)) *
                       (1.0 - KelvinSmoothstep(KELVIN_AIRY_FADE_START, KELVIN_AIRY_CUTOFF, z));
    const float t_cusp = 1.0 / sqrt(2.0);
    transverse = KelvinWakeBranch(k0, amplitude_factor, draft, t_cusp, b, y_abs, side, -offset,
                                  regularisation, fade * airy);
    divergent = KelvinWakeBranch(k0, amplitude_factor, draft, t_cusp, b, y_abs, side, offset,
                                 regularisation, fade * airy);
  }
  transverse.amplitude =
      min(transverse.amplitude, KELVIN_MAX_STEEPNESS / max(transverse.wavenumber, 1e-30));
  divergent.amplitude =
      min(divergent.amplitude, KELVIN_MAX_STEEPNESS / max(divergent.wavenumber, 1e-30));
}

#endif  // THALASSA_OCEAN_KELVIN_WAKE_GLSL
