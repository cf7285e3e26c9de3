// Spherical harmonics toolkit (thalassa/atmosphere/spherical_harmonics.hpp): each test checks an
// identity, not a printed formula. Orthonormality by quadratures exact for the degree
// (Gauss-Legendre in cos θ times a uniform rule in φ), the addition theorem at high order,
// closed forms at l <= 2, projection / reconstruction of band-limited functions, and the rotation
// matrices against a re-projection of the rotated function and the group laws.
//
// Measured errors are printed as "[measured] ..." lines (they are quoted in reports, not asserted
// beyond the tolerances); timings are printed, never asserted (DESIGN sec. 6).
#include <gtest/gtest.h>

#include "gauss_legendre.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "thalassa/atmosphere/spherical_harmonics.hpp"

namespace thalassa::sh {
namespace {

constexpr double kPi = std::numbers::pi;
const double kInvSqrt4Pi = 1.0 / std::sqrt(4.0 * kPi);
constexpr unsigned kSeed = 20020721;  // any fixed seed: the tests are deterministic

// ---- Helpers ---------------------------------------------------------------------------------

using test::gauss_legendre;
using test::Quadrature1d;

// A product rule on the sphere: Gauss-Legendre in t = cos θ (n_theta points) times the uniform
// rule at φ_k = 2 pi k / n_phi. For two harmonics of order <= L it is exact when n_theta >= L + 1
// (the θ parts multiply to a polynomial of degree <= 2L when m + m' is even) and n_phi >= 2L + 1
// (the φ parts are trigonometric polynomials of frequency m ± m' <= 2L; when m + m' is odd
// those frequencies are odd and nonzero and the φ sum is exactly 0).
struct SphereRule {
  std::vector<Vec3> directions;
  std::vector<double> weights;  // steradians, summing to 4 pi
};

SphereRule sphere_rule(int n_theta, int n_phi) {
  const Quadrature1d gl = gauss_legendre(n_theta);
  SphereRule rule;
  for (int i = 0; i < n_theta; ++i) {
    const double t = gl.x[i];
    const double u = std::sqrt((1.0 - t) * (1.0 + t));
    for (int k = 0; k < n_phi; ++k) {
      const double phi = 2.0 * kPi * k / n_phi;
      rule.directions.push_back({u * std::cos(phi), u * std::sin(phi), t});
      rule.weights.push_back(gl.w[i] * 2.0 * kPi / n_phi);
    }
  }
  return rule;
}

std::vector<double> random_coefficients(int order, int channels, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> c(coefficient_count(order) * channels);
  for (double& v : c) v = uniform(rng);
  return c;
}

Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Vec3 d{normal(rng), normal(rng), normal(rng)};
  const double r = std::hypot(d[0], d[1], d[2]);
  return {d[0] / r, d[1] / r, d[2] / r};
}

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) c[3 * i + j] += a[3 * i + k] * b[3 * k + j];
  return c;
}

Vec3 transpose_times(const Mat3& r, const Vec3& d) {  // R^T d
  return {r[0] * d[0] + r[3] * d[1] + r[6] * d[2], r[1] * d[0] + r[4] * d[1] + r[7] * d[2],
          r[2] * d[0] + r[5] * d[1] + r[8] * d[2]};
}

// A uniformly random rotation from a unit quaternion (Shoemake 1992).
Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  double w = normal(rng), x = normal(rng), y = normal(rng), z = normal(rng);
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  return {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
          2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
          2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
}

Mat3 rotation_z(double alpha) {  // counter-clockwise about +z (x towards y)
  const double c = std::cos(alpha), s = std::sin(alpha);
  return {c, -s, 0, s, c, 0, 0, 0, 1};
}

constexpr Mat3 kIdentity = {1, 0, 0, 0, 1, 0, 0, 0, 1};

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]));
  return e;
}

// ---- Known values ------------------------------------------------------------------------------

TEST(SphericalHarmonics, ClosedFormsUpToBandTwo) {
  std::mt19937_64 rng(kSeed);
  std::vector<Vec3> directions = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  for (int i = 0; i < 200; ++i) directions.push_back(random_direction(rng));
  const double c1 = std::sqrt(3.0 / (4.0 * kPi));
  const double c2 = 0.5 * std::sqrt(15.0 / kPi);
  const double c20 = 0.25 * std::sqrt(5.0 / kPi);
  const double c22 = 0.25 * std::sqrt(15.0 / kPi);
  std::vector<double> y(coefficient_count(2));
  for (const Vec3& d : directions) {
    const double x = d[0], yy = d[1], z = d[2];
    evaluate(2, d, y);
    EXPECT_NEAR(y[index(0, 0)], 1.0 / (2.0 * std::sqrt(kPi)), 1e-15);
    // No Condon-Shortley phase: band 1 is sqrt(3 / 4 pi) (y, z, x).
    EXPECT_NEAR(y[index(1, -1)], c1 * yy, 1e-15);
    EXPECT_NEAR(y[index(1, 0)], c1 * z, 1e-15);
    EXPECT_NEAR(y[index(1, 1)], c1 * x, 1e-15);
    EXPECT_NEAR(y[index(2, -2)], c2 * x * yy, 1e-15);
    EXPECT_NEAR(y[index(2, -1)], c2 * yy * z, 1e-15);
    EXPECT_NEAR(y[index(2, 0)], c20 * (3 * z * z - 1), 1e-15);
    EXPECT_NEAR(y[index(2, 1)], c2 * x * z, 1e-15);
    EXPECT_NEAR(y[index(2, 2)], c22 * (x * x - yy * yy), 1e-15);
    // The direction is normalised: a scaled one gives the same values.
    EXPECT_NEAR(evaluate(2, 1, {3 * x, 3 * yy, 3 * z}), c2 * x * z, 1e-15);
  }
}

TEST(SphericalHarmonics, LegendreClosedFormsUpToDegreeTwo) {
  std::vector<double> p(legendre_count(2));
  for (double theta = 0.0; theta <= kPi; theta += kPi / 37) {
    const double t = std::cos(theta), u = std::sin(theta);
    legendre(2, t, u, p);
    EXPECT_NEAR(p[legendre_index(0, 0)], 1.0, 1e-15);
    EXPECT_NEAR(p[legendre_index(1, 0)], std::sqrt(3.0) * t, 1e-15);
    EXPECT_NEAR(p[legendre_index(1, 1)], std::sqrt(3.0) * u, 1e-15);
    EXPECT_NEAR(p[legendre_index(2, 0)], std::sqrt(5.0) * (3 * t * t - 1) / 2, 1e-15);
    EXPECT_NEAR(p[legendre_index(2, 1)], std::sqrt(15.0) * t * u, 1e-15);
    EXPECT_NEAR(p[legendre_index(2, 2)], std::sqrt(15.0) / 2 * u * u, 1e-15);
  }
}

// Ties evaluate() to legendre(): Y_lm = P̄_lm {cos mφ, 1, sin |m|φ} / sqrt(4 pi), at order 200. The
// orthonormality tests at orders 100 and 200 use this product form.
TEST(SphericalHarmonics, EvaluateIsLegendreTimesTrigonometry) {
  constexpr int kOrder = 200;
  std::mt19937_64 rng(kSeed);
  std::vector<double> y(coefficient_count(kOrder)), p(legendre_count(kOrder));
  double worst = 0.0;
  for (int i = 0; i < 20; ++i) {
    const Vec3 d = random_direction(rng);
    evaluate(kOrder, d, y);
    legendre(kOrder, d[2], std::hypot(d[0], d[1]), p);
    const double phi = std::atan2(d[1], d[0]);
    for (int l = 0; l <= kOrder; ++l) {
      for (int m = -l; m <= l; ++m) {
        const double pm = p[legendre_index(l, std::abs(m))] * kInvSqrt4Pi;
        const double expected =
            m == 0 ? pm : (m > 0 ? pm * std::cos(m * phi) : pm * std::sin(-m * phi));
        worst = std::max(worst, std::abs(y[index(l, m)] - expected));
      }
    }
  }
  std::printf("[measured] order %d: max |evaluate - legendre * trig| = %.2e\n", kOrder, worst);
  EXPECT_LT(worst, 1e-12);
}

// ---- Orthonormality ------------------------------------------------------------------------

// Every pair up to order 30, with evaluate() at the nodes of an exact product rule.
TEST(SphericalHarmonics, FullGramMatrixIsIdentityToOrderThirty) {
  constexpr int kOrder = 30;
  const SphereRule rule = sphere_rule(kOrder + 1, 2 * kOrder + 1);
  const std::size_t n = coefficient_count(kOrder);
  std::vector<double> gram(n * n, 0.0), y(n);
  for (std::size_t k = 0; k < rule.directions.size(); ++k) {
    evaluate(kOrder, rule.directions[k], y);
    for (std::size_t i = 0; i < n; ++i) {
      const double wy = rule.weights[k] * y[i];
      double* row = &gram[i * n];
      for (std::size_t j = 0; j <= i; ++j) row[j] += wy * y[j];
    }
  }
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j <= i; ++j)
      worst = std::max(worst, std::abs(gram[i * n + j] - (i == j ? 1.0 : 0.0)));
  std::printf("[measured] order %d, all %zu pairs: max |G - I| = %.2e\n", kOrder, n * (n + 1) / 2,
              worst);
  EXPECT_LT(worst, 1e-10);
}

// Orders 100 and 200: the Gram entries by the same exact product rule, in its separated form
// (θ sum of legendre() products times φ sum of the trigonometric factors, which equals the rule
// applied to evaluate() by the test above). Checked: the whole diagonal; every pair (l, l') of the
// same m at order 100 (the pairs whose orthogonality rests on the Legendre recurrence, not on the
// φ integral); and kRandomPairs random pairs of each kind (same m, any m) at both orders.
void check_orthonormality_separated(int order, bool all_same_m_pairs) {
  constexpr int kRandomPairs = 300;
  const Quadrature1d gl = gauss_legendre(order + 1);
  const int n_phi = 2 * order + 1;
  const std::size_t lc = legendre_count(order);
  std::vector<double> p(gl.x.size() * lc);  // P̄ at each node
  for (std::size_t i = 0; i < gl.x.size(); ++i) {
    legendre(order, gl.x[i], std::span<double>(p).subspan(i * lc, lc));
  }
  auto theta_integral = [&](int l, int lp, int m_abs, int mp_abs) {
    double s = 0.0;
    const std::size_t a = legendre_index(l, m_abs), b = legendre_index(lp, mp_abs);
    for (std::size_t i = 0; i < gl.x.size(); ++i) s += gl.w[i] * p[i * lc + a] * p[i * lc + b];
    return s;
  };
  auto trig = [](int m, double phi) {
    return m == 0 ? 1.0 : (m > 0 ? std::cos(m * phi) : std::sin(-m * phi));
  };
  auto phi_integral = [&](int m, int mp) {
    double s = 0.0;
    for (int k = 0; k < n_phi; ++k) {
      const double phi = 2.0 * kPi * k / n_phi;
      s += trig(m, phi) * trig(mp, phi);
    }
    return s * 2.0 * kPi / n_phi;
  };
  auto gram = [&](int l, int m, int lp, int mp) {
    return theta_integral(l, lp, std::abs(m), std::abs(mp)) * phi_integral(m, mp) / (4.0 * kPi);
  };

  double worst_diagonal = 0.0, worst_pairs = 0.0;
  for (int l = 0; l <= order; ++l)
    for (int m = -l; m <= l; ++m)
      worst_diagonal = std::max(worst_diagonal, std::abs(gram(l, m, l, m) - 1.0));

  std::size_t pairs = 0;
  if (all_same_m_pairs) {
    // The Gram entry of (l, m), (l', m) is ∫ P̄_lm P̄_l'm dt times 1/2 (m = 0) or 1/4 (m != 0,
    // same trig factor); 1/2 bounds both.
    for (int m = 0; m <= order; ++m)
      for (int l = m; l <= order; ++l)
        for (int lp = m; lp < l; ++lp) {
          worst_pairs = std::max(worst_pairs, std::abs(theta_integral(l, lp, m, m)) / 2.0);
          ++pairs;
        }
  }
  std::mt19937_64 rng(kSeed + order);
  std::uniform_int_distribution<int> pick_l(0, order);
  for (int i = 0; i < 2 * kRandomPairs; ++i) {
    const int l = pick_l(rng), lp = pick_l(rng);
    std::uniform_int_distribution<int> pick_m(-l, l);
    const int m = pick_m(rng);
    int mp;
    if (i % 2 == 0 && std::abs(m) <= lp) {
      mp = m;  // same m: the Legendre part must vanish
    } else {
      std::uniform_int_distribution<int> pick_mp(-lp, lp);
      mp = pick_mp(rng);
    }
    if (l == lp && m == mp) continue;
    worst_pairs = std::max(worst_pairs, std::abs(gram(l, m, lp, mp)));
    ++pairs;
  }
  std::printf(
      "[measured] order %d: diagonal max |G - 1| = %.2e, %zu off-diagonal pairs max |G| = "
      "%.2e\n",
      order, worst_diagonal, pairs, worst_pairs);
  EXPECT_LT(worst_diagonal, 1e-10);
  EXPECT_LT(worst_pairs, 1e-10);
}

TEST(SphericalHarmonics, OrthonormalAtOrderHundred) { check_orthonormality_separated(100, true); }
TEST(SphericalHarmonics, OrthonormalAtOrderTwoHundred) {
  check_orthonormality_separated(200, false);
}

// ---- High orders: no overflow, the addition theorem ----------------------------------------

// Directions that stress the recurrences: the poles, within 1e-12 of them, the equator, and
// sin θ = 1/e, where u^m underflows first relative to the size of the values it seeds.
std::vector<double> stress_thetas() {
  const double inverse_e = std::asin(1.0 / std::exp(1.0));  // sin θ = 1/e
  std::vector<double> thetas = {0.0,        1e-300,     1e-12,       1e-6,    1e-3,
                                0.05,       0.3,        inverse_e,   kPi / 2, kPi - inverse_e,
                                kPi - 1e-3, kPi - 1e-9, kPi - 1e-12, kPi};
  for (int i = 1; i < 40; ++i) thetas.push_back(kPi * i / 40.0 + 0.0123);
  return thetas;
}

// sum_m P̄_lm(t)^2 = 2l + 1 (the addition theorem, Y form: sum_m Y_lm^2 = (2l + 1) / 4 pi), for
// every l <= order, relative error. A value lost to underflow or overflow breaks it.
double worst_addition_theorem_legendre(int order, double theta) {
  std::vector<double> p(legendre_count(order));
  legendre(order, std::cos(theta), std::sin(theta), p);
  double worst = 0.0;
  for (int l = 0; l <= order; ++l) {
    double sum = 0.0;
    for (int m = 0; m <= l; ++m) {
      const double v = p[legendre_index(l, m)];
      EXPECT_TRUE(std::isfinite(v)) << "l " << l << " m " << m << " theta " << theta;
      sum += v * v;
    }
    worst = std::max(worst, std::abs(sum / (2.0 * l + 1.0) - 1.0));
  }
  return worst;
}

// Tolerance: at t = ±1 the three-term recurrence has a double characteristic root, so rounding
// errors grow like l^2 eps down the m = 0 column: 1e-10 in the sum at l = 2000 at the poles
// (3e-11 at l = 1000), 1e-12 or less away from them. 1e-9 leaves a factor 10; a lost sectoral
// (no extended exponent) gives 6e-4 here.
TEST(SphericalHarmonics, LegendreFiniteAndAdditionTheoremAtDegreeTwoThousand) {
  constexpr int kOrder = 2000;
  double worst = 0.0;
  for (double theta : stress_thetas()) {
    worst = std::max(worst, worst_addition_theorem_legendre(kOrder, theta));
  }
  std::printf("[measured] l <= %d: max relative error of sum_m P̄_lm^2 = 2l + 1: %.2e\n", kOrder,
              worst);
  EXPECT_LT(worst, 1e-9);
}

// At l = 3000 and sin θ = 1/e, the sectoral u^m is below 1e-308 long before the column values
// it seeds are: a recurrence without the extended exponent loses part of the sum here.
TEST(SphericalHarmonics, LegendreBeyondTheDoubleRangeOfTheSectorals) {
  constexpr int kOrder = 3000;
  const double theta = std::asin(1.0 / std::exp(1.0));
  const double worst = worst_addition_theorem_legendre(kOrder, theta);
  std::printf(
      "[measured] l <= %d at sin θ = 1/e: max relative error of the addition theorem: "
      "%.2e\n",
      kOrder, worst);
  EXPECT_LT(worst, 1e-10);
}

// The Y form, through evaluate(), at orders 100 and 1000, every band l <= order.
void check_addition_theorem_y(int order, int random_directions) {
  std::mt19937_64 rng(kSeed + order);
  std::vector<Vec3> directions;
  for (double theta : stress_thetas()) directions.push_back(direction(theta, 0.7));
  for (int i = 0; i < random_directions; ++i) directions.push_back(random_direction(rng));
  std::vector<double> y(coefficient_count(order));
  double worst = 0.0;
  for (const Vec3& d : directions) {
    evaluate(order, d, y);
    for (int l = 0; l <= order; ++l) {
      double sum = 0.0;
      for (int m = -l; m <= l; ++m) sum += y[index(l, m)] * y[index(l, m)];
      worst = std::max(worst, std::abs(sum * 4.0 * kPi / (2.0 * l + 1.0) - 1.0));
    }
  }
  std::printf(
      "[measured] order %d, %zu directions: max relative error of sum_m Y_lm^2 = (2l + "
      "1) / 4 pi: %.2e\n",
      order, directions.size(), worst);
  EXPECT_LT(worst, 1e-10);
}

TEST(SphericalHarmonics, AdditionTheoremAtOrderHundred) { check_addition_theorem_y(100, 500); }
TEST(SphericalHarmonics, AdditionTheoremAtOrderThousand) { check_addition_theorem_y(1000, 40); }

// ---- Projection and reconstruction ------------------------------------------------------------

// A random band-limited function of order 10 (3 channels) sampled at the texel centres of a
// 256 x 128 lat-long map.
struct SampledMap {
  static constexpr int kOrder = 10;
  static constexpr int kWidth = 256;
  static constexpr int kHeight = 128;
  static constexpr int kChannels = 3;
  std::vector<double> coefficients;
  std::vector<double> values;
  SampledMap() {
    std::mt19937_64 rng(kSeed);
    coefficients = random_coefficients(kOrder, kChannels, rng);
    values.resize(static_cast<std::size_t>(kWidth) * kHeight * kChannels);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const std::size_t at = (static_cast<std::size_t>(y) * kWidth + x) * kChannels;
        reconstruct(coefficients, kOrder, kChannels, lat_long_direction(kWidth, kHeight, x, y),
                    std::span<double>(values).subspan(at, kChannels));
      }
  }
};

// Fejér's rule on the 128 rows is exact for polynomials in cos θ of degree < 128, the uniform φ
// sum for frequencies < 256; the products here have degree <= 10 + 20 and frequency <= 30, so
// the projection is exact up to rounding: the coefficients come back to ~1e-15, and even the
// projection to order 20 finds zeros above order 10. The tolerance 1e-10 is rounding with a wide
// margin (the brief's 1e-6 would also pass kTexelArea at H ~ 10^4).
TEST(SphericalHarmonics, ProjectionRecoversBandLimitedCoefficients) {
  const SampledMap map;
  const LatLongLayout layout{SampledMap::kWidth, SampledMap::kHeight, SampledMap::kChannels, 0};
  constexpr int kProjectionOrder = 20;
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> c = project_lat_long(map.values, layout, kProjectionOrder);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  double worst = 0.0;
  for (int l = 0; l <= kProjectionOrder; ++l)
    for (int m = -l; m <= l; ++m)
      for (int ch = 0; ch < SampledMap::kChannels; ++ch) {
        const double expected = l <= SampledMap::kOrder
                                    ? map.coefficients[index(l, m) * SampledMap::kChannels + ch]
                                    : 0.0;
        worst = std::max(worst, std::abs(c[index(l, m) * SampledMap::kChannels + ch] - expected));
      }
  std::printf(
      "[measured] 256 x 128 x 3 map, order-10 function projected to order 20: max "
      "coefficient error %.2e (%.2f ms, not asserted)\n",
      worst, ms);
  EXPECT_LT(worst, 1e-10);
}

// The texel-area weights (sin θ integrated over each band): the l = 0 coefficient of a constant
// is exact, band l gets an O((l pi / H)^2) error. Checked against the one-term estimate of the
// header, (l^2 - 1)(pi / H)^2 / 24 at l = 11 (the highest odd frequency of sin θ P̄_10,m), for
// coefficients in [-1, 1]; and that the error is far above kBandLimited's.
TEST(SphericalHarmonics, TexelAreaQuadratureErrorIsSecondOrder) {
  const SampledMap map;
  const LatLongLayout layout{SampledMap::kWidth, SampledMap::kHeight, SampledMap::kChannels, 0};
  const std::vector<double> c =
      project_lat_long(map.values, layout, SampledMap::kOrder, LatLongQuadrature::kTexelArea);
  const double worst = max_abs_difference(c, map.coefficients);
  const double h = kPi / SampledMap::kHeight;
  const double l = SampledMap::kOrder + 1;  // the highest odd frequency of sin θ P̄_lm
  const double predicted = (l * l - 1.0) * h * h / 24.0;
  std::printf(
      "[measured] kTexelArea, 256 x 128: max coefficient error %.2e (one-term estimate "
      "%.2e)\n",
      worst, predicted);
  EXPECT_LT(worst, predicted);
  EXPECT_GT(worst, 1e-6);  // the reason kBandLimited is the default

  // A constant map: both rules give the exact 4 pi c Y_00 = sqrt(4 pi) c; kBandLimited gives
  // exact zeros for every other coefficient, kTexelArea does not (sum_y w_y P̄_l0(cos θ_y) != 0).
  const std::vector<double> ones(64 * 32, 2.5);
  for (auto q : {LatLongQuadrature::kTexelArea, LatLongQuadrature::kBandLimited}) {
    const std::vector<double> k = project_lat_long(ones, {64, 32, 1, 0}, 4, q);
    EXPECT_NEAR(k[0], std::sqrt(4.0 * kPi) * 2.5, 1e-13);
    if (q == LatLongQuadrature::kBandLimited) {
      for (std::size_t i = 1; i < k.size(); ++i) EXPECT_NEAR(k[i], 0.0, 1e-13);
    } else {
      EXPECT_GT(std::abs(k[index(2, 0)]), 1e-4);
    }
  }
}

// Float input with a pixel stride (RGBA images: project RGB, skip alpha): the samples carry float
// rounding (relative 6e-8), so the coefficients agree to ~1e-6 of the function's size.
TEST(SphericalHarmonics, ProjectionOfFloatRgbaImage) {
  const SampledMap map;
  std::vector<float> rgba(static_cast<std::size_t>(SampledMap::kWidth) * SampledMap::kHeight * 4);
  for (std::size_t p = 0; p < rgba.size() / 4; ++p) {
    for (int ch = 0; ch < 3; ++ch) rgba[4 * p + ch] = static_cast<float>(map.values[3 * p + ch]);
    rgba[4 * p + 3] = 1e6f;  // alpha: must be ignored
  }
  const std::vector<double> c =
      project_lat_long(rgba, {SampledMap::kWidth, SampledMap::kHeight, 3, 4}, SampledMap::kOrder);
  const double worst = max_abs_difference(c, map.coefficients);
  std::printf("[measured] float RGBA input: max coefficient error %.2e\n", worst);
  EXPECT_LT(worst, 1e-5);
}

TEST(SphericalHarmonics, ReconstructLatLongMatchesPointEvaluation) {
  const SampledMap map;
  const std::vector<double> values =
      reconstruct_lat_long(map.coefficients, SampledMap::kOrder,
                           {SampledMap::kWidth, SampledMap::kHeight, SampledMap::kChannels, 0});
  const double worst = max_abs_difference(values, map.values);
  std::printf("[measured] reconstruct_lat_long vs reconstruct(direction): max difference %.2e\n",
              worst);
  EXPECT_LT(worst, 1e-12);
}

// Cost of a projection at a size the prefilter uses (printed, never asserted).
TEST(SphericalHarmonics, ProjectionCostIsReported) {
  constexpr int kWidth = 1024, kHeight = 512, kOrder = 30;
  std::vector<float> rgb(static_cast<std::size_t>(kWidth) * kHeight * 3);
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (float& v : rgb) v = uniform(rng);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> c = project_lat_long(rgb, {kWidth, kHeight, 3, 0}, kOrder);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("[timing] project_lat_long %d x %d x 3, order %d: %.1f ms\n", kWidth, kHeight, kOrder,
              ms);
  ASSERT_EQ(c.size(), coefficient_count(kOrder) * 3);
  for (double v : c) ASSERT_TRUE(std::isfinite(v));
}

// ---- Rotation --------------------------------------------------------------------------------

// g = D f must be the projection of the rotated function f(R^T d): re-projected by an exact
// product rule (orders <= order on both sides) and compared coefficient by coefficient, and
// compared pointwise at random directions.
void check_rotation_against_reprojection(int order) {
  std::mt19937_64 rng(kSeed + order);
  const std::vector<double> f = random_coefficients(order, 1, rng);
  const SphereRule rule = sphere_rule(order + 1, 2 * order + 1);
  double worst_coefficient = 0.0, worst_point = 0.0;
  for (int trial = 0; trial < 3; ++trial) {
    const Mat3 r = random_rotation(rng);
    const Rotation rotation(r, order);
    const std::vector<double> g = rotation.apply(f);

    std::vector<double> reprojected(coefficient_count(order), 0.0), y(coefficient_count(order));
    for (std::size_t k = 0; k < rule.directions.size(); ++k) {
      const double value = reconstruct(f, order, transpose_times(r, rule.directions[k]));
      evaluate(order, rule.directions[k], y);
      for (std::size_t i = 0; i < y.size(); ++i) reprojected[i] += rule.weights[k] * value * y[i];
    }
    worst_coefficient = std::max(worst_coefficient, max_abs_difference(g, reprojected));

    for (int i = 0; i < 50; ++i) {
      const Vec3 d = random_direction(rng);
      worst_point = std::max(worst_point, std::abs(reconstruct(g, order, d) -
                                                   reconstruct(f, order, transpose_times(r, d))));
    }
  }
  std::printf(
      "[measured] rotation order %d: D f vs re-projection of f(R^T d): max coefficient "
      "error %.2e, max pointwise error %.2e (coefficients in [-1, 1])\n",
      order, worst_coefficient, worst_point);
  EXPECT_LT(worst_coefficient, 1e-10);
  EXPECT_LT(worst_point, 1e-10);
}

TEST(SphericalHarmonics, RotationMatchesReprojectionAtOrderTen) {
  check_rotation_against_reprojection(10);
}
TEST(SphericalHarmonics, RotationMatchesReprojectionAtOrderFifty) {
  check_rotation_against_reprojection(50);
}

// D(R1 R2) = D(R1) D(R2), D D^T = I, D(identity) = I, band by band.
void check_rotation_group_laws(int order) {
  std::mt19937_64 rng(kSeed + 7 * order);
  double worst_compose = 0.0, worst_orthogonal = 0.0, worst_identity = 0.0;
  for (int trial = 0; trial < 3; ++trial) {
    const Mat3 r1 = random_rotation(rng), r2 = random_rotation(rng);
    const Rotation d1(r1, order), d2(r2, order), d12(multiply(r1, r2), order);
    for (int l = 0; l <= order; ++l) {
      for (int m = -l; m <= l; ++m)
        for (int mp = -l; mp <= l; ++mp) {
          double product = 0.0, gram = 0.0;
          for (int k = -l; k <= l; ++k) {
            product += d1(l, m, k) * d2(l, k, mp);
            gram += d1(l, m, k) * d1(l, mp, k);
          }
          worst_compose = std::max(worst_compose, std::abs(product - d12(l, m, mp)));
          worst_orthogonal = std::max(worst_orthogonal, std::abs(gram - (m == mp ? 1.0 : 0.0)));
        }
    }
  }
  const Rotation identity(kIdentity, order);
  for (int l = 0; l <= order; ++l)
    for (int m = -l; m <= l; ++m)
      for (int mp = -l; mp <= l; ++mp)
        worst_identity =
            std::max(worst_identity, std::abs(identity(l, m, mp) - (m == mp ? 1.0 : 0.0)));
  std::printf(
      "[measured] rotation order %d: max |D(R1 R2) - D(R1) D(R2)| = %.2e, max |D D^T - "
      "I| = %.2e, max |D(I) - I| = %.2e\n",
      order, worst_compose, worst_orthogonal, worst_identity);
  EXPECT_LT(worst_compose, 1e-10);
  EXPECT_LT(worst_orthogonal, 1e-10);
  EXPECT_LT(worst_identity, 1e-14);
}

TEST(SphericalHarmonics, RotationGroupLawsAtOrderTen) { check_rotation_group_laws(10); }
TEST(SphericalHarmonics, RotationGroupLawsAtOrderFifty) { check_rotation_group_laws(50); }

// About z by alpha, g(θ, φ) = f(θ, φ - alpha): only m and -m mix, by cos(m alpha), sin(m alpha).
TEST(SphericalHarmonics, RotationAboutZMatchesClosedForm) {
  double worst = 0.0;
  for (int order : {10, 50}) {
    for (double alpha : {0.3, -1.7, 2.9, kPi}) {
      const Rotation d(rotation_z(alpha), order);
      for (int l = 0; l <= order; ++l)
        for (int m = -l; m <= l; ++m)
          for (int mp = -l; mp <= l; ++mp) {
            const int a = std::abs(m);
            double expected = 0.0;
            if (m == 0 && mp == 0)
              expected = 1.0;
            else if (m != 0 && mp == m)
              expected = std::cos(a * alpha);
            else if (m > 0 && mp == -m)
              expected = -std::sin(a * alpha);
            else if (m < 0 && mp == -m)
              expected = std::sin(a * alpha);
            worst = std::max(worst, std::abs(d(l, m, mp) - expected));
          }
    }
  }
  std::printf("[measured] rotation about z, orders 10 and 50: max error vs closed form %.2e\n",
              worst);
  EXPECT_LT(worst, 1e-10);
}

TEST(SphericalHarmonics, RotationAppliesPerChannelAndInPlace) {
  constexpr int kOrder = 6, kChannels = 3;
  std::mt19937_64 rng(kSeed);
  const Rotation rotation(random_rotation(rng), kOrder);
  const std::vector<double> rgb = random_coefficients(kOrder, kChannels, rng);
  std::vector<double> in_place = rgb;
  rotation.apply(in_place, in_place, kChannels);
  for (int ch = 0; ch < kChannels; ++ch) {
    std::vector<double> one(coefficient_count(kOrder));
    for (std::size_t i = 0; i < one.size(); ++i) one[i] = rgb[i * kChannels + ch];
    const std::vector<double> rotated = rotation.apply(one);
    for (std::size_t i = 0; i < one.size(); ++i)
      EXPECT_NEAR(in_place[i * kChannels + ch], rotated[i], 1e-15);
  }
}

// ---- Bad input -----------------------------------------------------------------------------

TEST(SphericalHarmonics, BadInputThrows) {
  std::vector<double> small(3);
  EXPECT_THROW(evaluate(-1, {0, 0, 1}, small), std::invalid_argument);
  EXPECT_THROW(evaluate(2, {0, 0, 1}, small), std::invalid_argument);  // needs 9
  EXPECT_THROW(evaluate(0, {0, 0, 0}, small), std::invalid_argument);
  EXPECT_THROW(evaluate(0, {NAN, 0, 1}, small), std::invalid_argument);
  EXPECT_THROW(legendre(1, 1.5, small), std::invalid_argument);
  EXPECT_THROW(legendre(2, 0.5, small), std::invalid_argument);  // needs 6
  const std::vector<double> map(8 * 4, 1.0);
  EXPECT_THROW(project_lat_long(map, {0, 4, 1, 0}, 2), std::invalid_argument);
  EXPECT_THROW(project_lat_long(map, {8, 8, 1, 0}, 2), std::invalid_argument);  // too few values
  EXPECT_THROW(project_lat_long(map, {8, 4, 2, 1}, 2), std::invalid_argument);  // stride < channels
  EXPECT_THROW(Rotation({1, 0, 0, 0, 1, 0, 0, 0, -1}, 3), std::invalid_argument);  // reflection
  EXPECT_THROW(Rotation({2, 0, 0, 0, 1, 0, 0, 0, 1}, 3), std::invalid_argument);   // scale
  // A 1 x 1 map is legal and finite.
  const std::vector<double> one = {3.0};
  const std::vector<double> c = project_lat_long(one, {1, 1, 1, 0}, 3);
  for (double v : c) EXPECT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace thalassa::sh
