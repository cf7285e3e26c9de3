// PLACEHOLDER SKY of the foundation: a single-scattering Rayleigh sky over a plane-parallel
// atmosphere, seen from the ground, in closed form. It gives the default picture a physically
// sensible sky until the full atmosphere model (Bruneton's precomputed scattering) replaces it.
// No aerosols, no ozone, no multiple scattering, no Earth curvature.
//
// Frame: local east-north-up at the observer (x east, y north, z up); the ground is z = 0. All
// direction arguments are unit vectors pointing away from the observer (view_dir: toward the
// sky point looked at; sun_dir: toward the sun's centre). Units: spectral radiance in
// W m^-2 sr^-1 nm^-1 and spectral irradiance in W m^-2 nm^-1, per RGB channel evaluated at
// RGB_WAVELENGTHS (680, 550, 440 nm). CPU reference and tests:
// atmosphere/src/analytic_sky_reference.hpp, tests/unit/analytic_sky_test.cpp.
//
// Derivation of the sky radiance. Let t be the vertical optical depth measured downward from the
// top of the atmosphere (t = 0 at the top, t = tau at the ground; tau is the Rayleigh vertical
// optical depth of the whole atmosphere). In a plane-parallel atmosphere the slant optical depth
// along a direction of relative airmass m is m times the vertical one, for any vertical profile
// of the scatterers. A scattering point at depth t on the view ray receives the sun attenuated by
// exp(-m_s t), scatters the fraction beta p(nu) ds per unit solid angle toward the observer
// (beta the scattering coefficient, p(nu) = P_R(nu) / (4 pi) the phase function in sr^-1 with
// P_R = 3/4 (1 + nu^2), nu the cosine of the scattering angle), and the result is attenuated by
// exp(-m_v (tau - t)) on the way down. Along the view ray beta ds = m_v dt (the slant optical
// depth element), so
//   L = E_sun p(nu) m_v integral_0^tau exp(-m_s t - m_v (tau - t)) dt
//     = E_sun p(nu) m_v exp(-m_v tau) (1 - exp(-(m_s - m_v) tau)) / (m_s - m_v)
//     = E_sun p(nu) m_v tau D(m_s tau, m_v tau),
//   D(a, b) = (exp(-a) - exp(-b)) / (b - a),
// i.e. the usual closed form E_sun T_top P_R(nu) / (4 pi) m_v (exp(-tau m_s) - exp(-tau m_v)) /
// (m_v - m_s) with T_top = 1 (nothing absorbs above the scattering layer in a Rayleigh-only
// model; the twilight fade below takes that slot). The test checks it against a brute-force
// integral over altitude with an exponential profile.
// D is symmetric, D(a, a) = exp(-a), and AnalyticSkyExpQuotient evaluates it without
// cancellation.
//
// Airmass: Kasten & Young (1989), "Revised optical air mass tables and approximation formula",
// Applied Optics 28(22), 4735-4738: m(z) = 1 / (cos z + 0.50572 (96.07995 - z_deg)^-1.6364), which
// stays finite at the horizon (m = 37.92 at z = 90 deg) where 1 / cos z does not. It is fitted on
// z in [0, 90 deg] (it diverges at 96.08 deg), so cosines are clamped to [0, 1] first.

#ifndef THALASSA_ATMOSPHERE_ANALYTIC_SKY_GLSL
#define THALASSA_ATMOSPHERE_ANALYTIC_SKY_GLSL

#include "common/definitions.glsl"

// Rayleigh vertical optical depth of the whole atmosphere at sea-level pressure (1013.25 hPa),
// dimensionless, at 680, 550 and 440 nm, from Bodhaine et al. (1999), "On Rayleigh optical depth
// calculations", J. Atmos. Oceanic Technol. 16, 1854-1861, eq. (30) with lambda in um:
//   tau(lambda) = 0.0021520 (1.0455996 - 341.29061 lambda^-2 - 0.90230850 lambda^2)
//                 / (1 + 0.0027059889 lambda^-2 - 85.968563 lambda^2).
// (The often quoted 0.0364 is this formula's value at 700 nm, not 680 nm.) The test recomputes
// these from the formula.
const vec3 ANALYTIC_SKY_RAYLEIGH_OPTICAL_DEPTH = vec3(0.0409592, 0.0970652, 0.2426054);

// Top-of-atmosphere spectral solar irradiance, W m^-2 nm^-1, at 680, 550, 440 nm: the ASTM G-173
// extraterrestrial spectrum as tabulated in 10 nm bins in Bruneton's 2017 demo (demo.cc,
// kSolarIrradiance).
const vec3 ANALYTIC_SKY_SOLAR_IRRADIANCE = vec3(1.474, 1.8504, 1.91198);

// Angular radius of the sun's disc, rad (as in Bruneton's 2017 demo).
const Number ANALYTIC_SKY_SUN_ANGULAR_RADIUS = 0.00467;

// Kasten & Young (1989) airmass coefficients: m = 1 / (cos z + A (B - z_deg)^-C).
const Number KASTEN_YOUNG_A = 0.50572;
const Number KASTEN_YOUNG_B = 96.07995;  // deg
const Number KASTEN_YOUNG_C = 1.6364;

// Below this |b - a| AnalyticSkyExpQuotient uses its series: the truncation error there is at most
// THRESHOLD^7 / 8! = 2.5e-12 relative, and above it the direct form loses at most
// eps / THRESHOLD relative to cancellation (6e-7 in float, 2e-15 in double).
const Number ANALYTIC_SKY_SERIES_THRESHOLD = 0.1;

// Twilight placeholder: with the sun below the horizon the sky is the sky of a sun on the
// horizon times exp(-(sin h / sin WIDTH)^2), h < 0 the sun's elevation (the sines, not the
// angles: GPU asin is imprecise, about 1e-4 relative on llvmpipe, which the square of a ratio
// near 2 amplifies; the two forms differ by under 0.2% for h > -12 deg). A Gaussian so that the fade
// starts with zero slope; the width makes the sky 1/55 of its sunset value at h = -6 deg (end
// of civil twilight), the order of magnitude of the observed drop. Not physics: the full model
// replaces it.
const Number ANALYTIC_SKY_TWILIGHT_WIDTH = 3.0 * DEGREE;

// Intervals of the sky-irradiance quadrature (3-point Gauss-Legendre on each, so 12 sky
// evaluations): relative error below 1.2e-4 for every sun position, which the test bounds at 2e-4
// against a fine 2D quadrature of AnalyticSkyRadiance.
const int ANALYTIC_SKY_IRRADIANCE_INTERVALS = 4;

// Relative optical airmass (dimensionless) of a direction with cos(zenith) = mu, Kasten & Young
// (1989). mu is clamped to [0, 1]: directions below the horizon get the horizon's 37.92.
Number AnalyticSkyAirmass(IN(Number) mu) {
  Number mu_clamped = clamp(mu, 0.0, 1.0);
  Number zenith_deg = acos(mu_clamped) / DEGREE;
  return 1.0 / (mu_clamped + KASTEN_YOUNG_A * pow(KASTEN_YOUNG_B - zenith_deg, -KASTEN_YOUNG_C));
}

// Rayleigh phase function, sr^-1, for the cosine nu of the scattering angle: 3 (1 + nu^2) /
// (16 pi), normalised to 1 over the sphere (depolarisation neglected).
Number AnalyticSkyRayleighPhase(IN(Number) nu) {
  return 3.0 / (16.0 * PI) * (1.0 + nu * nu);
}

// D(a, b) = (exp(-a) - exp(-b)) / (b - a) for a, b >= 0 (dimensionless), without cancellation.
// D is symmetric, so D = exp(-min(a, b)) phi(d) with d = |b - a| >= 0 and
// phi(d) = (1 - exp(-d)) / d = -expm1(-d) / d in (0, 1]: nothing overflows, and for small d
// (where 1 - exp(-d) cancels; GLSL has no expm1) phi is its Taylor series
// sum_k (-d)^k / (k + 1)! = 1 - d/2 (1 - d/3 (1 - d/4 (...))), summed in Horner form to d^6.
Number AnalyticSkyExpQuotient(IN(Number) a, IN(Number) b) {
  Number d = abs(b - a);
  Number phi;
  if (d < ANALYTIC_SKY_SERIES_THRESHOLD) {
    phi = 1.0 - d / 7.0;
    phi = 1.0 - d / 6.0 * phi;
    phi = 1.0 - d / 5.0 * phi;
    phi = 1.0 - d / 4.0 * phi;
    phi = 1.0 - d / 3.0 * phi;
    phi = 1.0 - d / 2.0 * phi;
  } else {
    phi = (1.0 - exp(-d)) / d;
  }
  return exp(-min(a, b)) * phi;
}

vec3 AnalyticSkyExpQuotient(IN(vec3) a, IN(vec3) b) {
  return vec3(AnalyticSkyExpQuotient(a.x, b.x), AnalyticSkyExpQuotient(a.y, b.y),
              AnalyticSkyExpQuotient(a.z, b.z));
}

// Dimensionless factor on all sky light for a sun of unit direction sun_dir: 1 with the sun's
// centre at or above the horizon, the twilight placeholder's Gaussian fade below (see
// ANALYTIC_SKY_TWILIGHT_WIDTH). Never NaN; tends to 0 for the sun far below the horizon.
Number AnalyticSkyTwilightFade(IN(vec3) sun_dir) {
  Number x = min(clamp(sun_dir.z, -1.0, 1.0), 0.0) / sin(ANALYTIC_SKY_TWILIGHT_WIDTH);
  return exp(-x * x);
}

// Fraction (dimensionless) of the sun's disc above the horizon, smoothed: smoothstep of the
// centre's elevation over [-r, r], r the disc's angular radius. Placeholder for the exact
// circular-segment area; it only shapes the last 0.5 deg of a sunset.
Number AnalyticSunVisibleFraction(IN(vec3) sun_dir) {
  Number sin_radius = sin(ANALYTIC_SKY_SUN_ANGULAR_RADIUS);
  return smoothstep(-sin_radius, sin_radius, sun_dir.z);
}

// Solid angle of the sun's disc, sr: 2 pi (1 - cos r) written as 4 pi sin^2(r / 2), which does
// not cancel in float (1 - cos r is 1.1e-5).
Number AnalyticSunSolidAngle() {
  Number s = sin(0.5 * ANALYTIC_SKY_SUN_ANGULAR_RADIUS);
  return 4.0 * PI * s * s;
}

// Direct solar irradiance at the ground on a surface facing the sun, W m^-2 nm^-1:
// E_sun exp(-tau m_s) times the visible fraction of the disc (0 once the sun has set).
vec3 AnalyticSunTransmittedIrradiance(IN(vec3) sun_dir) {
  Number m_s = AnalyticSkyAirmass(sun_dir.z);
  return ANALYTIC_SKY_SOLAR_IRRADIANCE * exp(-ANALYTIC_SKY_RAYLEIGH_OPTICAL_DEPTH * m_s) *
         AnalyticSunVisibleFraction(sun_dir);
}

// Direct solar irradiance on a horizontal surface (normal +z), W m^-2 nm^-1.
vec3 AnalyticSunHorizontalIrradiance(IN(vec3) sun_dir) {
  return AnalyticSunTransmittedIrradiance(sun_dir) * max(sun_dir.z, 0.0);
}

// Radiance of the sun's disc seen from the ground, W m^-2 sr^-1 nm^-1: E_sun exp(-tau m_s) / Omega
// for view directions within the disc's angular radius of sun_dir, 0 elsewhere. A uniform disc
// (no limb darkening). The part of the disc below the horizon is the caller's to hide (views with
// view_dir.z < 0 see the ground or the sea). Membership compares the chord |view - sun| with
// 2 sin(r / 2) rather than a dot product with cos r, which float cannot resolve finely enough.
vec3 AnalyticSunDiscRadiance(IN(vec3) view_dir, IN(vec3) sun_dir) {
  if (length(view_dir - sun_dir) > 2.0 * sin(0.5 * ANALYTIC_SKY_SUN_ANGULAR_RADIUS)) {
    return vec3(0.0);
  }
  Number m_s = AnalyticSkyAirmass(sun_dir.z);
  return ANALYTIC_SKY_SOLAR_IRRADIANCE * exp(-ANALYTIC_SKY_RAYLEIGH_OPTICAL_DEPTH * m_s) /
         AnalyticSunSolidAngle();
}

// The closed form of the derivation at the top, E_sun fade phase m_v tau D(m_s tau, m_v tau),
// for a view of cosine mu_v and a phase factor `phase` (sr^-1, or sr^-1 rad once integrated over
// azimuth), W m^-2 sr^-1 nm^-1 (times rad). Shared by the radiance and its azimuthal integral.
vec3 AnalyticSkySingleScattering(IN(Number) mu_v, IN(vec3) sun_dir, IN(Number) phase) {
  Number m_v = AnalyticSkyAirmass(mu_v);
  Number m_s = AnalyticSkyAirmass(sun_dir.z);
  vec3 tau = ANALYTIC_SKY_RAYLEIGH_OPTICAL_DEPTH;
  return ANALYTIC_SKY_SOLAR_IRRADIANCE * (AnalyticSkyTwilightFade(sun_dir) * phase * m_v) * tau *
         AnalyticSkyExpQuotient(tau * m_s, tau * m_v);
}

// Single-scattering sky radiance, W m^-2 sr^-1 nm^-1, seen from the ground along view_dir, for
// the sun along sun_dir (both unit, east-north-up). The sun itself is not included (add
// AnalyticSunDiscRadiance). view_dir.z < 0 is the caller's (ground or sea); its airmass is the
// horizon's here so the result stays finite. The sun below the horizon gives the twilight
// placeholder's fading sky of a sun on the horizon.
vec3 AnalyticSkyRadiance(IN(vec3) view_dir, IN(vec3) sun_dir) {
  Number nu = clamp(dot(view_dir, sun_dir), -1.0, 1.0);
  return AnalyticSkySingleScattering(view_dir.z, sun_dir, AnalyticSkyRayleighPhase(nu));
}

// Integral of AnalyticSkyRadiance over the view azimuth phi in [0, 2 pi) at the view cosine
// mu_v in [0, 1], W m^-2 sr^-1 nm^-1 rad. Everything but the phase function depends on mu_v
// only, and with nu = a + b cos(phi), a = mu_v mu_s, b = sqrt((1 - mu_v^2)(1 - mu_s^2)),
// integral_0^2pi (1 + nu^2) dphi = 2 pi (1 + a^2) + pi b^2 exactly.
vec3 AnalyticSkyAzimuthalIntegral(IN(Number) mu_v, IN(vec3) sun_dir) {
  Number mu_s = clamp(sun_dir.z, -1.0, 1.0);
  Number a = mu_v * mu_s;
  Number b2 = max((1.0 - mu_v * mu_v) * (1.0 - mu_s * mu_s), 0.0);
  Number phase_integral = 3.0 / (16.0 * PI) * (2.0 * PI * (1.0 + a * a) + PI * b2);
  return AnalyticSkySingleScattering(mu_v, sun_dir, phase_integral);
}

// Irradiance from the whole sky (sun excluded) on a horizontal surface at the ground,
// W m^-2 nm^-1: E = integral over the upper hemisphere of L cos(theta_v) domega. With the
// elevation e (mu_v = sin e, domega = cos e de dphi) and the azimuthal integral A(mu_v) in
// closed form, E = integral_0^(pi/2) sin e cos e A(sin e) de. The integrand varies fastest near
// the horizon (the airmass), so e = (pi / 2) u^2 clusters the nodes there, and u in [0, 1] is
// integrated by composite 3-point Gauss-Legendre on ANALYTIC_SKY_IRRADIANCE_INTERVALS intervals.
vec3 AnalyticSkyIrradiance(IN(vec3) sun_dir) {
  // 3-point Gauss-Legendre on [-1, 1]: nodes 0, +-sqrt(3/5), weights 8/9, 5/9.
  Number outer_node = sqrt(0.6);
  Number du = 1.0 / Number(ANALYTIC_SKY_IRRADIANCE_INTERVALS);
  vec3 irradiance = vec3(0.0);
  for (int i = 0; i < ANALYTIC_SKY_IRRADIANCE_INTERVALS; ++i) {
    for (int j = -1; j <= 1; ++j) {
      Number u = (Number(i) + 0.5 + 0.5 * Number(j) * outer_node) * du;
      Number weight = (j == 0 ? 8.0 / 9.0 : 5.0 / 9.0) * 0.5 * du;
      Number elevation = 0.5 * PI * u * u;
      Number mu_v = sin(elevation);
      // de = pi u du.
      irradiance += AnalyticSkyAzimuthalIntegral(mu_v, sun_dir) *
                    (mu_v * cos(elevation) * PI * u * weight);
    }
  }
  return irradiance;
}

#endif  // THALASSA_ATMOSPHERE_ANALYTIC_SKY_GLSL
