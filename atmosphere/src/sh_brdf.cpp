// thalassa — BRDF coefficients, frequency-space convolution and SHRMs (Ramamoorthi & Hanrahan
// 2002). Contracts, conventions and sources are in the header
// (thalassa/atmosphere/sh_brdf.hpp); this file says how, and why where it is not obvious.

#include "thalassa/atmosphere/sh_brdf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "gauss_legendre.hpp"

namespace thalassa::sh {
namespace {

constexpr double kPi = std::numbers::pi;

// |C + V| below this (V within ~1e-12 rad of -C) has no normal that mirrors V into C.
constexpr double kMinHalfVectorLength = 1e-12;

void check_order(int order, const char* function, const char* what) {
  if (order < 0) {
    throw std::invalid_argument(std::string(function) + ": " + what + " must be >= 0, got " +
                                std::to_string(order));
  }
}

void check_count(int count, const char* function, const char* what) {
  if (count < 1) {
    throw std::invalid_argument(std::string(function) + ": " + what + " must be >= 1, got " +
                                std::to_string(count));
  }
}

Vec3 normalized(const Vec3& d, const char* function) {
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(n > 0.0) || !std::isfinite(n)) {
    throw std::invalid_argument(std::string(function) + ": direction is zero or not finite");
  }
  return {d[0] / n, d[1] / n, d[2] / n};
}

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// R^T d for a row-major 3x3 R.
Vec3 transpose_times(const Mat3& r, const Vec3& d) {
  return {r[0] * d[0] + r[3] * d[1] + r[6] * d[2], r[1] * d[0] + r[4] * d[1] + r[7] * d[2],
          r[2] * d[0] + r[5] * d[1] + r[8] * d[2]};
}

// Ry(alpha): rotation about +y by alpha (z toward x), row-major.
Mat3 rotation_y(double alpha) {
  const double c = std::cos(alpha), s = std::sin(alpha);
  return {c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c};
}

// The Legendre triangle P̄_lm(t) (toolkit normalisation) for every node t, order `order`:
// result[node * legendre_count(order) + legendre_index(l, m)].
std::vector<double> legendre_table(std::span<const double> nodes, int order) {
  const std::size_t count = legendre_count(order);
  std::vector<double> out(nodes.size() * count);
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const double t = nodes[k];
    legendre(order, t, std::sqrt((1.0 - t) * (1.0 + t)),
             std::span<double>(out).subspan(k * count, count));
  }
  return out;
}

}  // namespace

double convolution_constant(int l) {
  check_order(l, "convolution_constant", "l");
  return std::sqrt(4.0 * kPi / (2.0 * l + 1.0));
}

// ---- BRDFs ---------------------------------------------------------------------------------

ReparameterizedBrdf reparameterize_by_reflection(CosineWeightedBrdf brdf) {
  if (!brdf) {
    throw std::invalid_argument("reparameterize_by_reflection: empty BRDF");
  }
  return [brdf = std::move(brdf)](double theta_i, double theta_o, double phi) -> double {
    // Reflection frame: C = z, L in the xz plane (phi_i = 0), V at azimuth phi_o = phi.
    const Vec3 light = {std::sin(theta_i), 0.0, std::cos(theta_i)};
    const Vec3 view = {std::sin(theta_o) * std::cos(phi), std::sin(theta_o) * std::sin(phi),
                       std::cos(theta_o)};
    const Vec3 sum = {view[0], view[1], view[2] + 1.0};  // C + V
    const double length = std::sqrt(dot(sum, sum));
    if (length < kMinHalfVectorLength) {
      return 0.0;
    }
    const Vec3 normal = {sum[0] / length, sum[1] / length, sum[2] / length};
    const double light_z = dot(light, normal);
    if (light_z <= 0.0) {
      return 0.0;  // the light is below the surface whose normal mirrors V into C
    }
    // A tangent frame (t, b, N), right-handed; its azimuth is arbitrary (isotropic BRDF).
    const Vec3 helper = std::abs(normal[0]) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    const double h = dot(helper, normal);
    Vec3 t = {helper[0] - h * normal[0], helper[1] - h * normal[1], helper[2] - h * normal[2]};
    const double t_length = std::sqrt(dot(t, t));
    t = {t[0] / t_length, t[1] / t_length, t[2] / t_length};
    const Vec3 b = cross(normal, t);
    const Vec3 view_tangent = {dot(view, t), dot(view, b), dot(view, normal)};
    const Vec3 light_tangent = {dot(light, t), dot(light, b), light_z};
    return brdf(view_tangent, light_tangent);
  };
}

ReparameterizedBrdf phong_brdf(double exponent) {
  if (!(exponent > 0.0) || !std::isfinite(exponent)) {
    throw std::invalid_argument("phong_brdf: exponent must be finite and > 0");
  }
  const double scale = (exponent + 1.0) / (2.0 * kPi);
  return [exponent, scale](double theta_i, double, double) -> double {
    const double c = std::cos(theta_i);
    return c > 0.0 ? scale * std::pow(c, exponent) : 0.0;
  };
}

double phong_response(int l, double exponent) {
  check_order(l, "phong_response", "l");
  if (!(exponent > 0.0) || !std::isfinite(exponent)) {
    throw std::invalid_argument("phong_response: exponent must be finite and > 0");
  }
  const double s = exponent;
  double a = (l % 2 == 0) ? 1.0 : (s + 1.0) / (s + 2.0);
  for (int k = (l % 2 == 0) ? 2 : 3; k <= l; k += 2) {
    a *= (s - k + 2.0) / (s + k + 1.0);
  }
  return a;
}

CosineWeightedBrdf microfacet_brdf(double sigma) {
  if (!(sigma > 0.0) || !std::isfinite(sigma)) {
    throw std::invalid_argument("microfacet_brdf: sigma must be finite and > 0");
  }
  const double scale = 1.0 / (4.0 * kPi * sigma * sigma);
  return [sigma, scale](const Vec3& v, const Vec3& l) -> double {
    if (l[2] <= 0.0 || v[2] < 0.0) {
      return 0.0;
    }
    const Vec3 h = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    const double length = std::sqrt(dot(h, h));
    if (length < kMinHalfVectorLength) {
      return 0.0;
    }
    const double theta_h = std::acos(std::clamp(h[2] / length, -1.0, 1.0));
    const double x = theta_h / sigma;
    return scale * std::exp(-x * x);
  };
}

// ---- BRDF tables and coefficients ----------------------------------------------------------

BrdfTable::BrdfTable(const BrdfGrid& grid) : grid_(grid) {
  check_count(grid.theta_i_count, "BrdfTable", "theta_i_count");
  check_count(grid.theta_o_count, "BrdfTable", "theta_o_count");
  check_count(grid.phi_count, "BrdfTable", "phi_count");
  atmosphere::detail::gauss_legendre(grid.theta_i_count, cos_i_, weight_i_);
  atmosphere::detail::gauss_legendre(grid.theta_o_count, cos_o_, weight_o_);
  values_.assign(static_cast<std::size_t>(grid.theta_i_count) *
                     static_cast<std::size_t>(grid.theta_o_count) *
                     static_cast<std::size_t>(grid.phi_count),
                 0.0);
}

double BrdfTable::theta_i(int i) const { return std::acos(cos_i_.at(static_cast<std::size_t>(i))); }
double BrdfTable::theta_o(int j) const { return std::acos(cos_o_.at(static_cast<std::size_t>(j))); }
double BrdfTable::phi(int k) const { return (k + 0.5) * kPi / grid_.phi_count; }

BrdfTable tabulate(const ReparameterizedBrdf& brdf, const BrdfGrid& grid) {
  if (!brdf) {
    throw std::invalid_argument("tabulate: empty BRDF");
  }
  BrdfTable table(grid);
  for (int i = 0; i < grid.theta_i_count; ++i) {
    const double theta_i = table.theta_i(i);
    for (int j = 0; j < grid.theta_o_count; ++j) {
      const double theta_o = table.theta_o(j);
      for (int k = 0; k < grid.phi_count; ++k) {
        table.at(i, j, k) = brdf(theta_i, theta_o, table.phi(k));
      }
    }
  }
  return table;
}

BrdfCoefficients::BrdfCoefficients(int order_l, int order_p)
    : order_l_(order_l), order_p_(order_p) {
  check_order(order_l, "BrdfCoefficients", "order_l");
  check_order(order_p, "BrdfCoefficients", "order_p");
  values_.assign(static_cast<std::size_t>(order_l + 1) * static_cast<std::size_t>(order_p + 1) *
                     static_cast<std::size_t>(order_p + 1),
                 0.0);
}

double BrdfCoefficients::operator()(int l, int p, int q) const {
  if (l < 0 || l > order_l_ || p < 0 || p > order_p_) {
    throw std::invalid_argument("BrdfCoefficients: (l, p) out of range");
  }
  const int abs_q = std::abs(q);
  if (abs_q > std::min(l, p)) {
    return 0.0;
  }
  return values_[offset(l, p, abs_q)];
}

double& BrdfCoefficients::at(int l, int p, int q) {
  if (l < 0 || l > order_l_ || p < 0 || p > order_p_ || q < 0 || q > std::min(l, p)) {
    throw std::invalid_argument("BrdfCoefficients::at: (l, p, q) out of range");
  }
  return values_[offset(l, p, q)];
}

BrdfCoefficients project_brdf(const BrdfTable& table, int order_l, int order_p) {
  check_order(order_l, "project_brdf", "order_l");
  check_order(order_p, "project_brdf", "order_p");
  const BrdfGrid& grid = table.grid();
  const auto n_i = static_cast<std::size_t>(grid.theta_i_count);
  const auto n_o = static_cast<std::size_t>(grid.theta_o_count);
  const auto n_phi = static_cast<std::size_t>(grid.phi_count);
  const auto n_q = static_cast<std::size_t>(order_p + 1);

  // cos(q phi_k) times the phi weight 2 pi / phi_count of the even extension to [0, 2 pi).
  std::vector<double> phi_kernel(n_q * n_phi);
  for (std::size_t q = 0; q < n_q; ++q) {
    for (std::size_t k = 0; k < n_phi; ++k) {
      phi_kernel[q * n_phi + k] = (2.0 * kPi / static_cast<double>(n_phi)) *
                                  std::cos(static_cast<double>(q) * table.phi(static_cast<int>(k)));
    }
  }
  const std::vector<double> legendre_o = legendre_table(table.cos_theta_o(), order_p);
  const std::vector<double> legendre_i = legendre_table(table.cos_theta_i(), order_l);
  const std::size_t count_o = legendre_count(order_p);
  const std::size_t count_i = legendre_count(order_l);
  const auto w_o = table.weights_theta_o();
  const auto w_i = table.weights_theta_i();

  // rho_pq(theta_i) for one theta_i row at a time: [p * n_q + q].
  std::vector<double> rho_q(n_q);
  std::vector<double> rho_pq(n_q * n_q);
  BrdfCoefficients result(order_l, order_p);
  for (std::size_t i = 0; i < n_i; ++i) {
    std::fill(rho_pq.begin(), rho_pq.end(), 0.0);
    for (std::size_t j = 0; j < n_o; ++j) {
      // Step 1a: the phi integral.
      const double* row = &table.values()[(i * n_o + j) * n_phi];
      for (std::size_t q = 0; q < n_q; ++q) {
        double sum = 0.0;
        for (std::size_t k = 0; k < n_phi; ++k) {
          sum += phi_kernel[q * n_phi + k] * row[k];
        }
        rho_q[q] = sum;
      }
      // Step 1b: the theta_o integral against P̄_pq(cos theta_o).
      const double* p_o = &legendre_o[j * count_o];
      for (int p = 0; p <= order_p; ++p) {
        for (int q = 0; q <= p; ++q) {
          rho_pq[static_cast<std::size_t>(p) * n_q + static_cast<std::size_t>(q)] +=
              w_o[j] * rho_q[static_cast<std::size_t>(q)] * p_o[legendre_index(p, q)];
        }
      }
    }
    // Step 1c: the theta_i integral against P̄_lq(cos theta_i), with eq. 13's normalisation
    // 1 / (2 (2 - δ_q0)) for our P̄ (header).
    const double* p_i = &legendre_i[i * count_i];
    for (int l = 0; l <= order_l; ++l) {
      for (int p = 0; p <= order_p; ++p) {
        for (int q = 0; q <= std::min(l, p); ++q) {
          const double normalisation = q == 0 ? 0.5 : 0.25;
          result.at(l, p, q) +=
              normalisation * w_i[i] * p_i[legendre_index(l, q)] *
              rho_pq[static_cast<std::size_t>(p) * n_q + static_cast<std::size_t>(q)];
        }
      }
    }
  }
  return result;
}

BrdfCoefficients project_brdf(const ReparameterizedBrdf& brdf, const BrdfGrid& grid, int order_l,
                              int order_p) {
  return project_brdf(tabulate(brdf, grid), order_l, order_p);
}

// ---- Convolution and SHRMs ------------------------------------------------------------------

ReflectedLightField::ReflectedLightField(int order_l, int order_p)
    : order_l_(order_l), order_p_(order_p) {
  check_order(order_l, "ReflectedLightField", "order_l");
  check_order(order_p, "ReflectedLightField", "order_p");
  values_.assign(coefficient_count(order_l) * coefficient_count(order_p), 0.0);
}

ReflectedLightField convolve(std::span<const double> lighting, int lighting_order,
                             const BrdfCoefficients& brdf) {
  check_order(lighting_order, "convolve", "lighting_order");
  if (lighting.size() < coefficient_count(lighting_order)) {
    throw std::invalid_argument("convolve: lighting holds fewer than (order + 1)^2 values");
  }
  const int order_l = std::min(lighting_order, brdf.order_l());
  const int order_p = brdf.order_p();
  ReflectedLightField field(order_l, order_p);
  for (int l = 0; l <= order_l; ++l) {
    const double lambda = convolution_constant(l);
    for (int m = -l; m <= l; ++m) {
      const double light = lighting[index(l, m)];
      for (int p = 0; p <= order_p; ++p) {
        for (int q = -std::min(l, p); q <= std::min(l, p); ++q) {
          field.at(l, m, p, q) = lambda * light * brdf(l, p, q);  // eq. 5
        }
      }
    }
  }
  return field;
}

Mat3 reflection_frame(const Vec3& c) {
  const Vec3 d = normalized(c, "reflection_frame");
  const double sin_alpha = std::hypot(d[0], d[1]);
  const double cos_alpha = d[2];
  double cos_beta = 1.0, sin_beta = 0.0;
  if (sin_alpha > 0.0) {
    cos_beta = d[0] / sin_alpha;
    sin_beta = d[1] / sin_alpha;
  }
  // Columns e_alpha, e_beta, C of Rz(beta) Ry(alpha).
  return {cos_alpha * cos_beta, -sin_beta, sin_alpha * cos_beta,
          cos_alpha * sin_beta, cos_beta,  sin_alpha * sin_beta,
          -sin_alpha,           0.0,       cos_alpha};
}

std::vector<double> local_shrm(const ReflectedLightField& field, const Vec3& reflection) {
  const int order_l = field.order_l();
  const int order_p = field.order_p();
  const Rotation rotation(reflection_frame(reflection), order_l);
  std::vector<double> out(coefficient_count(order_p), 0.0);
  // B_pq = sum_l Lambda_l^-1 sum_m D^l_mq(R_C) B_lmpq (eq. 14, header).
  for (int l = 0; l <= order_l; ++l) {
    const double inverse_lambda = 1.0 / convolution_constant(l);
    for (int p = 0; p <= order_p; ++p) {
      for (int q = -std::min(l, p); q <= std::min(l, p); ++q) {
        double sum = 0.0;
        for (int m = -l; m <= l; ++m) {
          sum += rotation(l, m, q) * field(l, m, p, q);
        }
        out[index(p, q)] += inverse_lambda * sum;
      }
    }
  }
  return out;
}

std::vector<double> global_shrm(std::span<const double> local, int order_p,
                                const Vec3& reflection) {
  check_order(order_p, "global_shrm", "order_p");
  if (local.size() < coefficient_count(order_p)) {
    throw std::invalid_argument("global_shrm: local holds fewer than (order_p + 1)^2 values");
  }
  const Rotation rotation(reflection_frame(reflection), order_p);
  return rotation.apply(local.first(coefficient_count(order_p)));
}

double evaluate_shrm(std::span<const double> coefficients, int order_p, const Vec3& direction) {
  check_order(order_p, "evaluate_shrm", "order_p");
  if (coefficients.size() < coefficient_count(order_p)) {
    throw std::invalid_argument("evaluate_shrm: fewer than (order_p + 1)^2 coefficients");
  }
  return reconstruct(coefficients.first(coefficient_count(order_p)), order_p, direction);
}

double reflected_radiance(const ReflectedLightField& field, const Vec3& normal, const Vec3& view) {
  const Vec3 n = normalized(normal, "reflected_radiance");
  const Vec3 v = normalized(view, "reflected_radiance");
  const double n_v = dot(n, v);
  const Vec3 c = {2.0 * n_v * n[0] - v[0], 2.0 * n_v * n[1] - v[1], 2.0 * n_v * n[2] - v[2]};
  const std::vector<double> coefficients = local_shrm(field, c);
  const Vec3 omega_o = transpose_times(reflection_frame(c), v);
  return evaluate_shrm(coefficients, field.order_p(), omega_o);
}

std::span<const double> ShrmMap::texel(int x, int y) const {
  const std::size_t count = coefficient_count(order_p);
  const std::size_t offset = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                              static_cast<std::size_t>(x)) *
                             count;
  return std::span<const double>(coefficients).subspan(offset, count);
}

ShrmMap local_shrm_map(const ReflectedLightField& field, int width, int height) {
  check_count(width, "local_shrm_map", "width");
  check_count(height, "local_shrm_map", "height");
  const int order_l = field.order_l();
  const int order_p = field.order_p();
  const std::size_t count_p = coefficient_count(order_p);
  ShrmMap map;
  map.width = width;
  map.height = height;
  map.order_p = order_p;
  map.global = false;
  map.coefficients.assign(
      static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * count_p, 0.0);
  // Per row: cos_part[m' count_p + pq] and sin_part[...] (header, local_shrm_map) with
  // D^l(R_C) = Dz(beta) d^l(alpha) and Dz's columns m' (cos m'b at row m', sin m'b at row -m')
  // and -m' (-sin m'b at row m', cos m'b at row -m'):
  //   sum_m D^l_mq B_lm = d_0q B_l0 + sum_{m'>0} cos m'b (d_m'q B_lm' + d_-m'q B_l,-m')
  //                                          + sin m'b (d_m'q B_l,-m' - d_-m'q B_lm').
  const auto n_m = static_cast<std::size_t>(order_l + 1);
  std::vector<double> cos_part(n_m * count_p), sin_part(n_m * count_p);
  std::vector<double> cos_mb(n_m), sin_mb(n_m);
  for (int y = 0; y < height; ++y) {
    const double alpha = (y + 0.5) * kPi / height;
    const Rotation d(rotation_y(alpha), order_l);
    std::fill(cos_part.begin(), cos_part.end(), 0.0);
    std::fill(sin_part.begin(), sin_part.end(), 0.0);
    for (int l = 0; l <= order_l; ++l) {
      const double inverse_lambda = 1.0 / convolution_constant(l);
      for (int p = 0; p <= order_p; ++p) {
        for (int q = -std::min(l, p); q <= std::min(l, p); ++q) {
          const std::size_t pq = index(p, q);
          cos_part[pq] += inverse_lambda * d(l, 0, q) * field(l, 0, p, q);
          for (int m = 1; m <= l; ++m) {
            const double b_plus = field(l, m, p, q), b_minus = field(l, -m, p, q);
            const double d_plus = d(l, m, q), d_minus = d(l, -m, q);
            const std::size_t at = static_cast<std::size_t>(m) * count_p + pq;
            cos_part[at] += inverse_lambda * (d_plus * b_plus + d_minus * b_minus);
            sin_part[at] += inverse_lambda * (d_plus * b_minus - d_minus * b_plus);
          }
        }
      }
    }
    for (int x = 0; x < width; ++x) {
      const double beta = 2.0 * kPi * (x + 0.5) / width;
      for (std::size_t m = 0; m < n_m; ++m) {
        cos_mb[m] = std::cos(static_cast<double>(m) * beta);
        sin_mb[m] = std::sin(static_cast<double>(m) * beta);
      }
      double* out = &map.coefficients[(static_cast<std::size_t>(y) * width + x) * count_p];
      for (std::size_t pq = 0; pq < count_p; ++pq) {
        double sum = cos_part[pq];
        for (std::size_t m = 1; m < n_m; ++m) {
          sum += cos_mb[m] * cos_part[m * count_p + pq] + sin_mb[m] * sin_part[m * count_p + pq];
        }
        out[pq] = sum;
      }
    }
  }
  return map;
}

ShrmMap global_shrm_map(const ShrmMap& local) {
  if (local.global) {
    throw std::invalid_argument("global_shrm_map: the map is already global");
  }
  check_count(local.width, "global_shrm_map", "width");
  check_count(local.height, "global_shrm_map", "height");
  check_order(local.order_p, "global_shrm_map", "order_p");
  const std::size_t count_p = coefficient_count(local.order_p);
  if (local.coefficients.size() !=
      static_cast<std::size_t>(local.width) * static_cast<std::size_t>(local.height) * count_p) {
    throw std::invalid_argument("global_shrm_map: coefficient buffer has the wrong size");
  }
  ShrmMap map = local;
  map.global = true;
  const int order_p = local.order_p;
  std::vector<double> rotated(count_p);
  for (int y = 0; y < local.height; ++y) {
    const double alpha = (y + 0.5) * kPi / local.height;
    const Rotation d(rotation_y(alpha), order_p);
    for (int x = 0; x < local.width; ++x) {
      const double beta = 2.0 * kPi * (x + 0.5) / local.width;
      double* texel = &map.coefficients[(static_cast<std::size_t>(y) * local.width + x) * count_p];
      d.apply(std::span<const double>(texel, count_p), rotated);
      // Dz(beta) (spherical_harmonics.hpp, Rotation): g_pq = cos f_pq - sin f_p,-q,
      // g_p,-q = sin f_pq + cos f_p,-q for q > 0.
      for (int p = 0; p <= order_p; ++p) {
        texel[index(p, 0)] = rotated[index(p, 0)];
        for (int q = 1; q <= p; ++q) {
          const double c = std::cos(q * beta), s = std::sin(q * beta);
          const double plus = rotated[index(p, q)], minus = rotated[index(p, -q)];
          texel[index(p, q)] = c * plus - s * minus;
          texel[index(p, -q)] = s * plus + c * minus;
        }
      }
    }
  }
  return map;
}

std::vector<double> dynamic_reflection_map(const ShrmMap& global, const Vec3& view) {
  if (!global.global) {
    throw std::invalid_argument("dynamic_reflection_map: the map must be a global SHRM");
  }
  const std::size_t count_p = coefficient_count(global.order_p);
  const std::size_t texels =
      static_cast<std::size_t>(global.width) * static_cast<std::size_t>(global.height);
  if (global.coefficients.size() != texels * count_p) {
    throw std::invalid_argument("dynamic_reflection_map: coefficient buffer has the wrong size");
  }
  // Y_pq(V) once per frame (sec. 7.5), then a dot product per texel.
  std::vector<double> y(count_p);
  evaluate(global.order_p, normalized(view, "dynamic_reflection_map"), y);
  std::vector<double> out(texels, 0.0);
  for (std::size_t t = 0; t < texels; ++t) {
    double sum = 0.0;
    for (std::size_t pq = 0; pq < count_p; ++pq) {
      sum += global.coefficients[t * count_p + pq] * y[pq];
    }
    out[t] = sum;
  }
  return out;
}

}  // namespace thalassa::sh
