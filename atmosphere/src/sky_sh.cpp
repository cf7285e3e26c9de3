// thalassa — the sky in spherical harmonics for the engine. Contracts, conventions and sources are
// in the header (thalassa/atmosphere/sky_sh.hpp); this file says how.

#include "thalassa/atmosphere/sky_sh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace thalassa::atmosphere {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kChannels = 3;
constexpr int kIrradianceOrder = 2;

void check_grid(const SkyProjectionGrid& grid, const char* function) {
  if (grid.width < 2 || grid.height < 2 || grid.height % 2 != 0) {
    throw std::invalid_argument(std::string(function) +
                                ": the projection grid must be at least 2 x 2 with an even height");
  }
}

void check_order(int order, const char* function) {
  if (order < 0) throw std::invalid_argument(std::string(function) + ": order must be >= 0");
}

sh::LatLongLayout layout(const SkyProjectionGrid& grid) {
  return {grid.width, grid.height, kChannels, kChannels};
}

}  // namespace

std::vector<double> sample_sky(const SkyRadianceFunction& sky, const SkyProjectionGrid& grid) {
  check_grid(grid, "sample_sky");
  if (!sky) throw std::invalid_argument("sample_sky: no sky function");
  std::vector<double> samples(static_cast<std::size_t>(grid.width) *
                              static_cast<std::size_t>(grid.height) * kChannels);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const sh::Vec3 d = sh::lat_long_direction(grid.width, grid.height, x, y);
      const glm::dvec3 radiance = sky(glm::dvec3(d[0], d[1], d[2]));
      const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(grid.width) +
                              static_cast<std::size_t>(x)) *
                             kChannels;
      for (int c = 0; c < kChannels; ++c) samples[at + static_cast<std::size_t>(c)] = radiance[c];
    }
  }
  return samples;
}

std::vector<double> project_sky(std::span<const double> samples, const SkyProjectionGrid& grid,
                                int order) {
  check_grid(grid, "project_sky");
  check_order(order, "project_sky");
  return sh::project_lat_long(samples, layout(grid), order);
}

double clamped_cosine_response(int l) {
  check_order(l, "clamped_cosine_response");
  if (l == 0) return kPi;
  if (l == 1) return 2.0 * kPi / 3.0;
  if (l % 2 == 1) return 0.0;
  // c_l = l! / (2^l ((l/2)!)^2): c_0 = 1, c_(k+2) = c_k (k + 1) / (k + 2).
  double c = 1.0;
  for (int k = 0; k < l; k += 2) c *= (k + 1.0) / (k + 2.0);
  const double sign = (l / 2) % 2 == 1 ? 1.0 : -1.0;  // (-1)^(l/2 - 1)
  return 2.0 * kPi * sign / ((l + 2.0) * (l - 1.0)) * c;
}

IrradianceSh irradiance_sh(std::span<const double> radiance, int order) {
  if (order < kIrradianceOrder ||
      radiance.size() < sh::coefficient_count(order) * static_cast<std::size_t>(kChannels)) {
    throw std::invalid_argument("irradiance_sh: need radiance coefficients of order >= 2");
  }
  IrradianceSh e{};
  for (int l = 0; l <= kIrradianceOrder; ++l) {
    const double a = clamped_cosine_response(l);
    for (int m = -l; m <= l; ++m) {
      const std::size_t i = sh::index(l, m);
      for (int c = 0; c < kChannels; ++c)
        e[i][c] = a * radiance[i * kChannels + static_cast<std::size_t>(c)];
    }
  }
  return e;
}

glm::dvec3 evaluate_irradiance(const IrradianceSh& irradiance, const glm::dvec3& normal) {
  std::array<double, 9> y{};
  sh::evaluate(kIrradianceOrder, {normal.x, normal.y, normal.z}, y);
  glm::dvec3 e(0.0);
  for (std::size_t i = 0; i < y.size(); ++i) e += irradiance[i] * y[i];
  return e;
}

glm::dvec3 irradiance_to_order(std::span<const double> radiance, int order,
                               const glm::dvec3& normal) {
  check_order(order, "irradiance_to_order");
  if (radiance.size() < sh::coefficient_count(order) * static_cast<std::size_t>(kChannels))
    throw std::invalid_argument("irradiance_to_order: too few coefficients");
  std::vector<double> y(sh::coefficient_count(order));
  sh::evaluate(order, {normal.x, normal.y, normal.z}, y);
  glm::dvec3 e(0.0);
  for (int l = 0; l <= order; ++l) {
    const double a = clamped_cosine_response(l);
    for (int m = -l; m <= l; ++m) {
      const std::size_t i = sh::index(l, m);
      for (int c = 0; c < kChannels; ++c)
        e[c] += a * radiance[i * kChannels + static_cast<std::size_t>(c)] * y[i];
    }
  }
  return e;
}

sh::ReparameterizedBrdf slope_reflection_kernel(double slope_variance) {
  if (!(slope_variance > 0.0) || !std::isfinite(slope_variance))
    throw std::invalid_argument("slope_reflection_kernel: slope variance must be finite and > 0");
  return [s = slope_variance](double theta_i, double, double) -> double {
    const double c = std::cos(0.5 * theta_i);  // cos theta_f
    if (c <= 0.0) return 0.0;                  // theta_i = pi: a vertical facet, zero density
    const double t = std::tan(0.5 * theta_i);  // |zeta|
    return std::exp(-0.5 * t * t / s) / (2.0 * kPi * s) / (4.0 * c * c * c * c);
  };
}

double glossy_sky_slope_variance(const GlossySkySettings& settings, int level) {
  const double t = static_cast<double>(level) / static_cast<double>(settings.levels - 1);
  return settings.min_slope_variance *
         std::pow(settings.max_slope_variance / settings.min_slope_variance, t);
}

namespace {

void check_settings(const GlossySkySettings& settings, const char* function) {
  if (settings.levels < 2 || !(settings.min_slope_variance > 0.0) ||
      !(settings.max_slope_variance > settings.min_slope_variance) ||
      !std::isfinite(settings.max_slope_variance) || settings.map_width < 1 ||
      settings.map_height < 1 || settings.kernel_nodes < 2)
    throw std::invalid_argument(
        std::string(function) +
        ": need >= 2 levels, 0 < min < max slope variance, maps >= 1 x 1, >= 2 kernel nodes");
  check_grid(settings.projection, function);
}

}  // namespace

GlossySkyKernels glossy_sky_kernels(const GlossySkySettings& settings) {
  check_settings(settings, "glossy_sky_kernels");
  // Appendix C step 1 per level: the kernel's coefficients rho_l00 (P = 0: radially symmetric,
  // one theta_o node and one phi node suffice) and the smallest F that leaves at most epsilon of
  // its energy out (sec. 5.1).
  GlossySkyKernels kernels;
  for (int k = 0; k < settings.levels; ++k) {
    GlossySkyLevel level;
    level.slope_variance = glossy_sky_slope_variance(settings, k);
    const sh::BrdfTable table =
        sh::tabulate(slope_reflection_kernel(level.slope_variance), {settings.kernel_nodes, 1, 1});
    level.orders = sh::choose_orders(table, settings.epsilon, 16, 0);
    kernels.coefficients.push_back(sh::project_brdf(table, level.orders.order_l, 0));
    kernels.levels.push_back(level);
  }
  return kernels;
}

GlossySky glossy_sky(const SkyRadianceFunction& sky, const GlossySkySettings& settings) {
  return glossy_sky(sky, settings, glossy_sky_kernels(settings));
}

GlossySky glossy_sky(const SkyRadianceFunction& sky, const GlossySkySettings& settings,
                     const GlossySkyKernels& kernels) {
  check_settings(settings, "glossy_sky");
  if (kernels.levels.size() != static_cast<std::size_t>(settings.levels) ||
      kernels.coefficients.size() != kernels.levels.size())
    throw std::invalid_argument("glossy_sky: the kernels are not those of these settings");
  GlossySky out;
  out.width = settings.map_width;
  out.height = settings.map_height;
  out.levels = kernels.levels;
  out.lighting_order = kIrradianceOrder;
  for (const GlossySkyLevel& level : out.levels)
    out.lighting_order = std::max(out.lighting_order, level.orders.order_l);
  const std::vector<sh::BrdfCoefficients>& responses = kernels.coefficients;

  // The sky's coefficients, once, to the largest F (and the irradiance from the same ones).
  const std::vector<double> samples = sample_sky(sky, settings.projection);
  const std::vector<double> lighting =
      project_sky(samples, settings.projection, out.lighting_order);
  out.irradiance = irradiance_sh(lighting, out.lighting_order);
  out.horizontal_irradiance = irradiance_to_order(lighting, out.lighting_order, {0.0, 0.0, 1.0});

  // Eq. 5 for a radial kernel and the reconstruction, channel by channel (the toolkit's maps are
  // one channel).
  const std::size_t texels =
      static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height);
  out.rgba.assign(texels * 4 * static_cast<std::size_t>(settings.levels), 1.0f);
  std::vector<double> channel(sh::coefficient_count(out.lighting_order));
  for (int c = 0; c < kChannels; ++c) {
    for (std::size_t i = 0; i < channel.size(); ++i)
      channel[i] = lighting[i * kChannels + static_cast<std::size_t>(c)];
    for (int k = 0; k < settings.levels; ++k) {
      const std::vector<double> map =
          sh::radial_reflection_map(channel, out.lighting_order,
                                    responses[static_cast<std::size_t>(k)], out.width, out.height);
      float* level = out.rgba.data() + static_cast<std::size_t>(k) * texels * 4;
      for (std::size_t t = 0; t < texels; ++t)
        level[t * 4 + static_cast<std::size_t>(c)] = static_cast<float>(map[t]);
    }
  }
  return out;
}

}  // namespace thalassa::atmosphere
