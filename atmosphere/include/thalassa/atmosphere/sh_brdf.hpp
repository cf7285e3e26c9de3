// thalassa — frequency-space environment lighting for isotropic BRDFs: BRDF coefficients
// rho_lpq, the convolution B_lmpq = Lambda_l L_lm rho_lpq, and spherical harmonic reflection maps
// (SHRMs), local, global and the single dynamic reflection map of a distant viewer (issue 8,
// points 2 and 3). CPU only, double precision, no GL; standard library only.
//
// Source paper: Ramamoorthi & Hanrahan, "Frequency space environment map rendering" (SIGGRAPH
// 2002; ../shared/papers/002_*): sec. 3 (eq. 1-3, the reparameterisation of sec. 3.1), sec. 4
// (eq. 5-8), sec. 6.3 (Phong), sec. 7.1 (eq. 11), sec. 7.5 (eq. 12), appendix A (eq. 13, 14),
// appendix C (steps 1-3). Built on thalassa/atmosphere/spherical_harmonics.hpp, whose
// conventions (real SH without the Condon-Shortley phase, index l^2 + l + m, fully normalised
// P̄_lm, lat-long layout, Rotation) are used throughout. Tests: tests/unit/sh_brdf_test.cpp.
//
// Conventions
// -----------
// * The reflection (reparameterised) frame, sec. 3.1. For a view direction V (unit, from the
//   surface toward the eye) and a surface normal N, the reflection vector is
//   C = 2 (N.V) N - V. Angles are measured in a frame whose z axis is C:
//     theta_i = angle(C, L)  (light),  theta_o = angle(C, V)  (view),  phi = phi_o - phi_i,
//   the azimuths taken about C. theta_o = 2 theta_v (theta_v the view's angle from N), so
//   theta_o in [0, pi) covers every view above the surface; conversely N = (C + V) / |C + V|.
//   The reparameterised BRDF is rho-hat(theta_i, theta_o, phi) = rho(V, L) max(N.L, 0) (the
//   paper's rho-hat = rho cos theta_i of eq. 2, with the cosine taken against the true normal),
//   in sr^-1. It is even in phi (isotropic, bilaterally symmetric BRDFs). The reflected light
//   field is eq. 2 re-centred on C:
//     B(C; omega_o) = ∫ L(R_C omega_i) rho-hat(theta_i, theta_o, phi) d omega_i     (eq. 2)
//   where omega_i, omega_o are local directions in the reflection frame and R_C maps the local
//   frame to the global one (below).
// * The local frame of a reflection direction C = direction(alpha, beta) (spherical_harmonics.hpp
//   angles: alpha the polar angle from +z, beta the azimuth) is R_C = Rz(beta) Ry(alpha) (the
//   paper's R_{alpha,beta}): its columns are (e_alpha, e_beta, C) with
//   e_alpha = (cos a cos b, cos a sin b, -sin a), e_beta = (-sin b, cos b, 0). At the poles
//   (sin alpha = 0) beta = 0. A local direction w is the global R_C w.
// * BRDF coefficients, appendix A eq. 13. The paper's complex expansion, rewritten with the
//   toolkit's fully normalised P̄_lq (its U_q f_lq f_pq equals P̄_lq P̄_pq / 4 pi, and the
//   Condon-Shortley phases cancel in the product), is
//     rho-hat(theta_i, theta_o, phi) = sum_{l >= 0} sum_{p >= 0} sum_{q=0}^{min(l,p)}
//         rho_lpq P̄_lq(cos theta_i) P̄_pq(cos theta_o) cos(q phi) / (4 pi),
//     rho_lpq = (1 / (2 (2 - δ_q0))) ∫_0^π ∫_0^π ∫_0^2π rho-hat P̄_lq(cos θ_i) P̄_pq(cos θ_o)
//               cos(q φ) sin θ_i sin θ_o dφ dθ_o dθ_i,
//   identical (same numbers) to the paper's eq. 13 with K = 2 pi f_lq f_pq sin sin cos q phi.
//   l: the lighting order (theta_i, the angle of the light from C); p: the view-dependence order
//   (theta_o) and q (0 <= q <= min(l, p)) its azimuthal index. In the real basis the kernel is
//     rho-hat = sum_lpq rho_lp|q| Y_lq(omega_i) Y_pq(omega_o),  q = -min(l,p)..min(l,p),
//   diagonal in q (isotropy), with rho_lp,-q = rho_lpq.
//   Identities (tested): rho_000 = (1 / 4 pi) ∫∫ rho-hat dω_i dω_o, and for a radially symmetric
//   BRDF (rho-hat a function of theta_i only, e.g. Phong) rho_lpq = 0 for p > 0 and
//   rho_000 = ∫ rho-hat dω_i, the albedo; its normalised response (sec. 6.3's Lambda_l rho_l of
//   the 1D convolution B_lm = Lambda_l rho_l L_lm) is rho_l00 / sqrt(2l + 1).
// * Convolution, eq. 5: B_lmpq = Lambda_l L_lm rho_lp|q|, Lambda_l = sqrt(4 pi / (2l + 1)), for
//   |q| <= min(l, p) (0 otherwise), L_lm the lighting's coefficients (real, toolkit convention).
// * Local SHRM, eq. 6 and 14:  B(C; omega_o) = sum_pq B_pq(C) Y_pq(omega_o) with
//     B_pq(C) = sum_l sum_m Lambda_l^-1 D^l_mq(R_C) B_lmpq,
//   D^l the toolkit's real rotation matrices (Rotation(R_C)), which is the paper's
//   D^l_mq(alpha) e^{I m beta} in real form. The derivation: L(R_C w) = sum_lm' (sum_m
//   D^l_mm'(R_C) L_lm) Y_lm'(w), then the kernel's expansion above.
// * Global SHRM, eq. 7 and 8: B~(C; V) = B(C; R_C^T V) = sum_pq B~_pq(C) Y_pq(V) with V global
//   and B~_p(C) = D^p(R_C) B_p(C) (band by band).
// * Dynamic reflection map, eq. 12: for a distant viewer in the global direction V,
//   B~(alpha, beta) = sum_pq B~_pq(alpha, beta) Y_pq(V): one 2D map, looked up by C.
// * SHRM maps are lat-long maps over C in the toolkit's layout: texel (x, y) of a W x H map has
//   alpha = (y + 1/2) pi / H, beta = 2 pi (x + 1/2) / W; coefficient (p, q) of texel (x, y) is
//   at [(y W + x) coefficient_count(P) + index(p, q)]. One channel: call once per colour channel.
// * Radiance in any unit (the lighting's); rho-hat in sr^-1; angles in radians.
//
// Errors: negative orders, grid sizes below 1, non-finite or zero directions, mismatched buffer
// sizes throw std::invalid_argument (DESIGN sec. 4).
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "thalassa/atmosphere/spherical_harmonics.hpp"

namespace thalassa::sh {

// Lambda_l = sqrt(4 pi / (2l + 1)) of eq. 5.
double convolution_constant(int l);

// ---- BRDFs ---------------------------------------------------------------------------------

// A reparameterised isotropic BRDF rho-hat(theta_i, theta_o, phi) in the reflection frame (see
// the conventions), sr^-1, cosine included; theta_i, theta_o in [0, pi], phi in [0, pi].
using ReparameterizedBrdf = std::function<double(double theta_i, double theta_o, double phi)>;

// An isotropic BRDF in the ordinary (normal) frame, cosine-weighted: rho(v, l) max(l_z, 0) in
// sr^-1, for unit v (toward the eye) and l (toward the light) in a tangent frame whose z axis is
// the surface normal (x and y arbitrary: the caller promises isotropy). Must return 0 for
// l_z <= 0.
using CosineWeightedBrdf = std::function<double(const Vec3& view, const Vec3& light)>;

// The reparameterisation of sec. 3.1: rho-hat(theta_i, theta_o, phi) = brdf(V, L) with
// C = (0, 0, 1), L = (sin theta_i, 0, cos theta_i), V = (sin theta_o cos phi,
// sin theta_o sin phi, cos theta_o) in the reflection frame and N = (C + V) / |C + V|, both
// expressed in a tangent frame about N. 0 where L is below the surface (N.L <= 0) and at
// theta_o = pi (V = -C: no normal reflects V into C).
ReparameterizedBrdf reparameterize_by_reflection(CosineWeightedBrdf brdf);

// The normalised Phong BRDF in the reflection parameterisation, sec. 6.3:
//   rho-hat = (s + 1) / (2 pi) max(cos theta_i, 0)^s,
// independent of theta_o and phi (radially symmetric, P = 0 suffices); albedo exactly 1 (the
// integral over the hemisphere about C). exponent s > 0.
ReparameterizedBrdf phong_brdf(double exponent);

// The exact normalised response of phong_brdf: A_l = Lambda_l rho_l00 / sqrt(4 pi)
// = rho_l00 / sqrt(2l + 1) = (s + 1) ∫_0^1 t^s P_l(t) dt (P_l the Legendre polynomial), from
// Gradshteyn & Ryzhik 7.126.2 as the recurrence A_0 = 1, A_1 = (s + 1) / (s + 2),
// A_l = A_{l-2} (s - l + 2) / (s + l + 1). Sec. 6.3 approximates it by exp(-l^2 / 2s); the
// recurrence shows log A_l ≈ -l (l + 1) / 2s for l << s.
double phong_response(int l, double exponent);

// The simplified microfacet BRDF of eq. 11, cosine-weighted (the paper's rho-hat):
//   rho(v, l) cos theta_l = exp(-(theta_h / sigma)^2) / (4 pi sigma^2)  for l_z > 0 and v_z >= 0,
//   0 otherwise, theta_h = acos(N.H), H = (v + l) / |v + l|.
// The normalisation gives albedo -> 1 at normal view as sigma -> 0 (the lobe in L has
// d omega_L = 4 (V.H) d omega_H). sigma > 0 (radians).
CosineWeightedBrdf microfacet_brdf(double sigma);

// ---- BRDF tables and coefficients (appendix C, step 1) -------------------------------------

// The grid on which a reparameterised BRDF is tabulated: Gauss-Legendre nodes in cos theta_i
// (theta_i_count of them) and in cos theta_o (theta_o_count), and the midpoints
// phi_k = (k + 1/2) pi / phi_count of [0, pi]. These are the quadrature nodes of eq. 13's
// integrals: Gauss-Legendre integrates polynomials in cos theta of degree < 2 n exactly; the
// midpoint rule, through the even extension of rho-hat to [0, 2 pi), is the trapezoid rule of
// 2 phi_count points, exact for cos(k phi) with k < 2 phi_count. (The paper tabulates on an
// equally spaced grid; Gauss nodes make smooth BRDFs converge spectrally.) A BRDF that is
// smooth in theta_i needs theta_i_count > (F + its own degree) / 2; a Phong lobe of exponent s
// needs about (s + F) / 2.
struct BrdfGrid {
  int theta_i_count = 128;
  int theta_o_count = 32;
  int phi_count = 32;
};

// rho-hat sampled on a BrdfGrid: values[(i theta_o_count + j) phi_count + k]. Fill it with
// tabulate(), or set values() at the nodes theta_i(i), theta_o(j), phi(k) from measurements.
class BrdfTable {
 public:
  explicit BrdfTable(const BrdfGrid& grid);

  const BrdfGrid& grid() const { return grid_; }
  double theta_i(int i) const;  // radians
  double theta_o(int j) const;
  double phi(int k) const;
  // cos of the nodes and their Gauss-Legendre weights (the weights sum to 2).
  std::span<const double> cos_theta_i() const { return cos_i_; }
  std::span<const double> cos_theta_o() const { return cos_o_; }
  std::span<const double> weights_theta_i() const { return weight_i_; }
  std::span<const double> weights_theta_o() const { return weight_o_; }

  double& at(int i, int j, int k) { return values_[offset(i, j, k)]; }
  double at(int i, int j, int k) const { return values_[offset(i, j, k)]; }
  std::span<double> values() { return values_; }
  std::span<const double> values() const { return values_; }

 private:
  std::size_t offset(int i, int j, int k) const {
    return (static_cast<std::size_t>(i) * static_cast<std::size_t>(grid_.theta_o_count) +
            static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(grid_.phi_count) +
           static_cast<std::size_t>(k);
  }
  BrdfGrid grid_;
  std::vector<double> cos_i_, weight_i_, cos_o_, weight_o_;
  std::vector<double> values_;
};

// rho-hat evaluated at every node of the grid (theta_i_count * theta_o_count * phi_count calls).
BrdfTable tabulate(const ReparameterizedBrdf& brdf, const BrdfGrid& grid);

// The coefficients rho_lpq for l = 0..order_l (F), p = 0..order_p (P), q = 0..min(l, p).
class BrdfCoefficients {
 public:
  BrdfCoefficients(int order_l, int order_p);
  int order_l() const { return order_l_; }
  int order_p() const { return order_p_; }
  // rho_lp|q|; 0 when |q| > min(l, p). l <= order_l, p <= order_p.
  double operator()(int l, int p, int q) const;
  double& at(int l, int p, int q);  // 0 <= q <= min(l, p)

 private:
  std::size_t offset(int l, int p, int q) const {
    const auto n = static_cast<std::size_t>(order_p_ + 1);
    return (static_cast<std::size_t>(l) * n + static_cast<std::size_t>(p)) * n +
           static_cast<std::size_t>(q);
  }
  int order_l_ = 0;
  int order_p_ = 0;
  std::vector<double> values_;
};

// Appendix C step 1, the three separated sums of eq. 13 by the grid's quadrature:
//   rho_q(θ_i, θ_o) = 2 sum_k (pi / phi_count) rho-hat cos(q φ_k)             (= ∫_0^2π ... dφ)
//   rho_pq(θ_i)     = sum_j w_j rho_q(θ_i, θ_o,j) P̄_pq(cos θ_o,j)
//   rho_lpq         = (1 / (2 (2 - δ_q0))) sum_i w_i rho_pq(θ_i,i) P̄_lq(cos θ_i,i).
// Cost O(P S T^2 + P^2 S T + F P^2 S) for S = theta_i_count, T ~ theta_o_count ~ phi_count.
BrdfCoefficients project_brdf(const BrdfTable& table, int order_l, int order_p);
// tabulate() then project_brdf().
BrdfCoefficients project_brdf(const ReparameterizedBrdf& brdf, const BrdfGrid& grid, int order_l,
                              int order_p);

// ---- Convolution and SHRMs ------------------------------------------------------------------

// The reflected light field's coefficients B_lmpq (eq. 5), l = 0..order_l, |m| <= l,
// p = 0..order_p, |q| <= p, at [index(l, m) coefficient_count(order_p) + index(p, q)].
class ReflectedLightField {
 public:
  ReflectedLightField(int order_l, int order_p);
  int order_l() const { return order_l_; }
  int order_p() const { return order_p_; }
  double operator()(int l, int m, int p, int q) const {
    return values_[index(l, m) * coefficient_count(order_p_) + index(p, q)];
  }
  double& at(int l, int m, int p, int q) {
    return values_[index(l, m) * coefficient_count(order_p_) + index(p, q)];
  }

 private:
  int order_l_ = 0;
  int order_p_ = 0;
  std::vector<double> values_;
};

// Eq. 5: B_lmpq = Lambda_l L_lm rho_lp|q| for one channel of lighting coefficients
// (coefficient_count(lighting_order) values, toolkit layout). The result has order_l =
// min(lighting_order, brdf.order_l()) and order_p = brdf.order_p(). Cost O(F^2 P^2).
ReflectedLightField convolve(std::span<const double> lighting, int lighting_order,
                             const BrdfCoefficients& brdf);

// R_C = Rz(beta) Ry(alpha) for the unit (or any non-zero) direction c = direction(alpha, beta);
// beta = atan2(c_y, c_x) (0 at the poles).
Mat3 reflection_frame(const Vec3& c);

// The local SHRM at one reflection direction C (eq. 14): coefficient_count(order_p) values
// B_pq(C), toolkit index(p, q). Cost O(F^3) (one Rotation) + O(F^2 P^2).
std::vector<double> local_shrm(const ReflectedLightField& field, const Vec3& reflection);
// The global SHRM at C from its local SHRM (eq. 8): B~_p = D^p(R_C) B_p. Cost O(P^3).
std::vector<double> global_shrm(std::span<const double> local, int order_p, const Vec3& reflection);
// sum_pq coefficients[index(p, q)] Y_pq(direction): eq. 6 with a local omega_o (local SHRM) or
// eq. 7 / 12 with a global view V (global SHRM).
double evaluate_shrm(std::span<const double> coefficients, int order_p, const Vec3& direction);

// The reflected radiance toward the unit view V (global, from the surface to the eye) of a
// surface of unit normal N (global), N.V > 0: C = 2 (N.V) N - V, omega_o = R_C^T V, and
// eq. 6 from local_shrm(field, C). This is the renderer's evaluation, for tests and one-offs.
double reflected_radiance(const ReflectedLightField& field, const Vec3& normal, const Vec3& view);

// An SHRM over a lat-long map of reflection directions (layout in the conventions).
struct ShrmMap {
  int width = 0;
  int height = 0;
  int order_p = 0;
  bool global = false;  // false: B_pq(alpha, beta) of eq. 6; true: B~_pq of eq. 7
  std::vector<double> coefficients;
  std::span<const double> texel(int x, int y) const;
};

// The local SHRM at every texel centre, separated in alpha and beta (appendix C step 3):
// per row, d^l(alpha) = D^l(Ry(alpha)) and B_m'pq(alpha) = sum_l Lambda_l^-1 d^l_m'q B_lm'pq
// (cos and sin parts), O(F^3 + F^2 P^2) per row; per texel the sum over m' with cos m'beta,
// sin m'beta, O(F P^2). Equals local_shrm() at the texel's direction (tested to rounding).
ShrmMap local_shrm_map(const ReflectedLightField& field, int width, int height);
// Eq. 8 at every texel: B~_p = Dz(beta) d^p(alpha) B_p. Cost O(P^3) per texel.
ShrmMap global_shrm_map(const ShrmMap& local);
// Eq. 12: the single dynamic reflection map of a distant viewer in the global unit direction
// view, width * height values, rows top first: sum_pq B~_pq(texel) Y_pq(view).
std::vector<double> dynamic_reflection_map(const ShrmMap& global, const Vec3& view);

}  // namespace thalassa::sh
