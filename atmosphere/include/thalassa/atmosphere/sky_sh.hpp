// thalassa — the sky in spherical harmonics, for the engine (issue 8, point 6): the sky's
// irradiance as nine SH coefficients per channel (Ramamoorthi & Hanrahan 2001, "An efficient
// representation for irradiance environment maps"), and reflection maps of the sky prefiltered in
// frequency space for rough seas seen from afar (Ramamoorthi & Hanrahan 2002, sec. 3-4 and
// appendix C: ../shared/papers/002_*), built on the toolkit (spherical_harmonics.hpp,
// sh_brdf.hpp, sh_prefilter.hpp). CPU only, double precision, no GL: the GL layer
// (thalassa/atmosphere/gl/sky_shrm.hpp) feeds these from a SkyProvider and uploads the maps.
// Measured numbers: docs/spherical_harmonics.md, "In the engine".
//
// Conventions
// -----------
// * Frame: the east-north-up frame of the observer (x east, y north, z up) is the toolkit's SH
//   frame: theta is the zenith angle, phi the azimuth counter-clockwise from east (east 0, north
//   pi / 2). Lat-long maps (the toolkit's layout): row 0 at the zenith, column 0 at phi = 0.
// * Radiance in the provider's unit (W m^-2 sr^-1 nm^-1), irradiance in that times sr
//   (W m^-2 nm^-1), RGB; three channels adjacent in coefficient vectors ([index(l, m) 3 + c]).
// * "The ocean's sky" is the full sphere the sea reflects: the provider's sky above the horizon
//   (d_z >= 0) and its below-horizon radiance below (the ocean paper's sec. 6), never the sun:
//   the sun stays analytic (its own direct irradiance, its own glint), because a disc of 0.27
//   degrees in SH of any practical order rings across the whole sphere (its coefficients fall
//   off only as the disc's Bessel pattern, |L_lm| ~ L_sun Omega_sun sqrt((2l+1) / 4 pi) up to
//   l ~ 1 / 0.0047 = 200), and the ringing, multiplied by a sun 1e5 times brighter than the
//   sky, would swamp the sky everywhere.
//
// Errors: orders below 0, grids below 2 x 2 or of odd height, empty sky functions, slope variances
// or epsilon out of range throw std::invalid_argument (DESIGN sec. 4).
#pragma once

#include <array>
#include <functional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "thalassa/atmosphere/sh_prefilter.hpp"

namespace thalassa::atmosphere {

// The ocean's sky: radiance (RGB) arriving from the unit ENU direction d, the whole sphere.
using SkyRadianceFunction = std::function<glm::dvec3(const glm::dvec3& direction)>;

// The lat-long grid on which a sky is sampled for its projection (toolkit layout). The height
// must be even: a row boundary then lies on the horizon, so no row mixes the sky with the
// below-horizon radiance (the step there is the sharpest feature of the ocean's sky).
struct SkyProjectionGrid {
  int width = 256;   // texels along phi
  int height = 128;  // texels along theta (even)
};

// The sky sampled at the grid's texel centres: width * height * 3 values, rows top first.
std::vector<double> sample_sky(const SkyRadianceFunction& sky, const SkyProjectionGrid& grid);

// Its SH coefficients to `order` (coefficient_count(order) * 3 values), by the toolkit's
// band-limited lat-long quadrature (sh::project_lat_long, sh::LatLongQuadrature::kBandLimited).
std::vector<double> project_sky(std::span<const double> samples, const SkyProjectionGrid& grid,
                                int order);

// ---- Irradiance (order 2) ------------------------------------------------------------------

// Nine RGB coefficients E_lm (l <= 2, toolkit index) of the irradiance E(n) = ∫ L(w) max(n.w, 0)
// dw as a function of the unit normal n: E(n) = sum_lm E_lm Y_lm(n), W m^-2 nm^-1.
using IrradianceSh = std::array<glm::dvec3, 9>;

// A_l, the clamped cosine's response (Funk-Hecke: E_lm = A_l L_lm): pi, 2 pi / 3, pi / 4 for
// l = 0, 1, 2; 0 for odd l > 1; for even l, 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) l! /
// (2^l ((l/2)!)^2) (Ramamoorthi & Hanrahan 2001, eq. 8; evaluated by a ratio recurrence, no
// factorials). Dimensionless (sr).
double clamped_cosine_response(int l);

// E_lm = A_l L_lm for l <= 2 from radiance coefficients of order >= 2 (3 channels).
IrradianceSh irradiance_sh(std::span<const double> radiance, int order);
// E(n) = sum_lm E_lm Y_lm(n) (n any non-zero vector, normalised here).
glm::dvec3 evaluate_irradiance(const IrradianceSh& irradiance, const glm::dvec3& normal);
// The same with every band l <= order of the clamped cosine (A_l as above): the irradiance that
// the sampled sky itself has, without the order-2 truncation (for measuring that truncation).
glm::dvec3 irradiance_to_order(std::span<const double> radiance, int order,
                               const glm::dvec3& normal);

// ---- Prefiltered glossy sky (SHRM, R&H 2002 sec. 3-4, appendix C) ---------------------------

// The reflection kernel of the ocean's eq. 22 for a view along the mean normal: the probability
// density (sr^-1) of the reflected direction r = 2 (v.f) f - v over the sphere, for facet slopes
// zeta with the isotropic Gaussian density p(zeta) = exp(-|zeta|^2 / 2 s) / (2 pi s) (s: the
// per-axis slope variance), as a function of theta_i = angle(r, C), C the mirror direction:
//     k(theta_i) = p(tan(theta_i / 2)) / (4 cos^4(theta_i / 2)),
// from dzeta = d omega_f / cos^3 theta_f and d omega_r = 4 (v.f) d omega_f with
// theta_f = theta_i / 2 and v.f = cos theta_f. It integrates to 1 over the sphere (every slope
// reflects somewhere; the eq. 22 kernel without the Heaviside, as the ocean paper drops it) and
// does not depend on theta_o or phi: a radially symmetric reparameterised BRDF (sec. 3.1), so
// one reflection map per roughness suffices (P = 0). Fresnel is NOT in it: the ocean keeps eq.
// 26's effective Fresnel outside (I_sky = F-bar L-bar, eq. 21), because a Fresnel-weighted Ross
// BRDF is non-analytic in theta_o at grazing and needs a high view order P (sh_brdf_test.cpp:
// (F, P) = (12, 24) for 1 % on Ross), i.e. (P + 1)^2 maps per roughness instead of one.
// slope_variance > 0 and finite.
sh::ReparameterizedBrdf slope_reflection_kernel(double slope_variance);

struct GlossySkySettings {
  // Per-axis slope variances of the maps, spaced geometrically from min to max (levels >= 2).
  // min: the unresolved variance of the default sea seen from a few hundred metres (waves
  // shorter than ~1 m; its whole spectrum holds ~0.015 per axis, wave_set.hpp), where the eq. 27
  // fetch's over-simplified footprint starts to matter; smaller variances (the near sea seen
  // from a ship) read the sharpest map, whose lobe (2 sqrt(min) = 2.6 degrees, std) then
  // over-blurs them: shrm is for rough seas seen from afar. max: above the roughest sea the
  // scene keys make (0.015 per axis at 60 m/s with lambda_max = 30 m).
  int levels = 8;
  double min_slope_variance = 5e-4;
  double max_slope_variance = 2e-2;
  // The tolerance of sh::choose_orders (sec. 5.1's energy fraction of the BRDF left out) for the
  // lighting order F of each level.
  double epsilon = 0.01;
  // The sky's samples for the projection: F + (the sky's own band limit) < height keeps the
  // quadrature exact for band-limited skies (spherical_harmonics.hpp); 256 rows serve F <= ~60.
  SkyProjectionGrid projection{512, 256};
  // The stored reflection maps (lat-long, the toolkit's layout): 1.4 degree texels, a quarter of
  // the sharpest lobe's width.
  int map_width = 256;
  int map_height = 128;
  // Gauss-Legendre nodes in cos theta_i for the kernel's coefficients (sh::BrdfGrid): nodes
  // ~pi / 1024 = 0.18 degrees apart in theta_i, so the sharpest lobe (2.6 degrees, std) spans
  // ~15 of them.
  int kernel_nodes = 1024;
};

// The per-axis slope variance of map `level` (0 .. levels - 1).
double glossy_sky_slope_variance(const GlossySkySettings& settings, int level);

struct GlossySkyLevel {
  double slope_variance = 0.0;  // per axis
  sh::OrderChoice orders;       // F (order_l) chosen for settings.epsilon; P = 0
};

// The kernels' coefficients of every level (they depend on the settings only, not on the sky:
// compute them once per GlossySkySettings).
struct GlossySkyKernels {
  std::vector<GlossySkyLevel> levels;
  std::vector<sh::BrdfCoefficients> coefficients;  // rho_l00, l <= the level's F (P = 0)
};

// Appendix C step 1 per level: tabulates slope_reflection_kernel on settings.kernel_nodes
// Gauss-Legendre nodes, chooses F with sh::choose_orders(table, settings.epsilon) (P = 0) and
// projects the kernel to that F.
GlossySkyKernels glossy_sky_kernels(const GlossySkySettings& settings);

struct GlossySky {
  int width = 0;
  int height = 0;
  int lighting_order = 0;  // the largest F of the levels: the order of the sky's projection
  std::vector<GlossySkyLevel> levels;
  // The reflection maps, level after level, each width x height RGBA (alpha 1), rows top first
  // (toolkit layout): texel (x, y) of level k holds L-bar(C) = ∫ k_s(angle(C, w)) L(w) dw for the
  // mirror direction C at its centre (eq. 22 at normal view), W m^-2 sr^-1 nm^-1.
  std::vector<float> rgba;
  // The sky's irradiance from the same projection: the order-2 SH (any normal, R&H 2001), and
  // E(up) on the horizontal sea with every band of the projection (l <= lighting_order), which
  // the ocean's L_sea uses: the order-2 truncation of E(up) is 6 to 14 % for a sea-level sky
  // (bright at the horizon, then the step to the below-horizon radiance), against under 1.5 %
  // at order 8 (docs/spherical_harmonics.md, "In the engine").
  IrradianceSh irradiance{};
  glm::dvec3 horizontal_irradiance{0.0};
};

// Samples `sky` on settings.projection, projects it once to the largest F of the kernels,
// convolves (eq. 5 for a radial kernel: B_lm = A_l L_lm) and reconstructs each level.
// `kernels` must come from glossy_sky_kernels(settings).
GlossySky glossy_sky(const SkyRadianceFunction& sky, const GlossySkySettings& settings,
                     const GlossySkyKernels& kernels);
// The same, computing the kernels first.
GlossySky glossy_sky(const SkyRadianceFunction& sky, const GlossySkySettings& settings = {});

}  // namespace thalassa::atmosphere
