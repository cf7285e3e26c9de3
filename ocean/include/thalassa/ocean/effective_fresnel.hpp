// thalassa — the sea's effective Fresnel reflectance F-bar (Bruneton, Neyret & Holzschuch 2010,
// sec. 5.2, eq. 24) in double precision, and the table of it that the lighting passes read when a
// scene asks for eq. 24 instead of the paper's fit eq. 26 (ocean.effective_fresnel = "table";
// docs/ocean_fresnel.md has both errors).
#pragma once

#include <vector>

#include <glm/vec4.hpp>

namespace thalassa::ocean {

// The Schlick factor (1 - v.f)^5 averaged over the facets visible from v (eq. 24's integral):
//   I = integral q_vn^e(zeta, v) (1 - v.f(zeta))^5 d^2 zeta,   F-bar = R + (1 - R) I,
// for Gaussian slopes of variance `along` toward the view's azimuth (eq. 25's sigma_v^2) and
// `across` perpendicular to it (dimensionless; their correlation is left out: the integrand is
// even across, and the mean of the slope's square across is `across` with or without it), and its
// derivative dI/d(across). cos_theta_v is clamped to [0, 1] and the variances to [0, 1]; at
// variance 0 along, I is Schlick's (1 - cos theta_v)^5 for `across` 0. Dimensionless, I in
// [0, 1]. Gauss-Legendre panels in the slopes' standard coordinates, cut at the visibility's kink
// (v.f = 0), with q_vn^e's normalisation summed by the same nodes: within 7e-8 of an independent
// rule (tests/unit/ross_brdf_test.cpp).
struct SchlickAverage {
  double value = 0.0;              // I
  double across_derivative = 0.0;  // dI / d(across)
  // The visible facets' mean slope toward the view's azimuth, integral q_vn^e zeta.e (e the
  // view's horizontal direction: negative, the facets facing the eye), and the same weighted by
  // the Schlick factor, integral q_vn^e (1 - v.f)^5 zeta.e; dimensionless.
  double mean_slope = 0.0;
  double schlick_mean_slope = 0.0;
};
SchlickAverage effective_fresnel_schlick_average(double cos_theta_v, double along, double across);

// The table of effective_fresnel_schlick_average that the GPU reads (shaders/ocean/
// effective_fresnel.glsl) for isotropic slopes (across = along), with the derivative that carries
// it to anisotropic ones to first order in across - along:
//   I(cos theta_v, a, b) ~ I(cos theta_v, a, a) + (b - a) dI/db(cos theta_v, a, a).
// OCEAN_EFFECTIVE_FRESNEL_TABLE_COS_SIZE x _SIGMA_SIZE samples at the nodes of
// OceanEffectiveFresnelTableNode (shaders/ocean/ross_brdf.glsl), row-major with cos theta_v along
// a row, four floats each (I, dI/db and SchlickAverage's two mean slopes over sin theta_v: a
// GL_RGBA32F texture's texels).
struct EffectiveFresnelTable {
  int cos_size = 0;
  int sigma_size = 0;
  std::vector<float> values;

  // F-bar for Schlick's R = fresnel_r, the view's cosine cos_theta_v and the slope variances along
  // and across the view's azimuth (eq. 25's sigma_v^2 and the slopes' total variance less it),
  // bilinear between the samples as GL_LINEAR reads the texture (at
  // OceanEffectiveFresnelTablePosition), in double: the CPU twin of OceanSceneEffectiveFresnel.
  double lookup(double cos_theta_v, double along, double across, double fresnel_r) const;
  // The visible facets' Fresnel-weighted mean slope toward the view's azimuth (dimensionless),
  // read as the GPU reads it: the CPU twin of OceanFresnelWeightedMeanSlope at the table's
  // bilinear sample (ocean.sky_lobe_centre = "fresnel_weighted").
  double fresnel_weighted_mean_slope(double cos_theta_v, double along, double fresnel_r) const;

 private:
  glm::dvec4 sample(double cos_theta_v, double along) const;
};

// The table, computed once per process on first use (about 0.2 s; thread-safe).
const EffectiveFresnelTable& effective_fresnel_table();

}  // namespace thalassa::ocean
