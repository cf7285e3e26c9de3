// thalassa — environment-map prefiltering: the choice of the spherical-harmonic orders F and P
// for a requested error (issue 8, point 4), the brute-force angular-domain prefilter that is the
// baseline, and the frequency-space route assembled from the toolkit (issue 8, point 5).
// CPU only, double precision, standard library only.
//
// Source paper: Ramamoorthi & Hanrahan, "Frequency space environment map rendering" (SIGGRAPH
// 2002; ../shared/papers/002_*): sec. 5.1 (the error as the fraction of energy left out), sec.
// 6.2-6.3 and appendix D (angular and frequency costs, the Phong support), sec. 7.4 (tables 4
// and 5), appendix B (what the error of the reflected light field means), appendix C (how F and
// P are reduced once the tolerance is met). Built on spherical_harmonics.hpp and sh_brdf.hpp,
// whose conventions (lat-long layout, reflection frame R_C, local views omega_o, rho-hat in
// sr^-1 with the cosine included, rho_lpq) are used unchanged. Tests:
// tests/unit/sh_prefilter_test.cpp; the tables: tests/bench/sh_prefilter_bench.cpp and
// docs/spherical_harmonics.md.
//
// Conventions
// -----------
// * Error, sec. 5.1 and appendix B: the fraction of a signal's energy (the integral of its square)
//   that an approximation misses. For the BRDF, the energy is
//     E = ∫∫ rho-hat(omega_i, omega_o)^2 d omega_i d omega_o
//       = sum_{l, p >= 0} sum_{|q| <= min(l, p)} rho_lp|q|^2      (Parseval, real basis: q != 0
//   counted twice, for +q and -q), in sr^-2, and the predicted error of orders (F, P) is
//     epsilon_rho(F, P) = 1 - E(F, P) / E,  E(F, P) the same sum for l <= F, p <= P.
//   The paper (sec. 5.1) uses epsilon_rho as a conservative estimate of the error of the reflected
//   light field B (fig. 6: "taking the minimum of lighting and BRDF errors is almost always
//   equivalent to using the BRDF error"). The *measured* error of a prefiltered map B' against
//   the exact B is the same kind of quantity, the fraction of B's energy in the residual:
//     epsilon_B = ∫ (B' - B)^2 / ∫ B^2
//   integrated over the reflection directions C (lat-long texel solid angles) and, for a 3D
//   BRDF, over the local views omega_o (weights given by the caller). It is a squared relative
//   L2 error: sqrt(epsilon_B) is the relative RMS error.
// * Maps are one channel (call once per colour channel), lat-long, toolkit layout; radiance in
//   any unit (the environment's), reflected radiance in the same unit.
//
// Errors: epsilon outside (0, 1) or not finite, negative orders, sizes below 1, a multi-channel
// layout where one channel is required, mismatched buffer sizes and empty BRDFs throw
// std::invalid_argument; a tolerance that the given coefficients cannot meet throws
// std::domain_error (compute them to higher orders: appendix C repeats step 1).
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "thalassa/atmosphere/sh_brdf.hpp"
#include "thalassa/atmosphere/spherical_harmonics.hpp"

namespace thalassa::sh {

// ---- Error analysis: orders for a tolerance (sec. 5.1, appendix C step 1) ------------------

// ∫∫ rho-hat^2 d omega_i d omega_o (sr^-2) by the table's own quadrature (Gauss-Legendre in
// cos theta_i and cos theta_o, the even midpoint rule in phi): the total that the coefficients'
// energies tend to (Parseval). Cost O(table size).
double brdf_energy(const BrdfTable& table);
// The energy of the coefficients up to orders (F, P) = (order_l, order_p) (sr^-2):
// sum_{l <= F} sum_{p <= P} (rho_lp0^2 + 2 sum_{q=1}^{min(l,p)} rho_lpq^2). The orders must not
// exceed rho's.
double brdf_energy(const BrdfCoefficients& rho, int order_l, int order_p);

// The orders chosen for a tolerance and what they leave out.
struct OrderChoice {
  int order_l = 0;               // F: the lighting order (bands l = 0..F)
  int order_p = 0;               // P: the view order (bands p = 0..P)
  double predicted_error = 0.0;  // epsilon_rho(F, P) = 1 - captured / total, <= the tolerance
  double captured_energy = 0.0;  // E(F, P), sr^-2
  double total_energy = 0.0;     // E, sr^-2
};

// Appendix C step 1's rule with sec. 5.1's error: starting from rho's orders (F0, P0), which must
// capture (1 - epsilon) of total_energy (else std::domain_error), the smallest P with
// E(F0, P) >= (1 - epsilon) E, then the smallest F with E(F, P) >= (1 - epsilon) E ("see how far
// P can be reduced ..., and then also reduce F as much as possible"). P is reduced first because
// each band of P multiplies the SHRM's size by (P + 1)^2 / P^2, F only its cost linearly.
// total_energy: E from brdf_energy(table) (or an analytic value, e.g. phong_energy); it must be
// >= the coefficients' own energy to within kEnergyMismatch (.cpp, 1e-6) relative, else they and
// it disagree (aliased coefficients, a different BRDF): std::invalid_argument.
// epsilon in (0, 1). Cost O(F0 P0^2) per trial order, O((F0 + P0) F0 P0^2) in all.
OrderChoice choose_orders(const BrdfCoefficients& rho, double total_energy, double epsilon);

// The whole of appendix C step 1 for a tabulated BRDF: rho_lpq at (F0, P0) = (initial_order_l,
// min(initial_order_p, the largest P the table resolves)), doubled until they capture
// (1 - epsilon) of brdf_energy(table), then choose_orders(). The table resolves l <
// theta_i_count and p < min(theta_o_count, phi_count): up to there the quadrature is exact for
// the products of two basis functions (sh_brdf.hpp, BrdfGrid), so the P̄_lq, P̄_pq and cos q phi
// are discretely orthonormal and the coefficients' energy never exceeds brdf_energy(table)
// (Bessel's inequality); beyond, they alias. At those last orders the discrete basis is
// complete, so they always capture the table's whole energy: a choice that needs the last l
// (or the last p, when the table resolves p > 0) is refused with std::domain_error (the table
// is too coarse for this tolerance: tabulate the BRDF on a finer grid).
OrderChoice choose_orders(const BrdfTable& table, double epsilon, int initial_order_l = 16,
                          int initial_order_p = 4);

// The normalised Phong BRDF's coefficients (sh_brdf.hpp, phong_brdf) in closed form:
// rho_l00 = sqrt(2l + 1) A_l with A_l = phong_response(l, s), rho_lpq = 0 for p > 0;
// l = 0..order_l, order_p = 0. Cost O(order_l^2) (phong_response is O(l)).
BrdfCoefficients phong_coefficients(double exponent, int order_l);
// Its energy E = 4 pi ∫ rho-hat^2 d omega_i = 2 (s + 1)^2 / (2 s + 1) (sr^-2): rho-hat does not
// depend on omega_o, whose sphere gives the 4 pi.
double phong_energy(double exponent);

// ---- The angular-domain baseline (sec. 6.2: a hemispherical integral per output texel) ------

// A radially symmetric BRDF: rho-hat as a function of cos theta_i = C.L alone (sr^-1, cosine
// included, sec. 6.3), e.g. (s + 1) / (2 pi) max(C.L, 0)^s.
using RadialBrdf = std::function<double(double cos_theta_i)>;
// The normalised Phong BRDF of sh_brdf.hpp's phong_brdf as a RadialBrdf (exponent s > 0).
RadialBrdf phong_radial_brdf(double exponent);

// Appendix D: the angle theta* about C (radians) outside which a Phong lobe of exponent s holds
// a fraction epsilon of its integral ∫ rho-hat d omega_i: cos theta* = epsilon^(1 / (s + 1)).
// The paper's angular timings (table 4) integrate only within theta*, with epsilon = 0.05.
double phong_support(double exponent, double epsilon);
// The same for any reparameterised BRDF at the local view angle theta_o (radians): the smallest
// theta* with ∫_{theta_i <= theta*} rho-hat d omega_i >= (1 - epsilon) ∫ rho-hat d omega_i,
// by a midpoint rule of kSupportThetaSteps x kSupportPhiSteps in (theta_i, phi) (.cpp); rounded
// up to its theta step (pi / kSupportThetaSteps). Returns pi for a BRDF that is 0 at theta_o.
double brdf_support(const ReparameterizedBrdf& brdf, double theta_o, double epsilon);

struct AngularOptions {
  int width = 128;     // output texels along beta (the reflection direction's azimuth)
  int height = 128;    // output texels along alpha (its polar angle)
  double support = 0;  // radians: only input texels whose centre lies within this angle of C
                       // are summed (phong_support, brdf_support); 0 (or >= pi) means all of
                       // them, the exact baseline
};

// Brute-force prefiltering of a one-channel lat-long environment (layout.channels must be 1;
// pixel_stride may skip values) by a radially symmetric BRDF: for every output texel centre C,
//   B(C) = sum_texels L_t rho-hat(C . omega_t) delta_omega_t,
//   delta_omega_t = (2 pi / W) (cos theta_top - cos theta_bottom)    (exact texel solid angle),
// the input texel taken as constant over its area and its BRDF value at its centre (the
// midpoint rule, second order in the texel size). Returns options.width * options.height
// values, rows top first. Cost O(W_support S_L^2) per output texel, W_support the fraction of the
// input within options.support (the paper's W of table 3): rows and, in each row, the azimuths
// outside the support are skipped, not tested.
std::vector<double> angular_prefilter(std::span<const double> environment,
                                      const LatLongLayout& layout, const RadialBrdf& brdf,
                                      const AngularOptions& options);
// The same for a 3D isotropic BRDF at one local view omega_o = direction(theta_o, phi_o) in the
// reflection frame (sh_brdf.hpp): for every C, V = R_C omega_o, N = (C + V) / |C + V| and
//   B(C; omega_o) = sum_texels L_t brdf(V_t, L_t) delta_omega_t,
// V_t and L_t in a tangent frame about N (brdf returns 0 for L below the surface). This is
// eq. 2 evaluated by brute force, the quantity the local SHRM represents (eq. 6); texels where
// V = -C (theta_o = pi: no normal mirrors V into C) get 0.
std::vector<double> angular_prefilter(std::span<const double> environment,
                                      const LatLongLayout& layout, const CosineWeightedBrdf& brdf,
                                      double theta_o, double phi_o, const AngularOptions& options);

// ---- The frequency-space route (appendix C steps 1-3) ----------------------------------------

// rho truncated to orders (order_l, order_p) (each at most rho's).
BrdfCoefficients truncate(const BrdfCoefficients& rho, int order_l, int order_p);

// The reflection map of a radially symmetric BRDF (rho.order_p() may be anything; only p = 0 is
// used) from lighting coefficients of order lighting_order: B_lm = A_l L_lm with
// A_l = rho_l00 / sqrt(2l + 1) (sh_brdf.hpp, the Funk-Hecke form of eq. 5), l <= F =
// min(lighting_order, rho.order_l()), then reconstruct_lat_long at width x height texels.
// This is appendix C's radially symmetric case: cost O(F^2 + F S_B^2).
std::vector<double> radial_reflection_map(std::span<const double> lighting, int lighting_order,
                                          const BrdfCoefficients& rho, int width, int height);

// One explicit reflection map from a local SHRM (appendix C, "conversion ... to explicit
// forms"): B(C; omega_o) = sum_pq B_pq(C) Y_pq(omega_o) at every texel of the map, for the local
// view omega_o = direction(theta_o, phi_o) in the reflection frame. width * height values, rows
// top first. Cost O(P^2) per texel.
std::vector<double> local_reflection_map(const ShrmMap& local, double theta_o, double phi_o);

// ---- Measured error -------------------------------------------------------------------------

// Accumulates epsilon_B = ∫ (approximation - reference)^2 / ∫ reference^2 over lat-long maps of
// reflection directions (weights: the texel's solid angle) and, through `weight`, over views.
class EnergyError {
 public:
  // Adds one pair of width x height maps (rows top first), weighted by weight >= 0 (e.g. the
  // solid angle of the view it was computed for).
  void add(std::span<const double> approximation, std::span<const double> reference, int width,
           int height, double weight = 1.0);
  double residual() const { return residual_; }  // ∫ (approximation - reference)^2
  double total() const { return total_; }        // ∫ reference^2
  // residual / total (0 when both are 0; infinity when only the reference is 0).
  double relative() const;

 private:
  double residual_ = 0.0;
  double total_ = 0.0;
};

}  // namespace thalassa::sh
