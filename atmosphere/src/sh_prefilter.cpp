// thalassa — order selection, angular-domain prefiltering and the frequency-space route
// (Ramamoorthi & Hanrahan 2002, sec. 5-6, appendices B-D). Contracts, conventions and sources are
// in the header (thalassa/atmosphere/sh_prefilter.hpp); this file says how, and why where it is
// not obvious.

#include "thalassa/atmosphere/sh_prefilter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace thalassa::sh {
namespace {

constexpr double kPi = std::numbers::pi;

// choose_orders: the coefficients' energy may exceed the total it is compared with by this
// relative amount (rounding in sums of ~1e4 squares is ~1e-12; aliased coefficients of a table
// projected beyond its resolution overshoot by far more).
constexpr double kEnergyMismatch = 1e-6;

// brdf_support: the midpoint grid in (theta_i in [0, pi], phi in [0, pi]) on which rho-hat is
// integrated. pi / 2048 = 0.09 degrees resolves lobes down to sigma ~ 0.01 rad; 64 azimuths
// resolve the phi dependence of the BRDFs here (smooth, low order in phi: P <= 5, sec. 5.2).
constexpr int kSupportThetaSteps = 2048;
constexpr int kSupportPhiSteps = 64;

// |C + V| below this (V within ~1e-12 rad of -C): no normal mirrors V into C (as in sh_brdf.cpp).
constexpr double kMinHalfVectorLength = 1e-12;

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

void check_order(int order, const char* function, const char* what) {
  if (order < 0) {
    throw std::invalid_argument(std::string(function) + ": " + what + " must be >= 0, got " +
                                std::to_string(order));
  }
}

void check_epsilon(double epsilon, const char* function) {
  if (!(epsilon > 0.0 && epsilon < 1.0)) {  // also rejects NaN
    throw std::invalid_argument(std::string(function) + ": epsilon must be in (0, 1), got " +
                                std::to_string(epsilon));
  }
}

void check_exponent(double exponent, const char* function) {
  if (!(exponent > 0.0) || !std::isfinite(exponent)) {
    throw std::invalid_argument(std::string(function) + ": exponent must be finite and > 0");
  }
}

// Energy per (l, p) band pair: e[l (P + 1) + p] = rho_lp0^2 + 2 sum_{q=1}^{min(l,p)} rho_lpq^2
// (the real basis has +q and -q with the same coefficient).
std::vector<double> band_energies(const BrdfCoefficients& rho) {
  const int order_l = rho.order_l(), order_p = rho.order_p();
  std::vector<double> e(static_cast<std::size_t>(order_l + 1) *
                        static_cast<std::size_t>(order_p + 1));
  for (int l = 0; l <= order_l; ++l) {
    for (int p = 0; p <= order_p; ++p) {
      double sum = 0.0;
      for (int q = 0; q <= std::min(l, p); ++q) {
        const double c = rho(l, p, q);
        sum += (q == 0 ? 1.0 : 2.0) * c * c;
      }
      e[static_cast<std::size_t>(l) * static_cast<std::size_t>(order_p + 1) +
        static_cast<std::size_t>(p)] = sum;
    }
  }
  return e;
}

// E(F, P) from band_energies (rho's order_p + 1 columns).
double captured(const std::vector<double>& e, int order_p_all, int order_l, int order_p) {
  double sum = 0.0;
  for (int l = 0; l <= order_l; ++l) {
    for (int p = 0; p <= order_p; ++p) {
      sum += e[static_cast<std::size_t>(l) * static_cast<std::size_t>(order_p_all + 1) +
               static_cast<std::size_t>(p)];
    }
  }
  return sum;
}

// The environment, ready for brute-force integration: for every input texel its centre's
// direction and its radiance times its exact solid angle; per row, the centre's polar angle.
struct PreparedEnvironment {
  int width = 0, height = 0;
  std::vector<double> x, y, z;       // texel-centre directions, row-major
  std::vector<double> weighted;      // L_t delta_omega_t
  std::vector<double> theta;         // per row, radians
  std::vector<double> cos_t, sin_t;  // per row
};

PreparedEnvironment prepare(std::span<const double> environment, const LatLongLayout& layout,
                            const char* function) {
  if (layout.width < 1 || layout.height < 1) {
    throw std::invalid_argument(std::string(function) + ": map size must be >= 1x1");
  }
  if (layout.channels != 1) {
    throw std::invalid_argument(std::string(function) +
                                ": the environment must have one channel (call once per channel)");
  }
  const int stride = layout.pixel_stride == 0 ? 1 : layout.pixel_stride;
  if (stride < 1) {
    throw std::invalid_argument(std::string(function) + ": pixel_stride must be >= 1");
  }
  const std::size_t texels =
      static_cast<std::size_t>(layout.width) * static_cast<std::size_t>(layout.height);
  if (environment.size() < (texels - 1) * static_cast<std::size_t>(stride) + 1) {
    throw std::invalid_argument(std::string(function) + ": environment buffer too small");
  }
  PreparedEnvironment env;
  env.width = layout.width;
  env.height = layout.height;
  env.x.resize(texels);
  env.y.resize(texels);
  env.z.resize(texels);
  env.weighted.resize(texels);
  env.theta.resize(static_cast<std::size_t>(layout.height));
  env.cos_t.resize(env.theta.size());
  env.sin_t.resize(env.theta.size());
  const double delta_phi = 2.0 * kPi / layout.width;
  for (int row = 0; row < layout.height; ++row) {
    const double theta = (row + 0.5) * kPi / layout.height;
    // The texel's exact solid angle, delta_phi (cos theta_top - cos theta_bottom).
    const double solid_angle = delta_phi * (std::cos(row * kPi / layout.height) -
                                            std::cos((row + 1) * kPi / layout.height));
    const auto r = static_cast<std::size_t>(row);
    env.theta[r] = theta;
    env.cos_t[r] = std::cos(theta);
    env.sin_t[r] = std::sin(theta);
    for (int column = 0; column < layout.width; ++column) {
      const double phi = (column + 0.5) * delta_phi;
      const std::size_t t =
          r * static_cast<std::size_t>(layout.width) + static_cast<std::size_t>(column);
      env.x[t] = env.sin_t[r] * std::cos(phi);
      env.y[t] = env.sin_t[r] * std::sin(phi);
      env.z[t] = env.cos_t[r];
      const double value = environment[t * static_cast<std::size_t>(stride)];
      if (!std::isfinite(value)) {
        throw std::invalid_argument(std::string(function) + ": environment value not finite");
      }
      env.weighted[t] = value * solid_angle;
    }
  }
  return env;
}

void check_options(const AngularOptions& options, const char* function) {
  if (options.width < 1 || options.height < 1) {
    throw std::invalid_argument(std::string(function) + ": output size must be >= 1x1");
  }
  if (!(options.support >= 0.0) || std::isnan(options.support)) {
    throw std::invalid_argument(std::string(function) + ": support must be >= 0 radians");
  }
}

// Calls visit(t) for every input texel t whose centre is within `support` (radians) of the unit
// direction c = direction(alpha, beta); all texels when support is 0 or >= pi. Rows whose centre
// ring misses the cone are skipped, and in each row only the azimuth interval
// cos(phi - beta) >= r, r = (cos support - cos alpha cos theta) / (sin alpha sin theta), is
// visited (widened by a column each side against rounding, then tested exactly): the cost is the
// texels inside the cone plus O(rows), the paper's W S_L^2.
template <typename Visit>
void for_each_in_support(const PreparedEnvironment& env, const Vec3& c, double alpha, double beta,
                         double support, Visit&& visit) {
  const int width = env.width;
  if (support <= 0.0 || support >= kPi) {
    const std::size_t texels = env.weighted.size();
    for (std::size_t t = 0; t < texels; ++t) visit(t);
    return;
  }
  const double cos_support = std::cos(support);
  const double cos_a = std::cos(alpha), sin_a = std::sin(alpha);
  for (int row = 0; row < env.height; ++row) {
    const auto r = static_cast<std::size_t>(row);
    if (std::abs(env.theta[r] - alpha) > support) continue;
    const std::size_t base = r * static_cast<std::size_t>(width);
    const double denominator = sin_a * env.sin_t[r];
    const double ratio = denominator > 0.0 ? (cos_support - cos_a * env.cos_t[r]) / denominator
                                           : -std::numeric_limits<double>::infinity();
    int first = 0, last = width - 1;
    if (ratio > -1.0) {
      const double half = std::acos(std::min(ratio, 1.0));
      const double scale = width / (2.0 * kPi);
      first = static_cast<int>(std::floor((beta - half) * scale - 0.5)) - 1;
      last = static_cast<int>(std::ceil((beta + half) * scale - 0.5)) + 1;
      if (last - first + 1 >= width) {
        first = 0;
        last = width - 1;
      }
    }
    for (int column = first; column <= last; ++column) {
      const int wrapped = ((column % width) + width) % width;
      const std::size_t t = base + static_cast<std::size_t>(wrapped);
      if (c[0] * env.x[t] + c[1] * env.y[t] + c[2] * env.z[t] >= cos_support) visit(t);
    }
  }
}

}  // namespace

// ---- Error analysis -------------------------------------------------------------------------

double brdf_energy(const BrdfTable& table) {
  const BrdfGrid& grid = table.grid();
  const auto w_i = table.weights_theta_i();
  const auto w_o = table.weights_theta_o();
  // ∫_0^2pi d phi_i ∫_0^2pi d phi_o f(phi_o - phi_i) = 2 pi ∫_0^2pi f, and for f even in phi
  // ∫_0^2pi f = 2 (pi / phi_count) sum_k f(phi_k) (the midpoint nodes of [0, pi]).
  const double phi_weight = 2.0 * kPi * 2.0 * kPi / grid.phi_count;
  double sum = 0.0;
  for (int i = 0; i < grid.theta_i_count; ++i) {
    for (int j = 0; j < grid.theta_o_count; ++j) {
      double ring = 0.0;
      for (int k = 0; k < grid.phi_count; ++k) {
        const double v = table.at(i, j, k);
        ring += v * v;
      }
      sum += w_i[static_cast<std::size_t>(i)] * w_o[static_cast<std::size_t>(j)] * ring;
    }
  }
  return phi_weight * sum;
}

double brdf_energy(const BrdfCoefficients& rho, int order_l, int order_p) {
  check_order(order_l, "brdf_energy", "order_l");
  check_order(order_p, "brdf_energy", "order_p");
  if (order_l > rho.order_l() || order_p > rho.order_p()) {
    throw std::invalid_argument("brdf_energy: orders exceed the coefficients'");
  }
  return captured(band_energies(rho), rho.order_p(), order_l, order_p);
}

OrderChoice choose_orders(const BrdfCoefficients& rho, double total_energy, double epsilon) {
  check_epsilon(epsilon, "choose_orders");
  if (!(total_energy > 0.0) || !std::isfinite(total_energy)) {
    throw std::invalid_argument("choose_orders: total_energy must be finite and > 0");
  }
  const std::vector<double> e = band_energies(rho);
  const int order_l = rho.order_l(), order_p = rho.order_p();
  const double all = captured(e, order_p, order_l, order_p);
  if (all > total_energy * (1.0 + kEnergyMismatch)) {
    throw std::invalid_argument(
        "choose_orders: the coefficients hold more energy than total_energy (aliased "
        "coefficients, or the total of another BRDF)");
  }
  const double target = (1.0 - epsilon) * total_energy;
  if (all < target) {
    throw std::domain_error("choose_orders: orders (" + std::to_string(order_l) + ", " +
                            std::to_string(order_p) + ") leave out " +
                            std::to_string(1.0 - all / total_energy) +
                            " of the energy, more than epsilon = " + std::to_string(epsilon) +
                            ": compute the coefficients to higher orders");
  }
  // Appendix C: reduce P first, then F.
  OrderChoice choice;
  choice.order_p = order_p;
  for (int p = 0; p <= order_p; ++p) {
    if (captured(e, order_p, order_l, p) >= target) {
      choice.order_p = p;
      break;
    }
  }
  choice.order_l = order_l;
  for (int l = 0; l <= order_l; ++l) {
    if (captured(e, order_p, l, choice.order_p) >= target) {
      choice.order_l = l;
      break;
    }
  }
  choice.captured_energy = captured(e, order_p, choice.order_l, choice.order_p);
  choice.total_energy = total_energy;
  choice.predicted_error = std::max(0.0, 1.0 - choice.captured_energy / total_energy);
  return choice;
}

OrderChoice choose_orders(const BrdfTable& table, double epsilon, int initial_order_l,
                          int initial_order_p) {
  check_epsilon(epsilon, "choose_orders");
  check_order(initial_order_l, "choose_orders", "initial_order_l");
  check_order(initial_order_p, "choose_orders", "initial_order_p");
  const BrdfGrid& grid = table.grid();
  // The largest orders the table's quadrature keeps discretely orthonormal (header).
  const int max_l = grid.theta_i_count - 1;
  const int max_p = std::min(grid.theta_o_count, grid.phi_count) - 1;
  const double total = brdf_energy(table);
  if (!(total > 0.0)) {
    throw std::invalid_argument("choose_orders: the BRDF table is zero");
  }
  int order_l = std::min(initial_order_l, max_l);
  int order_p = std::min(initial_order_p, max_p);
  for (;;) {
    const BrdfCoefficients rho = project_brdf(table, order_l, order_p);
    if (brdf_energy(rho, order_l, order_p) >= (1.0 - epsilon) * total) {
      const OrderChoice choice = choose_orders(rho, total, epsilon);
      // At the table's last orders the discrete basis is complete (discrete Parseval: all of the
      // table's energy is captured whatever the BRDF), so needing them means the table is too
      // coarse to tell.
      if ((max_l > 0 && choice.order_l >= max_l) || (max_p > 0 && choice.order_p >= max_p)) {
        break;
      }
      return choice;
    }
    if (order_l == max_l && order_p == max_p) break;
    // Appendix C: "repeat the algorithm with larger values for F and P".
    order_l = std::min(std::max(2 * order_l, 1), max_l);
    order_p = std::min(std::max(2 * order_p, 1), max_p);
  }
  throw std::domain_error(
      "choose_orders: the BRDF table cannot resolve orders that meet epsilon = " +
      std::to_string(epsilon) + " (tabulate it on a finer grid)");
}

BrdfCoefficients phong_coefficients(double exponent, int order_l) {
  check_exponent(exponent, "phong_coefficients");
  check_order(order_l, "phong_coefficients", "order_l");
  BrdfCoefficients rho(order_l, 0);
  for (int l = 0; l <= order_l; ++l) {
    rho.at(l, 0, 0) = std::sqrt(2.0 * l + 1.0) * phong_response(l, exponent);
  }
  return rho;
}

double phong_energy(double exponent) {
  check_exponent(exponent, "phong_energy");
  // 4 pi * 2 pi ∫_0^1 ((s + 1) / 2 pi)^2 t^(2s) dt.
  return 2.0 * (exponent + 1.0) * (exponent + 1.0) / (2.0 * exponent + 1.0);
}

// ---- The angular-domain baseline ------------------------------------------------------------

RadialBrdf phong_radial_brdf(double exponent) {
  check_exponent(exponent, "phong_radial_brdf");
  const double scale = (exponent + 1.0) / (2.0 * kPi);
  return [exponent, scale](double cos_theta_i) -> double {
    return cos_theta_i > 0.0 ? scale * std::pow(cos_theta_i, exponent) : 0.0;
  };
}

double phong_support(double exponent, double epsilon) {
  check_exponent(exponent, "phong_support");
  check_epsilon(epsilon, "phong_support");
  return std::acos(std::pow(epsilon, 1.0 / (exponent + 1.0)));
}

double brdf_support(const ReparameterizedBrdf& brdf, double theta_o, double epsilon) {
  if (!brdf) {
    throw std::invalid_argument("brdf_support: empty BRDF");
  }
  check_epsilon(epsilon, "brdf_support");
  if (!(theta_o >= 0.0 && theta_o <= kPi)) {
    throw std::invalid_argument("brdf_support: theta_o must be in [0, pi]");
  }
  const double step = kPi / kSupportThetaSteps;
  std::vector<double> cumulative(kSupportThetaSteps);
  double sum = 0.0;
  for (int i = 0; i < kSupportThetaSteps; ++i) {
    const double theta_i = (i + 0.5) * step;
    double ring = 0.0;
    for (int k = 0; k < kSupportPhiSteps; ++k) {
      ring += brdf(theta_i, theta_o, (k + 0.5) * kPi / kSupportPhiSteps);
    }
    // ∫_0^2pi d phi = 2 ∫_0^pi (rho-hat is even in phi), times sin theta_i d theta_i.
    sum += std::sin(theta_i) * step * 2.0 * (kPi / kSupportPhiSteps) * ring;
    cumulative[static_cast<std::size_t>(i)] = sum;
  }
  if (!(sum > 0.0)) return kPi;
  const double target = (1.0 - epsilon) * sum;
  for (int i = 0; i < kSupportThetaSteps; ++i) {
    if (cumulative[static_cast<std::size_t>(i)] >= target) return (i + 1) * step;
  }
  return kPi;
}

std::vector<double> angular_prefilter(std::span<const double> environment,
                                      const LatLongLayout& layout, const RadialBrdf& brdf,
                                      const AngularOptions& options) {
  if (!brdf) {
    throw std::invalid_argument("angular_prefilter: empty BRDF");
  }
  check_options(options, "angular_prefilter");
  const PreparedEnvironment env = prepare(environment, layout, "angular_prefilter");
  std::vector<double> out(static_cast<std::size_t>(options.width) *
                          static_cast<std::size_t>(options.height));
  for (int y = 0; y < options.height; ++y) {
    const double alpha = (y + 0.5) * kPi / options.height;
    for (int x = 0; x < options.width; ++x) {
      const double beta = 2.0 * kPi * (x + 0.5) / options.width;
      const Vec3 c = direction(alpha, beta);
      double sum = 0.0;
      for_each_in_support(env, c, alpha, beta, options.support, [&](std::size_t t) {
        sum += env.weighted[t] * brdf(c[0] * env.x[t] + c[1] * env.y[t] + c[2] * env.z[t]);
      });
      out[static_cast<std::size_t>(y) * static_cast<std::size_t>(options.width) +
          static_cast<std::size_t>(x)] = sum;
    }
  }
  return out;
}

std::vector<double> angular_prefilter(std::span<const double> environment,
                                      const LatLongLayout& layout, const CosineWeightedBrdf& brdf,
                                      double theta_o, double phi_o, const AngularOptions& options) {
  if (!brdf) {
    throw std::invalid_argument("angular_prefilter: empty BRDF");
  }
  if (!(theta_o >= 0.0 && theta_o <= kPi) || !std::isfinite(phi_o)) {
    throw std::invalid_argument("angular_prefilter: theta_o must be in [0, pi], phi_o finite");
  }
  check_options(options, "angular_prefilter");
  const PreparedEnvironment env = prepare(environment, layout, "angular_prefilter");
  const Vec3 omega_o = direction(theta_o, phi_o);
  std::vector<double> out(
      static_cast<std::size_t>(options.width) * static_cast<std::size_t>(options.height), 0.0);
  for (int y = 0; y < options.height; ++y) {
    const double alpha = (y + 0.5) * kPi / options.height;
    for (int x = 0; x < options.width; ++x) {
      const double beta = 2.0 * kPi * (x + 0.5) / options.width;
      const Vec3 c = direction(alpha, beta);
      const Mat3 r = reflection_frame(c);
      // V = R_C omega_o (global), N = (C + V) / |C + V|.
      const Vec3 v = {r[0] * omega_o[0] + r[1] * omega_o[1] + r[2] * omega_o[2],
                      r[3] * omega_o[0] + r[4] * omega_o[1] + r[5] * omega_o[2],
                      r[6] * omega_o[0] + r[7] * omega_o[1] + r[8] * omega_o[2]};
      const Vec3 sum_cv = {c[0] + v[0], c[1] + v[1], c[2] + v[2]};
      const double length = std::sqrt(dot(sum_cv, sum_cv));
      if (length < kMinHalfVectorLength) continue;  // theta_o = pi: B = 0 (header)
      const Vec3 n = {sum_cv[0] / length, sum_cv[1] / length, sum_cv[2] / length};
      // A tangent frame (t, b, N); its azimuth is arbitrary (isotropic BRDF).
      const Vec3 helper = std::abs(n[0]) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
      const double h = dot(helper, n);
      Vec3 t = {helper[0] - h * n[0], helper[1] - h * n[1], helper[2] - h * n[2]};
      const double t_length = std::sqrt(dot(t, t));
      t = {t[0] / t_length, t[1] / t_length, t[2] / t_length};
      const Vec3 b = cross(n, t);
      const Vec3 view = {dot(v, t), dot(v, b), dot(v, n)};
      double sum = 0.0;
      for_each_in_support(env, c, alpha, beta, options.support, [&](std::size_t k) {
        const Vec3 l = {env.x[k], env.y[k], env.z[k]};
        const double l_z = dot(l, n);
        if (l_z <= 0.0) return;  // below the surface
        sum += env.weighted[k] * brdf(view, {dot(l, t), dot(l, b), l_z});
      });
      out[static_cast<std::size_t>(y) * static_cast<std::size_t>(options.width) +
          static_cast<std::size_t>(x)] = sum;
    }
  }
  return out;
}

// ---- The frequency-space route --------------------------------------------------------------

BrdfCoefficients truncate(const BrdfCoefficients& rho, int order_l, int order_p) {
  check_order(order_l, "truncate", "order_l");
  check_order(order_p, "truncate", "order_p");
  if (order_l > rho.order_l() || order_p > rho.order_p()) {
    throw std::invalid_argument("truncate: orders exceed the coefficients'");
  }
  BrdfCoefficients out(order_l, order_p);
  for (int l = 0; l <= order_l; ++l) {
    for (int p = 0; p <= order_p; ++p) {
      for (int q = 0; q <= std::min(l, p); ++q) out.at(l, p, q) = rho(l, p, q);
    }
  }
  return out;
}

std::vector<double> radial_reflection_map(std::span<const double> lighting, int lighting_order,
                                          const BrdfCoefficients& rho, int width, int height) {
  check_order(lighting_order, "radial_reflection_map", "lighting_order");
  if (lighting.size() < coefficient_count(lighting_order)) {
    throw std::invalid_argument("radial_reflection_map: lighting holds fewer than (order + 1)^2");
  }
  if (width < 1 || height < 1) {
    throw std::invalid_argument("radial_reflection_map: map size must be >= 1x1");
  }
  const int order = std::min(lighting_order, rho.order_l());
  // Eq. 5 for a radially symmetric BRDF (Funk-Hecke): B_lm = A_l L_lm, A_l = rho_l00 / sqrt(2l+1).
  std::vector<double> b(coefficient_count(order));
  for (int l = 0; l <= order; ++l) {
    const double response = rho(l, 0, 0) / std::sqrt(2.0 * l + 1.0);
    for (int m = -l; m <= l; ++m) b[index(l, m)] = response * lighting[index(l, m)];
  }
  return reconstruct_lat_long(b, order, LatLongLayout{width, height, 1, 0});
}

std::vector<double> local_reflection_map(const ShrmMap& local, double theta_o, double phi_o) {
  if (local.global) {
    throw std::invalid_argument("local_reflection_map: the map must be a local SHRM");
  }
  check_order(local.order_p, "local_reflection_map", "order_p");
  if (!std::isfinite(theta_o) || !std::isfinite(phi_o)) {
    throw std::invalid_argument("local_reflection_map: view angles must be finite");
  }
  const std::size_t count_p = coefficient_count(local.order_p);
  const std::size_t texels =
      static_cast<std::size_t>(local.width) * static_cast<std::size_t>(local.height);
  if (local.width < 1 || local.height < 1 || local.coefficients.size() != texels * count_p) {
    throw std::invalid_argument("local_reflection_map: coefficient buffer has the wrong size");
  }
  // Y_pq(omega_o) once per map, then a dot product per texel (eq. 6).
  std::vector<double> y(count_p);
  evaluate(local.order_p, direction(theta_o, phi_o), y);
  std::vector<double> out(texels);
  for (std::size_t t = 0; t < texels; ++t) {
    double sum = 0.0;
    for (std::size_t pq = 0; pq < count_p; ++pq)
      sum += local.coefficients[t * count_p + pq] * y[pq];
    out[t] = sum;
  }
  return out;
}

// ---- Measured error -------------------------------------------------------------------------

void EnergyError::add(std::span<const double> approximation, std::span<const double> reference,
                      int width, int height, double weight) {
  if (width < 1 || height < 1) {
    throw std::invalid_argument("EnergyError::add: map size must be >= 1x1");
  }
  const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (approximation.size() != texels || reference.size() != texels) {
    throw std::invalid_argument("EnergyError::add: maps must hold width * height values");
  }
  if (!(weight >= 0.0) || !std::isfinite(weight)) {
    throw std::invalid_argument("EnergyError::add: weight must be finite and >= 0");
  }
  const double delta_phi = 2.0 * kPi / width;
  for (int y = 0; y < height; ++y) {
    const double solid_angle =
        delta_phi * (std::cos(y * kPi / height) - std::cos((y + 1) * kPi / height));
    double residual = 0.0, total = 0.0;
    for (int x = 0; x < width; ++x) {
      const std::size_t t = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>(x);
      const double d = approximation[t] - reference[t];
      residual += d * d;
      total += reference[t] * reference[t];
    }
    residual_ += weight * solid_angle * residual;
    total_ += weight * solid_angle * total;
  }
}

double EnergyError::relative() const {
  if (total_ > 0.0) return residual_ / total_;
  return residual_ > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

}  // namespace thalassa::sh
