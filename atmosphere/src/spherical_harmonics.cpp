// thalassa — real spherical harmonics: Legendre recurrences, projection, reconstruction and
// rotation. Contracts, conventions and sources are in the header
// (thalassa/atmosphere/spherical_harmonics.hpp); this file says how, and why where it is not
// obvious.

#include "thalassa/atmosphere/spherical_harmonics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace thalassa::sh {
namespace {

constexpr double kPi = std::numbers::pi;
// 1 / sqrt(4 pi): turns a 4-pi-normalised P̄_lm trig(m phi) into an orthonormal Y_lm.
const double kInvSqrt4Pi = 1.0 / std::sqrt(4.0 * kPi);

// Extended exponent for the Legendre recurrences (Fukushima 2012, "X-numbers"): a value is
// x * kBig^e with an int e <= 0 and x kept within [kBigSmall, kBigLarge) while e < 0. 2^960
// and its square root 2^480 are Fukushima's choices: x never leaves the normal double range
// (|x| < 2^480 times one recurrence step's growth, far below 2^1023), and one rescale per step
// is always enough because a step changes |x| by much less than 2^480.
const double kBig = std::ldexp(1.0, 960);
const double kBigInv = std::ldexp(1.0, -960);
const double kBigLarge = std::ldexp(1.0, 480);
const double kBigSmall = std::ldexp(1.0, -480);

// The value x * kBig^e as a double: e = -1 may still be representable (gradual underflow);
// e <= -2 is below 2^(480 - 1920) and underflows to 0.
inline double from_extended(double x, int e) {
  if (e == 0) return x;
  if (e == -1) return x * kBigInv;
  return 0.0;
}

// Calls begin_column(m) and then visit(l, m, P̄_lm(t)) for l = m..order, for each m = 0..order
// in turn (column by column: all users of the values need them per m). t = cos θ, u = sin θ >= 0.
// The recurrences and their source are in the header (Holmes & Featherstone 2002, eq. 11-13,
// with Fukushima's extended exponent instead of their fixed 1e-280 scale).
template <class BeginColumn, class Visit>
void for_each_legendre(int order, double t, double u, BeginColumn&& begin_column, Visit&& visit) {
  double sectoral = 1.0;  // P̄_mm = sectoral * kBig^sectoral_exp; P̄_00 = 1
  int sectoral_exp = 0;
  for (int m = 0; m <= order; ++m) {
    if (m == 1) {
      sectoral *= std::sqrt(3.0) * u;  // P̄_11 = sqrt(3) u (the m = 0 column has no factor 2)
    } else if (m >= 2) {
      sectoral *= std::sqrt((2.0 * m + 1.0) / (2.0 * m)) * u;
    }
    if (sectoral != 0.0 && std::abs(sectoral) < kBigSmall) {
      sectoral *= kBig;
      --sectoral_exp;
    }
    begin_column(m);
    visit(m, m, from_extended(sectoral, sectoral_exp));
    if (m == order) break;
    // P̄_(m+1)m = sqrt(2m + 3) t P̄_mm (a_(m+1)m; b_(m+1)m = 0).
    double p_prev = sectoral;
    double p = std::sqrt(2.0 * m + 3.0) * t * sectoral;
    int e = sectoral_exp;
    visit(m + 1, m, from_extended(p, e));
    const double m_d = m;
    for (int l = m + 2; l <= order; ++l) {
      const double l_d = l;
      const double lm_minus = l_d - m_d;  // l - m
      const double lm_plus = l_d + m_d;   // l + m
      const double a = std::sqrt((2.0 * l_d - 1.0) * (2.0 * l_d + 1.0) / (lm_minus * lm_plus));
      const double b = std::sqrt((2.0 * l_d + 1.0) * (lm_plus - 1.0) * (lm_minus - 1.0) /
                                 (lm_minus * lm_plus * (2.0 * l_d - 3.0)));
      const double next = a * t * p - b * p_prev;
      p_prev = p;
      p = next;
      // While the column is below the double range, bring it back as it grows (both of the
      // recurrence's two terms by the same power, so the recurrence is unchanged).
      if (e < 0 && std::abs(p) >= kBigLarge) {
        p *= kBigInv;
        p_prev *= kBigInv;
        ++e;
      }
      visit(l, m, from_extended(p, e));
    }
  }
}

void check_order(int order, const char* function) {
  if (order < 0) {
    throw std::invalid_argument(std::string("thalassa::sh::") + function +
                                ": order must be >= 0, got " + std::to_string(order));
  }
}

void check_size(std::size_t have, std::size_t need, const char* function, const char* what) {
  if (have < need) {
    throw std::invalid_argument(std::string("thalassa::sh::") + function + ": " + what + " holds " +
                                std::to_string(have) + " values, needs " + std::to_string(need));
  }
}

// cos θ, sin θ, cos φ, sin φ of a direction, computed so that none loses precision at a pole:
// sin θ = hypot(x, y) / |d| rather than sqrt(1 - cos^2).
struct Angles {
  double cos_theta, sin_theta, cos_phi, sin_phi;
};

Angles angles_of(const Vec3& d, const char* function) {
  const double rho = std::hypot(d[0], d[1]);
  const double r = std::hypot(rho, d[2]);
  if (!(r > 0.0) || !std::isfinite(r)) {
    throw std::invalid_argument(std::string("thalassa::sh::") + function +
                                ": the direction must be finite and non-zero");
  }
  Angles a{d[2] / r, rho / r, 1.0, 0.0};
  if (rho > 0.0) {
    a.cos_phi = d[0] / rho;
    a.sin_phi = d[1] / rho;
  }
  return a;
}

struct CheckedLayout {
  std::size_t width, height, channels, stride;
};

CheckedLayout check_layout(const LatLongLayout& layout, const char* function) {
  if (layout.width < 1 || layout.height < 1 || layout.channels < 1 ||
      (layout.pixel_stride != 0 && layout.pixel_stride < layout.channels)) {
    throw std::invalid_argument(
        std::string("thalassa::sh::") + function +
        ": the lat-long layout needs width, height, channels >= 1 and pixel_stride 0 or >= "
        "channels");
  }
  const int stride = layout.pixel_stride == 0 ? layout.channels : layout.pixel_stride;
  return {static_cast<std::size_t>(layout.width), static_cast<std::size_t>(layout.height),
          static_cast<std::size_t>(layout.channels), static_cast<std::size_t>(stride)};
}

// cos(pi k / n) and sin(pi k / n) for k = 0..2n-1: every cos(m phi_x) of a lat-long row,
// phi_x = pi (2x + 1) / W, is cos(pi k / W) with k = m (2x + 1) mod 2W, so the DFT sums use
// correctly rounded values instead of a recurrence whose error grows with m.
struct TrigTable {
  explicit TrigTable(std::size_t n) : period(2 * n), cos_values(2 * n), sin_values(2 * n) {
    for (std::size_t k = 0; k < period; ++k) {
      const double angle = kPi * static_cast<double>(k) / static_cast<double>(n);
      cos_values[k] = std::cos(angle);
      sin_values[k] = std::sin(angle);
    }
  }
  std::size_t period;
  std::vector<double> cos_values, sin_values;
};

// Weights of the theta quadrature, ∫_0^pi g(θ) sin θ dθ ≈ sum_y w_y g(θ_y), θ_y = (y + 1/2) pi / H.
std::vector<double> theta_weights(std::size_t height, LatLongQuadrature quadrature) {
  std::vector<double> w(height);
  const double h = static_cast<double>(height);
  if (quadrature == LatLongQuadrature::kTexelArea) {
    // cos θ_top - cos θ_bottom = 2 sin(pi / 2H) sin θ_y (the difference form cancels near the
    // poles; this product does not).
    const double half_band = std::sin(kPi / (2.0 * h));
    for (std::size_t y = 0; y < height; ++y) {
      w[y] = 2.0 * half_band * std::sin(kPi * (static_cast<double>(y) + 0.5) / h);
    }
    return w;
  }
  // Fejér's first rule (header):
  //   w_y = (2/H) [1 - 2 sum_{j=1}^{floor(H/2)} cos(2 j θ_y) / (4j^2 - 1)],
  // with cos(2 j θ_y) = cos(pi j (2y + 1) / H) read from an exact table.
  const TrigTable table(height);
  for (std::size_t y = 0; y < height; ++y) {
    double sum = 0.0;
    const std::size_t step = 2 * y + 1;
    std::size_t k = 0;
    for (std::size_t j = 1; j <= height / 2; ++j) {
      k = (k + step) % table.period;
      const double jd = static_cast<double>(j);
      sum += table.cos_values[k] / (4.0 * jd * jd - 1.0);
    }
    w[y] = (2.0 / h) * (1.0 - 2.0 * sum);
  }
  return w;
}

template <class T>
std::vector<double> project(std::span<const T> values, const LatLongLayout& layout, int order,
                            LatLongQuadrature quadrature) {
  check_order(order, "project_lat_long");
  const CheckedLayout lay = check_layout(layout, "project_lat_long");
  check_size(values.size(), lay.width * lay.height * lay.stride, "project_lat_long", "values");
  const std::size_t ch = lay.channels;
  const auto frequencies = static_cast<std::size_t>(order) + 1;

  const TrigTable table(lay.width);
  const std::vector<double> w_theta = theta_weights(lay.height, quadrature);
  const double d_phi = 2.0 * kPi / static_cast<double>(lay.width);

  std::vector<double> coefficients(coefficient_count(order) * ch, 0.0);
  std::vector<double> cos_sums(frequencies * ch), sin_sums(frequencies * ch);
  for (std::size_t y = 0; y < lay.height; ++y) {
    // Step 1: the row's real DFT in phi, C_m = sum_x v cos(m phi_x), S_m = sum_x v sin(m phi_x).
    const T* row = values.data() + y * lay.width * lay.stride;
    for (std::size_t m = 0; m < frequencies; ++m) {
      double* c_out = &cos_sums[m * ch];
      double* s_out = &sin_sums[m * ch];
      std::fill(c_out, c_out + ch, 0.0);
      std::fill(s_out, s_out + ch, 0.0);
      const std::size_t step = (2 * m) % table.period;  // k advances by 2m per column
      std::size_t k = m % table.period;                 // k = m (2x + 1) at x = 0
      for (std::size_t x = 0; x < lay.width; ++x) {
        const double c = table.cos_values[k];
        const double s = table.sin_values[k];
        const T* v = row + x * lay.stride;
        for (std::size_t i = 0; i < ch; ++i) {
          c_out[i] += c * static_cast<double>(v[i]);
          s_out[i] += s * static_cast<double>(v[i]);
        }
        k += step;
        if (k >= table.period) k -= table.period;
      }
    }
    // Step 2: the theta quadrature, one Legendre column per m.
    const double theta = kPi * (static_cast<double>(y) + 0.5) / static_cast<double>(lay.height);
    const double weight = w_theta[y] * d_phi * kInvSqrt4Pi;
    for_each_legendre(
        order, std::cos(theta), std::sin(theta), [](int) {},
        [&](int l, int m, double p) {
          const double wp = weight * p;
          const auto mu = static_cast<std::size_t>(m);
          double* plus = &coefficients[index(l, m) * ch];
          for (std::size_t i = 0; i < ch; ++i) plus[i] += wp * cos_sums[mu * ch + i];
          if (m > 0) {
            double* minus = &coefficients[index(l, -m) * ch];
            for (std::size_t i = 0; i < ch; ++i) minus[i] += wp * sin_sums[mu * ch + i];
          }
        });
  }
  return coefficients;
}

}  // namespace

// ---- Directions ------------------------------------------------------------------------------

Vec3 direction(double theta, double phi) {
  const double s = std::sin(theta);
  return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

Vec3 lat_long_direction(int width, int height, int x, int y) {
  return direction(kPi * (y + 0.5) / height, 2.0 * kPi * (x + 0.5) / width);
}

// ---- Legendre functions and harmonics ---------------------------------------------------------

void legendre(int order, double cos_theta, double sin_theta, std::span<double> out) {
  check_order(order, "legendre");
  check_size(out.size(), legendre_count(order), "legendre", "out");
  if (!(std::abs(cos_theta) <= 1.0) || !(sin_theta >= 0.0 && sin_theta <= 1.0)) {
    throw std::invalid_argument(
        "thalassa::sh::legendre: cos_theta must be in [-1, 1] and sin_theta in [0, 1]");
  }
  for_each_legendre(
      order, cos_theta, sin_theta, [](int) {},
      [&](int l, int m, double p) { out[legendre_index(l, m)] = p; });
}

void legendre(int order, double cos_theta, std::span<double> out) {
  if (!(std::abs(cos_theta) <= 1.0)) {
    throw std::invalid_argument("thalassa::sh::legendre: cos_theta must be in [-1, 1]");
  }
  legendre(order, cos_theta, std::sqrt((1.0 - cos_theta) * (1.0 + cos_theta)), out);
}

void evaluate(int order, const Vec3& d, std::span<double> out) {
  check_order(order, "evaluate");
  check_size(out.size(), coefficient_count(order), "evaluate", "out");
  const Angles a = angles_of(d, "evaluate");
  // (cos mφ, sin mφ) by the angle-addition recurrence, advanced at each new column: the error
  // grows like m * 1e-16, 1e-13 at m = 1000, below what the tests ask.
  double cos_m = 1.0, sin_m = 0.0;
  for_each_legendre(
      order, a.cos_theta, a.sin_theta,
      [&](int m) {
        if (m == 0) return;
        const double c = cos_m * a.cos_phi - sin_m * a.sin_phi;
        sin_m = sin_m * a.cos_phi + cos_m * a.sin_phi;
        cos_m = c;
      },
      [&](int l, int m, double p) {
        const double y = p * kInvSqrt4Pi;
        if (m == 0) {
          out[index(l, 0)] = y;
        } else {
          out[index(l, m)] = y * cos_m;
          out[index(l, -m)] = y * sin_m;
        }
      });
}

double evaluate(int l, int m, const Vec3& d) {
  if (l < 0 || m < -l || m > l) {
    throw std::invalid_argument("thalassa::sh::evaluate: need 0 <= l and |m| <= l");
  }
  std::vector<double> y(coefficient_count(l));
  evaluate(l, d, y);
  return y[index(l, m)];
}

void reconstruct(std::span<const double> coefficients, int order, int channels, const Vec3& d,
                 std::span<double> out) {
  check_order(order, "reconstruct");
  if (channels < 1) throw std::invalid_argument("thalassa::sh::reconstruct: channels must be >= 1");
  const auto ch = static_cast<std::size_t>(channels);
  check_size(coefficients.size(), coefficient_count(order) * ch, "reconstruct", "coefficients");
  check_size(out.size(), ch, "reconstruct", "out");
  std::vector<double> y(coefficient_count(order));
  evaluate(order, d, y);
  std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(ch), 0.0);
  for (std::size_t k = 0; k < y.size(); ++k) {
    for (std::size_t c = 0; c < ch; ++c) out[c] += coefficients[k * ch + c] * y[k];
  }
}

double reconstruct(std::span<const double> coefficients, int order, const Vec3& d) {
  double value = 0.0;
  reconstruct(coefficients, order, 1, d, std::span<double>(&value, 1));
  return value;
}

// ---- Latitude-longitude maps ------------------------------------------------------------------

std::vector<double> project_lat_long(std::span<const float> values, const LatLongLayout& layout,
                                     int order, LatLongQuadrature quadrature) {
  return project(values, layout, order, quadrature);
}

std::vector<double> project_lat_long(std::span<const double> values, const LatLongLayout& layout,
                                     int order, LatLongQuadrature quadrature) {
  return project(values, layout, order, quadrature);
}

std::vector<double> reconstruct_lat_long(std::span<const double> coefficients, int order,
                                         const LatLongLayout& layout) {
  check_order(order, "reconstruct_lat_long");
  const CheckedLayout lay = check_layout(layout, "reconstruct_lat_long");
  const std::size_t ch = lay.channels;
  check_size(coefficients.size(), coefficient_count(order) * ch, "reconstruct_lat_long",
             "coefficients");
  const auto frequencies = static_cast<std::size_t>(order) + 1;
  const TrigTable table(lay.width);

  std::vector<double> out(lay.width * lay.height * ch, 0.0);
  std::vector<double> cos_parts(frequencies * ch), sin_parts(frequencies * ch);
  for (std::size_t y = 0; y < lay.height; ++y) {
    // a_m = sum_l f_lm Y-theta-part, b_m = sum_l f_l,-m Y-theta-part.
    std::fill(cos_parts.begin(), cos_parts.end(), 0.0);
    std::fill(sin_parts.begin(), sin_parts.end(), 0.0);
    const double theta = kPi * (static_cast<double>(y) + 0.5) / static_cast<double>(lay.height);
    for_each_legendre(
        order, std::cos(theta), std::sin(theta), [](int) {},
        [&](int l, int m, double p) {
          const double y_theta = p * kInvSqrt4Pi;
          const auto mu = static_cast<std::size_t>(m);
          const double* plus = &coefficients[index(l, m) * ch];
          for (std::size_t i = 0; i < ch; ++i) cos_parts[mu * ch + i] += y_theta * plus[i];
          if (m > 0) {
            const double* minus = &coefficients[index(l, -m) * ch];
            for (std::size_t i = 0; i < ch; ++i) sin_parts[mu * ch + i] += y_theta * minus[i];
          }
        });
    double* row = out.data() + y * lay.width * ch;
    for (std::size_t x = 0; x < lay.width; ++x) {
      const std::size_t step = (2 * x + 1) % table.period;  // k = m (2x + 1) mod 2W
      std::size_t k = 0;
      double* v = row + x * ch;
      for (std::size_t m = 0; m < frequencies; ++m) {
        const double c = table.cos_values[k];
        const double s = table.sin_values[k];
        for (std::size_t i = 0; i < ch; ++i) {
          v[i] += c * cos_parts[m * ch + i] + s * sin_parts[m * ch + i];
        }
        k += step;
        if (k >= table.period) k -= table.period;
      }
    }
  }
  return out;
}

// ---- Rotation ----------------------------------------------------------------------------------

namespace {

// Checks that r is a rotation: R R^T = I and det R = +1, to kRotationTolerance. Looser than
// rounding so that matrices built in float or from a quaternion pass; tight enough that a
// reflection or a scaled matrix does not (the recurrence would then silently give no rotation).
constexpr double kRotationTolerance = 1e-6;

void check_rotation(const Mat3& r) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double dot = 0.0;
      for (int k = 0; k < 3; ++k) dot += r[3 * i + k] * r[3 * j + k];
      const double expected = i == j ? 1.0 : 0.0;
      if (!(std::abs(dot - expected) <= kRotationTolerance)) {
        throw std::invalid_argument("thalassa::sh::Rotation: the matrix is not orthonormal");
      }
    }
  }
  const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                     r[2] * (r[3] * r[7] - r[4] * r[6]);
  if (!(det > 0.0)) {
    throw std::invalid_argument("thalassa::sh::Rotation: the matrix is a reflection (det < 0)");
  }
}

}  // namespace

Rotation::Rotation(const Mat3& r, int order) : order_(order) {
  check_order(order, "Rotation");
  check_rotation(r);
  matrices_.assign(band_offset(order + 1), 0.0);
  matrices_[0] = 1.0;  // D^0 = [1]
  if (order == 0) return;

  // D^1: Y_1 = sqrt(3 / 4 pi) (y, z, x), and the coefficients of g(d) = f(R^T d) for a linear f
  // = a . d are R a, so D^1_mm' = R[axis(m)][axis(m')] with axis(-1, 0, 1) = (y, z, x) = (1, 2, 0).
  constexpr int kAxis[3] = {1, 2, 0};
  double* d1 = &matrices_[band_offset(1)];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) d1[3 * i + j] = r[3 * kAxis[i] + kAxis[j]];
  }

  // Ivanic & Ruedenberg 1996, eq. 8.1-8.5 and Table 2 as corrected in 1998: with δ = δ_m0,
  //   D^l_mm' = u U + v V + w W,
  //   u = sqrt((l + m)(l - m) / n), v = 1/2 sqrt((1 + δ)(l + |m| - 1)(l + |m|) / n) (1 - 2δ),
  //   w = -1/2 sqrt((l - |m| - 1)(l - |m|) / n) (1 - δ),
  //   n = (l + m')(l - m') for |m'| < l, (2l)(2l - 1) for |m'| = l,
  // and U, V, W sums of the products P_i(a, b) of a D^1 and a D^(l-1) entry below.
  auto d1_at = [d1](int i, int j) { return d1[(i + 1) * 3 + (j + 1)]; };
  for (int l = 2; l <= order; ++l) {
    const double* prev = &matrices_[band_offset(l - 1)];
    const int n_prev = 2 * l - 1;
    auto prev_at = [prev, n_prev, l](int a, int b) {
      return prev[(a + l - 1) * n_prev + (b + l - 1)];
    };
    // P_i(a, b) of I&R eq. 8.5 (|a| <= l - 1, |b| <= l).
    auto p = [&](int i, int a, int b) {
      if (b == l) return d1_at(i, 1) * prev_at(a, l - 1) - d1_at(i, -1) * prev_at(a, -l + 1);
      if (b == -l) return d1_at(i, 1) * prev_at(a, -l + 1) + d1_at(i, -1) * prev_at(a, l - 1);
      return d1_at(i, 0) * prev_at(a, b);
    };
    double* band = &matrices_[band_offset(l)];
    const int n = 2 * l + 1;
    for (int m = -l; m <= l; ++m) {
      const int abs_m = std::abs(m);
      const double delta = m == 0 ? 1.0 : 0.0;
      for (int mp = -l; mp <= l; ++mp) {
        const double denom = std::abs(mp) == l ? (2.0 * l) * (2.0 * l - 1.0)
                                               : static_cast<double>(l + mp) * (l - mp);
        const double u = std::sqrt(static_cast<double>(l + m) * (l - m) / denom);
        const double v = 0.5 * std::sqrt((1.0 + delta) * (l + abs_m - 1.0) * (l + abs_m) / denom) *
                         (1.0 - 2.0 * delta);
        const double w = -0.5 *
                         std::sqrt(static_cast<double>(l - abs_m - 1) * (l - abs_m) / denom) *
                         (1.0 - delta);
        double value = 0.0;
        if (u != 0.0) value += u * p(0, m, mp);  // U = P_0(m, m')
        if (v != 0.0) {
          double big_v;
          if (m == 0) {
            big_v = p(1, 1, mp) + p(-1, -1, mp);
          } else if (m > 0) {
            big_v = m == 1 ? std::sqrt(2.0) * p(1, 0, mp) : p(1, m - 1, mp) - p(-1, -m + 1, mp);
          } else {
            big_v = m == -1 ? std::sqrt(2.0) * p(-1, 0, mp) : p(1, m + 1, mp) + p(-1, -m - 1, mp);
          }
          value += v * big_v;
        }
        if (w != 0.0) {  // w = 0 for m = 0 and |m| >= l - 1
          const double big_w =
              m > 0 ? p(1, m + 1, mp) + p(-1, -m - 1, mp) : p(1, m - 1, mp) - p(-1, -m + 1, mp);
          value += w * big_w;
        }
        band[(m + l) * n + (mp + l)] = value;
      }
    }
  }
}

std::span<const double> Rotation::band(int l) const {
  if (l < 0 || l > order_) {
    throw std::invalid_argument("thalassa::sh::Rotation::band: l out of range");
  }
  const auto n = static_cast<std::size_t>(2 * l + 1);
  return std::span<const double>(matrices_).subspan(band_offset(l), n * n);
}

void Rotation::apply(std::span<const double> in, std::span<double> out, int channels) const {
  if (channels < 1) throw std::invalid_argument("thalassa::sh::Rotation::apply: channels >= 1");
  const auto ch = static_cast<std::size_t>(channels);
  const std::size_t need = coefficient_count(order_) * ch;
  check_size(in.size(), need, "Rotation::apply", "in");
  check_size(out.size(), need, "Rotation::apply", "out");
  std::vector<double> band_out(static_cast<std::size_t>(2 * order_ + 1) * ch);
  for (int l = 0; l <= order_; ++l) {
    const auto n = static_cast<std::size_t>(2 * l + 1);
    const double* d = &matrices_[band_offset(l)];
    const std::size_t first = index(l, -l) * ch;
    // Into a temporary, so that in and out may alias.
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t c = 0; c < ch; ++c) {
        double sum = 0.0;
        for (std::size_t j = 0; j < n; ++j) sum += d[i * n + j] * in[first + j * ch + c];
        band_out[i * ch + c] = sum;
      }
    }
    std::copy(band_out.begin(), band_out.begin() + static_cast<std::ptrdiff_t>(n * ch),
              out.begin() + static_cast<std::ptrdiff_t>(first));
  }
}

std::vector<double> Rotation::apply(std::span<const double> in, int channels) const {
  if (channels < 1) throw std::invalid_argument("thalassa::sh::Rotation::apply: channels >= 1");
  std::vector<double> out(coefficient_count(order_) * static_cast<std::size_t>(channels));
  apply(in, out, channels);
  return out;
}

}  // namespace thalassa::sh
