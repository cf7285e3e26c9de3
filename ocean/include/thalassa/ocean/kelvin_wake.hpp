// thalassa — the Kelvin wake of a ship in deep water, as waves whose wavelength and slope
// variance are known at every point, so that it joins the ocean's geometry -> normals -> BRDF
// hierarchy (Bruneton, Neyret & Holzschuch 2010, sec. 6 "Local waves", fig. 12 left; issue 9,
// point 1). CPU, double precision; docs/wakes.md derives every formula below.
//
// Frame and units. The SHIP FRAME is a horizontal plane moving with the ship: its origin is the
// ship (the equivalent point disturbance), `e` the unit vector of its course, `n` = e turned
// 90 degrees counterclockwise seen from above (to port). A point is given by
//   behind  b = -(p - ship).e   metres, > 0 astern,
//   lateral y = (p - ship).n    metres, > 0 to port.
// Wave vectors are returned in (e, n) components, rad/m; angles in radians; times in seconds;
// lengths in metres; g = kGravity (wave_set.hpp).
//
// The model (linear deep-water theory, stationary phase; Lighthill, "Waves in Fluids" 1978,
// sec. 3.10; Whitham, "Linear and Nonlinear Waves" 1974, sec. 12.4): the steady pattern is the
// superposition over theta in (-pi/2, pi/2) of plane waves whose wave vector makes the angle
// theta with the course, k(theta) = k0 sec^2(theta) (cos theta e + sin theta n), k0 = g / U^2:
// the waves that keep pace with the ship, omega(k) = sqrt(g k) = k.U e (their phase speed
// sqrt(g / k) equals U cos theta). In the ship frame their phase at (b, y) is
//   psi(theta) = k(theta).(-b e + y n) = -k0 sqrt(1 + t^2) (b - y t),   t = tan theta,
// and only the theta where d psi / d theta = 0 contribute far from the ship:
//   y / b = t / (1 + 2 t^2)                                               (stationary phase)
// whose right side peaks at t = 1/sqrt(2) (the cusp, theta_c = 35.26 deg, k = 3/2 k0) with the
// value 1 / (2 sqrt 2): the wedge's half-angle asin(1/3) = 19.47 deg. Inside it two roots: the
// TRANSVERSE wave (t < 1/sqrt2; on the track t = 0 and lambda = 2 pi U^2 / g) and the DIVERGENT
// wave (t > 1/sqrt2, shorter, its crests nearly along the track close to it).
//
// Amplitude of a branch: A(theta) sqrt(2 pi / |psi''|) N, psi'' = d2 psi / d theta2 =
// -k0 (b - 4 y t)(1 + t^2)^(3/2), with the source's amplitude density A(theta) = a_ref
// exp(-k0 d t^2) (a source at depth d couples to a wave of wavenumber k as exp(-k d), and
// k - k0 = k0 t^2) and N the constant that makes the transverse wave on the track one transverse
// wavelength astern exactly a_ref high. Three regularisations keep every value finite
// (docs/wakes.md): at the cusp |psi''| is replaced by (psi''^4 + R^4)^(1/4) with R from the
// Airy (caustic) scale; outside the wedge both branches sit at the cusp and decay as
// exp(-2/3 z^(3/2)) (the Airy function's tail); near the ship (b < lambda0) and at the wake's end
// the amplitude fades (C1 smoothsteps). Each branch is then a trochoid whose steepness k h is
// clamped to kMaxTrochoidSteepness (wave_set.hpp).
#pragma once

#include <glm/glm.hpp>

#include "thalassa/ocean/wave_set.hpp"

namespace thalassa::ocean {

// The Kelvin half-angle asin(1/3), rad (19.471 deg): the wedge outside which the pattern decays.
inline constexpr double kKelvinHalfAngle = 0.33983690945412193;
// tan of it, 1 / (2 sqrt 2): the largest y / b of a stationary point.
inline constexpr double kKelvinTanHalfAngle = 0.35355339059327379;
// The cusp's wave angle atan(1 / sqrt 2), rad (35.264 deg): where the two branches meet.
inline constexpr double kKelvinCuspWaveAngle = 0.61547970867038734;
// The maximum of the Airy function Ai, 0.535656656 at z = -1.018792972 (Abramowitz & Stegun,
// table 10.13): scales the cusp regularisation R.
inline constexpr double kAiryMaximum = 0.53565665601569;
// Outside the wedge the amplitude is multiplied by exp(-2/3 z^(3/2)) (Ai's tail over its peak)
// and brought to 0 by a smoothstep between these two values of z: exp(-2/3 * 4^1.5) = 0.005.
inline constexpr double kWakeAiryFadeStart = 3.0;
inline constexpr double kWakeAiryCutoff = 4.0;
// Fraction of the wake's length over which its end fades out (smoothstep to 0).
inline constexpr double kWakeTailFraction = 0.2;
// Smallest phase speed of capillary-gravity waves on clean water, m/s: (4 g sigma / rho)^(1/4)
// with sigma = 0.0728 N/m, rho = 1000 kg/m^3 (water at 20 C). A disturbance slower than this
// makes no steady waves at all; the gravity-only model here also needs lambda0 >> 1.7 cm. Below
// this speed the wake is empty (every amplitude 0).
inline constexpr double kMinimumWakeSpeed = 0.2312;

// A ship's wake parameters (scene key wakes[], docs/scene.md).
struct KelvinWakeParams {
  double speed = 0.0;      // U, m/s; the wake is empty below kMinimumWakeSpeed
  double amplitude = 0.3;  // a_ref, m: transverse wave amplitude on the track lambda0 astern
  double draft = 3.0;      // d, m (> 0): depth of the equivalent source; damps short waves
  double length = 3000.0;  // m: how far astern the wake reaches (its end fades out)
  bool operator==(const KelvinWakeParams&) const = default;
};

// One branch of the pattern at a point: locally a trochoid (paper eq. 2) with these values.
struct WakeWave {
  double angle = 0.0;              // theta, rad: direction of k from the course, (-pi/2, pi/2)
  glm::dvec2 wave_vector{0.0};     // k, rad/m, ship frame (e, n components); 0 when empty
  double wavenumber = 0.0;         // |k| = k0 sec^2 theta, rad/m
  double wavelength = 0.0;         // 2 pi / |k|, m (0 when the wake is empty)
  double angular_frequency = 0.0;  // sqrt(g |k|) = k.(U e), rad/s
  double amplitude = 0.0;          // h, m, after the fades and the steepness clamp
  // The trochoid's argument theta_w = omega t - k.p + phi at this point (shaders/ocean/
  // trochoids.glsl: displacement [k/|k| h sin theta_w, h cos theta_w]), wrapped to [0, 2 pi):
  // -(psi(theta) + sign(psi'') pi/4), stationary in the ship frame.
  double argument = 0.0;
  bool clamped = false;  // the steepness clamp lowered the amplitude
  // Slope variance of this trochoid per unit horizontal area (Appendix A), dimensionless, for the
  // amplitude weighted by `weight` (w_r of eq. 4; 1 = all of it): 1 - sqrt(1 - (k w h)^2).
  double slope_variance(double weight = 1.0) const;
};

// The wake at a point: the transverse and the divergent branch (either may have amplitude 0).
struct KelvinWakeSample {
  WakeWave transverse;
  WakeWave divergent;
  bool inside_wedge = false;  // |y| / b <= tan(19.47 deg) and b > 0
  // Slope variances of both branches (eq. 4 for these two waves, weights w_r per branch) along
  // the unit direction `axis` (ship frame) and across it: the terms that join the BRDF's
  // sigma^2 when the renderer filters the waves out (axis = downwind in the ship frame).
  SlopeVariance slope_variance(glm::dvec2 axis, double weight_transverse = 1.0,
                               double weight_divergent = 1.0) const;
  // The wake's height above the mean sea (m) at this point as the sum of the two branches in
  // the linear (Airy-wave) form h cos(theta_w) — for tests and the CPU reference; the renderer
  // displaces the surface with the trochoids.
  double linear_height() const;
};

// k0 = g / U^2, rad/m; +inf below kMinimumWakeSpeed would be meaningless, so 0 is returned there.
double kelvin_transverse_wavenumber(double speed);
// lambda0 = 2 pi U^2 / g, m (0 below kMinimumWakeSpeed).
double kelvin_transverse_wavelength(double speed);
// A bound of how far a wake's two branches move a point horizontally anywhere, m: each trochoid
// by its amplitude, which the steepness clamp holds to kMaxTrochoidSteepness / k, and
// k = k0 sec^2(theta) >= k0 = g / U^2: 2 kMaxTrochoidSteepness U^2 / g (U = speed, m/s). The
// skirt's reach (ocean_node.cpp) and SeaState's scan radius.
double kelvin_wake_displacement_bound(double speed);

// The two roots t = tan(theta) of y / b = t / (1 + 2 t^2) for tau = |y| / b in
// [0, 1 / (2 sqrt 2)]: transverse 2 tau / (1 + s), divergent (1 + s) / (4 tau), s = sqrt(1 -
// 8 tau^2) (cancellation-free; the divergent root is +inf at tau = 0). tau above the limit is
// treated as the limit (both 1 / sqrt 2).
struct KelvinRoots {
  double transverse = 0.0;
  double divergent = 0.0;
};
KelvinRoots kelvin_stationary_roots(double tau);

// The ship-frame phase psi(theta) = -k0 sqrt(1 + t^2)(b - y t), rad, of the plane wave of angle
// theta at (b, y) (for tests of stationarity).
double kelvin_phase(double k0, double theta, double behind, double lateral);

// The wake at (behind, lateral) metres in the ship frame. Finite for every finite input (and
// for speed 0 or below kMinimumWakeSpeed: two empty waves); non-finite positions give an empty
// sample. Throws std::invalid_argument for parameters that are not finite, draft <= 0,
// amplitude < 0, length <= 0.
KelvinWakeSample kelvin_wake_at(const KelvinWakeParams& params, double behind, double lateral);

// The largest |y| (m) at which kelvin_wake_at can be non-zero for b <= length (the wedge plus
// its Airy tail, for the conservative culling bounds): length tan(19.47 deg) + the tail's width
// at b = length. 0 for an empty wake.
double kelvin_wake_half_width(const KelvinWakeParams& params);

// N, the pure number that makes the transverse amplitude on the track one lambda0 astern exactly
// a_ref (dimensionless; the same for every speed, since k0 b = 2 pi there): the shaders'
// amplitude factor is a_ref N (shaders/ocean/kelvin_wake.glsl).
double kelvin_reference_normalisation();

}  // namespace thalassa::ocean
