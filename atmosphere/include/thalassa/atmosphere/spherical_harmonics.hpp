// thalassa — real spherical harmonics in double precision, to any order: evaluation, projection
// of latitude-longitude maps, reconstruction and rotation (issue 8, point 1). CPU only, no GL.
//
// Source paper: Ramamoorthi & Hanrahan, "Frequency space environment map rendering" (SIGGRAPH
// 2002; ../shared/papers/002_*), sec. 3-4 (notation, the rotation formula eq. 8), sec. 6.1 and
// appendix C (projection separating theta and phi). Every function below states its contract,
// its cost and the source of its formula; the tests (tests/unit/spherical_harmonics_test.cpp)
// check each against an identity, not against a printed formula.
//
// Conventions (used by every function here)
// -----------------------------------------
// * Directions: a direction d = (x, y, z) (any frame the caller chooses; SH do not care) has
//   polar angle theta measured from +z, in [0, pi], and azimuth phi measured from +x towards +y,
//   so d = (sin theta cos phi, sin theta sin phi, cos theta). Angles in radians.
// * Legendre functions: P̄_lm (l >= m >= 0) are the *fully normalised* ("4-pi normalised")
//   associated Legendre functions of geodesy, WITHOUT the Condon-Shortley phase (-1)^m:
//       P̄_lm(t) = sqrt((2 - δ_m0) (2l + 1) (l - m)! / (l + m)!) P_lm(t),
//       P_lm(t) = (1 - t^2)^(m/2) d^m/dt^m P_l(t)              (no (-1)^m),
//   so that ∫_{-1}^{1} P̄_lm(t)^2 dt = 2 (2 - δ_m0) and (1 / 4 pi) ∫ (P̄_lm(cos θ) trig(m φ))^2 dω
//   = 1 with trig(mφ) = cos mφ or sin mφ (1 for m = 0); the addition theorem reads
//   sum_{m=0}^{l} P̄_lm(t)^2 = 2l + 1 for every t.
//   Stored in a triangle at legendre_index(l, m) = l (l + 1) / 2 + m.
// * Real spherical harmonics (orthonormal over the unit sphere, no Condon-Shortley phase):
//       Y_l0       = P̄_l0(cos θ) / sqrt(4 pi)
//       Y_lm       = P̄_lm(cos θ) cos(m φ) / sqrt(4 pi)      for m > 0
//       Y_l,-m     = P̄_lm(cos θ) sin(m φ) / sqrt(4 pi)      for m > 0
//   (for m != 0 this is sqrt(2) times the real or imaginary part of the complex Y_lm without the
//   phase). Hence l = 1 is (Y_1,-1, Y_10, Y_11) = sqrt(3 / 4 pi) (y, z, x), the convention of
//   Ramamoorthi & Hanrahan 2001 ("An efficient representation for irradiance environment maps")
//   and of Ivanic & Ruedenberg 1996 (whose rotation recurrence we use). google/spherical-harmonics
//   and Sloan's "Stupid SH tricks" include the Condon-Shortley phase instead: their Y_lm equal
//   ours times (-1)^m.
// * Coefficient vectors: the coefficient of Y_lm is at index(l, m) = l^2 + l + m, so a vector of
//   order L (bands l = 0..L) has coefficient_count(L) = (L + 1)^2 entries. With several channels
//   (RGB radiance) the channels of one coefficient are adjacent, at
//   [index(l, m) * channels + c]. A function's coefficients are f_lm = ∫ f Y_lm dω (the basis is
//   real, so no conjugate).
// * Latitude-longitude (equirectangular) maps of width W and height H: row y (0 = top) covers
//   theta in [y pi / H, (y + 1) pi / H] (row 0 touches the +z pole), column x covers phi in
//   [2 pi x / W, 2 pi (x + 1) / W]; the sample is at the texel's centre, theta = (y + 1/2) pi / H,
//   phi = 2 pi (x + 1/2) / W. Rows top first, pixels left to right, `pixel_stride` values per
//   pixel of which the first `channels` are used (RGBA images: channels 3, pixel_stride 4).
//   A map in another frame (e.g. ENU, zenith up) is mapped to ours by the caller's choice of
//   axes: x, y, z above are whatever axes the caller's map uses for phi = 0, phi = pi / 2, pole.
//
// All functions are pure (no global state) and safe to call from several threads.
// Errors: a negative order, a buffer too small, a zero or non-finite direction, a map size
// below 1 or a matrix that is not a rotation throw std::invalid_argument (DESIGN sec. 4: a
// clear error, never NaN).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace thalassa::sh {

// ---- Indexing ------------------------------------------------------------------------------

// Index of Y_lm in a coefficient vector (|m| <= l).
constexpr std::size_t index(int l, int m) {
  return static_cast<std::size_t>(l) * static_cast<std::size_t>(l) +
         static_cast<std::size_t>(l + m);
}
// Number of coefficients of bands 0..order: (order + 1)^2.
constexpr std::size_t coefficient_count(int order) {
  return static_cast<std::size_t>(order + 1) * static_cast<std::size_t>(order + 1);
}
// Index of P̄_lm (0 <= m <= l) in a Legendre triangle.
constexpr std::size_t legendre_index(int l, int m) {
  return static_cast<std::size_t>(l) * static_cast<std::size_t>(l + 1) / 2 +
         static_cast<std::size_t>(m);
}
// Number of P̄_lm for l = 0..order: (order + 1)(order + 2) / 2.
constexpr std::size_t legendre_count(int order) {
  return static_cast<std::size_t>(order + 1) * static_cast<std::size_t>(order + 2) / 2;
}

using Vec3 = std::array<double, 3>;
// A 3x3 matrix, row-major: m[3 * row + column].
using Mat3 = std::array<double, 9>;

// The unit direction of polar angle theta and azimuth phi (radians; conventions above).
Vec3 direction(double theta, double phi);
// The direction of the centre of texel (x, y) of a width x height lat-long map.
Vec3 lat_long_direction(int width, int height, int x, int y);

// ---- Legendre functions and harmonics ---------------------------------------------------

// Writes P̄_lm(cos θ) for 0 <= m <= l <= order to out[legendre_index(l, m)] (out must hold
// legendre_count(order) values). cos_theta in [-1, 1]; sin_theta = sin θ >= 0 is passed
// separately because near the poles 1 - cos^2 loses it (cos(1e-9) == 1 in double): callers who
// have the direction should pass hypot(x, y) / |d|.
//
// Method: the "standard forward column" recurrences for fully normalised functions, Holmes &
// Featherstone 2002 (J. Geodesy 76: 279-299), eq. 11-13: the sectoral P̄_mm = u sqrt((2m + 1) /
// 2m) P̄_(m-1)(m-1) (P̄_11 = sqrt(3) u), then down each column
//     P̄_lm = a_lm t P̄_(l-1)m - b_lm P̄_(l-2)m,
//     a_lm = sqrt((2l - 1)(2l + 1) / ((l - m)(l + m))),
//     b_lm = sqrt((2l + 1)(l + m - 1)(l - m - 1) / ((l - m)(l + m)(2l - 3))),
// with t = cos θ, u = sin θ: no factorials, every step bounded. The sectoral values u^m underflow
// double long before the column values they seed become negligible (u = 0.37, m = 740 at l =
// 2000); instead of H&F's fixed 1e-280 scale we carry a separate binary exponent through the
// sectoral and the column recurrence until the values are back in range (the "X-numbers" of
// Fukushima 2012, J. Geodesy 86: 271-285), so every order works and a value underflows to 0
// only when it truly is below ~1e-300. Cost O(order^2). Accuracy (the tests check the addition
// theorem sum_m P̄_lm^2 = 2l + 1): relative errors ~1e-13 at l = 2000 away from the poles; at
// t = ±1 the recurrence has a double characteristic root and rounding grows like l^2 eps down
// the m = 0 column, 3e-11 at l = 1000 and 1e-10 at l = 2000 (in the sum of squares).
void legendre(int order, double cos_theta, double sin_theta, std::span<double> out);
// Same, with sin θ = sqrt((1 - t)(1 + t)) (loses precision within ~1e-8 rad of a pole).
void legendre(int order, double cos_theta, std::span<double> out);

// Writes Y_lm(d) for l = 0..order, |m| <= l to out[index(l, m)] (out must hold
// coefficient_count(order) values). d need not be unit length (it is normalised; at the poles
// phi is taken as 0, where all m != 0 harmonics vanish anyway). cos mφ and sin mφ come from
// the angle-addition recurrence on (cos φ, sin φ) = (x, y) / hypot(x, y). Cost O(order^2),
// no allocation.
void evaluate(int order, const Vec3& d, std::span<double> out);
// One harmonic Y_lm(d) (cost O(l^2): for tests and one-offs; use evaluate() for many).
double evaluate(int l, int m, const Vec3& d);

// f(d) = sum_lm coefficients[index(l, m) * channels + c] Y_lm(d) for each channel c, written to
// out[c] (out holds `channels` values). coefficients holds coefficient_count(order) * channels.
// Cost O(order^2 * channels), allocates one buffer of coefficient_count(order) doubles.
void reconstruct(std::span<const double> coefficients, int order, int channels, const Vec3& d,
                 std::span<double> out);
// The one-channel form.
double reconstruct(std::span<const double> coefficients, int order, const Vec3& d);

// ---- Latitude-longitude maps -----------------------------------------------------------

struct LatLongLayout {
  int width = 0;         // W: texels along phi (>= 1)
  int height = 0;        // H: texels along theta (>= 1)
  int channels = 1;      // channels projected or written per texel (>= 1)
  int pixel_stride = 0;  // values per texel in the buffer; 0 means `channels`
};

// How a row's samples are weighted in the theta integral ∫ g(θ) sin θ dθ of the projection.
enum class LatLongQuadrature {
  // Fejér's first rule in t = cos θ (the row centres θ_y = (y + 1/2) pi / H are exactly its
  // Chebyshev nodes): w_y = (2 / H) [1 - 2 sum_{j=1}^{floor(H/2)} cos(2 j θ_y) / (4 j^2 - 1)]
  // (Fejér 1933; Waldvogel 2006, BIT 46: 195-202; positive weights, sum 2). It integrates
  // polynomials in cos θ of degree < H exactly. The product Y_lm f of a map band-limited to
  // order F_map and a harmonic of order l <= F is such a polynomial of degree F_map + F, so the
  // projection is EXACT (to rounding) whenever F_map + F < H and F_map + F < W (the phi sum, a
  // uniform rule, is exact for frequencies below W). These weights are the texel's exact
  // solid-angle weight with the aliased part of sin θ removed (w_y is (pi / H) times the Fourier
  // series of |sin θ| = 2/pi - (4/pi) sum_j cos(2jθ) / (4j^2 - 1) cut after frequency H). The
  // default.
  kBandLimited,
  // Each texel's value times its exact solid angle, (cos θ_top - cos θ_bottom) 2 pi / W: the
  // sin θ weight integrated over the row's band rather than taken at its centre, i.e. the exact
  // integral of a map that is constant over each texel, with Y_lm taken at the texel centre
  // (what cmgen / cmft do). The weights sum to 4 pi exactly, so a constant map's l = 0
  // coefficient is exact, but a band-limited function of order l gets a relative error of about
  // (l^2 - 1)(pi / H)^2 / 24 (3e-3 at l = 10, H = 128: the midpoint sum of sin(kθ) over the
  // rows), and a constant leaks into the l > 0 zonal coefficients. Use it when texels are box
  // averages of something sharper than the grid (a sun disc), not for smooth maps.
  kTexelArea,
};

// Projects a lat-long map (values as laid out by `layout`, conventions above) onto Y_lm up to
// `order` (F): returns coefficient_count(F) * channels values, [index(l, m) * channels + c].
//
// Method (paper sec. 6.1 and appendix C, separating theta and phi):
//  1. for each row y and each m = 0..F, the real DFT in phi, C_m(y) = sum_x v(x, y) cos(m φ_x)
//     and S_m(y) = sum_x v(x, y) sin(m φ_x), as direct sums with an exact table of cos(pi k / W)
//     (k = m (2x + 1) mod 2W): O(W H F channels);
//  2. for each row, the Legendre column of P̄_lm(cos θ_y) and the theta quadrature
//     f_lm += w_y (2 pi / W) P̄_lm / sqrt(4 pi) {C_m or S_m}: O(H F^2 channels).
// Total O(F W H channels + F^2 H channels), i.e. the paper's O(F S^2) for S = W ~ H > F (not
// O(F^2 S^2)); an FFT in step 1 would give O(S^2 log S) but does not pay at F ~ 30 and needs no
// library here. Allocates O(F channels + W + H) doubles.
std::vector<double> project_lat_long(
    std::span<const float> values, const LatLongLayout& layout, int order,
    LatLongQuadrature quadrature = LatLongQuadrature::kBandLimited);
std::vector<double> project_lat_long(
    std::span<const double> values, const LatLongLayout& layout, int order,
    LatLongQuadrature quadrature = LatLongQuadrature::kBandLimited);

// Evaluates the expansion at every texel centre of a lat-long map: returns width * height *
// channels values (pixel_stride is ignored: the result is packed, rows top first). Separated like
// the projection: per row, a_m = sum_l f_lm P̄_lm / sqrt(4 pi) (O(F^2)), then per texel
// sum_m a_m cos mφ + b_m sin mφ (O(F)). Cost O(H F^2 channels + W H F channels).
std::vector<double> reconstruct_lat_long(std::span<const double> coefficients, int order,
                                         const LatLongLayout& layout);

// ---- Rotation ----------------------------------------------------------------------------

// The rotation of SH coefficient vectors by a 3x3 rotation matrix R (row-major, orthonormal,
// det +1, checked to 1e-6): apply() maps the coefficients f_lm of a function f to those of the
// rotated function g(d) = f(R^T d) (g is f carried along by R: g(R d) = f(d)). Each band l
// transforms by its own (2l + 1) x (2l + 1) orthogonal matrix D^l,
//     g_lm = sum_m' D^l_mm' f_lm',
// the real form of the paper's D matrices of eq. 8 (there written for rotations about y and z:
// D^l(R) = the real Wigner matrix). D^l(R1 R2) = D^l(R1) D^l(R2); D^l(identity) = identity.
// D^1 is R itself with axes reordered (y, z, x), and for R = rotation about z by alpha (counter-
// clockwise, x towards y) D^l mixes only m and -m: g_lm = cos(m α) f_lm - sin(m α) f_l,-m,
// g_l,-m = sin(m α) f_lm + cos(m α) f_l,-m (m > 0).
//
// Construction: the recurrence of Ivanic & Ruedenberg, "Rotation matrices for real spherical
// harmonics. Direct determination by recursion", J. Phys. Chem. 100: 6342-6347 (1996), with the
// corrections of J. Phys. Chem. A 102: 9099-9100 (1998): D^l from D^(l-1) and D^1, each entry a
// combination of at most six products, band by band. Cost O(order^3) time and memory
// (sum_l (2l + 1)^2 entries). Measured: orthogonal to 1e-14 at order 10, 1e-12 at order 50.
class Rotation {
 public:
  Rotation(const Mat3& r, int order);

  int order() const { return order_; }
  // D^l_mm' for |m|, |m'| <= l <= order.
  double operator()(int l, int m, int m_prime) const {
    const int n = 2 * l + 1;
    return matrices_[band_offset(l) + static_cast<std::size_t>((m + l) * n + (m_prime + l))];
  }
  // Band l as a row-major (2l + 1) x (2l + 1) matrix, entry [(m + l) (2l + 1) + (m' + l)].
  std::span<const double> band(int l) const;

  // out = D in, for coefficient vectors of coefficient_count(order()) * channels values laid out
  // as above. in and out may be the same buffer. Cost O(order^3 channels).
  void apply(std::span<const double> in, std::span<double> out, int channels = 1) const;
  // The same, returning the result.
  std::vector<double> apply(std::span<const double> in, int channels = 1) const;

 private:
  static std::size_t band_offset(int l) {
    // sum_{k < l} (2k + 1)^2 = l (4 l^2 - 1) / 3
    const auto n = static_cast<std::size_t>(l);
    return n * (4 * n * n - 1) / 3;
  }
  int order_ = 0;
  std::vector<double> matrices_;  // all bands, band l at band_offset(l)
};

}  // namespace thalassa::sh
