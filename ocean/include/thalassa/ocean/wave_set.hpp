// thalassa — the wave set of the Bruneton, Neyret & Holzschuch 2010 ocean ("Real-time realistic
// ocean lighting using seamless transitions from geometry to BRDF", Computer Graphics Forum
// 29(2); "the paper" below): n trochoids sampled from the Pierson-Moskowitz spectrum (eq. 1) with
// Hasselmann directional spreading, or from the ad-hoc h ~ omega^-2 spectrum (sec. 7.1), their
// slope statistics (eq. 4, Appendix A), the index ranges of the resolved waves (sec. 7.1) and
// the per-frame wrapped phases that keep the float shaders' numbers small (issue 3, point 7).
// Everything here is CPU-side and in double precision; the per-wave GLSL functions are in
// shaders/ocean/trochoids.glsl.
//
// Frames and units. Directions are unit vectors in the local east-north-up frame (x east,
// y north), the frame the shaders work in, so the renderer needs no extra rotation. "Wind space"
// is the same plane with the axes (downwind, crosswind): downwind is the direction the wind
// blows TOWARD (the scene gives the one it blows FROM, DESIGN section 4), crosswind is downwind
// turned 90 degrees counterclockwise seen from above (toward north for a wind toward east).
// Angles are radians, counterclockwise from downwind. SI units: metres, seconds, rad/m, rad/s.
//
// Order. Wave 0 is the LONGEST (lambda_max) and wave n - 1 the shortest (lambda_min):
// lambda_i = lambda_max q^i, q = (lambda_min / lambda_max)^(1 / (n - 1)). The waves that a grid
// cell or a pixel resolves are then a prefix [0, count) of the list, and the ones it filters out
// entirely a suffix, so shaders loop over i < count and the CPU gives the suffix's slope
// variance as one precomputed number (WaveSet::tail_variance).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "thalassa/engine/scene.hpp"

namespace thalassa::ocean {

// Gravity, m s^-2: the paper's value (sec. 3.1).
inline constexpr double kGravity = 9.81;

// Pierson & Moskowitz (1964), "A proposed spectral form for fully developed wind seas based on
// the similarity theory of S. A. Kitaigorodskii", J. Geophys. Res. 69(24), 5181-5190, as the
// paper's eq. 1 quotes them: the Phillips constant alpha and the shape constant beta
// (dimensionless).
inline constexpr double kPiersonMoskowitzAlpha = 8.1e-3;
inline constexpr double kPiersonMoskowitzBeta = 0.74;

// Largest steepness k h of a trochoid (dimensionless). A trochoid with k h >= 1 loops (its crest
// is a cusp at 1); the clamp is set where its steepest slope, atan(k h / sqrt(1 - (k h)^2)),
// is 30 degrees: the half-angle of Stokes' limiting wave (its crest encloses 120 degrees; Stokes
// 1880), the steepest a real gravity wave gets before it breaks. The same bound from wave height:
// Michell (1893) found the limiting H / lambda = 0.142, i.e. k h = pi 0.142 = 0.446. With the
// physical amplitude scale below, Pierson-Moskowitz waves never reach it (k h <= sqrt(2 alpha
// Delta), 0.36 at most for the scene's widest band, see make_wave_set): the clamp guards the
// degenerate and future cases and is reported (WaveSet::clamped_count).
inline constexpr double kMaxTrochoidSteepness = 0.5;

// N_min and N_max of the filtering weights w(N_min, N_max, lambda / L) (paper sec. 7.1: below
// Nyquist's 2, "in practice this gives too much blur, so we use in fact N_min = 1.0 and
// N_max = 2.5").
inline constexpr double kDefaultNMin = 1.0;
inline constexpr double kDefaultNMax = 2.5;

// One trochoid wave train (paper eq. 2). Its argument at the rest point p (metres, east-north-
// up, absolute: from the frame in which the scene's waves are defined) and time t (seconds) is
//   theta = omega t - k.p + phase,
// and its displacement [d h sin(theta), h cos(theta)] (shaders/ocean/trochoids.glsl).
struct Wave {
  double wavelength = 0.0;           // lambda_i, m
  double wavenumber = 0.0;           // |k_i| = 2 pi / lambda_i, rad/m
  double angular_frequency = 0.0;    // omega_i = sqrt(g |k_i|) (deep water), rad/s
  double amplitude = 0.0;            // h_i, m, after the clamp k_i h_i <= max_steepness
  double angle = 0.0;                // direction of travel in wind space, rad, [-pi, pi]
  glm::dvec2 direction{1.0, 0.0};    // unit direction of travel, east-north-up
  glm::dvec2 wave_vector{0.0, 0.0};  // k_i = |k_i| direction, rad/m, east-north-up
  double phase = 0.0;                // phi_i, rad, [0, 2 pi): theta at t = 0, p = 0
  bool clamped = false;              // true when the steepness clamp lowered the amplitude
};

// Slope variances (dimensionless) along the two wind-space axes: the variances of the slope
// components dz/d(downwind) and dz/d(crosswind), per unit horizontal area.
struct SlopeVariance {
  double along = 0.0;   // downwind
  double across = 0.0;  // crosswind
  double total() const { return along + across; }
};

struct WaveSet {
  std::vector<Wave> waves;  // i = 0 longest ... n - 1 shortest
  double lambda_min = 0.0;  // m, wavelength of the last wave
  double lambda_max = 0.0;  // m, wavelength of the first wave
  // lambda_i / lambda_{i+1} >= 1, the progression's ratio; 1 when n == 1 or lambda_min ==
  // lambda_max (all waves then share one wavelength).
  double wavelength_ratio = 1.0;
  // Width of the band of ln(omega) that each wave stands for (dimensionless), see make_wave_set.
  double log_omega_band = 0.0;
  WaveSpectrum spectrum = WaveSpectrum::PiersonMoskowitz;
  double wind_speed = 0.0;         // m/s (the scene's, at 19.5 m), negative counts as 0
  glm::dvec2 downwind{0.0, -1.0};  // unit, east-north-up: where the wind blows toward
  glm::dvec2 crosswind{1.0, 0.0};  // unit, east-north-up: downwind turned 90 deg CCW
  // Wavelength of the Pierson-Moskowitz spectrum's peak, m: 2 pi g / omega_p^2 with omega_p =
  // (4 beta / 5)^(1/4) g / V; 0 for a calm sea.
  double peak_wavelength = 0.0;
  double max_steepness = kMaxTrochoidSteepness;  // the clamp applied, dimensionless
  int clamped_count = 0;  // how many waves the clamp lowered (for the statistics)
  // tail_variance[i] = slope variance (eq. 4 with w_r = 1) of the waves j >= i, summed from the
  // short end in double: n + 1 entries, tail_variance[n] = 0, tail_variance[0] = the total.
  std::vector<SlopeVariance> tail_variance;
};

// Builds the wave set of an ocean's settings (scene.hpp: wind speed at 19.5 m in m/s, wind
// direction in degrees clockwise from north that the wind blows FROM, spectrum, n = waves,
// lambda_min, lambda_max in m, seed). Deterministic: the same settings give bit-identical waves
// with the same compiler and math library (the random numbers themselves are identical on every
// platform; the angles derived from them through cos, exp and log may differ in their last bits
// between math libraries, never in their order). Throws std::invalid_argument for n outside
// [1, 4096], wavelengths that are not finite and positive or lambda_min > lambda_max, or
// max_steepness outside (0, 1).
//
// Wavelengths: geometric progression from lambda_max (i = 0) down to lambda_min (i = n - 1),
// k = 2 pi / lambda, omega = sqrt(g k) (deep water).
//
// Amplitudes, Pierson-Moskowitz (eq. 1 with its absolute scale): S(omega) is the one-sided
// frequency spectrum of the surface height (m^2 s), Var(z) = integral_0^inf S domega (for PM
// alpha V^4 / (4 beta g^2), i.e. H_s = 4 sqrt(Var) = 0.21 V^2 / g, the known PM result). Wave i
// stands for the band of ln(omega) of width Delta centred on ln(omega_i); a wave h cos(theta)
// has height variance h^2 / 2, so equal variances give
//   h_i = sqrt(2 S(omega_i) omega_i Delta)   (domega = omega dln(omega)),
// the midpoint rule of integral S omega dln(omega): the wave set's height variance is the
// spectrum's over the band (the test checks it). Since omega ~ lambda^(-1/2), Delta =
// ln(lambda_max / lambda_min) / (2 (n - 1)), but at least ln(2) / (2 n): waves crowded into less
// than an octave of wavelength (lambda_min ~ lambda_max, or n == 1) share one octave's energy
// instead of vanishing. Each wave carries all of its band's energy in ONE direction, drawn from
// the directional distribution (below): the direction-resolved spectrum is sampled, not
// integrated, so the slope variances along and across the wind are right on average over the
// waves. In the spectrum's high-frequency range S ~ alpha g^2 omega^-5, which gives a constant
// steepness k h = sqrt(2 alpha Delta) (0.032 for the default 60 waves from 2 cm to 30 m).
// Wind height: eq. 1 uses V at 20 m, Pierson & Moskowitz used the weather ships' anemometers at
// 19.5 m, the scene's wind is at 19.5 m: the 2.5 % difference of height is a ~0.1 % difference of
// wind speed in a logarithmic profile, so they are treated as equal. Calm sea (wind <= 0):
// omega_0 = g / V -> inf and S = 0 for every omega, so every amplitude is 0 (a flat sea); the
// directions are still drawn (isotropic), and nothing is infinite or NaN.
//
// Amplitudes, omega^-2 (sec. 7.1's ad-hoc spectrum h(omega) ~ omega^-2, i.e. h ~ 1 / k: every
// wave has the same steepness k h = c). Scale: c is set so that the total slope variance
// (eq. 4, w_r = 1) equals the Pierson-Moskowitz wave set's for the same settings:
// n (1 - sqrt(1 - c^2)) = sigma_PM^2. The two spectra then give the same BRDF seen from afar
// (sec. 3.2), and the omega^-2 set is PM's saturation range extended to all wavelengths.
//
// Directions: Hasselmann, Dunckel & Ewing (1980), "Directional wave spectra observed during
// JONSWAP 1973", J. Phys. Oceanogr. 10, 1264-1280, the spreading function
//   D(theta) = N(s) cos^(2s)(theta / 2),  N(s) = 2^(2s - 1) Gamma(s + 1)^2 / (pi Gamma(2s + 1)),
//   s = 6.97 (omega / omega_p)^4.06                         for omega < 1.05 omega_p,
//   s = 9.77 (omega / omega_p)^(-2.33 - 1.45 (V / c_p - 1.17))  for omega >= 1.05 omega_p,
// theta the angle from downwind, omega_p the spectrum's peak, c_p = g / omega_p the peak's phase
// speed (Hasselmann et al. use the wind at 10 m; the fully developed PM sea has V / c_p =
// (4 beta / 5)^(1/4) = 0.877 at 19.5 m, 0.82 at 10 m: the exponent changes by 0.09, ignored).
// The spreading is narrowest near the peak (s ~ 9) and widens away from it: far above the peak
// (the capillary end of the default set, omega / omega_p ~ 60) s ~ 0.005, almost isotropic.
// Each angle is drawn by inversion of D's cumulative distribution (tabulated per wave), from one
// uniform number per wave: unlike rejection sampling, a last-bit difference of a math library
// can perturb an angle but never desynchronise the random stream.
//
// Random numbers: std::mt19937_64 seeded with settings.seed (its output sequence is specified
// by the C++ standard), u = (bits >> 11) 2^-53 in [0, 1) (not std::uniform_real_distribution,
// whose algorithm is unspecified). Wave i draws two numbers, in order of i: its angle, then its
// phase phi_i = 2 pi u.
WaveSet make_wave_set(const OceanSettings& settings, double max_steepness = kMaxTrochoidSteepness);

// Pierson-Moskowitz spectrum S(omega) (eq. 1), m^2 s, for the angular frequency omega (rad/s)
// and the wind speed V (m/s at 19.5 m): alpha g^2 omega^-5 exp(-beta (omega_0 / omega)^4),
// omega_0 = g / V. 0 for V <= 0 (calm) or omega <= 0.
double pierson_moskowitz_spectrum(double omega, double wind_speed);

// Angular frequency of the PM spectrum's peak, rad/s: dS/domega = 0 gives omega_p^4 =
// (4 beta / 5) omega_0^4, omega_p = (4 beta / 5)^(1/4) g / V = 0.877 g / V. +inf for V <= 0.
double pierson_moskowitz_peak_angular_frequency(double wind_speed);

// Hasselmann et al.'s spreading exponent s (dimensionless, >= 0) at the angular frequency omega
// for the peak omega_p (both rad/s; omega_p = +inf gives 0: isotropic), for the fully developed
// sea's V / c_p (see make_wave_set).
double hasselmann_spreading_exponent(double omega, double peak_omega);

// Hasselmann et al.'s spreading function D(theta) = N(s) cos^(2s)(theta / 2), rad^-1, for the
// angle theta (rad, from downwind) and the exponent s >= 0: integral_-pi^pi D dtheta = 1.
double hasselmann_spreading(double theta, double s);

// The angle theta in [-pi, pi] (rad) whose cumulative probability under D(.; s) is u in [0, 1]:
// the inverse CDF, from a per-call table of the CDF (1024 intervals of theta / 2 in [0, pi / 2],
// Simpson's rule, quadratic inversion inside an interval): |F(theta(u)) - u| < 1e-7 (measured
// 5.6e-8 for s from 0 to 30); exactly antisymmetric: theta(1 - u) = -theta(u) when 1 - u is
// exact (always for u = m 2^-53).
double sample_hasselmann_angle(double u, double s);

// Eq. 4 for one wave: its slope variance 1 - sqrt(1 - (k w h)^2) (Appendix A) for the weight w
// = w_r (1 for the total), projected on the wind axes with the squared direction cosines
// (cos^2 angle, sin^2 angle). Cancellation-free (TrochoidSlopeVariance in trochoids.glsl).
SlopeVariance trochoid_slope_variance(const Wave& wave, double weight = 1.0);

// Slope variance of the waves j >= first (eq. 4, w_r = 1): wave_set.tail_variance[first],
// first clamped to [0, n]. total_slope_variance is the whole set's (first = 0).
SlopeVariance tail_slope_variance(const WaveSet& wave_set, int first);
SlopeVariance total_slope_variance(const WaveSet& wave_set);

// The weight w(n_min, n_max, ratio) of sec. 3.2 (WaveFilterWeight in trochoids.glsl).
double wave_filter_weight(double n_min, double n_max, double ratio);

// The waves that a length L (metres: a projected grid cell for w_p, a pixel's footprint for
// w_n) resolves, for the weights w(n_min, n_max, lambda_i / L) (n_max > n_min > 0):
// waves [0, positive) have w > 0, i.e. xbar = (lambda_i / L - n_min) / (n_max - n_min) > 0,
// waves [0, full) have w = 1 (xbar >= 1: the clamp saturates), full <= positive. Both from the
// geometric progression with logarithms, O(1) (then checked against these exact tests on the
// wave at the boundary). L = 0 resolves every wave, L = +inf none. Throws std::invalid_argument
// for L < 0 or NaN, or n_max <= n_min.
struct ResolvedRange {
  int positive = 0;
  int full = 0;
};
ResolvedRange resolved_wave_range(const WaveSet& wave_set, double length,
                                  double n_min = kDefaultNMin, double n_max = kDefaultNMax);

// The slope variance that the BRDF must hold for a pixel of footprint `pixel_size` (metres):
// eq. 4 with w_r = 1 - w_n, w_n = w(n_min, n_max, lambda_i / pixel_size), "computed as the
// total minus the resolved part" (sec. 7.1) in a form without cancellation: the waves i >=
// positive have w_n = 0 and contribute tail_variance[positive], precomputed; the others their
// eq. 4 term with w_r = 1 - w_n. (The shader does the same: one uniform per range boundary and
// a loop over the resolved waves.)
SlopeVariance unresolved_slope_variance(const WaveSet& wave_set, double pixel_size,
                                        double n_min = kDefaultNMin, double n_max = kDefaultNMax);

// The wrapped phase of a wave for the time t (seconds) and the frame origin x0 (metres,
// east-north-up, in the frame of the wave set):
//   Phi = (omega t - k.x0 + phi) mod 2 pi   in [0, 2 pi),
// so that a shader computes the argument theta = Phi - k.x with x relative to x0 (small numbers).
// Exact argument reduction: each product (omega t, k_x x0_x, k_y x0_y) is split into a double
// and its exact rounding error (FMA), the double reduced modulo 2 pi with a two-part 2 pi
// (Cody & Waite 1980, with FMAs), and the parts summed near [-4 pi, 4 pi]: the error is a few
// 1e-16 rad for |omega t|, |k.x0| up to ~1e15 rad (t = 1e9 s and x0 = 5e6 m give ~5e10 and 3e10
// for 2 cm waves; naive double loses up to ~5e-5 rad there). At t = 0 and x0 = 0 it is phi
// exactly. Non-finite inputs give 0.
double wrapped_phase(const Wave& wave, double time, glm::dvec2 origin);
std::vector<double> wrapped_phases(const WaveSet& wave_set, double time, glm::dvec2 origin);

// A unit direction of the waves' chart (the frame the wave set is defined in) as seen in a
// renderer's frame whose east and north unit vectors, in chart coordinates, are the columns of
// `frame_axes` (planet/nadir_frame.hpp, wave_axes): the wave vector k turns as k^T axes, i.e.
// axes^T k, renormalised (the axes are a rotation to ~1e-5).
inline glm::dvec2 chart_direction_in_frame(const glm::dmat2& frame_axes, glm::dvec2 direction) {
  return glm::normalize(glm::transpose(frame_axes) * direction);
}

}  // namespace thalassa::ocean
