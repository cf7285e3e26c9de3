// Identity tests of the foundation's placeholder sky (shaders/atmosphere/analytic_sky.glsl),
// through its double-precision CPU reference. Frame: east-north-up (x east, y north, z up).

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

#include <gtest/gtest.h>

#include "analytic_sky_reference.hpp"
#include "reference_test_support.hpp"

namespace thalassa::glsl {
namespace {

using test::Direction;
using test::IsFiniteNonNegative;
using test::RelativeDifference;

double MaxRelativeDifference(const vec3& a, const vec3& b) {
  return std::max(
      {RelativeDifference(a.x, b.x), RelativeDifference(a.y, b.y), RelativeDifference(a.z, b.z)});
}

// D(a, b) = (exp(-a) - exp(-b)) / (b - a) in long double with expm1, the reference for the
// stable form: D = exp(-a) * (-expm1(-(b - a))) / (b - a).
long double ExpQuotientLongDouble(long double a, long double b) {
  const long double d = b - a;
  if (d == 0.0L) return std::exp(-a);
  return std::exp(-a) * -std::expm1(-d) / d;
}

// Single scattering seen from the ground, integrated over altitude z (m) with an exponential
// scatterer profile of scale height H: beta(z) = (tau / H) exp(-z / H), so that the vertical
// optical depth above z is tau exp(-z / H). Plane-parallel with the given airmasses: the sun's
// optical depth to z is m_s tau exp(-z / H), the view path's from the ground to z is
// m_v tau (1 - exp(-z / H)), and the path element is ds = m_v dz. Composite Simpson in long
// double on [0, 40 H]. Independent of the closed form's change of variable.
long double BruteForceSkyRadiance(long double solar_irradiance, long double tau, long double m_v,
                                  long double m_s, long double phase) {
  constexpr long double kScaleHeight = 8000.0L;  // m; the result does not depend on it.
  constexpr long double kTop = 40.0L * kScaleHeight;
  constexpr int kSteps = 20000;  // even
  const long double h = kTop / kSteps;
  auto integrand = [&](long double z) {
    const long double depth_above = tau * std::exp(-z / kScaleHeight);
    const long double beta = depth_above / kScaleHeight;
    return beta * std::exp(-m_s * depth_above) * std::exp(-m_v * (tau - depth_above)) * m_v;
  };
  long double sum = integrand(0.0L) + integrand(kTop);
  for (int i = 1; i < kSteps; ++i) sum += (i % 2 == 1 ? 4.0L : 2.0L) * integrand(i * h);
  return solar_irradiance * phase * sum * h / 3.0L;
}

TEST(AnalyticSky, OpticalDepthsFollowBodhaineFormula) {
  // Bodhaine et al. (1999), eq. (30), lambda in um.
  auto tau = [](double lambda) {
    const double l2 = lambda * lambda;
    return 0.0021520 * (1.0455996 - 341.29061 / l2 - 0.90230850 * l2) /
           (1.0 + 0.0027059889 / l2 - 85.968563 * l2);
  };
  const vec3 expected(tau(RGB_WAVELENGTHS.x / 1000.0), tau(RGB_WAVELENGTHS.y / 1000.0),
                      tau(RGB_WAVELENGTHS.z / 1000.0));
  EXPECT_LT(MaxRelativeDifference(ANALYTIC_SKY_RAYLEIGH_OPTICAL_DEPTH, expected), 1e-5);
}

TEST(AnalyticSky, AirmassLimits) {
  // Kasten & Young (1989): 1 at the zenith (to 3e-4), 37.92 at the horizon, ~1 / cos z between.
  EXPECT_NEAR(AnalyticSkyAirmass(1.0), 1.0, 3e-4);
  EXPECT_NEAR(AnalyticSkyAirmass(0.0), 37.92, 0.01);
  EXPECT_NEAR(AnalyticSkyAirmass(0.5), 2.0, 0.01);
  // Below the horizon: the horizon's value, not the fit's divergence at 96 deg.
  EXPECT_EQ(AnalyticSkyAirmass(-0.1), AnalyticSkyAirmass(0.0));
  EXPECT_EQ(AnalyticSkyAirmass(-1.0), AnalyticSkyAirmass(0.0));
}

TEST(AnalyticSky, RayleighPhaseIsNormalised) {
  // integral over the sphere = 2 pi integral_-1^1 P(nu) dnu, Simpson (exact for a quadratic).
  const double integral = 2.0 * PI * 2.0 / 6.0 *
                          (AnalyticSkyRayleighPhase(-1.0) + 4.0 * AnalyticSkyRayleighPhase(0.0) +
                           AnalyticSkyRayleighPhase(1.0));
  EXPECT_NEAR(integral, 1.0, 1e-14);
}

TEST(AnalyticSky, ClosedFormEqualsBruteForceIntegral) {
  const vec3 tau = ANALYTIC_SKY_RAYLEIGH_OPTICAL_DEPTH;
  const vec3 e_sun = ANALYTIC_SKY_SOLAR_IRRADIANCE;
  // Sun zeniths up to the horizon; view zeniths up to exactly horizontal; azimuths such that
  // m_v = m_s occurs (equal zeniths) as well as the sun's vertical.
  for (double sun_zenith : {0.0, 30.0, 60.0, 85.0, 90.0}) {
    for (double view_zenith : {0.0, 30.0, 60.0, 85.0, 89.0, 90.0}) {
      for (double view_azimuth : {0.0, 70.0, 180.0}) {
        const vec3 sun = Direction(sun_zenith, 0.0);
        const vec3 view = Direction(view_zenith, view_azimuth);
        const vec3 radiance = AnalyticSkyRadiance(view, sun);
        const double m_v = AnalyticSkyAirmass(view.z);
        const double m_s = AnalyticSkyAirmass(sun.z);
        const double phase = AnalyticSkyRayleighPhase(dot(view, sun));
        for (int c = 0; c < 3; ++c) {
          const long double expected = BruteForceSkyRadiance(e_sun[c], tau[c], m_v, m_s, phase);
          EXPECT_LT(RelativeDifference(radiance[c], static_cast<double>(expected)), 1e-6)
              << "sun zenith " << sun_zenith << " view zenith " << view_zenith << " azimuth "
              << view_azimuth << " channel " << c;
        }
      }
    }
  }
}

TEST(AnalyticSky, ExpQuotientMatchesLongDoubleOnBothSidesOfTheSeriesBranch) {
  const double threshold = ANALYTIC_SKY_SERIES_THRESHOLD;
  for (double a : {0.0, 0.04, 0.5, 3.0, 9.2}) {
    // d = |b - a| across the branch point, at the branch point, near and at 0, and far.
    for (double d : {0.0, 1e-15, 1e-12, 1e-8, 1e-4, 1e-2, threshold * (1.0 - 1e-12), threshold,
                     threshold * (1.0 + 1e-12), 0.2, 1.0, 5.0, 9.0}) {
      for (double sign : {1.0, -1.0}) {
        const double b = a + sign * d;
        if (b < 0.0) continue;
        const double value = AnalyticSkyExpQuotient(a, b);
        const long double expected = ExpQuotientLongDouble(a, b);
        EXPECT_LT(RelativeDifference(value, static_cast<double>(expected)), 1e-11)
            << "a " << a << " b " << b;
      }
    }
    // Continuity at the branch point: the two sides differ by the function's own change only.
    const double below = AnalyticSkyExpQuotient(a, a + threshold * (1.0 - 1e-12));
    const double above = AnalyticSkyExpQuotient(a, a + threshold * (1.0 + 1e-12));
    EXPECT_LT(RelativeDifference(below, above), 1e-11) << "a " << a;
    // D(a, a) = exp(-a) exactly.
    EXPECT_EQ(AnalyticSkyExpQuotient(a, a), std::exp(-a));
  }
}

TEST(AnalyticSky, RadianceIsContinuousAcrossEqualAirmasses) {
  // m_v = m_s when the view and the sun have the same zenith angle: radiance on either side.
  for (double zenith : {0.5, 30.0, 75.0, 89.5}) {
    const vec3 sun = Direction(zenith, 0.0);
    for (double step : {1e-9, 1e-6}) {
      const vec3 lower = AnalyticSkyRadiance(Direction(zenith - step, 120.0), sun);
      const vec3 at = AnalyticSkyRadiance(Direction(zenith, 120.0), sun);
      const vec3 upper = AnalyticSkyRadiance(Direction(zenith + step, 120.0), sun);
      // The radiance changes by its derivative (< 1 per degree relative) times the step.
      const double tolerance = 2.0 * step;
      EXPECT_LT(MaxRelativeDifference(lower, at), tolerance) << "zenith " << zenith;
      EXPECT_LT(MaxRelativeDifference(upper, at), tolerance) << "zenith " << zenith;
    }
  }
}

TEST(AnalyticSky, SymmetricAboutTheSunsVerticalPlane) {
  const double sun_azimuth = 37.0;
  for (double sun_zenith : {10.0, 50.0, 89.0, 93.0}) {
    const vec3 sun = Direction(sun_zenith, sun_azimuth);
    for (double view_zenith : {0.0, 20.0, 60.0, 90.0}) {
      for (double offset : {5.0, 45.0, 90.0, 170.0}) {
        const vec3 left = AnalyticSkyRadiance(Direction(view_zenith, sun_azimuth - offset), sun);
        const vec3 right = AnalyticSkyRadiance(Direction(view_zenith, sun_azimuth + offset), sun);
        EXPECT_GT(left.z, 0.0);
        EXPECT_LT(MaxRelativeDifference(left, right), 1e-12)
            << "sun zenith " << sun_zenith << " view zenith " << view_zenith << " offset "
            << offset;
      }
    }
  }
}

TEST(AnalyticSky, BrightensTowardTheHorizonForAHighSun) {
  // Views at least 90 deg in azimuth away from a sun within 30 deg of the zenith. Red, green and
  // luminance grow monotonically from 30 deg elevation down to the horizon. Blue grows too but
  // turns over within a few degrees of the horizon, where extinction along the 38-airmass path
  // wins (a real effect: the horizon is whiter than the sky above it); it must still be brighter
  // at the horizon than at the zenith.
  for (double sun_zenith : {0.0, 15.0, 30.0}) {
    const vec3 sun = Direction(sun_zenith, 0.0);
    for (double view_azimuth : {90.0, 135.0, 180.0, 270.0}) {
      vec3 previous = AnalyticSkyRadiance(Direction(60.0, view_azimuth), sun);
      for (double elevation = 29.75; elevation >= 0.0; elevation -= 0.25) {
        const vec3 current = AnalyticSkyRadiance(Direction(90.0 - elevation, view_azimuth), sun);
        EXPECT_GT(current.x, previous.x) << "elevation " << elevation;
        EXPECT_GT(current.y, previous.y) << "elevation " << elevation;
        if (elevation >= 5.0) {
          EXPECT_GT(current.z, previous.z) << "elevation " << elevation;
        }
        const double luminance = 0.2126 * current.x + 0.7152 * current.y + 0.0722 * current.z;
        const double previous_luminance =
            0.2126 * previous.x + 0.7152 * previous.y + 0.0722 * previous.z;
        EXPECT_GT(luminance, previous_luminance) << "elevation " << elevation;
        previous = current;
      }
      const vec3 horizon = AnalyticSkyRadiance(Direction(90.0, view_azimuth), sun);
      const vec3 zenith = AnalyticSkyRadiance(vec3(0.0, 0.0, 1.0), sun);
      EXPECT_GT(horizon.x, zenith.x);
      EXPECT_GT(horizon.y, zenith.y);
      EXPECT_GT(horizon.z, zenith.z);
    }
  }
}

TEST(AnalyticSky, IrradianceQuadratureMatchesFineHemisphereIntegral) {
  // E = integral of L cos(theta_v) domega over the upper hemisphere, by the midpoint rule in
  // elevation (fine) and azimuth (periodic, so spectrally accurate); symmetric about the sun's
  // vertical plane (tested above), so azimuth over [0, pi] twice.
  constexpr int kElevationSteps = 2000;
  constexpr int kAzimuthSteps = 180;
  for (double sun_zenith : {0.0, 45.0, 80.0, 89.9, 90.0, 95.0}) {
    const vec3 sun = Direction(sun_zenith, 0.0);
    vec3 expected(0.0);
    const double de = 0.5 * PI / kElevationSteps;
    const double dphi = PI / kAzimuthSteps;
    for (int i = 0; i < kElevationSteps; ++i) {
      const double elevation = (i + 0.5) * de;
      for (int j = 0; j < kAzimuthSteps; ++j) {
        const double azimuth = (j + 0.5) * dphi;
        const vec3 view(std::cos(elevation) * std::sin(azimuth),
                        std::cos(elevation) * std::cos(azimuth), std::sin(elevation));
        expected += AnalyticSkyRadiance(view, sun) *
                    (2.0 * std::sin(elevation) * std::cos(elevation) * de * dphi);
      }
    }
    const vec3 irradiance = AnalyticSkyIrradiance(sun);
    EXPECT_LT(MaxRelativeDifference(irradiance, expected), 2e-4) << "sun zenith " << sun_zenith;
  }
}

TEST(AnalyticSky, SunDiscRadianceIntegratesToTheTransmittedIrradiance) {
  for (double sun_zenith : {0.0, 45.0, 85.0}) {
    const vec3 sun = Direction(sun_zenith, 200.0);
    // The disc is uniform: radiance times its solid angle is the irradiance from the sun.
    const vec3 centre = AnalyticSunDiscRadiance(sun, sun);
    EXPECT_LT(MaxRelativeDifference(centre * AnalyticSunSolidAngle(),
                                    AnalyticSunTransmittedIrradiance(sun)),
              1e-12);
    const double radius = ANALYTIC_SKY_SUN_ANGULAR_RADIUS / DEGREE;
    const vec3 inside = AnalyticSunDiscRadiance(Direction(sun_zenith + 0.99 * radius, 200.0), sun);
    const vec3 outside = AnalyticSunDiscRadiance(Direction(sun_zenith + 1.01 * radius, 200.0), sun);
    EXPECT_EQ(inside, centre);
    EXPECT_EQ(outside, vec3(0.0));
    // Beer-Lambert along the sun's airmass, and cos-weighted on a horizontal surface.
    const vec3 expected = ANALYTIC_SKY_SOLAR_IRRADIANCE *
                          exp(-ANALYTIC_SKY_RAYLEIGH_OPTICAL_DEPTH * AnalyticSkyAirmass(sun.z));
    EXPECT_LT(MaxRelativeDifference(AnalyticSunTransmittedIrradiance(sun), expected), 1e-14);
    EXPECT_LT(MaxRelativeDifference(AnalyticSunHorizontalIrradiance(sun), expected * sun.z), 1e-14);
  }
  // The solid angle of a cone of half-angle r: 2 pi (1 - cos r).
  const double r = ANALYTIC_SKY_SUN_ANGULAR_RADIUS;
  EXPECT_LT(RelativeDifference(AnalyticSunSolidAngle(), 2.0 * PI * (1.0 - std::cos(r))), 1e-9);
}

TEST(AnalyticSky, SunSetsAndSkyFadesSmoothly) {
  // The direct sun is gone once the disc is below the horizon, half there at its centre.
  const double radius = ANALYTIC_SKY_SUN_ANGULAR_RADIUS / DEGREE;
  EXPECT_EQ(AnalyticSunTransmittedIrradiance(Direction(90.0 + 1.01 * radius, 0.0)), vec3(0.0));
  EXPECT_NEAR(AnalyticSunVisibleFraction(Direction(90.0, 0.0)), 0.5, 1e-12);
  EXPECT_EQ(AnalyticSunVisibleFraction(Direction(90.0 - 1.01 * radius, 0.0)), 1.0);
  // The sky is continuous as the sun crosses the horizon (it changes by less than 10 times its
  // value per degree of sun elevation there), then fades monotonically to ~0.
  const vec3 view = Direction(45.0, 180.0);
  const double step = 1e-7;  // deg
  const vec3 above = AnalyticSkyRadiance(view, Direction(90.0 - step, 0.0));
  const vec3 below = AnalyticSkyRadiance(view, Direction(90.0 + step, 0.0));
  EXPECT_LT(MaxRelativeDifference(above, below), 10.0 * 2.0 * step);
  vec3 previous = below;
  for (double depression = 1.0; depression <= 90.0; depression += 1.0) {
    const vec3 current = AnalyticSkyRadiance(view, Direction(90.0 + depression, 0.0));
    EXPECT_TRUE(IsFiniteNonNegative(current));
    EXPECT_LT(current.y, previous.y + 1e-300) << "depression " << depression;
    previous = current;
  }
  EXPECT_LT(AnalyticSkyRadiance(view, Direction(96.0, 0.0)).y, 0.05 * above.y);
}

TEST(AnalyticSky, FiniteForExtremeSunAndViewDirections) {
  for (double sun_zenith : {0.0, 89.9, 90.0, 95.0, 180.0}) {
    for (double sun_azimuth : {0.0, 123.0}) {
      const vec3 sun = Direction(sun_zenith, sun_azimuth);
      EXPECT_TRUE(IsFiniteNonNegative(AnalyticSunTransmittedIrradiance(sun)));
      EXPECT_TRUE(IsFiniteNonNegative(AnalyticSunHorizontalIrradiance(sun)));
      EXPECT_TRUE(IsFiniteNonNegative(AnalyticSkyIrradiance(sun)));
      for (double view_zenith = 0.0; view_zenith <= 90.0; view_zenith += 2.5) {
        for (double view_azimuth = 0.0; view_azimuth < 360.0; view_azimuth += 30.0) {
          const vec3 view = Direction(view_zenith, view_azimuth);
          EXPECT_TRUE(IsFiniteNonNegative(AnalyticSkyRadiance(view, sun)))
              << "sun " << sun_zenith << " view " << view_zenith << " " << view_azimuth;
          EXPECT_TRUE(IsFiniteNonNegative(AnalyticSunDiscRadiance(view, sun)));
        }
      }
      // Exactly horizontal views (z == 0 bit for bit), and the view equal to the sun.
      for (const vec3& view : {vec3(1.0, 0.0, 0.0), vec3(0.0, -1.0, 0.0), sun}) {
        EXPECT_TRUE(IsFiniteNonNegative(AnalyticSkyRadiance(view, sun)));
        EXPECT_TRUE(IsFiniteNonNegative(AnalyticSunDiscRadiance(view, sun)));
      }
    }
  }
}

}  // namespace
}  // namespace thalassa::glsl
