// Identity tests of the foundation's placeholder sea (shaders/ocean/flat_sea.glsl), through its
// double-precision CPU reference. Frame: east-north-up (x east, y north, z up), sea at z = 0.

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

#include <gtest/gtest.h>

#include "flat_sea_reference.hpp"
#include "thalassa/planet/camera_frame.hpp"

namespace thalassa::glsl {
namespace {

// Unit direction of a zenith angle and an azimuth (clockwise from north), both in degrees.
vec3 Direction(double zenith_deg, double azimuth_deg) {
  return thalassa::sun_direction(zenith_deg, azimuth_deg);
}

double RelativeDifference(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(b), std::numeric_limits<double>::min());
}

bool IsFiniteNonNegative(const vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0 &&
         v.y >= 0.0 && v.z >= 0.0;
}

// Fraction of the sun's power (on a horizontal unit area) that the glint sends into the upper
// hemisphere: rho(s) = integral over v.z > 0 of f(v, s) cos theta_v domega_v, with the BRDF
// f = FlatSeaGlintFactor / cos theta_s. Integrated in polar coordinates (alpha, psi) about the
// mirror direction, where the lobe is, with alpha = pi t^2 so that steps are fine near the peak:
// domega = sin(alpha) dalpha dpsi, dalpha = 2 pi t dt. Independent of the slope-space derivation.
double GlintDirectionalAlbedo(const vec3& sun, double slope_variance) {
  constexpr int kRadialSteps = 1500;
  constexpr int kAzimuthSteps = 240;
  const vec3 mirror(-sun.x, -sun.y, sun.z);
  // An orthonormal frame (t1, t2, mirror).
  const vec3 helper = std::abs(mirror.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  const vec3 t1 = normalize(cross(helper, mirror));
  const vec3 t2 = cross(mirror, t1);
  const double dt = 1.0 / kRadialSteps;
  const double dpsi = 2.0 * PI / kAzimuthSteps;
  double albedo = 0.0;
  for (int i = 0; i < kRadialSteps; ++i) {
    const double t = (i + 0.5) * dt;
    const double alpha = PI * t * t;
    const double dalpha = 2.0 * PI * t * dt;
    for (int j = 0; j < kAzimuthSteps; ++j) {
      const double psi = (j + 0.5) * dpsi;
      const vec3 view = std::cos(alpha) * mirror +
                        std::sin(alpha) * (std::cos(psi) * t1 + std::sin(psi) * t2);
      if (view.z <= 0.0) continue;
      albedo += FlatSeaGlintFactor(view, sun, slope_variance) / sun.z * view.z *
                std::sin(alpha) * dalpha * dpsi;
    }
  }
  return albedo;
}

// The same fraction counted on the facets: a facet of slope zeta (normal h) covers 1 / cos
// theta_h of horizontal area, intercepts E (s.h) per unit of its area, and mirrors the fraction
// R(s.h) of it, so rho(s) = integral R(s.h) (s.h) / (cos theta_h cos theta_s) p(zeta) dzeta over
// the facets that face the sun and send the light upward. Midpoint rule on [-12 sigma, 12 sigma]^2.
double FresnelWeightedInterceptedFlux(const vec3& sun, double slope_variance) {
  constexpr int kSteps = 800;
  const double half_width = 12.0 * std::sqrt(slope_variance);
  const double h = 2.0 * half_width / kSteps;
  double flux = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double zx = -half_width + (i + 0.5) * h;
    for (int j = 0; j < kSteps; ++j) {
      const double zy = -half_width + (j + 0.5) * h;
      const vec3 normal = normalize(vec3(-zx, -zy, 1.0));
      const double cos_incidence = dot(sun, normal);
      const vec3 view = 2.0 * cos_incidence * normal - sun;
      if (cos_incidence <= 0.0 || view.z <= 0.0) continue;
      flux += FlatSeaFresnel(cos_incidence) * cos_incidence / (normal.z * sun.z) *
              FlatSeaSlopePdf(zx, zy, slope_variance) * h * h;
    }
  }
  return flux;
}

TEST(FlatSea, FresnelMatchesExactFormulaAndLimits) {
  const double n = FLAT_SEA_REFRACTIVE_INDEX;
  // Normal incidence: ((n - 1) / (n + 1))^2; grazing: 1.
  EXPECT_NEAR(FlatSeaFresnel(1.0), (n - 1.0) * (n - 1.0) / ((n + 1.0) * (n + 1.0)), 1e-15);
  EXPECT_DOUBLE_EQ(FlatSeaFresnel(0.0), 1.0);
  // Clamped outside [0, 1].
  EXPECT_EQ(FlatSeaFresnel(-0.5), FlatSeaFresnel(0.0));
  EXPECT_EQ(FlatSeaFresnel(1.5), FlatSeaFresnel(1.0));
  // In between: Fresnel's sine and tangent laws (an independent form of the same equations),
  // R = (sin^2(i - t) / sin^2(i + t) + tan^2(i - t) / tan^2(i + t)) / 2, sin t = sin i / n.
  double previous = FlatSeaFresnel(1.0);
  for (double incidence_deg = 1.0; incidence_deg < 90.0; incidence_deg += 1.0) {
    const double i = incidence_deg * DEGREE;
    const double t = std::asin(std::sin(i) / n);
    const double r_s = std::pow(std::sin(i - t) / std::sin(i + t), 2.0);
    const double r_p = std::pow(std::tan(i - t) / std::tan(i + t), 2.0);
    const double value = FlatSeaFresnel(std::cos(i));
    EXPECT_NEAR(value, 0.5 * (r_s + r_p), 1e-14) << "incidence " << incidence_deg;
    // Unpolarised reflectance grows monotonically with incidence.
    EXPECT_GT(value, previous) << "incidence " << incidence_deg;
    previous = value;
  }
  // At Brewster's angle (tan i = n) i + t = 90 deg, so the p reflectance vanishes and R is half
  // the s reflectance, sin^2(i - t) / sin^2(i + t) = sin^2(2 i - 90 deg).
  const double brewster = std::atan(n);
  const double amplitude_s = std::sin(2.0 * brewster - 0.5 * PI);
  EXPECT_NEAR(FlatSeaFresnel(std::cos(brewster)), 0.5 * amplitude_s * amplitude_s, 1e-14);
}

TEST(FlatSea, CoxMunkSlopeVariance) {
  EXPECT_DOUBLE_EQ(FlatSeaSlopeVariance(0.0), 0.003);
  EXPECT_DOUBLE_EQ(FlatSeaSlopeVariance(10.0), 0.003 + 0.0512);
  EXPECT_DOUBLE_EQ(FlatSeaSlopeVariance(60.0), 0.003 + 0.3072);
  EXPECT_DOUBLE_EQ(FlatSeaSlopeVariance(-5.0), 0.003);
}

TEST(FlatSea, SlopePdfIntegratesToOneWithTotalVarianceSigmaSquared) {
  // Midpoint rule on [-10 sigma, 10 sigma]^2 (the tail beyond holds exp(-100) of the mass).
  constexpr int kSteps = 400;
  for (double sigma2 : {1e-4, 0.003, 0.0542, 0.3102}) {
    const double half_width = 10.0 * std::sqrt(sigma2);
    const double h = 2.0 * half_width / kSteps;
    double mass = 0.0;
    double second_moment = 0.0;
    for (int i = 0; i < kSteps; ++i) {
      const double zx = -half_width + (i + 0.5) * h;
      for (int j = 0; j < kSteps; ++j) {
        const double zy = -half_width + (j + 0.5) * h;
        const double p = FlatSeaSlopePdf(zx, zy, sigma2) * h * h;
        mass += p;
        second_moment += p * (zx * zx + zy * zy);
      }
    }
    EXPECT_NEAR(mass, 1.0, 1e-10) << "sigma^2 " << sigma2;
    // Cox & Munk's variance is the total one, <zx^2 + zy^2>.
    EXPECT_NEAR(second_moment / sigma2, 1.0, 1e-10) << "sigma^2 " << sigma2;
  }
}

TEST(FlatSea, GlintBrdfIsReciprocal) {
  // f(v, s) = GlintFactor(v, s) / cos theta_s must equal f(s, v) (away from the grazing clamp).
  for (double zenith_a : {0.0, 20.0, 50.0, 80.0}) {
    for (double zenith_b : {5.0, 35.0, 70.0, 85.0}) {
      for (double azimuth : {150.0, 180.0, 200.0}) {
        const vec3 a = Direction(zenith_a, 0.0);
        const vec3 b = Direction(zenith_b, azimuth);
        const double f_ab = FlatSeaGlintFactor(a, b, 0.05) / b.z;
        const double f_ba = FlatSeaGlintFactor(b, a, 0.05) / a.z;
        EXPECT_GT(f_ab, 0.0);
        EXPECT_LT(RelativeDifference(f_ab, f_ba), 1e-12);
      }
    }
  }
}

TEST(FlatSea, GlintConservesEnergy) {
  // The fraction of the sun's power sent back up by the glint is at most 1 (it is about R, a few
  // percent, except at grazing sun). Without shadowing it can exceed 1 for a grazing sun over a
  // rough sea (f grows as 1 / cos theta_s), so the sun stops at 80 deg here.
  for (double wind_speed : {0.0, 5.0, 20.0, 60.0}) {
    for (double sun_zenith : {0.0, 30.0, 60.0, 80.0}) {
      const vec3 sun = Direction(sun_zenith, 25.0);
      const double albedo = GlintDirectionalAlbedo(sun, FlatSeaSlopeVariance(wind_speed));
      EXPECT_GT(albedo, 0.0);
      EXPECT_LE(albedo, 1.0) << "wind " << wind_speed << " sun zenith " << sun_zenith;
    }
  }
}

TEST(FlatSea, GlintReflectsTheFresnelWeightedFluxOnTheFacets) {
  // The radiance formula's 1 / (4 cos^4 theta_h cos theta_v) is the Jacobian between facet
  // slopes and view directions: integrated over the views, the glint must return exactly the
  // Fresnel-weighted flux that the facets intercept. The cases keep the lobe inside the upper
  // hemisphere, where both quadratures agree to 3e-10; a wrong power of cos theta_h would be off
  // by ~sigma^2 / 2 relative, 5e-5 at sigma^2 = 1e-4.
  for (double slope_variance : {1e-4, 1e-3, 0.003}) {
    for (double sun_zenith : {0.0, 30.0, 60.0}) {
      const vec3 sun = Direction(sun_zenith, 110.0);
      const double albedo = GlintDirectionalAlbedo(sun, slope_variance);
      const double flux = FresnelWeightedInterceptedFlux(sun, slope_variance);
      EXPECT_LT(RelativeDifference(albedo, flux), 1e-8)
          << "sigma^2 " << slope_variance << " sun zenith " << sun_zenith;
    }
  }
}

TEST(FlatSea, GlintReflectsTheFresnelFractionOfTheSunForSmallSlopes) {
  // As sigma -> 0 the glint becomes the mirror image of the sun: the reflected fraction of its
  // power tends to R(theta_s), with a relative error of order sigma^2 (measured: 3e-4 at
  // sigma^2 = 1e-4 for a sun at 60 deg).
  for (double sun_zenith : {0.0, 30.0, 60.0, 75.0}) {
    const vec3 sun = Direction(sun_zenith, 110.0);
    const double fresnel = FlatSeaFresnel(sun.z);
    const double error_rough = std::abs(GlintDirectionalAlbedo(sun, 1e-3) / fresnel - 1.0);
    const double error_smooth = std::abs(GlintDirectionalAlbedo(sun, 1e-4) / fresnel - 1.0);
    EXPECT_LT(error_smooth, 1e-3) << "sun zenith " << sun_zenith;
    EXPECT_LT(error_smooth, 0.2 * error_rough + 1e-9) << "sun zenith " << sun_zenith;
  }
}

TEST(FlatSea, RadianceCombinesMirrorGlintAndDeepWater) {
  const vec3 deep = FLAT_SEA_DEFAULT_DEEP_REFLECTANCE;
  for (double sun_zenith : {20.0, 70.0}) {
    const vec3 sun = Direction(sun_zenith, 0.0);
    const vec3 irradiance = AnalyticSunHorizontalIrradiance(sun) + AnalyticSkyIrradiance(sun);
    for (double view_zenith : {0.0, 40.0, 80.0}) {
      const vec3 view = Direction(view_zenith, 160.0);
      const double fresnel = FlatSeaFresnel(view.z);
      const vec3 expected =
          fresnel * AnalyticSkyRadiance(vec3(-view.x, -view.y, view.z), sun) +
          FlatSeaSunGlint(view, sun, 7.0) + (1.0 - fresnel) * deep * irradiance / PI;
      const vec3 radiance = FlatSeaRadiance(view, sun, 7.0, deep);
      for (int c = 0; c < 3; ++c) {
        EXPECT_LT(RelativeDifference(radiance[c], expected[c]), 1e-14);
      }
      EXPECT_EQ(radiance, FlatSeaRadianceWithIrradiance(view, sun, 7.0, deep, irradiance));
    }
    // At an exactly horizontal view R = 1: the sea is a perfect mirror plus the glint.
    const vec3 horizontal(0.0, -1.0, 0.0);
    const vec3 expected =
        AnalyticSkyRadiance(horizontal, sun) + FlatSeaSunGlint(horizontal, sun, 7.0);
    const vec3 radiance = FlatSeaRadiance(horizontal, sun, 7.0, deep);
    for (int c = 0; c < 3; ++c) EXPECT_LT(RelativeDifference(radiance[c], expected[c]), 1e-14);
  }
}

TEST(FlatSea, FiniteForExtremeSunViewAndWind) {
  const vec3 deep = FLAT_SEA_DEFAULT_DEEP_REFLECTANCE;
  for (double wind_speed : {0.0, 60.0}) {
    for (double sun_zenith : {0.0, 89.9, 90.0, 95.0, 180.0}) {
      const vec3 sun = Direction(sun_zenith, 0.0);
      for (double view_zenith = 0.0; view_zenith <= 90.0; view_zenith += 2.5) {
        for (double view_azimuth = 0.0; view_azimuth < 360.0; view_azimuth += 15.0) {
          const vec3 view = Direction(view_zenith, view_azimuth);
          const vec3 radiance = FlatSeaRadiance(view, sun, wind_speed, deep);
          EXPECT_TRUE(IsFiniteNonNegative(radiance))
              << "wind " << wind_speed << " sun " << sun_zenith << " view " << view_zenith
              << " " << view_azimuth;
        }
      }
      // Exactly horizontal views, the view toward the sun, and v = -s (no mirroring facet).
      for (const vec3& view : {vec3(0.0, 1.0, 0.0), vec3(0.0, -1.0, 0.0), vec3(1.0, 0.0, 0.0),
                               sun, -sun, vec3(-sun.x, -sun.y, sun.z)}) {
        EXPECT_TRUE(IsFiniteNonNegative(FlatSeaRadiance(view, sun, wind_speed, deep)));
        EXPECT_TRUE(std::isfinite(FlatSeaGlintFactor(view, sun, 0.0)));
      }
    }
  }
  // The sun below the horizon leaves no glint. A horizontal view near the mirror direction of a
  // low sun sees a strong glint, finite thanks to the clamp of cos theta_v: with R <= 1,
  // p <= 1 / (pi sigma^2) and cos theta_h near 1 it is below 1 / (4 pi sigma^2 cos_min).
  EXPECT_EQ(FlatSeaSunGlint(Direction(85.0, 180.0), Direction(95.0, 0.0), 0.0), vec3(0.0));
  const double sigma2 = FlatSeaSlopeVariance(0.0);
  const double grazing = FlatSeaGlintFactor(vec3(0.0, -1.0, 0.0), Direction(89.0, 0.0), sigma2);
  EXPECT_GT(grazing, 0.0);
  EXPECT_LT(grazing, 1.0 / (4.0 * PI * sigma2 * FLAT_SEA_MIN_COS_VIEW) * 1.001);
}

}  // namespace
}  // namespace thalassa::glsl
