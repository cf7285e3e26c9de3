// One trochoid (Gerstner) wave train of the Bruneton, Neyret & Holzschuch 2010 ocean ("Real-time
// realistic ocean lighting using seamless transitions from geometry to BRDF", Computer Graphics
// Forum 29(2)): its displacement (paper eq. 2), the partial derivatives of that displacement
// (for the normals of eq. 3), its slope variance (Appendix A, for eq. 4) and the filtering weight
// w(a, b, x) of sec. 3.2. The sums over the waves, and the choice of which waves to sum, belong
// to the shaders that include this file; the wave parameters come from the CPU
// (ocean/include/thalassa/ocean/wave_set.hpp). CPU reference: ocean/src/trochoids_reference.hpp;
// tests: tests/unit/wave_set_test.cpp.
//
// Frame: a local east-north-up frame (x east, y north, z up) tangent to the sea at rest, whose
// origin x0 is chosen by the CPU each frame (near the camera). Positions x in that frame are
// metres *relative to x0*, so they stay small numbers.
//
// Eq. 2 writes the wave's argument as omega t - k.x (radians). With a random phase phi per wave
// and the frame origin x0 it is
//   theta = omega t - k.(x0 + x) + phi = Phi - k.x,   Phi = (omega t - k.x0 + phi) mod 2 pi,
// where Phi, the wrapped phase, is computed on the CPU in double precision with an exact
// argument reduction (wrapped_phase in wave_set.hpp). So a float shader never sees omega t
// (5e8 rad for a 2 cm wave at t = 1e7 s) nor k.x0 (1.6e9 rad for the same wave 5,000 km away):
// only Phi in [0, 2 pi) and k.x for the local x (paper sec. 7.1; issue 3, point 7).
//
// The displacement of the rest point x (eq. 2), for the unit direction of travel d = k / |k|
// and the amplitude h (metres):
//   t(x) = [ d h sin(theta), h cos(theta) ],   theta = Phi - k.x,
// so the displaced point is (x + t_xy, t_z). At theta = 0 the point is on a crest (z = h) and the
// rest points around it are pulled toward it (d(x + t_xy)/dx = 1 - k h cos(theta) < 1): the
// crests are sharp, the troughs flat. Along d this is the trochoid of Appendix A,
// X(s) = s - h sin(k s), Z(s) = h cos(k s) (at Phi = 0), a valid curve only for k h < 1: at
// k h = 1 the crest is a cusp, beyond it the curve loops. The CPU keeps k h below its clamp
// (kMaxTrochoidSteepness, 0.5) for every wave.
//
// Derivatives (for eq. 3's normals): with dtheta/dx_j = -k_j (k_j = |k| d_j),
//   dt/dx_j = -|k| d_j [ d h cos(theta), -h sin(theta) ]
//           = [ -|k| h d_j d cos(theta), |k| h d_j sin(theta) ].
// Eq. 3's normal is (e_x + sum w_n dt/dx) x (e_y + sum w_n dt/dy) (cross product), with e_x,
// e_y the unit vectors (x, y, 0); for a single wave its z component is
// 1 - k h cos(theta) > 0, the Jacobian of the horizontal displacement.

#ifndef THALASSA_OCEAN_TROCHOIDS_GLSL
#define THALASSA_OCEAN_TROCHOIDS_GLSL

#include "common/definitions.glsl"

// The filtering weight of sec. 3.2 (dimensionless, in [0, 1]):
//   w(a, b, x) = 3 xbar^2 - 2 xbar^3,   xbar = clamp((x - a) / (b - a), 0, 1),
// for x = lambda / L, the wavelength over the projected size L of a grid cell (w_p) or of a pixel
// (w_n), with a = N_min and b = N_max (1.0 and 2.5 in the paper's sec. 7.1).
// w = 0 for lambda <= N_min L (filtered out), w = 1 for lambda >= N_max L (resolved), a C1
// smoothstep in between. Written as xbar^2 (3 - 2 xbar): exactly 1 when the clamp saturates, and
// > 0 whenever x > a (so the CPU's index ranges, which use the same tests, agree with it).
// For n_max <= n_min it is the limit n_max -> n_min+, a step: 0 below n_min, 1 from n_min on
// (finite where the ratio form would divide 0 by 0).
Number WaveFilterWeight(IN(Number) n_min, IN(Number) n_max, IN(Number) ratio) {
  if (n_max <= n_min) {
    return ratio < n_min ? 0.0 : 1.0;
  }
  Number xbar = clamp((ratio - n_min) / (n_max - n_min), 0.0, 1.0);
  return xbar * xbar * (3.0 - 2.0 * xbar);
}

// The argument theta (radians) of a wave at the local position (metres, relative to the frame's
// origin x0, local east-north-up): theta = phase - k.position, with phase the wrapped phase Phi
// (radians, in [0, 2 pi), from the CPU) and wave_vector k = |k| d (rad/m, local east-north-up).
Number TrochoidArgument(IN(vec2) wave_vector, IN(Number) phase, IN(vec2) position) {
  return phase - dot(wave_vector, position);
}

// The same argument at the point origin + local (metres, local east-north-up; origin as
// `position` above, local a small offset from it), as theta = Phi_o - k.local with Phi_o =
// (phase - k.origin) mod 2 pi: for many points near one origin whose arguments' differences
// matter, not their common value (the reference's lattice, ocean/reference_sun_scatter.comp).
// In float, phase - k.position is a number up to |k| |position| (3,900 rad for a 0.04 m wave 25 m
// away) rounded to 2.4e-4 rad, independently at each point, as is the position itself; here
// Phi_o carries that rounding but is the same float for every point of one origin (PRECISE),
// and k.local is small, so the differences between nearby points keep their digits
// (tests/gpu/numerics_test.cpp, GpuNumericsTest.TrochoidArgumentFromAnOrigin). Phi_o's rounding
// moves all the points of one origin together, by at most 2.4e-4 rad / |k|.
Number TrochoidArgumentFrom(IN(vec2) wave_vector, IN(Number) phase, IN(vec2) origin,
                            IN(vec2) local) {
  PRECISE Number origin_phase = phase - dot(wave_vector, origin);
  origin_phase = origin_phase - 2.0 * PI * floor(origin_phase / (2.0 * PI));
  return origin_phase - dot(wave_vector, local);
}

// Eq. 2's t_i (metres, local east-north-up): the displacement of the rest point whose argument
// is theta = argument, for a wave travelling along the unit vector direction with amplitude h =
// amplitude (metres). Multiply by the weight w_p to filter it.
vec3 TrochoidDisplacement(IN(vec2) direction, IN(Number) amplitude, IN(Number) argument) {
  Number horizontal = amplitude * sin(argument);
  return vec3(direction.x * horizontal, direction.y * horizontal, amplitude * cos(argument));
}

// The partial derivatives dt/dx and dt/dy (dimensionless: metres per metre, local east-north-up)
// of TrochoidDisplacement with respect to the rest position (x east, y north), for the wave of
// unit direction `direction`, wavenumber |k| = wavenumber (rad/m) and amplitude h (metres), at
// the argument theta = argument. Multiply by the weight w_n and add to (1, 0, 0) and (0, 1, 0)
// for eq. 3.
void TrochoidDisplacementDerivatives(IN(vec2) direction, IN(Number) wavenumber,
                                     IN(Number) amplitude, IN(Number) argument,
                                     OUT(vec3) d_dx, OUT(vec3) d_dy) {
  Number kh = wavenumber * amplitude;
  Number c = kh * cos(argument);  // dt/dx_j = [-c d_j d, s d_j] (see the top of the file).
  Number s = kh * sin(argument);
  d_dx = vec3(-c * direction.x * direction.x, -c * direction.x * direction.y, s * direction.x);
  d_dy = vec3(-c * direction.y * direction.x, -c * direction.y * direction.y, s * direction.y);
}

// The variance of the slope of one trochoid along its direction of travel (dimensionless), per
// unit horizontal area (Appendix A):
//   sigma^2 = (1 / lambda) integral_0^lambda (dz/dx)^2 dx = 1 - sqrt(1 - (k h)^2),
// for the steepness k h = steepness (times w_r for eq. 4), written without the cancellation of
// 1 - sqrt(1 - y) for small y: 1 - sqrt(1 - y) = y / (1 + sqrt(1 - y)). (As printed, 1 -
// sqrt(...) in float loses every digit below k h ~ 3e-4, where sigma^2 ~ 5e-8 < 2^-24.) The
// variance of the slope across the direction of travel is 0; eq. 4 projects this one onto the
// wind axes with the squared direction cosines. The steepness is clamped to [0, 1] (a trochoid
// with k h >= 1 loops; its variance tends to 1 at the cusp), so the result is finite in [0, 1].
// Toward the cusp (s = k h -> 1) 1 - y cancels in its turn: y = s^2 is rounded to a relative
// epsilon, i.e. by up to 1.1e-16 (6e-8 in float) absolute, against 1 - y ~ 2 (1 - s) (in float a
// relative error 3e-8 / (1 - s) of 1 - y: 5e-7 on the variance at s = 1 - 2^-13). Written
// (1 - s)(1 + s) it is exact to a few ulps for every s: 1 - s is exact for s in [0.5, 1]
// (Sterbenz) and the product is rounded once.
Number TrochoidSlopeVariance(IN(Number) steepness) {
  Number s = min(abs(steepness), 1.0);
  return s * s / (1.0 + sqrt((1.0 - s) * (1.0 + s)));
}

#endif  // THALASSA_OCEAN_TROCHOIDS_GLSL
