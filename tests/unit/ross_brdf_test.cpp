// Identity tests of the Ross et al. ocean BRDF (shaders/ocean/ross_brdf.glsl and
// shaders/ocean/smith.glsl; Bruneton, Neyret & Holzschuch 2010, sec. 4-5), through its
// double-precision CPU reference. Frame: the tangent frame of the mean surface (x along the wind,
// y across, z the mean normal) unless a test says otherwise. Slope variances are per axis.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "reference_test_support.hpp"
#include "ross_brdf_reference.hpp"
#include "thalassa/ocean/effective_fresnel.hpp"
#include "trochoids_reference.hpp"

namespace thalassa::glsl {
namespace {

using test::RelativeDifference;

constexpr long double kPiL = 3.141592653589793238462643383279502884L;

// Unit direction in the tangent frame from a zenith angle (from z) and an azimuth (from x
// toward y), both in degrees; exactly horizontal at 90 deg (cos(pi / 2) is 6e-17 in double).
vec3 TangentDirection(double zenith_deg, double azimuth_deg) {
  const double phi = azimuth_deg * DEGREE;
  if (zenith_deg == 90.0) return vec3(std::cos(phi), std::sin(phi), 0.0);
  const double theta = zenith_deg * DEGREE;
  return vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

bool IsFinite(double x) { return std::isfinite(x); }
bool IsFinite(const vec2& x) { return std::isfinite(x.x) && std::isfinite(x.y); }

// Gauss-Legendre nodes and weights on [-1, 1] (Newton's iteration on P_n from the Chebyshev
// guesses, as in Numerical Recipes' gauleg): exact for polynomials of degree 2n - 1.
struct GaussLegendre {
  std::vector<double> x;
  std::vector<double> w;
};

GaussLegendre MakeGaussLegendre(int n) {
  GaussLegendre rule;
  rule.x.resize(n);
  rule.w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(PI * (i + 0.75) / (n + 0.5));
    double derivative = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0;
      double p1 = 0.0;
      for (int k = 1; k <= n; ++k) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
      }
      derivative = n * (z * p0 - p1) / (z * z - 1.0);
      const double step = p0 / derivative;
      z -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.x[i] = z;
    rule.w[i] = 2.0 / ((1.0 - z * z) * derivative * derivative);
  }
  return rule;
}

// The integral over the slope plane of a function g(zeta) that vanishes where v.f <= 0, i.e.
// beyond the line v_z - v_x zeta_x - v_y zeta_y = 0, and whose derivative may jump there (the
// kink of max(v.f, 0)). The quadrature is centred on 0 and scaled by sigma: zeta = (sigma_x s_x,
// sigma_y s_y), so that p is the standard normal in s; then rotated so that the kink is the grid
// line t1 = v_z / c (s = t1 e1 + t2 e2, e1 = (v_x sigma_x, v_y sigma_y) / c, c = |.|), and the
// square [-half_width, half_width]^2 (the normal's mass beyond 8 is 1e-15) is cut into unit
// panels of Gauss-Legendre points, with a panel edge on the kink: the integrand is smooth on each
// panel. d^2 zeta = sigma_x sigma_y d^2 s.
double IntegrateOverVisibleSlopes(const vec3& v, const vec2& slope_variance,
                                  const std::function<double(const vec2&)>& g,
                                  const GaussLegendre& rule, double half_width = 8.0) {
  const vec2 sigma(std::sqrt(slope_variance.x), std::sqrt(slope_variance.y));
  vec2 e1(1.0, 0.0);
  double t1_max = half_width;
  const double c = std::hypot(v.x * sigma.x, v.y * sigma.y);
  if (c > 0.0) {
    e1 = vec2(v.x * sigma.x, v.y * sigma.y) / c;
    t1_max = std::min(half_width, v.z / c);
  }
  const vec2 e2(-e1.y, e1.x);
  if (t1_max <= -half_width) return 0.0;
  const int panels_1 = std::max(1, static_cast<int>(std::ceil(t1_max + half_width)));
  const int panels_2 = static_cast<int>(std::ceil(2.0 * half_width));
  const double width_1 = (t1_max + half_width) / panels_1;
  const double width_2 = 2.0 * half_width / panels_2;
  double sum = 0.0;
  for (int i = 0; i < panels_1; ++i) {
    for (size_t a = 0; a < rule.x.size(); ++a) {
      const double t1 = -half_width + width_1 * (i + 0.5 * (rule.x[a] + 1.0));
      for (int j = 0; j < panels_2; ++j) {
        for (size_t b = 0; b < rule.x.size(); ++b) {
          const double t2 = -half_width + width_2 * (j + 0.5 * (rule.x[b] + 1.0));
          const vec2 s = t1 * e1 + t2 * e2;
          const vec2 zeta(sigma.x * s.x, sigma.y * s.y);
          sum += rule.w[a] * rule.w[b] * g(zeta);
        }
      }
    }
  }
  return sum * 0.25 * width_1 * width_2 * sigma.x * sigma.y;
}

// The pairs of per-axis slope standard deviations (sigma_x, sigma_y) of the identity tests:
// isotropic from 1e-3 to 0.7, and anisotropic ones (along-wind larger, smaller, and extreme).
const std::vector<vec2>& SigmaPairs() {
  static const std::vector<vec2> pairs = {{1e-3, 1e-3}, {0.01, 0.01}, {0.1, 0.1},  {0.3, 0.3},
                                          {0.7, 0.7},   {0.2, 0.05},  {0.05, 0.2}, {0.7, 1e-3},
                                          {1e-3, 0.5},  {0.3, 0.7}};
  return pairs;
}

// ---------------------------------------------------------------------------------------------
// a. Eq. 11: q_vn^e integrates to 1.

// The printed eq. 9, a = (2 sigma_w^2 tan theta)^(-1/2), for the record (see the test below).
double PrintedSmithA(const vec3& v, const vec2& slope_variance) {
  const double sin_theta = std::hypot(v.x, v.y);
  return 1.0 / std::sqrt(2.0 * OceanSlopeVarianceToward(v, slope_variance) * sin_theta / v.z);
}

TEST(RossBrdf, VisibleSlopeDistributionIntegratesToOne) {
  // Eq. 11, the identity that decides eq. 9: integral q_vn^e(zeta, v) d^2 zeta = 1, for theta_v
  // from 0 to 89.9 deg, several azimuths, per-axis sigma from 1e-3 to 0.7 (isotropic and
  // anisotropic). The quadrature's own error is below 1e-12 (at theta_v = 0, where
  // cos theta (1 + Lambda) = 1 exactly, it integrates p alone); what is measured is the error
  // of Lambda (A&S 7.1.26 and the continued fraction, 3e-6 relative at most on Lambda).
  // Bound: the 1e-3.
  const GaussLegendre rule = MakeGaussLegendre(8);
  double worst = 0.0;
  std::string worst_case;
  for (const vec2& sigma : SigmaPairs()) {
    const vec2 slope_variance = sigma * sigma;
    for (double zenith : {0.0, 10.0, 30.0, 50.0, 70.0, 80.0, 85.0, 89.0, 89.9}) {
      for (double azimuth : {0.0, 30.0, 90.0, 135.0, 200.0}) {
        if (zenith == 0.0 && azimuth != 0.0) continue;
        const vec3 v = TangentDirection(zenith, azimuth);
        const double integral = IntegrateOverVisibleSlopes(
            v, slope_variance,
            [&](const vec2& zeta) { return OceanVisibleSlopePdfE(zeta, v, slope_variance); }, rule);
        const double error = std::abs(integral - 1.0);
        EXPECT_LT(error, 1e-3) << "sigma " << sigma.x << " " << sigma.y << " theta_v " << zenith
                               << " phi_v " << azimuth;
        if (error > worst) {
          worst = error;
          worst_case = "sigma (" + std::to_string(sigma.x) + ", " + std::to_string(sigma.y) +
                       ") theta_v " + std::to_string(zenith) + " phi_v " + std::to_string(azimuth);
        }
      }
    }
  }
  std::printf("eq. 11: worst |integral q_vn^e - 1| = %.3g at %s\n", worst, worst_case.c_str());

  // The printed eq. 9 fails the identity: it agrees with the corrected one only at 45 deg
  // (tan = tan^2 = 1), and where both make Lambda negligible. Measured with sigma^2 = 0.1 per
  // axis: the integral with the printed a is 1.000 at theta_v = 45 deg, 1.048 at 70 deg,
  // 1.282 at 80 deg and 5.03 at 89 deg; with the corrected a, 1 to 1e-7 at all of them.
  const vec2 slope_variance(0.1, 0.1);
  for (double zenith : {45.0, 70.0, 80.0, 89.0}) {
    const vec3 v = TangentDirection(zenith, 20.0);
    const double facing_integral = IntegrateOverVisibleSlopes(
        v, slope_variance,
        [&](const vec2& zeta) {
          return OceanSlopePdf(zeta, slope_variance) *
                 std::max(v.z - v.x * zeta.x - v.y * zeta.y, 0.0);
        },
        rule);
    const double printed =
        facing_integral / (v.z * (1.0 + OceanSmithLambda(PrintedSmithA(v, slope_variance))));
    const double corrected = facing_integral / OceanSmithFacingAreaToward(v, slope_variance);
    std::printf(
        "eq. 11 at theta_v %.0f deg, sigma^2 0.1: integral %.6f with the corrected "
        "eq. 9, %.6f with the printed one\n",
        zenith, corrected, printed);
    EXPECT_NEAR(corrected, 1.0, 1e-5);
    if (zenith == 45.0) {
      EXPECT_NEAR(printed, 1.0, 1e-5);
    } else {
      EXPECT_GT(std::abs(printed - 1.0), 0.01) << "theta_v " << zenith;
    }
  }
}

TEST(RossBrdf, AnisotropicSmithAReducesToTheIsotropicForm) {
  // For isotropic slopes of total variance sigma^2 (sigma^2 / 2 per axis) a = cot theta / sigma
  // in every azimuth: OceanSmithA with sigma_sin = sigma sin theta.
  for (double total : {1e-6, 0.003, 0.054, 0.31}) {
    const vec2 slope_variance(0.5 * total, 0.5 * total);
    for (double zenith : {0.0, 1.0, 30.0, 60.0, 85.0, 89.9, 90.0}) {
      const double cos_theta = std::cos(zenith * M_PI / 180.0);
      const double sigma_sin = std::sqrt(total * (1.0 - cos_theta * cos_theta));
      const double isotropic = OceanSmithLambda(OceanSmithA(cos_theta, sigma_sin));
      for (double azimuth : {0.0, 70.0, 250.0}) {
        const vec3 v = TangentDirection(zenith, azimuth);
        const double ross = OceanSmithLambdaToward(v, slope_variance);
        EXPECT_LE(std::abs(ross - isotropic), 1e-12 * isotropic + 1e-300)
            << "sigma^2 " << total << " theta " << zenith << " phi " << azimuth;
        EXPECT_LT(RelativeDifference(OceanSmithFacingAreaToward(v, slope_variance),
                                     OceanSmithFacingArea(cos_theta, sigma_sin)),
                  1e-12);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// b. Lambda and erfc.

// Lambda(a) in long double from the closed form eq. 8, Lambda = (exp(-a^2) / (a sqrt(pi)) -
// erfc(a)) / 2. The two terms cancel to Lambda / erfc ~ 1 / (2 a^2) for large a; with long
// double's 64-bit significand (epsilon 1.1e-19) the rounding left is below 1e-16 relative for the
// a <= 5.5 where Lambda > 1e-15.
long double ReferenceLambda(long double a) {
  return 0.5L * (std::exp(-a * a) / (a * std::sqrt(kPiL)) - std::erfc(a));
}

TEST(RossBrdf, SmithLambdaMatchesLongDoubleClosedForm) {
  // Over its whole range: a from 1e-8 (a horizon 1e-8 rad away for sigma = 1) to
  // OCEAN_SMITH_MAX_A on a logarithmic grid, 40 points per decade.
  double worst = 0.0;
  double worst_a = 0.0;
  for (int step = 0; step <= 40 * 9; ++step) {
    const double a = std::min(1e-8 * std::pow(10.0, step / 40.0), OCEAN_SMITH_MAX_A * 0.999999);
    const double reference = static_cast<double>(ReferenceLambda(a));
    const double lambda = OceanSmithLambda(a);
    ASSERT_TRUE(std::isfinite(lambda));
    if (reference > 1e-15) {
      const double error = RelativeDifference(lambda, reference);
      if (error > worst) {
        worst = error;
        worst_a = a;
      }
      EXPECT_LE(error, 1e-5) << "a " << a;
    } else {
      // Below 1e-15 Lambda only needs to be negligible next to the 1 it is added to.
      EXPECT_LE(lambda, 1e-15) << "a " << a;
    }
    // cos theta Lambda from its own cancellation-free form, with cos theta = a sigma_sin.
    for (double sigma_sin : {1e-5, 0.1, 1.0}) {
      const double cos_theta = a * sigma_sin;
      if (cos_theta > 1.0) continue;
      const double cos_lambda = OceanSmithCosLambda(cos_theta, sigma_sin);
      EXPECT_LE(std::abs(cos_lambda - cos_theta * reference),
                1e-5 * cos_theta * reference + 1e-15 * sigma_sin)
          << "a " << a << " sigma_sin " << sigma_sin;
    }
  }
  std::printf("Lambda: worst relative error %.3g at a = %.4g\n", worst, worst_a);
  // The ends: 0 from OCEAN_SMITH_MAX_A on (the zenith), finite and large at a = 0 (the horizon).
  EXPECT_EQ(OceanSmithLambda(OCEAN_SMITH_MAX_A), 0.0);
  EXPECT_EQ(OceanSmithLambda(1e30), 0.0);
  EXPECT_TRUE(std::isfinite(OceanSmithLambda(0.0)));
  EXPECT_GT(OceanSmithLambda(0.0), 1e8);
  // At the horizon cos theta Lambda is exactly sigma_sin / (2 sqrt(pi)).
  EXPECT_NEAR(OceanSmithCosLambda(0.0, 0.3), 0.3 / (2.0 * std::sqrt(PI)), 1e-16);
  EXPECT_EQ(OceanSmithA(1.0, 0.0), OCEAN_SMITH_MAX_A);
  EXPECT_EQ(OceanSmithA(0.0, 0.5), OCEAN_SMITH_MIN_A);
}

TEST(RossBrdf, ErfcMatchesStdErfc) {
  // Abramowitz & Stegun 7.1.26 promises an absolute error of at most 1.5e-7 for x >= 0; allow
  // 2e-7. Negative arguments go through erfc(x) = 2 - erfc(-x), with the same absolute error.
  double worst = 0.0;
  for (double x = -6.0; x <= 6.0 + 1e-9; x += 1e-3) {
    const double error = std::abs(OceanErfc(x) - std::erfc(x));
    worst = std::max(worst, error);
    EXPECT_LE(error, 2e-7) << "x " << x;
  }
  std::printf("erfc: worst absolute error on [-6, 6]: %.3g\n", worst);
  EXPECT_NEAR(OceanErfc(0.0), 1.0, 2e-7);
}

// ---------------------------------------------------------------------------------------------
// c. The BRDF: eq. 13 as printed, reciprocity, energy.

TEST(RossBrdf, BrdfIsEq13AndReciprocal) {
  // OceanRossBrdf evaluates eq. 13 after simplification; here eq. 13 is evaluated as printed,
  // q_vn(zeta_h, v, l) F(v.h) / (4 h_z^3 cos theta_l v.h), from OceanVisibleSlopePdf. Then
  // brdf(v, l) = brdf(l, v).
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  for (const vec2& sigma : {vec2(0.05, 0.05), vec2(0.2, 0.07), vec2(0.03, 0.3)}) {
    const vec2 slope_variance = sigma * sigma;
    for (double zenith_v : {0.0, 20.0, 60.0, 85.0, 89.9}) {
      for (double zenith_l : {5.0, 40.0, 75.0, 89.0}) {
        for (double azimuth : {0.0, 45.0, 160.0, 180.0, 290.0}) {
          const vec3 v = TangentDirection(zenith_v, 30.0);
          const vec3 l = TangentDirection(zenith_l, 30.0 + azimuth);
          const vec3 h = normalize(v + l);
          const vec2 zeta_h = OceanHalfVectorSlopes(v, l);
          const double printed = OceanVisibleSlopePdf(zeta_h, v, l, slope_variance) *
                                 OceanSchlickFresnel(dot(v, h), r) /
                                 (4.0 * std::pow(h.z, 3.0) * l.z * dot(v, h));
          const double brdf = OceanRossBrdf(v, l, slope_variance, r);
          EXPECT_LT(RelativeDifference(brdf, printed), 1e-12)
              << "theta_v " << zenith_v << " theta_l " << zenith_l << " dphi " << azimuth;
          EXPECT_LT(RelativeDifference(OceanRossBrdf(l, v, slope_variance, r), brdf), 1e-13);
          // Eq. 15 per unit L_sun Omega_sun is brdf cos theta_l, for variances above the clamp.
          EXPECT_LT(RelativeDifference(OceanReflectedSun(v, l, slope_variance, r), brdf * l.z),
                    1e-12);
        }
      }
    }
  }
}

// The directional albedo integral over the light hemisphere of g(l) cos theta_l d omega_l, for
// g(l) = brdf(v, l) (times an optional factor), in polar coordinates (alpha, psi) about the
// mirror direction m = (-v_x, -v_y, v_z), where the lobe is. alpha = s tan(t atan(pi / s)) for
// t uniform in (0, 1) puts half the radial steps within the lobe's angular scale s (domega =
// sin alpha dalpha dpsi). Independent of the slope-space derivation.
double HemisphereIntegral(const vec3& v, double lobe_scale,
                          const std::function<double(const vec3&)>& g, int radial_steps = 600,
                          int azimuth_steps = 256) {
  const vec3 m(-v.x, -v.y, v.z);
  const vec3 helper = std::abs(m.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  const vec3 t1 = normalize(cross(helper, m));
  const vec3 t2 = cross(m, t1);
  const double k = std::atan(PI / lobe_scale);
  const double dt = 1.0 / radial_steps;
  const double dpsi = 2.0 * PI / azimuth_steps;
  double sum = 0.0;
  for (int i = 0; i < radial_steps; ++i) {
    const double t = (i + 0.5) * dt;
    const double tangent = std::tan(t * k);
    const double alpha = lobe_scale * tangent;
    const double dalpha = lobe_scale * k * (1.0 + tangent * tangent) * dt;
    for (int j = 0; j < azimuth_steps; ++j) {
      const double psi = (j + 0.5) * dpsi;
      const vec3 l =
          std::cos(alpha) * m + std::sin(alpha) * (std::cos(psi) * t1 + std::sin(psi) * t2);
      if (l.z <= 0.0) continue;
      sum += g(l) * l.z * std::sin(alpha) * dalpha * dpsi;
    }
  }
  return sum;
}

// The angular scale of the BRDF lobe (radians): twice the largest slope standard deviation.
double LobeScale(const vec2& slope_variance) {
  return 2.0 * std::sqrt(std::max(slope_variance.x, slope_variance.y));
}

// The directional albedo counted on the facets: integral of
// q_vn(zeta, v, r) F(v.f) H(r_z) d^2 zeta, r = 2 (v.f) f - v.
double FacetAlbedo(const vec3& v, const vec2& slope_variance, double r, const GaussLegendre& rule) {
  return IntegrateOverVisibleSlopes(
      v, slope_variance,
      [&](const vec2& zeta) {
        const vec3 f = OceanFacetNormal(zeta);
        const vec3 reflected = 2.0 * dot(v, f) * f - v;
        return OceanVisibleSlopePdf(zeta, v, reflected, slope_variance) *
               OceanSchlickFresnel(dot(v, f), r);
      },
      rule);
}

TEST(RossBrdf, BrdfAlbedoIsTheReflectionCountedOnTheFacets) {
  // The light-space integral of the BRDF (its directional albedo) equals the same reflection
  // counted on the facets: each visible, lit facet of slopes zeta mirrors the light from
  // r = 2 (v.f) f - v with reflectance F(v.f), so albedo(v) = integral q_vn(zeta, v, r) F(v.f)
  // H(r_z) d^2 zeta. This checks the change of variables eq. 12 inside eq. 13: with the paper's
  // printed h_z^2 (the slides have h_z^3) in eq. 12, eq. 13 would carry h_z^2 and the albedo
  // would be the facet count weighted by h_z, measured 1.0 % smaller at sigma^2 = 0.01 per
  // axis and 6-8 % at 0.09. The H(r_z) cut (light below the horizon) is a curve across the
  // slope-space grid and a curve across the light-space one, so the two quadratures agree to
  // 5e-4 only (measured, at theta_v = 60 deg where the cut crosses the lobe), well below
  // those differences.
  const GaussLegendre rule = MakeGaussLegendre(8);
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  double worst = 0.0;
  for (const vec2& sigma : {vec2(0.1, 0.1), vec2(0.3, 0.3), vec2(0.3, 0.12)}) {
    const vec2 slope_variance = sigma * sigma;
    for (double zenith : {0.0, 30.0, 60.0}) {
      const vec3 v = TangentDirection(zenith, 20.0);
      const double albedo = HemisphereIntegral(v, LobeScale(slope_variance), [&](const vec3& l) {
        return OceanRossBrdf(v, l, slope_variance, r);
      });
      const double albedo_with_hz2 =
          HemisphereIntegral(v, LobeScale(slope_variance), [&](const vec3& l) {
            return OceanRossBrdf(v, l, slope_variance, r) * normalize(v + l).z;
          });
      const double facets = FacetAlbedo(v, slope_variance, r, rule);
      const double error = RelativeDifference(albedo, facets);
      worst = std::max(worst, error);
      std::printf(
          "albedo sigma (%.2f, %.2f) theta_v %2.0f: light space %.6f, facets %.6f, "
          "with eq. 12's h_z^2 %.6f\n",
          sigma.x, sigma.y, zenith, albedo, facets, albedo_with_hz2);
      EXPECT_LT(error, 1e-3) << "sigma " << sigma.x << " " << sigma.y << " theta_v " << zenith;
      EXPECT_GT(RelativeDifference(albedo_with_hz2, facets), 5e-3);
    }
  }
  std::printf("BRDF albedo against the facet count: worst relative difference %.3g\n", worst);
}

TEST(RossBrdf, BrdfConservesEnergyAndTendsToFresnel) {
  // The directional albedo is at most 1 for every tested v and sigma, with R = 0.02 and with
  // R = 1 (a perfect mirror, where the bound rests on the masking-shadowing term alone): q_vn <=
  // q_vn^e since Lambda_l >= 0, F <= 1 and eq. 11. Integrated over light directions where the
  // lobe is at most 4 times longer than wide (the polar quadrature about the mirror direction
  // cannot resolve a lobe 700 times longer than wide), and counted on the facets (equal to it,
  // see the test above) for every pair, the extreme ones included.
  const GaussLegendre rule = MakeGaussLegendre(8);
  double largest = 0.0;
  for (const vec2& sigma : SigmaPairs()) {
    const vec2 slope_variance = sigma * sigma;
    const bool light_space = std::max(sigma.x, sigma.y) <= 4.0 * std::min(sigma.x, sigma.y) &&
                             std::max(sigma.x, sigma.y) >= 0.01;
    for (double zenith : {0.0, 45.0, 80.0, 89.0, 89.9}) {
      const vec3 v = TangentDirection(zenith, 60.0);
      for (double r : {OCEAN_DEFAULT_FRESNEL_R, 1.0}) {
        const double facets = FacetAlbedo(v, slope_variance, r, rule);
        EXPECT_GT(facets, 0.0);
        EXPECT_LE(facets, 1.0) << "sigma " << sigma.x << " " << sigma.y << " theta_v " << zenith
                               << " R " << r;
        largest = std::max(largest, facets);
        if (!light_space) continue;
        const double albedo = HemisphereIntegral(
            v, LobeScale(slope_variance),
            [&](const vec3& l) { return OceanRossBrdf(v, l, slope_variance, r); }, 300, 128);
        EXPECT_GT(albedo, 0.0);
        // The light-space quadrature's own error (measured up to 1e-5 for R = 1, where the
        // true albedo is 1 - O(sigma^2) at normal incidence) is allowed for.
        EXPECT_LE(albedo, 1.0 + 2e-5)
            << "sigma " << sigma.x << " " << sigma.y << " theta_v " << zenith << " R " << r;
        largest = std::max(largest, albedo);
      }
    }
  }
  std::printf("BRDF directional albedo: largest %.5f (R = 1 included)\n", largest);
  // As sigma -> 0 the albedo tends to Schlick's F(cos theta_v), the reflectance of a flat
  // mirror, with a relative error of order sigma^2 (down to the light-space quadrature's own
  // 2e-6).
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  for (double zenith : {0.0, 30.0, 60.0, 75.0}) {
    const vec3 v = TangentDirection(zenith, 110.0);
    const double fresnel = OceanSchlickFresnel(v.z, r);
    double previous_error = 1.0;
    for (double variance : {1e-3, 1e-4, 1e-6}) {
      const vec2 slope_variance(variance, 0.5 * variance);
      const double albedo = HemisphereIntegral(
          v, LobeScale(slope_variance),
          [&](const vec3& l) { return OceanRossBrdf(v, l, slope_variance, r); }, 300, 128);
      const double error = std::abs(albedo / fresnel - 1.0);
      std::printf("albedo -> F: theta_v %2.0f sigma^2 %.0e: relative error %.3g\n", zenith,
                  variance, error);
      EXPECT_LT(error, std::max(10.0 * variance, 2e-5)) << "theta_v " << zenith;
      if (previous_error > 2e-5) {
        EXPECT_LT(error, previous_error) << "theta_v " << zenith;
      }
      previous_error = error;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// d. The effective Fresnel fit (eq. 26) against eq. 24.

// Eq. 24 by quadrature: R + (1 - R) integral q_vn^e(zeta, v) (1 - v.f)^5 d^2 zeta, with
// q_vn^e = p (v_z - v.zeta)_+ / (cos theta_v (1 + Lambda_v)) (eq. 10; its normalisation from
// OceanSmithFacingAreaToward, evaluated once).
double EffectiveFresnelByQuadrature(const vec3& v, const vec2& slope_variance, double r,
                                    const GaussLegendre& rule) {
  const double facing_area = OceanSmithFacingAreaToward(v, slope_variance);
  const double integral = IntegrateOverVisibleSlopes(
      v, slope_variance,
      [&](const vec2& zeta) {
        const double facing = v.z - v.x * zeta.x - v.y * zeta.y;  // v.f / f_z > 0 here
        if (facing <= 0.0) return 0.0;
        const double inverse_norm = 1.0 / std::sqrt(1.0 + dot(zeta, zeta));
        const double x = 1.0 - facing * inverse_norm;  // 1 - v.f
        const double x2 = x * x;
        return OceanSlopePdf(zeta, slope_variance) * facing * x2 * x2 * x;
      },
      rule, 7.0);
  return r + (1.0 - r) * integral / facing_area;
}

// The measured worst and mean absolute errors of eq. 26 over the grid below, plus a 10 % margin.
constexpr double kEffectiveFresnelWorstBound = 0.0375;  // measured 0.0339
constexpr double kEffectiveFresnelMeanBound = 0.0038;   // measured 0.00343
// The same for eq. 24's integrator against the rule here and for its table (measured + 10 %).
// (Measured 4.1e-8, 2.5e-5 relative, 1.19e-3 worst and 1.49e-4 mean against eq. 24, 6.9e-4
// between the samples.)
constexpr double kEffectiveFresnelIntegratorBound = 1e-7;
constexpr double kEffectiveFresnelDerivativeBound = 1e-4;
constexpr double kEffectiveFresnelTableWorstBound = 1.3e-3;
constexpr double kEffectiveFresnelTableMeanBound = 1.65e-4;
constexpr double kEffectiveFresnelTableInterpolationBound = 7.6e-4;
// The visible mean slopes (measured 4.4e-12 against Stein's lemma, 3.6e-8 against the 2D rule,
// in sigma_v) and the table's Fresnel-weighted one between its samples (1.09e-2 sigma_v, 1.08e-3
// absolute).
constexpr double kVisibleMeanSlopeBound = 1e-7;
constexpr double kFresnelWeightedSlopeTableBound = 0.012;
constexpr double kFresnelWeightedSlopeTableAbsoluteBound = 1.2e-3;

TEST(RossBrdf, EffectiveFresnelFitAgainstEq24) {
  // Eq. 26 against eq. 24 over theta_v in [0, 89] deg and sigma_v^2 in [1e-4, 0.25], isotropic
  // and anisotropic (sigma_y^2 = sigma_x^2 / 2 and 2 sigma_x^2, at phi_v = 0, 45, 90 deg, with
  // sigma_x^2 chosen so that eq. 25 gives the grid's sigma_v^2), R = 0.02. The table of the
  // absolute error is printed (docs/ocean_fresnel.md holds it). The bounds are the measured
  // worst and mean errors with a 10 % margin, so that a regression of the fit, of eq. 25 or of
  // q_vn^e fails.
  const GaussLegendre rule = MakeGaussLegendre(6);
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  const std::vector<double> variances = {1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.03, 0.06, 0.1, 0.16, 0.25};
  struct Config {
    double ratio;  // sigma_y^2 / sigma_x^2
    double azimuth_deg;
    const char* name;
  };
  const std::vector<Config> configs = {{1.0, 30.0, "isotropic"},
                                       {0.5, 0.0, "sy2 = sx2/2, phi 0"},
                                       {0.5, 45.0, "sy2 = sx2/2, phi 45"},
                                       {0.5, 90.0, "sy2 = sx2/2, phi 90"},
                                       {2.0, 45.0, "sy2 = 2 sx2, phi 45"}};
  const std::vector<double> zenith_band_edges = {0.0, 30.0, 60.0, 75.0, 85.0, 89.0};
  const int zenith_bands = static_cast<int>(zenith_band_edges.size()) - 1;
  std::vector<double> worst_by_variance(variances.size(), 0.0);
  std::vector<double> sum_by_variance(variances.size(), 0.0);
  std::vector<int> count_by_variance(variances.size(), 0);
  std::vector<double> worst_by_zenith(zenith_bands, 0.0);
  std::vector<double> sum_by_zenith(zenith_bands, 0.0);
  std::vector<int> count_by_zenith(zenith_bands, 0);
  std::vector<double> worst_by_config(configs.size(), 0.0);
  double worst = 0.0;
  double worst_signed = 0.0;
  std::string worst_case;
  double sum = 0.0;
  int count = 0;
  for (size_t c = 0; c < configs.size(); ++c) {
    const Config& config = configs[c];
    const double phi = config.azimuth_deg * DEGREE;
    const double cos2 = std::cos(phi) * std::cos(phi);
    const double sin2 = 1.0 - cos2;
    for (size_t k = 0; k < variances.size(); ++k) {
      const double sigma_x2 = variances[k] / (cos2 + config.ratio * sin2);
      const vec2 slope_variance(sigma_x2, config.ratio * sigma_x2);
      for (int zenith_deg = 0; zenith_deg <= 89; ++zenith_deg) {
        const vec3 v = TangentDirection(zenith_deg, config.azimuth_deg);
        const double view_variance = OceanSlopeVarianceToward(v, slope_variance);
        if (zenith_deg > 0) {
          EXPECT_NEAR(view_variance, variances[k], 1e-12 * variances[k]);
        }
        const double fit = OceanEffectiveFresnel(v.z, view_variance, r);
        const double exact = EffectiveFresnelByQuadrature(v, slope_variance, r, rule);
        const double error = std::abs(fit - exact);
        if (error > worst) {
          worst = error;
          worst_signed = fit - exact;
          worst_case = std::string(config.name) + ", sigma_v^2 " + std::to_string(variances[k]) +
                       ", theta_v " + std::to_string(zenith_deg) + ": fit " + std::to_string(fit) +
                       ", eq. 24 " + std::to_string(exact);
        }
        sum += error;
        ++count;
        worst_by_variance[k] = std::max(worst_by_variance[k], error);
        sum_by_variance[k] += error;
        ++count_by_variance[k];
        worst_by_config[c] = std::max(worst_by_config[c], error);
        for (int b = 0; b < zenith_bands; ++b) {
          const bool last = b == zenith_bands - 1;
          if (zenith_deg >= zenith_band_edges[b] &&
              (zenith_deg < zenith_band_edges[b + 1] || (last && zenith_deg <= 89))) {
            worst_by_zenith[b] = std::max(worst_by_zenith[b], error);
            sum_by_zenith[b] += error;
            ++count_by_zenith[b];
          }
        }
      }
    }
  }
  std::printf("| sigma_v^2 | worst abs. error | mean abs. error |\n|---|---|---|\n");
  for (size_t k = 0; k < variances.size(); ++k) {
    std::printf("| %g | %.4f | %.4f |\n", variances[k], worst_by_variance[k],
                sum_by_variance[k] / count_by_variance[k]);
  }
  std::printf("\n| theta_v (deg) | worst abs. error | mean abs. error |\n|---|---|---|\n");
  for (int b = 0; b < zenith_bands; ++b) {
    std::printf("| [%g, %g%s | %.4f | %.4f |\n", zenith_band_edges[b], zenith_band_edges[b + 1],
                b == zenith_bands - 1 ? "]" : ")", worst_by_zenith[b],
                sum_by_zenith[b] / count_by_zenith[b]);
  }
  std::printf("\n| configuration | worst abs. error |\n|---|---|\n");
  for (size_t c = 0; c < configs.size(); ++c) {
    std::printf("| %s | %.4f |\n", configs[c].name, worst_by_config[c]);
  }
  std::printf(
      "\neq. 26: worst absolute error %.4f (fit - eq. 24 = %+.4f) at %s; mean %.5f over "
      "%d points\n",
      worst, worst_signed, worst_case.c_str(), sum / count, count);
  EXPECT_LT(worst, kEffectiveFresnelWorstBound);
  EXPECT_LT(sum / count, kEffectiveFresnelMeanBound);
  // At sigma_v = 0 the fit is Schlick's formula, which eq. 24 becomes (q_vn^e -> Dirac).
  for (double cos_theta : {0.0, 0.3, 0.7, 1.0}) {
    EXPECT_DOUBLE_EQ(OceanEffectiveFresnel(cos_theta, 0.0, r), OceanSchlickFresnel(cos_theta, r));
  }
}

// Eq. 24's own integrator (ocean/effective_fresnel.hpp: one rule, panels cut at the kink, the
// normalisation summed by the same nodes) against the independent rule above (8-point panels,
// the normalisation from Smith's Lambda, eq. 9, whose approximation errs by 3e-6 relative):
// theta_v from 0 to 90 deg, sigma_v^2 from 1e-8 to 1, isotropic slopes and slopes a factor 2
// apart (the view along the wind, where along and across are the axes' variances); its
// derivative across against central differences of the value.
TEST(RossBrdf, EffectiveFresnelIntegratorAgreesWithAnIndependentRule) {
  const GaussLegendre rule = MakeGaussLegendre(8);
  double worst = 0.0, worst_derivative = 0.0;
  std::string where;
  for (double ratio : {1.0, 0.5, 2.0}) {
    for (double variance : {1e-8, 1e-6, 1e-4, 1e-3, 0.01, 0.03, 0.1, 0.3, 0.5}) {
      for (double zenith_deg = 0.0; zenith_deg <= 90.0;
           zenith_deg += zenith_deg < 80.0 ? 5.0 : 0.5) {
        const vec3 v = TangentDirection(zenith_deg, 0.0);
        const double across = ratio * variance;
        const ocean::SchlickAverage ours =
            ocean::effective_fresnel_schlick_average(v.z, variance, across);
        const double independent =
            EffectiveFresnelByQuadrature(v, vec2(variance, across), 0.0, rule);
        ASSERT_TRUE(std::isfinite(ours.value) && std::isfinite(ours.across_derivative))
            << variance << " " << zenith_deg;
        const double error = std::abs(ours.value - independent);
        if (error > worst) {
          worst = error;
          where = "sigma_v^2 " + std::to_string(variance) + ", ratio " + std::to_string(ratio) +
                  ", theta_v " + std::to_string(zenith_deg);
        }
        // Differences of step h = across / 1000, where they resolve the change (from variances of
        // 1e-6: below, the step is under the rule's resolution) within the clamp to 1.
        const double h = 1e-3 * across;
        if (variance < 1e-6 || across + h > 1.0) continue;
        const double difference =
            (ocean::effective_fresnel_schlick_average(v.z, variance, across + h).value -
             ocean::effective_fresnel_schlick_average(v.z, variance, across - h).value) /
            (2.0 * h);
        worst_derivative =
            std::max(worst_derivative, std::abs(ours.across_derivative - difference) /
                                           std::max(std::abs(difference), 1e-3));
      }
    }
  }
  std::printf(
      "eq. 24's integrator against the independent rule: worst %.2e at %s; its derivative "
      "across against differences: %.2e relative\n",
      worst, where.c_str(), worst_derivative);
  EXPECT_LT(worst, kEffectiveFresnelIntegratorBound);
  EXPECT_LT(worst_derivative, kEffectiveFresnelDerivativeBound);
  // sigma_v -> 0: Schlick's factor, the Dirac's limit, and (1 - cos theta_v)^5 (5/2) cos theta_v
  // ... its first change across: d/db E[(1 - mu / sqrt(1 + b s^2))^5] = 5/2 mu (1 - mu)^4 at b = 0.
  for (double cos_theta : {0.0, 0.2, 0.5, 0.9, 1.0}) {
    const ocean::SchlickAverage flat =
        ocean::effective_fresnel_schlick_average(cos_theta, 0.0, 0.0);
    EXPECT_NEAR(flat.value, std::pow(1.0 - cos_theta, 5.0), 1e-14) << cos_theta;
    if (cos_theta > 0.0) {
      EXPECT_NEAR(flat.across_derivative, 2.5 * cos_theta * std::pow(1.0 - cos_theta, 4.0), 1e-12)
          << cos_theta;
    }
    EXPECT_NEAR(ocean::effective_fresnel_schlick_average(cos_theta, 1e-12, 1e-12).value,
                std::pow(1.0 - cos_theta, 5.0), 1e-5);
  }
}

// The visible facets' mean slopes that centre the sky's lobe (ocean.sky_lobe_centre =
// "fresnel_weighted"). Their plain mean toward the view has a closed form by Stein's lemma: with
// s standard normal, a = cos theta_v and b = sin theta_v sigma_v, E[(a - b s)_+ s] = -b Phi(a/b)
// and E[(a - b s)_+] = a Phi(a/b) + b phi(a/b) (eq. 11's normalisation), so E_q[zeta.e] =
// -sigma_v b Phi / (a Phi + b phi): the integrator's is checked against it; the Schlick-weighted
// one against the independent 2D rule; and the table's Fresnel-weighted mean slope, as the GPU
// reads it, against the integrator between its samples.
TEST(RossBrdf, VisibleMeanSlopesAgainstSteinsLemmaAndAnIndependentRule) {
  const GaussLegendre rule = MakeGaussLegendre(8);
  double worst_mean = 0.0, worst_weighted = 0.0;
  for (double variance : {1e-6, 1e-4, 1e-3, 0.01, 0.03, 0.1, 0.3, 1.0}) {
    const double sigma = std::sqrt(variance);
    for (double zenith_deg = 0.0; zenith_deg <= 90.0; zenith_deg += zenith_deg < 80.0 ? 5.0 : 0.5) {
      const vec3 v = TangentDirection(zenith_deg, 0.0);
      const ocean::SchlickAverage ours =
          ocean::effective_fresnel_schlick_average(v.z, variance, variance);
      const double a = v.z, b = v.x * sigma;
      double closed = 0.0;
      if (b > 0.0) {
        const double c = a / b;
        const double phi = std::exp(-0.5 * c * c) / std::sqrt(2.0 * M_PI);
        const double cdf = 0.5 * std::erfc(-c / std::sqrt(2.0));
        closed = -sigma * b * cdf / (a * cdf + b * phi);
      }
      worst_mean = std::max(worst_mean, std::abs(ours.mean_slope - closed) / sigma);
      const vec2 s2(variance, variance);
      const double facing_area = OceanSmithFacingAreaToward(v, s2);
      const double weighted =
          IntegrateOverVisibleSlopes(
              v, s2,
              [&](const vec2& zeta) {
                const double facing = v.z - v.x * zeta.x;
                if (facing <= 0.0) return 0.0;
                const double x = 1.0 - facing / std::sqrt(1.0 + dot(zeta, zeta));
                return OceanSlopePdf(zeta, s2) * facing * x * x * x * x * x * zeta.x;
              },
              rule, 7.0) /
          facing_area;
      if (v.x > 0.0)
        worst_weighted =
            std::max(worst_weighted, std::abs(ours.schlick_mean_slope - weighted) / sigma);
    }
  }
  std::printf(
      "visible mean slope against Stein's lemma: %.2e; Schlick-weighted against the 2D rule: %.2e "
      "(in sigma_v)\n",
      worst_mean, worst_weighted);
  EXPECT_LT(worst_mean, kVisibleMeanSlopeBound);
  EXPECT_LT(worst_weighted, kVisibleMeanSlopeBound);

  // The table's Fresnel-weighted mean slope between its samples: in units of sigma_v where the
  // lobe is at least 0.01 wide (the sky map's filter footprint there is many texels), absolute
  // (slope) everywhere.
  const ocean::EffectiveFresnelTable& table = ocean::effective_fresnel_table();
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  double worst_relative = 0.0, worst_absolute = 0.0;
  std::string where;
  for (int j = 0; j + 1 < table.sigma_size; ++j) {
    for (int i = 0; i + 1 < table.cos_size; ++i) {
      const vec2 node = OceanEffectiveFresnelTableNode(i + 0.5, j + 0.5);
      const double variance = node.y * node.y;
      const ocean::SchlickAverage exact =
          ocean::effective_fresnel_schlick_average(node.x, variance, variance);
      const double expected = (r * exact.mean_slope + (1.0 - r) * exact.schlick_mean_slope) /
                              (r + (1.0 - r) * exact.value);
      const double error =
          std::abs(table.fresnel_weighted_mean_slope(node.x, variance, r) - expected);
      worst_absolute = std::max(worst_absolute, error);
      if (node.y >= 0.01 && error / node.y > worst_relative) {
        worst_relative = error / node.y;
        where = "cos theta_v " + std::to_string(node.x) + ", sigma_v " + std::to_string(node.y);
      }
    }
  }
  std::printf(
      "the table's Fresnel-weighted mean slope between its samples: %.2e sigma_v (sigma_v >= "
      "0.01; at %s), %.2e absolute\n",
      worst_relative, where.c_str(), worst_absolute);
  EXPECT_LT(worst_relative, kFresnelWeightedSlopeTableBound);
  EXPECT_LT(worst_absolute, kFresnelWeightedSlopeTableAbsoluteBound);
}

// The table that replaces eq. 26 where a scene asks for it (ocean.effective_fresnel = "table"),
// read as the GPU reads it (bilinear), against eq. 24 by the independent rule, on the grid of
// EffectiveFresnelFitAgainstEq24 (isotropic slopes, and anisotropic ones, which the table
// reaches from isotropic ones to first order in the variance across the view) and on a finer one
// at grazing views (theta_v from 80 to 89.9 deg by 0.1), where the fit errs most. The bounds are
// the measured errors plus 10 %.
TEST(RossBrdf, EffectiveFresnelTableAgainstEq24) {
  const GaussLegendre rule = MakeGaussLegendre(6);
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  const ocean::EffectiveFresnelTable& table = ocean::effective_fresnel_table();
  ASSERT_EQ(table.cos_size, OCEAN_EFFECTIVE_FRESNEL_TABLE_COS_SIZE);
  ASSERT_EQ(table.sigma_size, OCEAN_EFFECTIVE_FRESNEL_TABLE_SIGMA_SIZE);
  const std::vector<double> variances = {1e-4, 3e-4, 1e-3, 3e-3, 0.01, 0.03, 0.06, 0.1, 0.16, 0.25};
  struct Config {
    double ratio;  // sigma_y^2 / sigma_x^2
    double azimuth_deg;
  };
  const std::vector<Config> configs = {
      {1.0, 30.0}, {0.5, 0.0}, {0.5, 45.0}, {0.5, 90.0}, {2.0, 45.0}};
  std::vector<double> zeniths;
  for (int k = 0; k < 80; ++k) zeniths.push_back(k);
  for (int k = 800; k < 900; ++k) zeniths.push_back(0.1 * k);
  double worst_table = 0.0, worst_fit = 0.0, sum_table = 0.0, sum_fit = 0.0;
  double worst_band[3] = {0, 0, 0}, worst_fit_band[3] = {0, 0, 0};
  std::string where;
  int count = 0;
  for (const Config& config : configs) {
    const double phi = config.azimuth_deg * DEGREE;
    const double cos2 = std::cos(phi) * std::cos(phi);
    for (double variance : variances) {
      const double sigma_x2 = variance / (cos2 + config.ratio * (1.0 - cos2));
      const vec2 slope_variance(sigma_x2, config.ratio * sigma_x2);
      for (double zenith_deg : zeniths) {
        const vec3 v = TangentDirection(zenith_deg, config.azimuth_deg);
        const double view_variance = OceanSlopeVarianceToward(v, slope_variance);
        const double exact = EffectiveFresnelByQuadrature(v, slope_variance, r, rule);
        const double across = slope_variance.x + slope_variance.y - view_variance;
        const double from_table = table.lookup(v.z, view_variance, across, r);
        const double error = std::abs(from_table - exact);
        const double fit_error = std::abs(OceanEffectiveFresnel(v.z, view_variance, r) - exact);
        // 0: isotropic; anisotropic to 89 deg (the fit's grid) and beyond.
        const int band = config.ratio == 1.0 ? 0 : zenith_deg <= 89.0 ? 1 : 2;
        worst_band[band] = std::max(worst_band[band], error);
        worst_fit_band[band] = std::max(worst_fit_band[band], fit_error);
        if (error > worst_table) {
          worst_table = error;
          where = "sigma_v^2 " + std::to_string(variance) + ", theta_v " +
                  std::to_string(zenith_deg) + ", ratio " + std::to_string(config.ratio) +
                  ", phi " + std::to_string(config.azimuth_deg) + ": table " +
                  std::to_string(from_table) + ", eq. 24 " + std::to_string(exact);
        }
        worst_fit = std::max(worst_fit, fit_error);
        sum_table += error;
        sum_fit += fit_error;
        ++count;
      }
    }
  }
  std::printf(
      "F-bar against eq. 24 over %d points: table worst %.2e mean %.2e (at %s); eq. 26 worst "
      "%.4f mean %.5f\n",
      count, worst_table, sum_table / count, where.c_str(), worst_fit, sum_fit / count);
  std::printf(
      "worst table / eq. 26: isotropic %.2e / %.4f, anisotropic to 89 deg %.2e / %.4f, beyond "
      "%.2e / %.4f\n",
      worst_band[0], worst_fit_band[0], worst_band[1], worst_fit_band[1], worst_band[2],
      worst_fit_band[2]);
  EXPECT_LT(worst_table, kEffectiveFresnelTableWorstBound);
  EXPECT_LT(sum_table / count, kEffectiveFresnelTableMeanBound);
  EXPECT_GT(worst_fit, 20.0 * worst_table);  // what the table is for
}

// The table between its samples, isotropic: bilinear in (sqrt(cos theta_v), sqrt(sigma_v)) against
// eq. 24 at the centres of its cells and of their edges, where interpolation errs most; and its
// limits: Schlick's factor at sigma_v = 0, R at normal incidence (to the slopes' own 1e-3), finite
// values in [R, 1] for inputs out of range (cos theta_v < 0 or > 1, variances < 0 or > 1).
TEST(RossBrdf, EffectiveFresnelTableBetweenItsSamples) {
  const ocean::EffectiveFresnelTable& table = ocean::effective_fresnel_table();
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  double worst = 0.0;
  std::string where;
  for (int j = 0; j + 1 < table.sigma_size; ++j) {
    for (int i = 0; i + 1 < table.cos_size; ++i) {
      for (const vec2& offset : {vec2(0.5, 0.5), vec2(0.5, 0.0), vec2(0.0, 0.5)}) {
        const vec2 node = OceanEffectiveFresnelTableNode(i + offset.x, j + offset.y);
        const double variance = node.y * node.y;
        const double exact =
            r +
            (1.0 - r) * ocean::effective_fresnel_schlick_average(node.x, variance, variance).value;
        const double error = std::abs(table.lookup(node.x, variance, variance, r) - exact);
        if (error > worst) {
          worst = error;
          where = "cos theta_v " + std::to_string(node.x) + ", sigma_v " + std::to_string(node.y);
        }
      }
    }
  }
  std::printf("table between its samples: worst %.2e at %s\n", worst, where.c_str());
  EXPECT_LT(worst, kEffectiveFresnelTableInterpolationBound);
  for (int i = 0; i < table.cos_size; ++i) {
    const double cos_theta = OceanEffectiveFresnelTableNode(i, 0.0).x;
    EXPECT_NEAR(table.lookup(cos_theta, 0.0, 0.0, r), OceanSchlickFresnel(cos_theta, r), 1e-7) << i;
  }
  EXPECT_NEAR(table.lookup(1.0, 0.25, 0.25, r), r, 2e-3);
  for (double cos_theta : {-1.0, -1e-3, 0.0, 1e-6, 0.5, 1.0, 1.5}) {
    for (double variance : {-1.0, 0.0, 1e-12, 0.04, 1.0, 1e6}) {
      const double f = table.lookup(cos_theta, variance, 2.0 * variance, r);
      EXPECT_TRUE(std::isfinite(f) && f >= r && f <= 1.0) << cos_theta << " " << variance;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// e. The stereographic sky-map mapping and its derivatives.

// An orthonormal tangent frame (t_x, t_y, n) in the sky map's frame: the mean normal n tilted
// by `tilt_deg` from the zenith toward `azimuth_deg`, the wind t_x at `wind_deg` about n.
void TiltedFrame(double tilt_deg, double azimuth_deg, double wind_deg, vec3& t_x, vec3& t_y,
                 vec3& n) {
  n = TangentDirection(tilt_deg, azimuth_deg);
  const vec3 helper = std::abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  const vec3 a = normalize(cross(helper, n));
  const vec3 b = cross(n, a);
  const double w = wind_deg * DEGREE;
  t_x = std::cos(w) * a + std::sin(w) * b;
  t_y = cross(n, t_x);
}

TEST(RossBrdf, StereographicMappingMapsZenithAndHorizon) {
  EXPECT_EQ(OceanStereographic(vec3(0.0, 0.0, 1.0)), vec2(0.0, 0.0));
  for (double azimuth = 0.0; azimuth < 360.0; azimuth += 15.0) {
    const vec2 u = OceanStereographic(TangentDirection(90.0, azimuth));
    EXPECT_NEAR(length(u), 1.0, 1e-15) << "azimuth " << azimuth;
    // The radius is tan(theta / 2), in the direction of the azimuth.
    for (double zenith : {10.0, 60.0, 120.0, 170.0}) {
      const vec2 w = OceanStereographic(TangentDirection(zenith, azimuth));
      EXPECT_NEAR(length(w), std::tan(0.5 * zenith * DEGREE), 1e-13);
      EXPECT_NEAR(std::atan2(w.y, w.x),
                  std::atan2(std::sin(azimuth * DEGREE), std::cos(azimuth * DEGREE)), 1e-12);
    }
  }
  // For a flat, level surface seen from v, the reflected ray is (-v_x, -v_y, v_z): its
  // coordinates are -(v_x, v_y) / (1 + v_z).
  const vec3 v = TangentDirection(70.0, 33.0);
  const vec2 u = OceanSkyMapCoordinates(v, vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0),
                                        vec3(0.0, 0.0, 1.0), vec2(0.0));
  EXPECT_NEAR(u.x, -v.x / (1.0 + v.z), 1e-15);
  EXPECT_NEAR(u.y, -v.y / (1.0 + v.z), 1e-15);
}

TEST(RossBrdf, SkyMapDerivativesMatchFiniteDifferences) {
  // The analytic du/dzeta at zeta = 0 against central differences of u(v, zeta) (Algorithm 5.1's
  // procedure U, OceanSkyMapCoordinates), step 1e-5: truncation ~1e-10 |u'''|, rounding 1e-11,
  // against the 1e-6 relative asked. Level and tilted normals, several winds, views from the
  // zenith to grazing.
  double worst = 0.0;
  const double step = 1e-5;
  for (double tilt : {0.0, 10.0, 35.0}) {
    for (double wind : {0.0, 50.0, 200.0}) {
      vec3 t_x, t_y, n;
      TiltedFrame(tilt, 120.0, wind, t_x, t_y, n);
      for (double zenith : {0.0, 20.0, 50.0, 75.0, 88.0}) {
        for (double azimuth : {0.0, 100.0, 300.0}) {
          const vec3 v = TangentDirection(zenith, azimuth);
          if (dot(v, n) <= 0.05) continue;
          vec2 u0, du_x, du_y;
          OceanSkyMapGradients(v, t_x, t_y, n, u0, du_x, du_y);
          const vec2 zero(0.0);
          EXPECT_LT(length(u0 - OceanSkyMapCoordinates(v, t_x, t_y, n, zero)), 1e-15);
          const vec2 fd_x = (OceanSkyMapCoordinates(v, t_x, t_y, n, vec2(step, 0.0)) -
                             OceanSkyMapCoordinates(v, t_x, t_y, n, vec2(-step, 0.0))) /
                            (2.0 * step);
          const vec2 fd_y = (OceanSkyMapCoordinates(v, t_x, t_y, n, vec2(0.0, step)) -
                             OceanSkyMapCoordinates(v, t_x, t_y, n, vec2(0.0, -step))) /
                            (2.0 * step);
          const double error_x = length(du_x - fd_x) / length(du_x);
          const double error_y = length(du_y - fd_y) / length(du_y);
          worst = std::max({worst, error_x, error_y});
          EXPECT_LT(error_x, 1e-6) << "tilt " << tilt << " wind " << wind << " theta_v " << zenith
                                   << " phi_v " << azimuth;
          EXPECT_LT(error_y, 1e-6) << "tilt " << tilt << " wind " << wind << " theta_v " << zenith
                                   << " phi_v " << azimuth;
        }
      }
    }
  }
  std::printf("sky-map derivatives: worst relative difference to central differences %.3g\n",
              worst);
}

TEST(RossBrdf, SkyMapMappingIsFiniteAtTheNadir) {
  // A vertical wall (n horizontal) seen from the zenith reflects the view straight down,
  // r = (0, 0, -1), the mapping's singular point: U is defined there as
  // (OCEAN_SKY_MAP_MAX_RADIUS, 0), and within 2 / OCEAN_SKY_MAP_MAX_RADIUS rad of it the radius
  // is held at OCEAN_SKY_MAP_MAX_RADIUS, continuously with the exact mapping outside.
  const vec3 n(1.0, 0.0, 0.0);
  const vec3 t_x(0.0, 1.0, 0.0);
  const vec3 t_y(0.0, 0.0, 1.0);
  const vec3 v(0.0, 0.0, 1.0);
  vec2 u0, du_x, du_y;
  OceanSkyMapGradients(v, t_x, t_y, n, u0, du_x, du_y);
  EXPECT_EQ(u0, vec2(OCEAN_SKY_MAP_MAX_RADIUS, 0.0));
  EXPECT_TRUE(IsFinite(du_x) && IsFinite(du_y));
  EXPECT_EQ(OceanStereographic(vec3(0.0, 0.0, -1.0)), vec2(OCEAN_SKY_MAP_MAX_RADIUS, 0.0));
  // Approaching the nadir: finite everywhere, radius tan(theta / 2) until it reaches the cap.
  for (double nadir_distance : {1e-1, 1e-2, 3e-3, 2.1e-3, 1.9e-3, 1e-4, 1e-8, 0.0}) {
    const double theta = PI - nadir_distance;
    const vec3 r(std::sin(theta) * 0.6, std::sin(theta) * 0.8, std::cos(theta));
    const vec2 u = OceanStereographic(r);
    ASSERT_TRUE(IsFinite(u));
    EXPECT_LE(length(u), OCEAN_SKY_MAP_MAX_RADIUS * (1.0 + 1e-9));
    EXPECT_NEAR(length(u), std::min(std::tan(0.5 * theta), OCEAN_SKY_MAP_MAX_RADIUS),
                1e-6 * length(u) + 1e-12);
    EXPECT_TRUE(IsFinite(OceanStereographicDerivative(r, vec3(1.0, -1.0, 0.5))));
  }
}

// ---------------------------------------------------------------------------------------------
// f. Limits and extreme inputs.

TEST(RossBrdf, ReflectedSunConservesTheFresnelWeightedFluxAsSigmaVanishes) {
  // Eq. 15 per unit L_sun Omega_sun, integrated over the view directions with cos theta_v,
  // is the reflected fraction of the sun's flux on the surface (L_sun Omega_sun cos theta_l),
  // times cos theta_l: for a flat sea, Schlick's F(cos theta_l). With the clamp of sec. 5.1 the
  // glint keeps the sun's disc size and the integral stays F for sigma^2 = 0 and 1e-8 (without
  // the clamp p(zeta) would be a Dirac: infinite at 0, NaN at sigma^2 = 0). Measured relative
  // error: below 1e-5 (the clamp's own sigma^2 = 1.35e-6 sets the error O(sigma^2)).
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  const double sun_lobe = 2.0 * std::sqrt(OCEAN_SUN_MIN_SLOPE_VARIANCE);
  double worst = 0.0;
  for (double zenith : {0.0, 30.0, 60.0, 80.0}) {
    const vec3 l = TangentDirection(zenith, 45.0);
    const double fresnel = OceanSchlickFresnel(l.z, r);
    for (double variance : {0.0, 1e-8, 1e-7}) {
      const vec2 slope_variance(variance, 0.3 * variance);
      // Clamped: the same values as at the clamp itself.
      EXPECT_EQ(OceanReflectedSun(vec3(-l.x, -l.y, l.z), l, slope_variance, r),
                OceanReflectedSun(vec3(-l.x, -l.y, l.z), l, vec2(OCEAN_SUN_MIN_SLOPE_VARIANCE), r));
      const double flux = HemisphereIntegral(
          l, sun_lobe, [&](const vec3& v) { return OceanReflectedSun(v, l, slope_variance, r); },
          400, 128);
      const double error = std::abs(flux / (l.z * fresnel) - 1.0);
      worst = std::max(worst, error);
      EXPECT_LT(error, 1e-4) << "theta_l " << zenith << " sigma^2 " << variance;
    }
  }
  std::printf("reflected sun, sigma^2 -> 0: worst relative error of the flux %.3g\n", worst);
  // The unclamped BRDF at sigma^2 = 1e-8 per axis is finite and conserves energy too.
  const vec3 v = TangentDirection(40.0, 10.0);
  const vec2 tiny(1e-8, 1e-8);
  const double albedo = HemisphereIntegral(
      v, LobeScale(tiny), [&](const vec3& l) { return OceanRossBrdf(v, l, tiny, r); }, 400, 128);
  EXPECT_NEAR(albedo / OceanSchlickFresnel(v.z, r), 1.0, 1e-4);
}

TEST(RossBrdf, FiniteForExtremeInputs) {
  // theta_v, theta_l in [0, 90] deg (90 exactly), the light below the horizon, v = l, v = -l,
  // slope variances from 0 and 1e-8 to 1, isotropic and anisotropic.
  const double r = OCEAN_DEFAULT_FRESNEL_R;
  int checked = 0;
  const std::vector<double> zeniths = {0.0, 1e-6, 30.0, 60.0, 89.0, 89.9, 89.999, 90.0};
  const std::vector<double> light_zeniths = {0.0, 1e-6, 45.0, 89.9, 90.0, 90.1, 120.0, 180.0};
  for (double sx2 : {0.0, 1e-8, 1e-4, 0.1, 1.0}) {
    for (double sy2 : {1e-8, 0.02, 1.0}) {
      const vec2 slope_variance(sx2, sy2);
      for (double zenith_v : zeniths) {
        for (double azimuth_v : {0.0, 90.0, 225.0}) {
          const vec3 v = TangentDirection(zenith_v, azimuth_v);
          std::vector<vec3> lights = {v, -v, vec3(-v.x, -v.y, v.z)};
          for (double zenith_l : light_zeniths) {
            for (double azimuth_l : {0.0, 135.0, 180.0}) {
              lights.push_back(TangentDirection(zenith_l, azimuth_l));
            }
          }
          for (const vec3& l : lights) {
            const double brdf = OceanRossBrdf(v, l, slope_variance, r);
            const double sun = OceanReflectedSun(v, l, slope_variance, r);
            const vec2 zeta_h = OceanHalfVectorSlopes(v, l);
            const double q = OceanVisibleSlopePdf(zeta_h, v, l, slope_variance);
            const double q0 = OceanVisibleSlopePdf(vec2(0.0), v, l, slope_variance);
            ASSERT_TRUE(IsFinite(brdf) && brdf >= 0.0)
                << "sigma^2 " << sx2 << " " << sy2 << " v " << zenith_v << " " << azimuth_v << " l "
                << l.x << " " << l.y << " " << l.z << ": " << brdf;
            ASSERT_TRUE(IsFinite(sun) && sun >= 0.0) << sun;
            ASSERT_TRUE(IsFinite(zeta_h));
            ASSERT_TRUE(IsFinite(q) && q >= 0.0) << q;
            ASSERT_TRUE(IsFinite(q0) && q0 >= 0.0) << q0;
            // Reciprocal up to rounding (1e-11 relative where the BRDF reaches 1e17 sr^-1, a
            // flat sea's mirror direction at grazing incidence).
            EXPECT_LE(std::abs(OceanRossBrdf(l, v, slope_variance, r) - brdf), 1e-9 * brdf);
            if (l.z <= 0.0) {
              EXPECT_EQ(sun, 0.0);
            }
            ++checked;
          }
          ASSERT_TRUE(IsFinite(OceanVisibleSlopePdfE(vec2(0.0), v, slope_variance)));
          ASSERT_TRUE(IsFinite(OceanVisibleSlopePdfE(vec2(0.3, -0.2), v, slope_variance)));
          ASSERT_TRUE(IsFinite(OceanSmithLambdaToward(v, slope_variance)));
          ASSERT_GT(OceanSmithFacingAreaToward(v, slope_variance), 0.0);
          const double view_variance = OceanSlopeVarianceToward(v, slope_variance);
          ASSERT_TRUE(IsFinite(view_variance));
          const double fresnel = OceanEffectiveFresnel(v.z, view_variance, r);
          ASSERT_TRUE(IsFinite(fresnel) && fresnel >= r && fresnel <= 1.0) << fresnel;
          for (double tilt : {0.0, 60.0, 90.0}) {
            vec3 t_x, t_y, n;
            TiltedFrame(tilt, 0.0, 30.0, t_x, t_y, n);
            vec2 u0, du_x, du_y;
            OceanSkyMapGradients(v, t_x, t_y, n, u0, du_x, du_y);
            ASSERT_TRUE(IsFinite(u0) && IsFinite(du_x) && IsFinite(du_y));
            ASSERT_TRUE(IsFinite(OceanSkyMapCoordinates(v, t_x, t_y, n, vec2(0.5, -2.0))));
          }
        }
      }
    }
  }
  std::printf("extreme inputs: %d (v, l, sigma) combinations finite\n", checked);
  // The light at or below the horizon shadows every facet; a view below the surface sees none.
  EXPECT_EQ(
      OceanReflectedSun(TangentDirection(30.0, 0.0), TangentDirection(90.0, 180.0), vec2(0.01), r),
      0.0);
  EXPECT_EQ(
      OceanRossBrdf(TangentDirection(95.0, 0.0), TangentDirection(30.0, 180.0), vec2(0.01), r),
      0.0);
  // A horizontal view toward the glint of a low sun is finite and positive without any clamp.
  const double grazing = OceanReflectedSun(TangentDirection(90.0, 180.0),
                                           TangentDirection(85.0, 0.0), vec2(0.02, 0.01), r);
  EXPECT_GT(grazing, 0.0);
  EXPECT_TRUE(std::isfinite(grazing));
}

TEST(RossBrdf, SlopeVarianceTowardAndWeights) {
  // Eq. 25 against the paper's angle form, sigma_x^2 cos^2 phi + sigma_y^2 sin^2 phi with
  // phi = atan(v.t_y, v.t_x); the azimuthal mean at the zenith.
  const vec2 slope_variance(0.04, 0.01);
  for (double azimuth = 0.0; azimuth < 360.0; azimuth += 20.0) {
    const vec3 v = TangentDirection(50.0, azimuth);
    const double phi = std::atan2(v.y, v.x);
    EXPECT_NEAR(OceanSlopeVarianceToward(v, slope_variance),
                0.04 * std::cos(phi) * std::cos(phi) + 0.01 * std::sin(phi) * std::sin(phi), 1e-16);
  }
  EXPECT_DOUBLE_EQ(OceanSlopeVarianceToward(vec3(0.0, 0.0, 1.0), slope_variance), 0.025);
  // The weights of sec. 3.2: 0 below a, 1 above b, 3 x^2 - 2 x^3 between, 1/2 at the middle.
  EXPECT_EQ(WaveFilterWeight(1.0, 2.5, 0.5), 0.0);
  EXPECT_EQ(WaveFilterWeight(1.0, 2.5, 1.0), 0.0);
  EXPECT_EQ(WaveFilterWeight(1.0, 2.5, 2.5), 1.0);
  EXPECT_EQ(WaveFilterWeight(1.0, 2.5, 40.0), 1.0);
  EXPECT_DOUBLE_EQ(WaveFilterWeight(1.0, 2.5, 1.75), 0.5);
  EXPECT_DOUBLE_EQ(WaveFilterWeight(1.0, 2.5, 1.3), 3.0 * 0.04 - 2.0 * 0.008);
  EXPECT_EQ(WaveFilterWeight(2.0, 2.0, 1.9), 0.0);
  EXPECT_EQ(WaveFilterWeight(2.0, 2.0, 2.0), 1.0);
  // Eq. 7 is normalised with per-axis variances: its peak is 1 / (2 pi sigma_x sigma_y).
  EXPECT_DOUBLE_EQ(OceanSlopePdf(vec2(0.0), slope_variance), 1.0 / (2.0 * PI * 0.2 * 0.1));
  EXPECT_DOUBLE_EQ(OceanSlopePdf(vec2(0.2, 0.0), slope_variance),
                   std::exp(-0.5) / (2.0 * PI * 0.2 * 0.1));
}

// The average of the standard normal density over [x - h, x + h] against std::erfc in double,
// across the switch from its Taylor series to differences of tails (h = 0.25) and far into the
// tails, where the A&S 7.1.26 scaled erfc keeps its relative precision: the largest relative
// error is printed (measured 3.6e-3 up to 6 standard deviations out, 1.4e-2 from 6 to 9).
TEST(RossBrdf, NormalBoxAverageMatchesErfc) {
  double worst_near = 0.0, worst_far = 0.0;
  for (double x = 0.0; x <= 9.0; x += 0.0625) {
    for (double h : {0.0, 1e-6, 0.01, 0.1, 0.2499, 0.25, 0.2501, 0.5, 1.0, 2.5, 5.0, 12.0}) {
      const double exact =
          h == 0.0
              ? std::exp(-0.5 * x * x) / std::sqrt(2.0 * PI)
              : 0.5 * (std::erfc((x - h) / std::sqrt(2.0)) - std::erfc((x + h) / std::sqrt(2.0))) /
                    (2.0 * h);
      const double value = OceanNormalBoxAverage(x, h);
      ASSERT_TRUE(IsFinite(value));
      EXPECT_EQ(value, OceanNormalBoxAverage(-x, h));
      if (exact < 1e-300) continue;
      const double error = std::abs(value / exact - 1.0);
      (x - h <= 6.0 ? worst_near : worst_far) =
          std::max(x - h <= 6.0 ? worst_near : worst_far, error);
    }
  }
  std::printf("box average of the normal density: relative error %.2e within 6 sd, %.2e to 9\n",
              worst_near, worst_far);
  EXPECT_LT(worst_near, 5e-3);
  EXPECT_LT(worst_far, 2e-2);
}

// The pixel's average of eq. 7 (OceanPixelSlopePdf) against the integral over its parallelogram
// (512 x 512 midpoints), and the energy it conserves: summed over a lattice of pixels d_x and
// d_y apart and times the pixel's slope area |d_x x d_y|, it is the integral of p, 1, wherever
// the lattice falls. Exact (to the erfc's precision) for a pixel whose sides lie along the wind
// axes; the conditioning approximation elsewhere. Slope variances of the 3 m/s sea (2.4e-4, 7.2e-5)
// and pixels from a tenth of a standard deviation to ten across, turned and sheared. Measured:
// axis-aligned within 2.3e-6 of the lobe's brightest pixel; turned and sheared pixels within
// 0.6 % of it; the energy within 1.4e-4 of 1 (printed).
TEST(RossBrdf, PixelSlopePdfIsTheAverageOverThePixel) {
  const vec2 s2(2.4e-4, 7.2e-5);
  const vec2 sigma = sqrt(s2);
  constexpr int kGrid = 512;
  const auto integral = [&](const vec2& zeta, const vec2& d_x, const vec2& d_y) {
    double sum = 0.0;
    for (int j = 0; j < kGrid; ++j)
      for (int i = 0; i < kGrid; ++i)
        sum += OceanSlopePdf(
            zeta + ((i + 0.5) / kGrid - 0.5) * d_x + ((j + 0.5) / kGrid - 0.5) * d_y, s2);
    return sum / (kGrid * kGrid);
  };
  struct Pixel {
    vec2 d_x, d_y;  // in standard deviations
    bool aligned;
  };
  const std::vector<Pixel> pixels = {
      {vec2(0.1, 0.0), vec2(0.0, 0.1), true},   {vec2(4.8, 0.0), vec2(0.0, 0.4), true},
      {vec2(0.0, 4.8), vec2(0.4, 0.0), true},   {vec2(10.0, 0.0), vec2(0.0, 10.0), true},
      {vec2(3.0, 3.0), vec2(-0.3, 0.3), false}, {vec2(4.0, 1.0), vec2(2.0, 2.0), false},
      {vec2(6.0, -2.0), vec2(1.0, 5.0), false}, {vec2(2.0, 0.5), vec2(1.9, 0.6), false},
  };
  double worst_aligned = 0.0, worst_turned = 0.0, worst_energy = 0.0;
  for (const Pixel& pixel : pixels) {
    const vec2 d_x = pixel.d_x * sigma, d_y = pixel.d_y * sigma;
    // The lobe's brightest pixel over a lattice through the origin (what errors are relative to).
    double peak = 0.0;
    std::vector<std::pair<vec2, double>> samples;
    for (const vec2 phase : {vec2(0.0), vec2(0.5, 0.5), vec2(0.25, 0.7)}) {
      double energy = 0.0;
      for (int j = -100; j <= 100; ++j) {  // to 9 standard deviations for the smallest pixel
        for (int i = -100; i <= 100; ++i) {
          const vec2 zeta = (i + phase.x) * d_x + (j + phase.y) * d_y;
          if (length(zeta / sigma) > 9.0) continue;
          const double value = OceanPixelSlopePdf(zeta, d_x, d_y, s2);
          ASSERT_TRUE(IsFinite(value));
          energy += value;
          peak = std::max(peak, value);
          if (std::abs(i) <= 2 && std::abs(j) <= 2 && phase.x > 0.2)
            samples.push_back({zeta, value});
        }
      }
      energy *= std::abs(d_x.x * d_y.y - d_x.y * d_y.x);
      worst_energy = std::max(worst_energy, std::abs(energy - 1.0));
    }
    for (const auto& [zeta, value] : samples) {
      const double error = std::abs(value - integral(zeta, d_x, d_y)) / peak;
      (pixel.aligned ? worst_aligned : worst_turned) =
          std::max(pixel.aligned ? worst_aligned : worst_turned, error);
    }
  }
  std::printf(
      "pixel's average of p: aligned %.2e, turned and sheared %.2e of the brightest "
      "pixel; energy within %.2e of 1\n",
      worst_aligned, worst_turned, worst_energy);
  EXPECT_LT(worst_aligned, 1e-3);
  EXPECT_LT(worst_turned, 0.03);
  EXPECT_LT(worst_energy, 0.01);
  // A pixel that does not move is the point's density; degenerate pixels stay finite.
  const vec2 zeta(0.01, -0.004);
  EXPECT_LT(RelativeDifference(OceanPixelSlopePdf(zeta, vec2(0.0), vec2(0.0), s2),
                               OceanSlopePdf(zeta, s2)),
            1e-12);
  for (const vec2 d : {vec2(0.0), vec2(1e-20), vec2(1e3), vec2(0.5, -0.5)}) {
    EXPECT_TRUE(IsFinite(OceanPixelSlopePdf(zeta, d, d, s2)));  // parallel sides: a segment
    EXPECT_TRUE(IsFinite(OceanPixelSlopePdf(zeta, d, vec2(0.0), vec2(0.0))));
    EXPECT_TRUE(IsFinite(OceanPixelSlopePdf(vec2(1e3), d, vec2(d.y, -d.x), vec2(1.0))));
  }
}

// A pixel's light is eq. 15 integrated over the pixel's view directions; the full method
// evaluates OceanReflectedSunOverPixel at the centre with the mirror slope's changes across the
// pixel. Checked against the integral (64 x 64 directions a pixel) on rows of pixels 0.0109 rad
// wide (the default suite's: 45 degrees over 72 rows) looking toward a sun 10 degrees high along
// the wind, the glitter path on the edge between two columns and on a column's middle. On the 3
// m/s sea (slope variances 2.4e-4, 7.2e-5) eq. 15 at the centre draws 0.03 to 0.67 of the rows'
// light with the path on the edge, 1.3 to 2.4 times it on the middle; the pixel's average 0.998
// to 1.007 from 6 degrees above the sea, 1.017 to 1.022 at 3 and 1.038 to 1.047 at 1.5, where
// the factors of eq. 15 held at the centre (the masking, h_z^-4) change across the pixel: its
// lower edge sees the sea at 1.19 degrees, its upper at 1.81 (printed). On a 20 m/s sea (0.02 per
// axis) both are within 0.1 %.
TEST(RossBrdf, SunOverAPixelIsEq15AveragedOverThePixel) {
  constexpr double kPixel = 0.0109;  // rad
  constexpr int kSub = 64;
  const vec3 l = TangentDirection(80.0, 180.0);
  // Toward the eye from the sea, elevation and azimuth in radians (the eye toward +x).
  const auto view = [](double elevation, double azimuth) {
    return vec3(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                std::sin(elevation));
  };
  for (const vec2 slope_variance : {vec2(2.4e-4, 7.2e-5), vec2(0.02, 0.02)}) {
    const bool calm = slope_variance.x < 1e-3;
    for (const double offset : {0.5, 0.0}) {
      for (const double elevation_deg : {1.5, 3.0, 6.0, 12.0}) {
        double averaged = 0.0, over_pixel = 0.0, centre = 0.0;
        for (int column = -12; column < 12; ++column) {
          const double e = elevation_deg * DEGREE, a = (column + offset) * kPixel;
          double sum = 0.0;
          for (int j = 0; j < kSub; ++j) {
            for (int i = 0; i < kSub; ++i) {
              const vec3 v = view(e + ((j + 0.5) / kSub - 0.5) * kPixel,
                                  a + ((i + 0.5) / kSub - 0.5) * kPixel);
              sum += OceanReflectedSun(v, l, slope_variance, OCEAN_DEFAULT_FRESNEL_R);
            }
          }
          averaged += sum / (kSub * kSub);
          const vec2 zeta_dx = OceanHalfVectorSlopes(view(e, a + 0.5 * kPixel), l) -
                               OceanHalfVectorSlopes(view(e, a - 0.5 * kPixel), l);
          const vec2 zeta_dy = OceanHalfVectorSlopes(view(e + 0.5 * kPixel, a), l) -
                               OceanHalfVectorSlopes(view(e - 0.5 * kPixel, a), l);
          over_pixel += OceanReflectedSunOverPixel(view(e, a), l, slope_variance,
                                                   OCEAN_DEFAULT_FRESNEL_R, zeta_dx, zeta_dy);
          centre += OceanReflectedSun(view(e, a), l, slope_variance, OCEAN_DEFAULT_FRESNEL_R);
        }
        std::printf(
            "variance %.1e, path at %.1f of a column, view %4.1f deg above the sea: over the "
            "pixel / averaged %.4f, centre / averaged %.4f\n",
            slope_variance.x, offset, elevation_deg, over_pixel / averaged, centre / averaged);
        ASSERT_GT(averaged, 0.0);
        EXPECT_LT(std::abs(over_pixel / averaged - 1.0), !calm                 ? 0.001
                                                         : elevation_deg < 2.0 ? 0.06
                                                         : elevation_deg < 5.0 ? 0.03
                                                                               : 0.01);
        if (calm && offset == 0.5) {
          EXPECT_LT(centre / averaged, 0.7);  // what the average is for
        }
      }
    }
  }
  // No motion: eq. 15 itself.
  const vec3 v = view(0.1, 0.02);
  EXPECT_LT(RelativeDifference(
                OceanReflectedSunOverPixel(v, l, vec2(2.4e-4, 7.2e-5), 0.02, vec2(0.0), vec2(0.0)),
                OceanReflectedSun(v, l, vec2(2.4e-4, 7.2e-5), 0.02)),
            1e-12);
}

}  // namespace
}  // namespace thalassa::glsl
