// Order selection, angular prefiltering and the measured error (thalassa/atmosphere/
// sh_prefilter.hpp; Ramamoorthi & Hanrahan 2002, sec. 5, 6, appendices B-D). Each test checks an
// identity or a property that could fail:
// - energies: Parseval (the coefficients' energy tends to the table's quadrature of rho-hat^2,
//   and to the closed form for Phong); the Phong support of appendix D found numerically;
// - order selection (appendix C): the orders meet the tolerance, are the smallest that do, and
//   grow as epsilon shrinks; Phong's F follows appendix D's sqrt(-s log epsilon);
// - the angular baseline: a constant environment gives albedo x constant (Phong's albedo is 1,
//   the microfacet's from an independent quadrature); the support loop visits exactly the texels
//   within the support; it converges at second order to the SH route on a band-limited
//   environment (where the SH route is exact);
// - the radially symmetric shortcut equals the general SHRM route (eq. 14 with P = 0);
// - the measured error epsilon_B falls as epsilon falls and stays below the prediction times a
//   factor taken from measurement (stated at the assertion);
// - bad input throws.
//
// Measured values are printed as "[measured] ..." lines; asserted bounds are the measured values
// with a margin, stated at each assertion.
#include <gtest/gtest.h>

#include "gauss_legendre.hpp"
#include "synthetic_sky.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "thalassa/atmosphere/sh_brdf.hpp"
#include "thalassa/atmosphere/sh_prefilter.hpp"
#include "thalassa/atmosphere/spherical_harmonics.hpp"

namespace thalassa::sh {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr unsigned kSeed = 20020721;  // any fixed seed: the tests are deterministic

// Random lighting of order `order` with coefficients decaying as exp(-l^2 / 8) and a positive
// mean (L_00 = 3 sqrt(4 pi)), sampled on a width x height lat-long map.
std::vector<double> band_limited_map(int order, int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> c(coefficient_count(order));
  for (int l = 0; l <= order; ++l) {
    for (int m = -l; m <= l; ++m) c[index(l, m)] = u(rng) * std::exp(-0.125 * l * l);
  }
  c[index(0, 0)] = 3.0 * std::sqrt(4.0 * kPi);
  return reconstruct_lat_long(c, order, LatLongLayout{width, height, 1, 0});
}

double max_relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return worst / scale;
}

// The directional albedo ∫ brdf(V, L) d omega_L (the BRDF is cosine-weighted) for a view at
// theta_v from the normal, by Gauss-Legendre in cos theta_L on [0, 1] times a uniform azimuth
// rule, in the tangent frame: independent of the reflection-frame code under test.
double directional_albedo(const CosineWeightedBrdf& brdf, double theta_v) {
  constexpr int kNodes = 200, kAzimuths = 400;
  const test::Quadrature1d g = test::gauss_legendre(kNodes);
  const Vec3 view = {std::sin(theta_v), 0.0, std::cos(theta_v)};
  double sum = 0.0;
  for (int i = 0; i < kNodes; ++i) {
    const double t = 0.5 * (g.x[i] + 1.0), st = std::sqrt(1.0 - t * t);
    double ring = 0.0;
    for (int k = 0; k < kAzimuths; ++k) {
      const double phi = 2.0 * kPi * (k + 0.5) / kAzimuths;
      ring += brdf(view, {st * std::cos(phi), st * std::sin(phi), t});
    }
    sum += 0.5 * g.w[i] * ring * 2.0 * kPi / kAzimuths;
  }
  return sum;
}

// ---- Energies and supports ------------------------------------------------------------------

// Parseval: the closed-form Phong energy 2 (s + 1)^2 / (2s + 1) is the limit of the coefficients'
// energy and the table's quadrature of rho-hat^2; the microfacet table's coefficients at the
// largest orders it resolves hold nearly all its quadrature energy and never more (Bessel).
TEST(ShPrefilterEnergy, ParsevalForPhongAndMicrofacet) {
  for (double s : {8.0, 64.0}) {
    const double closed = phong_energy(s);
    const double sum = brdf_energy(phong_coefficients(s, 200), 200, 0);
    const double table = brdf_energy(tabulate(phong_brdf(s), BrdfGrid{256, 2, 2}));
    std::printf(
        "[measured] Phong s = %g: coefficients / closed - 1 = %.1e, table / closed - 1 = "
        "%.1e\n",
        s, sum / closed - 1.0, table / closed - 1.0);
    // Measured: 4e-16 (the tail beyond l = 200 is below rounding) and 3e-14 (256 Gauss nodes
    // across the C^s kink of max(cos, 0)^s at 90 degrees).
    EXPECT_NEAR(sum / closed, 1.0, 1e-12) << "s = " << s;
    EXPECT_NEAR(table / closed, 1.0, 1e-10) << "s = " << s;
  }
  const BrdfTable table =
      tabulate(reparameterize_by_reflection(microfacet_brdf(0.3)), BrdfGrid{48, 16, 16});
  const double total = brdf_energy(table);
  const double held = brdf_energy(project_brdf(table, 47, 15), 47, 15);
  std::printf("[measured] microfacet 0.3: coefficients (47, 15) / table = %.6f\n", held / total);
  EXPECT_LE(held, total * (1.0 + 1e-9));  // Bessel's inequality for the discrete inner product
  EXPECT_GT(held / total, 0.99);          // measured 0.99925: the horizon cut's slow tail
}

// Appendix D: cos theta* = epsilon^(1 / (s + 1)) for Phong, found here by integrating the
// reparameterised BRDF numerically (brdf_support), to within its theta step.
TEST(ShPrefilterEnergy, NumericalSupportMatchesAppendixD) {
  constexpr double kStep = kPi / 2048;  // brdf_support's theta step
  for (double s : {8.0, 64.0, 512.0}) {
    for (double epsilon : {0.05, 0.01}) {
      const double analytic = phong_support(s, epsilon);
      const double numeric = brdf_support(phong_brdf(s), 1.0, epsilon);
      EXPECT_GE(numeric, analytic - 1e-12) << "s = " << s << ", epsilon = " << epsilon;
      EXPECT_LE(numeric, analytic + kStep) << "s = " << s << ", epsilon = " << epsilon;
    }
  }
  // A rougher lobe needs a wider support.
  const ReparameterizedBrdf rough = reparameterize_by_reflection(microfacet_brdf(0.4));
  const ReparameterizedBrdf sharp = reparameterize_by_reflection(microfacet_brdf(0.1));
  EXPECT_GT(brdf_support(rough, 1.0, 0.05), 2.0 * brdf_support(sharp, 1.0, 0.05));
}

// ---- Order selection -----------------------------------------------------------------------

// Appendix C with sec. 5.1's error: the chosen orders meet the tolerance, are the smallest that
// do (P first, then F), and grow as epsilon shrinks; Phong's F follows appendix D.
TEST(ShPrefilterOrders, MeetToleranceMinimallyAndGrowAsEpsilonShrinks) {
  const std::vector<double> epsilons = {0.3, 0.1, 0.03, 0.01, 0.003, 0.001};
  for (double s : {8.0, 32.0, 128.0, 512.0}) {
    const BrdfCoefficients rho = phong_coefficients(s, 150);
    const double total = phong_energy(s);
    int previous = -1;
    for (double epsilon : epsilons) {
      const OrderChoice c = choose_orders(rho, total, epsilon);
      EXPECT_EQ(c.order_p, 0);
      EXPECT_LE(c.predicted_error, epsilon);
      EXPECT_GE(c.order_l, previous) << "s = " << s << ", epsilon = " << epsilon;
      if (c.order_l > 0) {
        EXPECT_LT(brdf_energy(rho, c.order_l - 1, 0), (1.0 - epsilon) * total);  // minimal
      }
      // Appendix D: F ~ sqrt(-s log epsilon) (from exp(-l^2 / 2s)); measured 0.07 .. 0.87 below.
      EXPECT_NEAR(c.order_l, std::sqrt(-s * std::log(epsilon)), 1.0)
          << "s = " << s << ", epsilon = " << epsilon;
      previous = c.order_l;
    }
  }
  for (double sigma : {0.2, 0.4}) {
    const BrdfTable table =
        tabulate(reparameterize_by_reflection(microfacet_brdf(sigma)), BrdfGrid{64, 16, 16});
    const double total = brdf_energy(table);
    int previous_l = -1, previous_p = -1;
    for (double epsilon : {0.3, 0.1, 0.03, 0.01}) {
      const OrderChoice c = choose_orders(table, epsilon);
      std::printf("[measured] microfacet %.1f, epsilon %.2f: F = %d, P = %d, predicted %.2e\n",
                  sigma, epsilon, c.order_l, c.order_p, c.predicted_error);
      EXPECT_LE(c.predicted_error, epsilon);
      EXPECT_NEAR(c.total_energy, total, 1e-12 * total);
      EXPECT_GE(c.order_l, previous_l) << "sigma = " << sigma << ", epsilon = " << epsilon;
      EXPECT_GE(c.order_p, previous_p) << "sigma = " << sigma << ", epsilon = " << epsilon;
      const BrdfCoefficients rho = project_brdf(table, c.order_l, c.order_p);
      if (c.order_l > 0) {
        EXPECT_LT(brdf_energy(rho, c.order_l - 1, c.order_p), (1.0 - epsilon) * total);
      }
      previous_l = c.order_l;
      previous_p = c.order_p;
    }
  }
}

// ---- The angular baseline --------------------------------------------------------------------

// A constant environment c gives c times the albedo: 1 for the normalised Phong lobe (and
// 1 - epsilon within its appendix-D support), the directional albedo for the microfacet BRDF.
TEST(ShPrefilterAngular, ConstantEnvironmentGivesAlbedoTimesConstant) {
  constexpr double kRadiance = 2.5;
  const LatLongLayout layout{128, 64, 1, 0};
  const std::vector<double> env(128 * 64, kRadiance);
  for (double s : {8.0, 64.0}) {
    for (double epsilon : {0.0, 0.05}) {
      const double support = epsilon > 0.0 ? phong_support(s, epsilon) : 0.0;
      const std::vector<double> b =
          angular_prefilter(env, layout, phong_radial_brdf(s), AngularOptions{16, 8, support});
      double worst = 0.0;
      for (double v : b) worst = std::max(worst, std::abs(v / kRadiance - (1.0 - epsilon)));
      std::printf("[measured] Phong s = %g, support epsilon %.2f: max |B / c - albedo| = %.1e\n", s,
                  epsilon, worst);
      // Measured 7e-4 .. 1.8e-3 at 128 x 64 input: the midpoint rule's (texel size)^2 error.
      EXPECT_LT(worst, 3e-3) << "s = " << s;
    }
  }
  const CosineWeightedBrdf brdf = microfacet_brdf(0.3);
  for (double theta_o : {0.3, 1.2, 2.0}) {
    const double albedo = directional_albedo(brdf, 0.5 * theta_o);  // theta_o = 2 theta_v
    const std::vector<double> b =
        angular_prefilter(env, layout, brdf, theta_o, 0.4, AngularOptions{16, 8, 0.0});
    double worst = 0.0;
    for (double v : b) worst = std::max(worst, std::abs(v / kRadiance - albedo) / albedo);
    std::printf("[measured] microfacet 0.3, theta_o %.1f: albedo %.4f, max relative error %.1e\n",
                theta_o, albedo, worst);
    EXPECT_LT(worst, 3e-3) << "theta_o = " << theta_o;  // measured <= 1e-3
  }
}

// The support loop skips rows and azimuths: it must visit exactly the texels whose centre is
// within the support, as a naive loop over every texel does (including output texels at the
// poles and cones that wrap around phi = 0 or cover a pole).
TEST(ShPrefilterAngular, SupportVisitsExactlyTheTexelsWithin) {
  constexpr int kW = 48, kH = 24, kOutW = 12, kOutH = 6;
  const std::vector<double> env = band_limited_map(5, kW, kH, kSeed);
  const LatLongLayout layout{kW, kH, 1, 0};
  const RadialBrdf brdf = phong_radial_brdf(2.0);
  for (double support : {0.2, 0.7, 2.0}) {
    const std::vector<double> b =
        angular_prefilter(env, layout, brdf, AngularOptions{kOutW, kOutH, support});
    for (int y = 0; y < kOutH; ++y) {
      for (int x = 0; x < kOutW; ++x) {
        const Vec3 c = lat_long_direction(kOutW, kOutH, x, y);
        double naive = 0.0;
        for (int row = 0; row < kH; ++row) {
          const double solid_angle =
              (2.0 * kPi / kW) * (std::cos(row * kPi / kH) - std::cos((row + 1) * kPi / kH));
          for (int column = 0; column < kW; ++column) {
            const Vec3 d = lat_long_direction(kW, kH, column, row);
            const double cos_angle = c[0] * d[0] + c[1] * d[1] + c[2] * d[2];
            if (cos_angle >= std::cos(support)) {
              naive +=
                  env[static_cast<std::size_t>(row * kW + column)] * brdf(cos_angle) * solid_angle;
            }
          }
        }
        EXPECT_NEAR(b[static_cast<std::size_t>(y * kOutW + x)], naive, 1e-12 * std::abs(naive))
            << "support " << support << ", texel " << x << ", " << y;
      }
    }
  }
}

// On a band-limited environment the SH route is exact (the projection is exact, the convolution
// is eq. 5), so the angular baseline must converge to it; its midpoint rule is second order:
// doubling the input resolution divides the difference by 4.
TEST(ShPrefilterAngular, ConvergesToShRouteOnBandLimitedEnvironment) {
  constexpr int kOrder = 4;
  for (double s : {2.0, 8.0}) {
    std::vector<double> differences;
    for (int h : {64, 128}) {
      const LatLongLayout layout{2 * h, h, 1, 0};
      const std::vector<double> env = band_limited_map(kOrder, 2 * h, h, kSeed);
      const std::vector<double> lighting = project_lat_long(env, layout, kOrder);
      const std::vector<double> sh =
          radial_reflection_map(lighting, kOrder, phong_coefficients(s, kOrder), 16, 8);
      const std::vector<double> angular =
          angular_prefilter(env, layout, phong_radial_brdf(s), AngularOptions{16, 8, 0.0});
      differences.push_back(max_relative_difference(angular, sh));
    }
    std::printf(
        "[measured] Phong s = %g: angular vs SH, max relative %.2e (H = 64), %.2e (H = "
        "128)\n",
        s, differences[0], differences[1]);
    EXPECT_LT(differences[1], 3e-4) << "s = " << s;  // measured 4.8e-5 (s = 2), 1.6e-4 (s = 8)
    EXPECT_NEAR(differences[0] / differences[1], 4.0, 0.5) << "s = " << s;  // measured 4.0
  }
  // Microfacet: a band-limited lighting of order 3 makes F = 3 exact; the view order P is not
  // band-limited (the horizon cut N.L = 0), so the SH route converges in P.
  constexpr int kLightOrder = 3;
  const LatLongLayout layout{256, 128, 1, 0};
  const std::vector<double> env = band_limited_map(kLightOrder, 256, 128, kSeed);
  const std::vector<double> lighting = project_lat_long(env, layout, kLightOrder);
  const CosineWeightedBrdf brdf = microfacet_brdf(0.4);
  const BrdfTable table = tabulate(reparameterize_by_reflection(brdf), BrdfGrid{32, 48, 48});
  for (double theta_o : {0.4, 1.5}) {
    const std::vector<double> angular =
        angular_prefilter(env, layout, brdf, theta_o, 0.7, AngularOptions{8, 4, 0.0});
    double previous = 1.0;
    for (int p : {4, 8, 16}) {
      const ShrmMap shrm = local_shrm_map(
          convolve(lighting, kLightOrder, project_brdf(table, kLightOrder, p)), 8, 4);
      const double d = max_relative_difference(angular, local_reflection_map(shrm, theta_o, 0.7));
      std::printf("[measured] microfacet 0.4, theta_o %.1f, P = %d: max relative %.2e\n", theta_o,
                  p, d);
      EXPECT_LT(d, previous) << "theta_o = " << theta_o << ", P = " << p;
      previous = d;
    }
    EXPECT_LT(previous, 5e-4) << "theta_o = " << theta_o;  // measured 3.3e-4, 2.7e-4 at P = 16
  }
}

// ---- The frequency-space route ----------------------------------------------------------

// The radially symmetric shortcut (B_lm = A_l L_lm, reconstruct) equals the general route
// (eq. 5, then the local SHRM of eq. 14 with P = 0, times Y_00): the same numbers to rounding.
TEST(ShPrefilterFrequency, RadialShortcutEqualsShrm) {
  constexpr int kOrder = 10;
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> lighting(coefficient_count(kOrder));
  for (double& c : lighting) c = u(rng);
  const BrdfCoefficients rho = phong_coefficients(16.0, kOrder);
  const std::vector<double> shortcut = radial_reflection_map(lighting, kOrder, rho, 12, 6);
  const std::vector<double> shrm =
      local_reflection_map(local_shrm_map(convolve(lighting, kOrder, rho), 12, 6), 0.3, 1.1);
  EXPECT_LT(max_relative_difference(shortcut, shrm), 1e-12);
}

// ---- The measured error (sec. 5.1, appendix B) ----------------------------------------------

// For Phong (several s) and the microfacet BRDF, the measured error epsilon_B of the SH route at
// the chosen orders, against the exact angular integral on the synthetic sky, falls as epsilon
// falls and stays below the predicted BRDF error (the paper's "conservative" estimate, fig. 6).
TEST(ShPrefilterError, MeasuredFallsWithEpsilonAndStaysBelowPrediction) {
  // Measured ratio measured / predicted: 0.02 .. 0.16 (Phong), 0.05 .. 0.55 (microfacet, the
  // highest at epsilon = 0.3). The factor asserted is 1: the prediction is an upper bound here.
  constexpr double kFactor = 1.0;
  constexpr int kW = 128, kH = 64, kOutW = 32, kOutH = 16;
  test::SyntheticSky sky;
  sky.sun_radius = 0.15;  // radians: resolved by the 128 x 64 test map (2.8-degree texels)
  sky.sun_peak = 40.0;
  const std::vector<double> env = sky.lat_long(kW, kH);
  const LatLongLayout layout{kW, kH, 1, 0};
  const std::vector<double> epsilons = {0.3, 0.1, 0.03, 0.01};

  for (double s : {8.0, 32.0, 128.0}) {
    const std::vector<double> exact =
        angular_prefilter(env, layout, phong_radial_brdf(s), AngularOptions{kOutW, kOutH, kPi / 2});
    const BrdfCoefficients rho = phong_coefficients(s, 80);
    std::vector<double> measured;
    for (double epsilon : epsilons) {
      const OrderChoice c = choose_orders(rho, phong_energy(s), epsilon);
      const std::vector<double> lighting = project_lat_long(env, layout, c.order_l);
      EnergyError e;
      e.add(radial_reflection_map(lighting, c.order_l, rho, kOutW, kOutH), exact, kOutW, kOutH);
      std::printf("[measured] Phong s = %g, epsilon %.2f: F = %d, predicted %.2e, measured %.2e\n",
                  s, epsilon, c.order_l, c.predicted_error, e.relative());
      EXPECT_LE(e.relative(), kFactor * c.predicted_error) << "s = " << s << ", eps " << epsilon;
      if (!measured.empty()) {
        EXPECT_LE(e.relative(), measured.back()) << "s = " << s;
      }
      measured.push_back(e.relative());
    }
    EXPECT_LT(measured.back(), 0.1 * measured.front()) << "s = " << s;
  }

  constexpr int kViews = 4;
  for (double sigma : {0.2, 0.4}) {
    const CosineWeightedBrdf brdf = microfacet_brdf(sigma);
    const BrdfTable table = tabulate(reparameterize_by_reflection(brdf), BrdfGrid{64, 16, 16});
    std::vector<std::vector<double>> exact;
    for (int v = 0; v < kViews; ++v) {
      exact.push_back(angular_prefilter(env, layout, brdf, (v + 0.5) * kPi / kViews, 1.3 * v,
                                        AngularOptions{kOutW, kOutH, 0.0}));
    }
    std::vector<double> measured;
    for (double epsilon : epsilons) {
      const OrderChoice c = choose_orders(table, epsilon);
      const std::vector<double> lighting = project_lat_long(env, layout, c.order_l);
      const ShrmMap shrm = local_shrm_map(
          convolve(lighting, c.order_l, project_brdf(table, c.order_l, c.order_p)), kOutW, kOutH);
      EnergyError e;
      for (int v = 0; v < kViews; ++v) {
        const double theta_o = (v + 0.5) * kPi / kViews;
        e.add(local_reflection_map(shrm, theta_o, 1.3 * v), exact[static_cast<std::size_t>(v)],
              kOutW, kOutH, std::sin(theta_o));
      }
      std::printf(
          "[measured] microfacet %.1f, epsilon %.2f: F = %d, P = %d, predicted %.2e, "
          "measured %.2e\n",
          sigma, epsilon, c.order_l, c.order_p, c.predicted_error, e.relative());
      EXPECT_LE(e.relative(), kFactor * c.predicted_error) << "sigma " << sigma;
      if (!measured.empty()) {
        EXPECT_LT(e.relative(), measured.back()) << "sigma " << sigma;
      }
      measured.push_back(e.relative());
    }
    EXPECT_LT(measured.back(), 0.1 * measured.front()) << "sigma = " << sigma;
  }
}

// ---- Bad input ------------------------------------------------------------------------------

TEST(ShPrefilterErrors, BadInputThrows) {
  const BrdfCoefficients rho = phong_coefficients(8.0, 20);
  const double total = phong_energy(8.0);
  for (double epsilon : {0.0, -0.1, 1.0, std::nan("")}) {
    EXPECT_THROW(choose_orders(rho, total, epsilon), std::invalid_argument) << epsilon;
    EXPECT_THROW(phong_support(8.0, epsilon), std::invalid_argument) << epsilon;
  }
  EXPECT_THROW(choose_orders(rho, 0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(choose_orders(rho, 0.5 * total, 0.1), std::invalid_argument);  // too small a total
  EXPECT_THROW(choose_orders(phong_coefficients(512.0, 5), phong_energy(512.0), 0.01),
               std::domain_error);  // order 5 cannot hold 99% of a sharp lobe
  // Nor can a table of 8 nodes: its discrete Parseval makes order 7 hold "all" its energy, and
  // needing the table's last order is the sign that it is too coarse.
  EXPECT_THROW(choose_orders(tabulate(phong_brdf(512.0), BrdfGrid{8, 1, 1}), 0.01),
               std::domain_error);
  EXPECT_NO_THROW(choose_orders(tabulate(phong_brdf(8.0), BrdfGrid{32, 1, 1}), 0.01));
  EXPECT_THROW(brdf_energy(rho, 21, 0), std::invalid_argument);
  EXPECT_THROW(phong_coefficients(0.0, 4), std::invalid_argument);
  EXPECT_THROW(truncate(rho, 4, 1), std::invalid_argument);

  const std::vector<double> env(8 * 4, 1.0);
  const LatLongLayout layout{8, 4, 1, 0};
  const RadialBrdf phong = phong_radial_brdf(8.0);
  EXPECT_THROW(angular_prefilter(env, LatLongLayout{8, 4, 3, 0}, phong, AngularOptions{}),
               std::invalid_argument);  // one channel only
  EXPECT_THROW(angular_prefilter(std::vector<double>(5, 1.0), layout, phong, AngularOptions{}),
               std::invalid_argument);  // buffer too small
  EXPECT_THROW(angular_prefilter(env, layout, phong, AngularOptions{0, 4, 0.0}),
               std::invalid_argument);
  EXPECT_THROW(angular_prefilter(env, layout, phong, AngularOptions{4, 4, -1.0}),
               std::invalid_argument);
  EXPECT_THROW(angular_prefilter(env, layout, RadialBrdf{}, AngularOptions{}),
               std::invalid_argument);
  EXPECT_THROW(angular_prefilter(env, layout, microfacet_brdf(0.2), 4.0, 0.0, AngularOptions{}),
               std::invalid_argument);  // theta_o beyond pi
  std::vector<double> bad = env;
  bad[3] = std::nan("");
  EXPECT_THROW(angular_prefilter(bad, layout, phong, AngularOptions{4, 4, 0.0}),
               std::invalid_argument);

  EnergyError e;
  EXPECT_THROW(e.add(env, std::vector<double>(3, 1.0), 8, 4), std::invalid_argument);
  EXPECT_THROW(e.add(env, env, 8, 4, -1.0), std::invalid_argument);
  EXPECT_EQ(e.relative(), 0.0);
  ShrmMap global;
  global.global = true;
  EXPECT_THROW(local_reflection_map(global, 0.1, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace thalassa::sh
