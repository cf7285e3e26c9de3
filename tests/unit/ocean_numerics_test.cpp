// The stiff regions of the ocean's CPU reference functions (issue 7, point 2; DESIGN section 4,
// "Numerics"): shaders/ocean/smith.glsl, ross_brdf.glsl and trochoids.glsl compiled as C++ in
// double, swept where they cancel, divide by small numbers or tend to a limit, and compared with
// independent high-precision evaluations (long double, series, continued fractions) or with their
// limits. The GPU (float) versions are compared with these references over the same sweeps in
// tests/gpu/numerics_test.cpp; docs/numerics.md tabulates both. Frame: the tangent frame of the
// mean surface (x along the wind, y across, z the mean normal); slope variances are per axis.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "reference_test_support.hpp"
#include "ross_brdf_reference.hpp"
#include "trochoids_reference.hpp"

namespace thalassa::glsl {
namespace {

using test::RelativeDifference;

constexpr long double kPiL = 3.141592653589793238462643383279502884L;
constexpr double kDoubleMin = std::numeric_limits<double>::min();  // smallest normal double

// Unit direction in the tangent frame from a zenith angle (from z) and an azimuth (from x toward
// y), both in degrees; exactly horizontal at 90 deg.
vec3 TangentDirection(double zenith_deg, double azimuth_deg) {
  const double phi = azimuth_deg * DEGREE;
  if (zenith_deg == 90.0) return vec3(std::cos(phi), std::sin(phi), 0.0);
  const double theta = zenith_deg * DEGREE;
  return vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// ---------------------------------------------------------------------------------------------
// a. Smith's Lambda(a), eq. 8, from a = 1e-4 to 1e4.

// Lambda from the printed closed form (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2 in long double
// (64-bit significand, epsilon 1.1e-19, glibc's erfcl within a few ulp): the cancellation costs
// a factor 2 a^2, so it is good to 1e-17 for a <= 5.
long double ClosedFormLambda(long double a) {
  return 0.5L * (std::exp(-a * a) / (a * std::sqrt(kPiL)) - std::erfc(a));
}

// Lambda from Laplace's continued fraction for erfcx (A&S 7.1.14) with `terms` terms, in long
// double, written without cancellation as Lambda = exp(-a^2) r / (2 sqrt(pi) a (a + r)), r the
// fraction's tail (see shaders/ocean/smith.glsl). With 4000 terms its truncation error is below
// long double's rounding for a >= 1.5; independent of the closed form (no erfc at all).
long double ContinuedFractionLambda(long double a, int terms = 4000) {
  long double tail = 0.0L;
  for (int k = terms; k >= 1; --k) tail = 0.5L * k / (a + tail);
  return 0.5L * std::exp(-a * a) * tail / (std::sqrt(kPiL) * a * (a + tail));
}

// The high-precision reference: the closed form below a = 2, the continued fraction above (the
// two agree to 1e-17 on [2, 5], checked below).
long double ReferenceLambda(long double a) {
  return a < 2.0L ? ClosedFormLambda(a) : ContinuedFractionLambda(a);
}

// The sweep: a log-spaced from 1e-4 to 1e4, 50 points per decade, plus both sides of every
// boundary between the forms of smith.glsl.
std::vector<double> LambdaSweep() {
  std::vector<double> a;
  for (int i = 0; i <= 8 * 50; ++i) a.push_back(std::pow(10.0, -4.0 + i / 50.0));
  for (double edge : {OCEAN_SMITH_SPLIT_A, OCEAN_SMITH_ASYMPTOTIC_A, OCEAN_SMITH_MAX_A}) {
    a.push_back(edge);
    a.push_back(std::nextafter(edge, 0.0));
  }
  std::sort(a.begin(), a.end());
  return a;
}

TEST(OceanNumerics, LambdaReferencesAgree) {
  // The two high-precision evaluations, independent of each other and of the code under test,
  // agree where both are accurate: this is what makes them a reference.
  double worst = 0.0;
  for (double a = 2.0; a <= 5.0; a += 0.05) {
    const long double closed = ClosedFormLambda(a);
    const long double fraction = ContinuedFractionLambda(a);
    worst = std::max(worst, static_cast<double>(std::abs(closed / fraction - 1.0L)));
  }
  std::printf("Lambda references: closed form vs continued fraction on [2, 5]: %.3g\n", worst);
  EXPECT_LT(worst, 1e-16);
}

TEST(OceanNumerics, LambdaIsStableFromTinyToHugeA) {
  // Worst relative error per range of smith.glsl, where the reference is a normal double; where
  // it is not (a > 26.6), the result must be below the normal range too (absolute error below
  // 2.2e-308) and never negative.
  struct Range {
    const char* name;
    double lo, hi, bound;
    double worst = 0.0, worst_a = 0.0;
  };
  std::vector<Range> ranges = {
      {"[1e-4, 1.2) polynomial", 0.0, OCEAN_SMITH_SPLIT_A, 6e-6},
      {"[1.2, 6) continued fraction", OCEAN_SMITH_SPLIT_A, OCEAN_SMITH_ASYMPTOTIC_A, 6e-6},
      {"[6, 28) asymptotic series", OCEAN_SMITH_ASYMPTOTIC_A, OCEAN_SMITH_MAX_A, 1e-8},
      {"[28, 1e4] zero", OCEAN_SMITH_MAX_A, 1e30, 0.0}};
  int subnormal = 0;
  for (double a : LambdaSweep()) {
    const double lambda = OceanSmithLambda(a);
    ASSERT_TRUE(std::isfinite(lambda) && lambda >= 0.0) << "a " << a;
    const long double reference = ReferenceLambda(a);
    if (reference < kDoubleMin) {
      ++subnormal;
      EXPECT_LT(lambda, kDoubleMin) << "a " << a;
      continue;
    }
    const double error = RelativeDifference(lambda, static_cast<double>(reference));
    for (Range& range : ranges) {
      if (a >= range.lo && a < range.hi) {
        if (error > range.worst) range.worst = error, range.worst_a = a;
        EXPECT_LE(error, range.bound) << range.name << ", a " << a;
      }
    }
  }
  EXPECT_EQ(OceanSmithLambda(OCEAN_SMITH_MAX_A), 0.0);
  EXPECT_GT(subnormal, 100);  // the sweep does reach the underflow
  for (const Range& range : ranges) {
    std::printf("Lambda %-30s worst relative error %.3g at a = %.4g\n", range.name, range.worst,
                range.worst_a);
  }
}

TEST(OceanNumerics, PrintedLambdaCancelsCatastrophically) {
  // For the record, why the stable forms exist: the printed form evaluated with the erfc that a
  // shader has (A&S 7.1.26, absolute error 1.5e-7) is wrong by 1 % at a = 3 and by 35 % at
  // a = 5, growing as exp(a^2); with a correctly rounded erfc it loses only 2 a^2 ulps (in float
  // 3e-6 at a = 5), but no GLSL erfc is correctly rounded.
  for (double a : {2.0, 3.0, 4.0, 5.0}) {
    const double printed = 0.5 * (std::exp(-a * a) / (a * std::sqrt(PI)) - OceanErfc(a));
    const double reference = static_cast<double>(ReferenceLambda(a));
    const float printed_float =
        0.5f *
        (std::exp(-float(a) * float(a)) / (float(a) * std::sqrt(float(PI))) - std::erfc(float(a)));
    std::printf(
        "printed Lambda at a = %.0f: relative error %.3g (A&S erfc, double), %.3g (float)\n", a,
        RelativeDifference(printed, reference), RelativeDifference(printed_float, reference));
    EXPECT_LT(RelativeDifference(OceanSmithLambda(a), reference), 1e-6) << a;
    if (a >= 3.0) {
      EXPECT_GT(RelativeDifference(printed, reference), 1e-2) << a;
    }
  }
}

TEST(OceanNumerics, LambdaTendsToItsLimits) {
  const double sqrt_pi = std::sqrt(PI);
  // a -> 0 (grazing): 2 a sqrt(pi) Lambda = exp(-a^2) - a sqrt(pi) erfc(a) = 1 - a sqrt(pi)
  // + a^2 + O(a^3), so Lambda ~ 1 / (2 a sqrt(pi)) with a relative correction - a sqrt(pi).
  for (double a = 1e-9; a <= 1e-1; a *= 10.0) {
    const double scaled = 2.0 * a * sqrt_pi * OceanSmithLambda(a);
    EXPECT_NEAR(scaled, 1.0 - a * sqrt_pi, 2.0 * a * a + 1e-7) << "a " << a;
  }
  // Below OCEAN_SMITH_MIN_A a is raised to it: finite, 2.8e8 at most, also at a = 0.
  EXPECT_EQ(OceanSmithLambda(0.0), OceanSmithLambda(OCEAN_SMITH_MIN_A));
  EXPECT_LT(OceanSmithLambda(0.0), 2.9e8);
  // a -> inf (the zenith): Lambda 4 sqrt(pi) a^3 exp(a^2) = 1 - 3 / (2 a^2) + 15 / (4 a^4) - ...,
  // an enveloping series: the error of the two-term truncation is below the third term. Taken
  // in logarithms (exp(a^2) overflows from a = 26.6), while Lambda is a normal double.
  for (double a = 2.0; a <= 26.0; a *= 1.1) {
    const double lambda = OceanSmithLambda(a);
    const double ratio = std::exp(std::log(lambda) + a * a + std::log(4.0 * sqrt_pi * a * a * a));
    EXPECT_NEAR(ratio, 1.0 - 1.5 / (a * a), 15.0 / (4.0 * std::pow(a, 4.0)) + 1e-5) << "a " << a;
  }
  EXPECT_EQ(OceanSmithLambda(1e30), 0.0);
  EXPECT_EQ(OceanSmithLambda(std::numeric_limits<double>::infinity()), 0.0);
  // Decreasing everywhere, continuous across the boundaries between the forms (to their own
  // accuracy), and 0 at the zenith.
  const std::vector<double> sweep = LambdaSweep();
  for (std::size_t i = 1; i < sweep.size(); ++i) {
    EXPECT_LE(OceanSmithLambda(sweep[i]), OceanSmithLambda(sweep[i - 1])) << "a " << sweep[i];
  }
  for (double edge : {OCEAN_SMITH_SPLIT_A, OCEAN_SMITH_ASYMPTOTIC_A}) {
    EXPECT_LT(
        RelativeDifference(OceanSmithLambda(std::nextafter(edge, 0.0)), OceanSmithLambda(edge)),
        6e-6)
        << edge;
  }
  EXPECT_EQ(OceanSmithA(1.0, 0.0), OCEAN_SMITH_MAX_A);
  EXPECT_EQ(OceanSmithLambdaToward(vec3(0.0, 0.0, 1.0), vec2(0.01, 0.02)), 0.0);
}

TEST(OceanNumerics, CosLambdaAndFacingAreaAreStableToTheHorizon) {
  // cos theta Lambda = a sigma_sin Lambda(a) for cos theta = a sigma_sin, from its own form
  // (smith.glsl), against the reference, for the slope "sigma sin" of a calm sea near the zenith
  // (1e-6), a rough one (0.1) and the largest (1); down to the horizon (cos theta -> 0), where it
  // tends to sigma_sin / (2 sqrt(pi)).
  double worst = 0.0;
  for (double sigma_sin : {1e-6, 0.1, 1.0}) {
    for (double a : LambdaSweep()) {
      const double cos_theta = a * sigma_sin;
      if (cos_theta > 1.0) continue;
      const long double reference = cos_theta * ReferenceLambda(a);
      const double cos_lambda = OceanSmithCosLambda(cos_theta, sigma_sin);
      ASSERT_TRUE(std::isfinite(cos_lambda) && cos_lambda >= 0.0);
      if (reference < kDoubleMin) {
        EXPECT_LT(cos_lambda, kDoubleMin);
        continue;
      }
      const double error = RelativeDifference(cos_lambda, static_cast<double>(reference));
      worst = std::max(worst, error);
      EXPECT_LE(error, 6e-6) << "a " << a << " sigma_sin " << sigma_sin;
      const double facing = OceanSmithFacingArea(cos_theta, sigma_sin);
      EXPECT_LE(RelativeDifference(facing, static_cast<double>(cos_theta + reference)), 6e-6);
    }
    const double horizon = sigma_sin / (2.0 * std::sqrt(PI));
    EXPECT_NEAR(OceanSmithCosLambda(0.0, sigma_sin), horizon, 1e-16 * horizon);
    EXPECT_NEAR(OceanSmithFacingArea(0.0, sigma_sin), horizon, 1e-16 * horizon);
    // The limit is approached linearly in cos theta: slope -1/2 (the a sqrt(pi) term above),
    // so |f(cos) - f(0)| <= cos theta.
    for (double cos_theta = 1e-2 * sigma_sin; cos_theta > 1e-12 * sigma_sin; cos_theta *= 0.1) {
      EXPECT_LE(std::abs(OceanSmithCosLambda(cos_theta, sigma_sin) - horizon), cos_theta);
    }
  }
  std::printf("cos theta Lambda: worst relative error %.3g\n", worst);
}

// ---------------------------------------------------------------------------------------------
// b. 1 - sqrt(1 - x): the trochoid's slope variance (Appendix A).

// 1 - sqrt(1 - s^2) in long double: its Taylor series sum_n c_n y^n (c_1 = 1/2,
// c_(n+1) = c_n (2n - 1) / (2n + 2), all positive: no cancellation) for y = s^2 < 1/4, and above
// it the closed form with 1 - s^2 = (1 - s)(1 + s) (exact factors; 1 - sqrt() loses < 1 digit).
long double ReferenceTrochoidVariance(long double s) {
  const long double y = s * s;
  if (y < 0.25L) {
    long double term = 0.5L * y;
    long double sum = 0.0L;
    for (int n = 1; n < 200 && term > 1e-25L * sum; ++n) {
      sum += term;
      term *= y * (2.0L * n - 1.0L) / (2.0L * n + 2.0L);
    }
    return sum;
  }
  return 1.0L - std::sqrt((1.0L - s) * (1.0L + s));
}

TEST(OceanNumerics, TrochoidSlopeVarianceFromFlatToTheCusp) {
  // Steepness s = k h from 1e-8 (sigma^2 = 5e-17, where the printed 1 - sqrt(1 - s^2) is 0 in
  // double) to the cusp s = 1, approached as 1 - 1e-k: there 1 - s^2 cancels unless it is
  // written (1 - s)(1 + s).
  std::vector<double> steepness;
  for (int i = 0; i <= 8 * 20; ++i) steepness.push_back(std::pow(10.0, -8.0 + i / 20.0));
  for (int k = 1; k <= 15; ++k) steepness.push_back(1.0 - std::pow(10.0, -k));
  double worst_small = 0.0, worst_cusp = 0.0;
  for (double s : steepness) {
    const double variance = TrochoidSlopeVariance(s);
    const double error =
        RelativeDifference(variance, static_cast<double>(ReferenceTrochoidVariance(s)));
    (s < 0.5 ? worst_small : worst_cusp) = std::max(s < 0.5 ? worst_small : worst_cusp, error);
    EXPECT_LE(error, 4e-16) << "s " << s;
    // Symmetric in the sign of s.
    EXPECT_EQ(TrochoidSlopeVariance(-s), variance);
  }
  std::printf("trochoid slope variance: worst relative error %.3g (s < 0.5), %.3g (s -> 1)\n",
              worst_small, worst_cusp);
  // The limits: s^2 / 2 as s -> 0, 1 at and beyond the cusp.
  EXPECT_EQ(TrochoidSlopeVariance(0.0), 0.0);
  EXPECT_DOUBLE_EQ(TrochoidSlopeVariance(1e-8), 0.5e-16);
  EXPECT_EQ(TrochoidSlopeVariance(1.0), 1.0);
  EXPECT_EQ(TrochoidSlopeVariance(3.0), 1.0);
  // The printed form has no correct digit at s = 1e-8 (it returns 1.1e-16 for 5e-17).
  EXPECT_GT(RelativeDifference(1.0 - std::sqrt(1.0 - 1e-16), 0.5e-16), 0.5);
}

// ---------------------------------------------------------------------------------------------
// c. sigma -> 0: the reflected sun stays finite and keeps its energy.

// The integral over view directions v of g(v) cos theta_v d omega_v, in polar coordinates
// (alpha, psi) about the mirror direction m = (-l_x, -l_y, l_z) of l, where the glint is;
// alpha = s tan(t atan(pi / s)), t uniform in (0, 1), puts half the radial steps within the
// lobe's angular scale s. Views below the horizon do not count (v_z <= 0).
double ViewHemisphereIntegral(const vec3& l, double lobe_scale,
                              const std::function<double(const vec3&)>& g, int radial_steps,
                              int azimuth_steps) {
  const vec3 m(-l.x, -l.y, l.z);
  const vec3 helper = std::abs(m.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  const vec3 t1 = normalize(cross(helper, m));
  const vec3 t2 = cross(m, t1);
  const double k = std::atan(PI / lobe_scale);
  const double dt = 1.0 / radial_steps;
  const double dpsi = 2.0 * PI / azimuth_steps;
  double sum = 0.0;
  for (int i = 0; i < radial_steps; ++i) {
    const double tangent = std::tan((i + 0.5) * dt * k);
    const double alpha = lobe_scale * tangent;
    const double dalpha = lobe_scale * k * (1.0 + tangent * tangent) * dt;
    for (int j = 0; j < azimuth_steps; ++j) {
      const double psi = (j + 0.5) * dpsi;
      const vec3 v =
          std::cos(alpha) * m + std::sin(alpha) * (std::cos(psi) * t1 + std::sin(psi) * t2);
      if (v.z <= 0.0) continue;
      sum += g(v) * v.z * std::sin(alpha) * dalpha * dpsi;
    }
  }
  return sum;
}

TEST(OceanNumerics, ReflectedSunKeepsItsEnergyAsSigmaVanishes) {
  // Eq. 15 per unit L_sun Omega_sun, integrated over the view directions with cos theta_v, is
  // the sun's reflected flux per unit of its flux on a horizontal surface, times cos theta_l. As
  // sigma -> 0 the sea becomes a mirror and the integral must tend to cos theta_l F(cos theta_l)
  // (Schlick's eq. 14 at the sun's incidence), although the BRDF tends to a Dirac: the sun's
  // minimum variance (OCEAN_SUN_MIN_SLOPE_VARIANCE, sec. 5.1) stops the narrowing at the disc's
  // size. Swept from a rough sea (sigma^2 = 1e-2 per axis) to 0, isotropic and anisotropic,
  // for the sun from the zenith to 88 deg.
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  double worst_clamped = 0.0;
  for (double zenith : {0.0, 30.0, 60.0, 80.0, 88.0}) {
    const vec3 l = TangentDirection(zenith, 45.0);
    const double expected = l.z * OceanSchlickFresnel(l.z, r);
    std::string row;
    for (double variance : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-9, 0.0}) {
      for (double anisotropy : {1.0, 0.3}) {
        const vec2 slope_variance(variance, anisotropy * variance);
        const double lobe = 2.0 * std::sqrt(std::max(variance, OCEAN_SUN_MIN_SLOPE_VARIANCE));
        // The integrand is finite everywhere, including at its peak (the mirror direction).
        const double peak = OceanReflectedSun(vec3(-l.x, -l.y, l.z), l, slope_variance, r);
        ASSERT_TRUE(std::isfinite(peak) && peak > 0.0) << variance;
        // Toward a grazing sun the glint narrows across the plane of incidence by cos theta_l
        // (d zeta_y = sin theta_v d phi / (cos theta_v + cos theta_l)): the azimuthal steps
        // about the mirror direction grow as 1 / cos theta_l to resolve it.
        const int azimuth_steps = std::min(2048, static_cast<int>(128.0 / l.z));
        const double flux = ViewHemisphereIntegral(
            l, lobe, [&](const vec3& v) { return OceanReflectedSun(v, l, slope_variance, r); }, 200,
            azimuth_steps);
        const double error = flux / expected - 1.0;
        if (anisotropy == 1.0) {
          char cell[32];
          std::snprintf(cell, sizeof(cell), " %+.2e", error);
          row += cell;
        }
        if (variance <= OCEAN_SUN_MIN_SLOPE_VARIANCE) {
          // Below the clamp: the same values as at the clamp, and the mirror's flux to 1e-4
          // plus the clamp's own O(sigma^2 / cos^2 theta_l) (measured: 2e-5 up to 80 deg,
          // 1.1e-4 to 1.5e-4 at 88 deg with the quadrature, where 0.2 sigma^2 / cos^2 = 2.2e-4).
          EXPECT_EQ(peak, OceanReflectedSun(vec3(-l.x, -l.y, l.z), l,
                                            vec2(OCEAN_SUN_MIN_SLOPE_VARIANCE), r));
          worst_clamped = std::max(worst_clamped, std::abs(error));
          EXPECT_LT(std::abs(error), 1e-4 + 0.2 * OCEAN_SUN_MIN_SLOPE_VARIANCE / (l.z * l.z))
              << "theta_l " << zenith << " sigma^2 " << variance;
        } else {
          // Above it, a rough sea's albedo differs from the mirror's by O(sigma^2 / cos^2):
          // bounded, and shrinking with sigma^2 (checked down to the clamp).
          EXPECT_LT(std::abs(error), 1e-4 + 40.0 * variance / (l.z * l.z))
              << "theta_l " << zenith << " sigma^2 " << variance << " anisotropy " << anisotropy;
        }
      }
    }
    std::printf("reflected sun flux / (cos F) - 1, theta_l %4.1f, sigma^2 1e-2 .. 0:%s\n", zenith,
                row.c_str());
  }
  std::printf("reflected sun, sigma^2 at or below the clamp: worst relative flux error %.3g\n",
              worst_clamped);
}

// ---------------------------------------------------------------------------------------------
// d. theta_v -> 90 deg (grazing): finite, continuous, the right limits.

TEST(OceanNumerics, GrazingViewLimits) {
  // Each function of the view at theta_v = 90 - 10^-k deg tends to its value at exactly 90 deg,
  // linearly in cos theta_v (|f(theta) - f(90)| <= 50 |f(90)| cos theta_v, or the absolute
  // equivalent where f(90) = 0), and f(90) is the documented limit.
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  const vec2 slope_variance(0.02, 0.01);
  const vec3 sun = TangentDirection(80.0, 180.0);  // its glint is toward azimuth 0, 80 deg
  const double sigma_sin = OceanSmithSigmaSin(TangentDirection(90.0, 0.0), slope_variance);
  struct Limit {
    const char* name;
    std::function<double(const vec3&)> f;
    double expected_at_90;  // NaN: no closed form, only continuity is checked
  };
  const double view_variance =
      OceanSlopeVarianceToward(TangentDirection(90.0, 0.0), slope_variance);
  const double sigma_v = std::sqrt(view_variance);
  const std::vector<Limit> limits = {
      {"facing area", [&](const vec3& v) { return OceanSmithFacingAreaToward(v, slope_variance); },
       sigma_sin / (2.0 * std::sqrt(PI))},
      {"cos Lambda", [&](const vec3& v) { return OceanSmithCosLambdaToward(v, slope_variance); },
       sigma_sin / (2.0 * std::sqrt(PI))},
      {"reflected sun", [&](const vec3& v) { return OceanReflectedSun(v, sun, slope_variance, r); },
       std::numeric_limits<double>::quiet_NaN()},
      {"Ross BRDF", [&](const vec3& v) { return OceanRossBrdf(v, sun, slope_variance, r); },
       std::numeric_limits<double>::quiet_NaN()},
      {"Schlick", [&](const vec3& v) { return OceanSchlickFresnel(v.z, r); }, 1.0},
      {"effective Fresnel",
       [&](const vec3& v) {
         return OceanEffectiveFresnel(v.z, OceanSlopeVarianceToward(v, slope_variance), r);
       },
       r + (1.0 - r) / (1.0 + OCEAN_EFFECTIVE_FRESNEL_SCALE * sigma_v * std::sqrt(sigma_v))},
  };
  for (const Limit& limit : limits) {
    const double at_90 = limit.f(TangentDirection(90.0, 0.0));
    ASSERT_TRUE(std::isfinite(at_90)) << limit.name;
    EXPECT_GT(at_90, 0.0) << limit.name;
    if (!std::isnan(limit.expected_at_90)) {
      EXPECT_NEAR(at_90, limit.expected_at_90, 1e-15 * limit.expected_at_90) << limit.name;
    }
    double worst_slope = 0.0;
    for (int k = 0; k <= 12; ++k) {
      const vec3 v = TangentDirection(90.0 - std::pow(10.0, -k), 0.0);
      const double value = limit.f(v);
      ASSERT_TRUE(std::isfinite(value)) << limit.name << " k " << k;
      const double slope = std::abs(value - at_90) / (std::abs(at_90) * v.z);
      worst_slope = std::max(worst_slope, slope);
      EXPECT_LE(slope, 50.0) << limit.name << " at 90 - 1e-" << k << " deg";
    }
    std::printf("grazing %-18s value at 90 deg %.6g, |f - f(90)| / (f(90) cos theta_v) <= %.3g\n",
                limit.name, at_90, worst_slope);
  }
  // Below the horizon nothing is seen.
  EXPECT_EQ(OceanReflectedSun(TangentDirection(90.0 + 1e-9, 0.0), sun, slope_variance, r), 0.0);
}

// ---------------------------------------------------------------------------------------------
// e. The effective Fresnel (eq. 26) as sigma_v -> 0 and at grazing incidence.

TEST(OceanNumerics, EffectiveFresnelTendsToSchlick) {
  // With x = 1 - cos theta_v and c = OCEAN_EFFECTIVE_FRESNEL_SCALE, F-bar - Schlick =
  // (1 - R) (x^e / (1 + c sigma^1.5) - x^5), e = 5 exp(-2.69 sigma); |x^e - x^5| <= |e - 5|
  // max_t x^t |ln x| <= 13.45 sigma / (e (5 - 13.45 sigma)) and x^e c sigma^1.5 <= c sigma^1.5,
  // so |F-bar - Schlick| <= (1 - R) (1.1 sigma + 22.7 sigma^1.5) for sigma <= 0.1: the fit is
  // continuous at sigma_v = 0, where it is Schlick's eq. 14 (to rounding: pow(x, 5) vs x^5).
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  double worst_at_zero = 0.0;
  for (double cos_theta : {1.0, 0.999999, 0.9, 0.5, 0.1, 1e-3, 1e-6, 1e-9, 0.0}) {
    const double schlick = OceanSchlickFresnel(cos_theta, r);
    worst_at_zero = std::max(worst_at_zero,
                             RelativeDifference(OceanEffectiveFresnel(cos_theta, 0.0, r), schlick));
    EXPECT_NEAR(OceanEffectiveFresnel(cos_theta, 0.0, r), schlick, 1e-15) << cos_theta;
    EXPECT_EQ(OceanEffectiveFresnel(cos_theta, -1e-3, r), OceanEffectiveFresnel(cos_theta, 0.0, r));
    for (double sigma = 1e-8; sigma <= 0.1; sigma *= 10.0) {
      const double fresnel = OceanEffectiveFresnel(cos_theta, sigma * sigma, r);
      ASSERT_TRUE(std::isfinite(fresnel));
      EXPECT_GE(fresnel, r);
      EXPECT_LE(fresnel, 1.0);
      EXPECT_LE(std::abs(fresnel - schlick),
                (1.0 - r) * (1.1 * sigma + 22.7 * sigma * std::sqrt(sigma)) + 1e-15)
          << "cos theta_v " << cos_theta << " sigma_v " << sigma;
    }
  }
  std::printf("effective Fresnel at sigma_v = 0 vs Schlick: worst relative difference %.3g\n",
              worst_at_zero);
  // Grazing: x = 1, x^e = 1 for every sigma: F-bar = R + (1 - R) / (1 + c sigma^1.5) exactly;
  // normal incidence: x = 0, F-bar = R, for every sigma including a slope variance far beyond
  // the documented [0, 1], where the exponent 5 exp(-2.69 sigma) underflows to 0 (pow(0, 0)).
  for (double variance : {0.0, 1e-6, 0.02, 1.0, 1e4, 1e6}) {
    const double sigma = std::sqrt(variance);
    EXPECT_DOUBLE_EQ(
        OceanEffectiveFresnel(0.0, variance, r),
        r + (1.0 - r) / (1.0 + OCEAN_EFFECTIVE_FRESNEL_SCALE * sigma * std::sqrt(sigma)));
    EXPECT_EQ(OceanEffectiveFresnel(1.0, variance, r), r) << variance;
  }
}

// ---------------------------------------------------------------------------------------------
// f. The stereographic mapping near its singular point, the nadir.

TEST(OceanNumerics, StereographicMappingIsAccurateNearTheNadir) {
  // U(r) = (r_x, r_y) / (1 + r_z) for a ray r at a distance eps (radians) from the nadir: its
  // radius is cot(eps / 2) ~ 2 / eps up to OCEAN_SKY_MAP_MAX_RADIUS (eps = 2e-3), then held
  // there. 1 + r_z ~ eps^2 / 2 is a cancellation: the rounding of r_z (1.1e-16) becomes a
  // relative error 2.2e-16 / eps^2 of U (5e-11 at the cap in double, 3 % in float), although the
  // direction of r is known to 1e-16 / eps (from r_x and r_y). The reference is the exact
  // mapping of the direction r / |r| of the rounded vector, in long double:
  // U = (r_x, r_y) (|r| - r_z) / (r_x^2 + r_y^2), no cancellation for r_z < 0.
  double worst = 0.0;
  for (double eps = 1.0; eps > 1e-9; eps *= 0.5) {
    for (double azimuth : {0.0, 37.0, 90.0, 200.0}) {
      const vec3 r(std::sin(eps) * std::cos(azimuth * DEGREE),
                   std::sin(eps) * std::sin(azimuth * DEGREE), -std::cos(eps));
      const long double rx = r.x, ry = r.y, rz = r.z;
      const long double rho2 = rx * rx + ry * ry;
      const long double scale = (std::sqrt(rho2 + rz * rz) - rz) / rho2;
      const long double radius = std::sqrt(rho2) * scale;
      const vec2 u = OceanStereographic(r);
      ASSERT_TRUE(std::isfinite(u.x) && std::isfinite(u.y)) << eps;
      EXPECT_LE(length(u), OCEAN_SKY_MAP_MAX_RADIUS * (1.0 + 1e-15)) << eps;
      if (radius < 0.999 * OCEAN_SKY_MAP_MAX_RADIUS) {
        const double error = std::hypot(u.x - static_cast<double>(rx * scale),
                                        u.y - static_cast<double>(ry * scale)) /
                             static_cast<double>(radius);
        worst = std::max(worst, error);
        EXPECT_LT(error, 1e-15) << "eps " << eps << " azimuth " << azimuth;
        // The derivative along a tangent direction dr (r . dr = 0): finite and, against its
        // long double reference with d = 1 + r_z written as rho^2 / (|r| - r_z), accurate.
        const vec3 dr = normalize(cross(r, vec3(0.3, -0.4, 0.5)));
        const vec2 du = OceanStereographicDerivative(r, dr);
        const long double d = rho2 / (std::sqrt(rho2 + rz * rz) - rz);
        const long double du_x = dr.x / d - rx * (dr.z / (d * d));
        const long double du_y = dr.y / d - ry * (dr.z / (d * d));
        const double derivative_error =
            std::hypot(du.x - static_cast<double>(du_x), du.y - static_cast<double>(du_y)) /
            static_cast<double>(std::hypot(du_x, du_y));
        worst = std::max(worst, derivative_error);
        EXPECT_LT(derivative_error, 1e-14) << "eps " << eps << " azimuth " << azimuth;
      } else {
        // At and beyond the cap: radius OCEAN_SKY_MAP_MAX_RADIUS along (r_x, r_y).
        EXPECT_NEAR(length(u), OCEAN_SKY_MAP_MAX_RADIUS, 1e-9) << eps;
        EXPECT_NEAR(std::atan2(u.y, u.x), std::atan2(r.y, r.x), 1e-12) << eps;
        const vec2 du = OceanStereographicDerivative(r, vec3(1.0, -1.0, 0.5));
        EXPECT_TRUE(std::isfinite(du.x) && std::isfinite(du.y)) << eps;
      }
    }
  }
  std::printf("stereographic mapping near the nadir: worst relative error %.3g\n", worst);
  // The nadir itself and the zenith.
  EXPECT_EQ(OceanStereographic(vec3(0.0, 0.0, -1.0)), vec2(OCEAN_SKY_MAP_MAX_RADIUS, 0.0));
  EXPECT_EQ(OceanStereographic(vec3(0.0, 0.0, 1.0)), vec2(0.0, 0.0));
}

}  // namespace
}  // namespace thalassa::glsl
