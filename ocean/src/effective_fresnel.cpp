#include "thalassa/ocean/effective_fresnel.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "ross_brdf_reference.hpp"

namespace thalassa::ocean {
namespace {

// The 6-point Gauss-Legendre rule on [-1, 1] (Abramowitz & Stegun, table 25.4): exact for
// polynomials of degree 11, on panels one standard deviation wide.
constexpr std::array<double, 3> kNodes = {0.2386191860831969086305017, 0.6612093864662645136613996,
                                          0.9324695142031520278123016};
constexpr std::array<double, 3> kWeights = {
    0.4679139345726910473898703, 0.3607615730481386075698335, 0.1713244923791703450402961};
// The slopes are integrated to this many standard deviations (the Gaussian's tail beyond holds
// 1.2e-15 of it).
constexpr double kHalfWidth = 8.0;
constexpr double kInvSqrt2Pi = 0.39894228040143267793994605993;
// sin theta_v at which the table's mean slopes over sin theta_v stand for their limit at normal
// view (their relative change from there to 0 is of order this squared).
constexpr double kNearNormalSine = 1e-3;

// Calls g(t, w) at the nodes and weights of panels of width at most 1 spanning [a, b].
template <typename G>
void for_each_node(double a, double b, G&& g) {
  const int panels = std::max(1, static_cast<int>(std::ceil(b - a)));
  const double width = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    const double middle = a + width * (p + 0.5);
    for (std::size_t k = 0; k < kNodes.size(); ++k) {
      const double w = 0.5 * width * kWeights[k];
      g(middle - 0.5 * width * kNodes[k], w);
      g(middle + 0.5 * width * kNodes[k], w);
    }
  }
}

}  // namespace

SchlickAverage effective_fresnel_schlick_average(double cos_theta_v, double along, double across) {
  const double mu = std::clamp(cos_theta_v, 0.0, 1.0);
  const double a = std::clamp(along, 0.0, 1.0), b = std::clamp(across, 0.0, 1.0);
  const double sigma = std::sqrt(a);
  // The view v = (sin theta, 0, mu) in a frame turned to its azimuth, and the slopes
  // zeta = (sqrt(a) s1, sqrt(b) s2) with s1, s2 standard normal. A facet faces the eye where
  // v.f sqrt(1 + |zeta|^2) = mu - sin theta sqrt(a) s1 > 0 (eq. 10's (v.f)_+): s1 < s_max, the
  // kink, on a panel edge. q_vn^e's normalisation, the integral of p (v.f)_+ / f_z, is summed by
  // the same nodes (it is cos theta_v (1 + Lambda_v), eq. 11), so that the average is a ratio of
  // two sums of one rule.
  const double sin_theta = std::sqrt(std::max(1.0 - mu * mu, 0.0));
  if (mu == 0.0 && sigma == 0.0) return {1.0, 0.0, 0.0, 0.0};  // a flat sea seen edge-on: v.f -> 0
  const double s_max = sin_theta * sigma > mu / kHalfWidth
                           ? std::min(kHalfWidth, mu / (sin_theta * sigma))
                           : kHalfWidth;
  double weighted = 0.0, weighted_derivative = 0.0, facing_area = 0.0;
  double mean_s1 = 0.0, weighted_s1 = 0.0;
  for_each_node(-kHalfWidth, s_max, [&](double s1, double w1) {
    const double facing = mu - sin_theta * sigma * s1;  // v.f / f_z
    if (facing <= 0.0) return;
    const double p1 = w1 * kInvSqrt2Pi * std::exp(-0.5 * s1 * s1) * facing;
    facing_area += p1;
    mean_s1 += p1 * s1;
    // Across the view's azimuth the integrand is even in s2: twice [0, kHalfWidth].
    double across_sum = 0.0, across_derivative = 0.0;
    for_each_node(0.0, kHalfWidth, [&](double s2, double w2) {
      const double inverse_fz2 = 1.0 + a * s1 * s1 + b * s2 * s2;  // 1 / f_z^2
      const double inverse_fz = std::sqrt(inverse_fz2);
      const double x = 1.0 - facing / inverse_fz;  // 1 - v.f
      const double x4 = (x * x) * (x * x);
      const double weight = 2.0 * w2 * kInvSqrt2Pi * std::exp(-0.5 * s2 * s2);
      across_sum += weight * x4 * x;
      // d(x^5)/db = 5 x^4 dx/db, dx/db = facing s2^2 / (2 (1 / f_z)^3).
      across_derivative += weight * 5.0 * x4 * facing * s2 * s2 / (2.0 * inverse_fz2 * inverse_fz);
    });
    weighted += p1 * across_sum;
    weighted_s1 += p1 * s1 * across_sum;
    weighted_derivative += p1 * across_derivative;
  });
  if (!(facing_area > 0.0)) return {1.0, 0.0, 0.0, 0.0};
  return {std::clamp(weighted / facing_area, 0.0, 1.0), weighted_derivative / facing_area,
          sigma * mean_s1 / facing_area, sigma * weighted_s1 / facing_area};
}

glm::dvec4 EffectiveFresnelTable::sample(double cos_theta_v, double along) const {
  const glm::dvec2 position = glsl::OceanEffectiveFresnelTablePosition(cos_theta_v, along);
  const int i = std::clamp(static_cast<int>(position.x), 0, cos_size - 2);
  const int j = std::clamp(static_cast<int>(position.y), 0, sigma_size - 2);
  const double fx = position.x - i, fy = position.y - j;
  auto at = [&](int x, int y) {
    const float* texel = &values[4 * (std::size_t(y) * cos_size + x)];
    return glm::dvec4(texel[0], texel[1], texel[2], texel[3]);
  };
  return (1.0 - fy) * ((1.0 - fx) * at(i, j) + fx * at(i + 1, j)) +
         fy * ((1.0 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
}

double EffectiveFresnelTable::lookup(double cos_theta_v, double along, double across,
                                     double fresnel_r) const {
  return glsl::OceanEffectiveFresnelFromTable(glm::dvec2(sample(cos_theta_v, along)), along, across,
                                              fresnel_r);
}

double EffectiveFresnelTable::fresnel_weighted_mean_slope(double cos_theta_v, double along,
                                                          double fresnel_r) const {
  const double mu = std::clamp(cos_theta_v, 0.0, 1.0);
  return glsl::OceanFresnelWeightedMeanSlope(sample(mu, along), std::sqrt(1.0 - mu * mu),
                                             fresnel_r);
}

const EffectiveFresnelTable& effective_fresnel_table() {
  static const EffectiveFresnelTable table = [] {
    EffectiveFresnelTable t;
    t.cos_size = glsl::OCEAN_EFFECTIVE_FRESNEL_TABLE_COS_SIZE;
    t.sigma_size = glsl::OCEAN_EFFECTIVE_FRESNEL_TABLE_SIGMA_SIZE;
    t.values.resize(4 * std::size_t(t.cos_size) * t.sigma_size);
    for (int j = 0; j < t.sigma_size; ++j) {
      for (int i = 0; i < t.cos_size; ++i) {
        const glm::dvec2 node = glsl::OceanEffectiveFresnelTableNode(i, j);
        const double variance = node.y * node.y;
        const SchlickAverage average =
            effective_fresnel_schlick_average(node.x, variance, variance);
        // The mean slopes over sin theta_v, smooth at normal view (where both vanish): there the
        // limit, the ratio at kNearNormalSine.
        const double sine = std::sqrt(std::max(1.0 - node.x * node.x, 0.0));
        const bool normal = sine < kNearNormalSine;
        const SchlickAverage slopes =
            normal ? effective_fresnel_schlick_average(
                         std::sqrt(1.0 - kNearNormalSine * kNearNormalSine), variance, variance)
                   : average;
        const double slope_sine = normal ? kNearNormalSine : sine;
        const std::size_t k = 4 * (std::size_t(j) * t.cos_size + i);
        t.values[k] = static_cast<float>(average.value);
        t.values[k + 1] = static_cast<float>(average.across_derivative);
        t.values[k + 2] = static_cast<float>(slopes.mean_slope / slope_sine);
        t.values[k + 3] = static_cast<float>(slopes.schlick_mean_slope / slope_sine);
      }
    }
    return t;
  }();
  return table;
}

}  // namespace thalassa::ocean
