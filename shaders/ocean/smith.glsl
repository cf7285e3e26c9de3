// Smith's masking function Lambda for Gaussian slopes, and the complementary error function it
// needs, for the Ross et al. BRDF (ocean/ross_brdf.glsl). CPU reference:
// ocean/src/ross_brdf_reference.hpp; tests: tests/unit/ross_brdf_test.cpp.
//
// Smith 1967 ("Geometrical shadowing of a random rough surface", IEEE Trans. Antennas Propag.
// 15(5), 668-671): a facet is seen from a direction w (zenith angle theta from the mean normal)
// unless the surface rises above the ray beyond it. For uncorrelated Gaussian heights and slopes,
// Lambda is the mean excess slope beyond the ray's, per unit ray slope mu = cot theta:
//   Lambda(theta) = (1 / mu) integral_mu^inf (q - mu) P(q) dq,
// with P the pdf of the slope q along w's azimuth: Gaussian of variance sigma_w^2 (the slope
// variance in that azimuth, Bruneton et al. 2010 eq. 25). With a = mu / sqrt(2 sigma_w^2) the
// Gaussian integrals give (Bruneton, Neyret & Holzschuch 2010, eq. 8)
//   Lambda(a) = (exp(-a^2) - a sqrt(pi) erfc(a)) / (2 a sqrt(pi)),
//   a = cot theta / sqrt(2 sigma_w^2) = cos theta / (sqrt(2 sigma_w^2) sin theta)   (eq. 9,
// corrected: see ross_brdf.glsl). Everything here is written in terms of a, or of cos theta and
// the "sigma sin" s = sqrt(2 sigma_w^2) sin theta (dimensionless), a = cos theta / s, which is
// finite at the zenith (s = 0) and at the horizon (cos theta = 0).
//
// The same integral gives the identity behind eq. 10-11 (the visible-slope distribution
// integrates to 1), checked numerically by the tests:
//   integral max(0, w.f) / f_z p(zeta) d^2 zeta = integral (cos theta - sin theta q)_+ P(q) dq
//                                               = cos theta (1 + Lambda),
// the area of the facets facing w, projected onto the plane normal to w, per unit horizontal
// area ("facing area", OceanSmithFacingArea).

#ifndef THALASSA_OCEAN_SMITH_GLSL
#define THALASSA_OCEAN_SMITH_GLSL

#include "common/definitions.glsl"

// Abramowitz & Stegun (1964), Handbook of Mathematical Functions, 7.1.26 (from Hastings 1955):
//   erfc(x) = t (a1 + t (a2 + t (a3 + t (a4 + t a5)))) exp(-x^2) + eps(x),  t = 1 / (1 + p x),
// |eps(x)| <= 1.5e-7 for x >= 0. Dimensionless.
const Number ERFC_AS_7_1_26_P = 0.3275911;
const Number ERFC_AS_7_1_26_A1 = 0.254829592;
const Number ERFC_AS_7_1_26_A2 = -0.284496736;
const Number ERFC_AS_7_1_26_A3 = 1.421413741;
const Number ERFC_AS_7_1_26_A4 = -1.453152027;
const Number ERFC_AS_7_1_26_A5 = 1.061405429;

// Lambda(a) is evaluated in four ranges. Writing Lambda = exp(-a^2) g(a) / 2 with
// g(a) = 1 / (a sqrt(pi)) - erfcx(a) and erfcx(a) = exp(a^2) erfc(a) (the exp(-a^2) of both
// terms factored out, so nothing underflows before the product). The printed form
// (exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2 is never evaluated: its two terms agree to a
// relative 1 / (2 a^2) for large a, so it keeps only the digits of erfc beyond that (with A&S
// 7.1.26's absolute error of 1.5e-7 it is off by 3 % at a = 3 and by a factor 60 at a = 4;
// tests/unit/ocean_numerics_test.cpp measures it). Each form below has no such cancellation:
// - a < OCEAN_SMITH_SPLIT_A: erfcx from A&S 7.1.26's polynomial. Its absolute error on erfc,
//   1.5e-7, is 7.5e-8 on Lambda, and Lambda >= Lambda(1.2) = 0.0109 here: relative error
//   <= 7e-6 (measured against mpmath on a 0.02 grid: 2.6e-6). Toward a = 0 the first term of g,
//   1 / (a sqrt(pi)), dominates and the relative error falls as a. Above the split the
//   polynomial is useless for Lambda: the cancellation in g grows as 2 a^2 and the polynomial's
//   relative error on erfcx grows to 38 % as a -> inf (t P(t) -> a1 / (p a) = 0.778 / a instead
//   of 0.564 / a).
// - OCEAN_SMITH_SPLIT_A <= a < OCEAN_SMITH_ASYMPTOTIC_A: Laplace's continued fraction
//   erfcx(a) = (1 / sqrt(pi)) / (a + (1/2) / (a + (2/2) / (a + (3/2) / (a + ...)))) (A&S 7.1.14).
//   With r = (1/2) / (a + (2/2) / (a + ...)) (its tail, all terms positive),
//   g = (1 / a - 1 / (a + r)) / sqrt(pi) = r / (sqrt(pi) a (a + r)): no cancellation at all.
//   Truncated after OCEAN_SMITH_CONTINUED_FRACTION_TERMS terms (the last denominator's tail set
//   to 0), its relative error is 3.1e-6 at a = 1.2, 1.4e-7 at 2, 4e-13 at 4 (mpmath).
// - OCEAN_SMITH_ASYMPTOTIC_A <= a < OCEAN_SMITH_MAX_A: the asymptotic series of erfcx (A&S
//   7.1.23) with the leading 1 / (a sqrt(pi)) cancelled analytically, u = 1 / (2 a^2):
//   g = u / (a sqrt(pi)) sum_m (-1)^m (2m + 1)!! u^m,
//   Lambda = exp(-a^2) / (4 sqrt(pi) a^3) (1 - 3 u + 15 u^2 - 105 u^3 + ...),
//   an alternating sum whose terms fall by (2m + 3) u <= 21 / 72 each up to the tenth and whose
//   first correction is 3 u <= 4 %: it loses a few ulps at most, not 2 a^2 of them. Truncated
//   after 10 terms, the remainder is below the first term left out, 13749310575 u^10 = 3.7e-9
//   at a = 6 (the series of erfc is enveloping, A&S 7.1.24). Lambda used to be set to 0 here (it
//   is below 1.5e-19 and only ever added to 1); it now keeps its relative accuracy, at the cost
//   of an exp and ten multiply-adds, no loop.
// - a >= OCEAN_SMITH_MAX_A: Lambda = 0, its correctly rounded value in double: Lambda(28) =
//   exp(-784) / (4 sqrt(pi) 28^3) = 1e-345, below the smallest subnormal double (4.9e-324). (In
//   float exp(-a^2) underflows from a = 9.4 on, so the GPU returns 0 there already.) It also
//   covers the zenith (sin theta = 0, a = inf) without a division by 0.
//   The worst relative error over the four ranges, measured by
//   tests/unit/ocean_numerics_test.cpp against long double on a log grid from a = 1e-4 to 1e4:
//   3.1e-6, at the split (docs/numerics.md).
// - a < OCEAN_SMITH_MIN_A (grazing, cot theta < 1e-9 sqrt(2 sigma_w^2)): a is raised to it, so
//   that Lambda <= 1 / (2 sqrt(pi) 1e-9) = 2.8e8 stays finite (also in single precision). Callers
//   that need cos theta (1 + Lambda) at the horizon use OceanSmithFacingArea, which is exact
//   there.
const Number OCEAN_SMITH_SPLIT_A = 1.2;
const int OCEAN_SMITH_CONTINUED_FRACTION_TERMS = 24;
const Number OCEAN_SMITH_ASYMPTOTIC_A = 6.0;
const Number OCEAN_SMITH_MAX_A = 28.0;
const Number OCEAN_SMITH_MIN_A = 1.0e-9;

// exp(x^2) erfc(x) (dimensionless) for x >= 0, from A&S 7.1.26's polynomial: accurate only in
// the sense that its product with exp(-x^2) is erfc(x) within 1.5e-7 (see ERFC_AS_7_1_26_P).
Number OceanScaledErfcPolynomial(IN(Number) x) {
  Number t = 1.0 / (1.0 + ERFC_AS_7_1_26_P * x);
  return t * (ERFC_AS_7_1_26_A1 + t * (ERFC_AS_7_1_26_A2 + t * (ERFC_AS_7_1_26_A3 +
         t * (ERFC_AS_7_1_26_A4 + t * ERFC_AS_7_1_26_A5))));
}

// Complementary error function (GLSL has none), dimensionless, absolute error <= 1.5e-7:
// A&S 7.1.26 for x >= 0 and erfc(x) = 2 - erfc(-x) below.
Number OceanErfc(IN(Number) x) {
  Number abs_x = abs(x);
  Number value = exp(-abs_x * abs_x) * OceanScaledErfcPolynomial(abs_x);
  return x < 0.0 ? 2.0 - value : value;
}

// g(a) = 1 / (a sqrt(pi)) - exp(a^2) erfc(a) = 2 exp(a^2) Lambda(a), for
// OCEAN_SMITH_SPLIT_A <= a < OCEAN_SMITH_ASYMPTOTIC_A, from the continued fraction's tail r (see
// OCEAN_SMITH_SPLIT_A), evaluated from its last term up.
Number OceanSmithScaledLambdaTail(IN(Number) a) {
  Number tail = 0.0;
  for (int k = OCEAN_SMITH_CONTINUED_FRACTION_TERMS; k >= 1; --k) {
    tail = 0.5 * Number(k) / (a + tail);
  }
  return tail / (sqrt(PI) * a * (a + tail));
}

// g(a) = 2 exp(a^2) Lambda(a) for a >= OCEAN_SMITH_ASYMPTOTIC_A, from the asymptotic series of
// erfcx with its leading term cancelled analytically (see OCEAN_SMITH_SPLIT_A): u = 1 / (2 a^2),
// g = u / (a sqrt(pi)) (1 - 3 u + 15 u^2 - ... - 654729075 u^9), the coefficients (2m + 1)!!,
// summed by Horner's rule (every partial sum is positive and close to its first term).
Number OceanSmithScaledLambdaAsymptotic(IN(Number) a) {
  Number u = 0.5 / (a * a);
  Number series = 1.0 - u * (3.0 - u * (15.0 - u * (105.0 - u * (945.0 - u * (10395.0 -
                  u * (135135.0 - u * (2027025.0 - u * (34459425.0 - u * 654729075.0))))))));
  return u * series / (sqrt(PI) * a);
}

// g(a) = 2 exp(a^2) Lambda(a) (dimensionless) for OCEAN_SMITH_MIN_A <= a < OCEAN_SMITH_MAX_A:
// the polynomial below the split, the continued fraction above, the asymptotic series from
// OCEAN_SMITH_ASYMPTOTIC_A on.
Number OceanSmithScaledLambda(IN(Number) a) {
  if (a < OCEAN_SMITH_SPLIT_A) {
    return 1.0 / (a * sqrt(PI)) - OceanScaledErfcPolynomial(a);
  }
  return a < OCEAN_SMITH_ASYMPTOTIC_A ? OceanSmithScaledLambdaTail(a) :
                                        OceanSmithScaledLambdaAsymptotic(a);
}

// a = cos theta / sigma_sin (dimensionless, eq. 9 corrected), for cos theta = cos_theta (clamped
// to [0, 1]) and sigma_sin = sqrt(2 sigma_w^2) sin theta >= 0, held in [OCEAN_SMITH_MIN_A,
// OCEAN_SMITH_MAX_A] without ever dividing by 0: OCEAN_SMITH_MAX_A (Lambda = 0) at the zenith
// and wherever Lambda < 1e-345, OCEAN_SMITH_MIN_A at the horizon.
Number OceanSmithA(IN(Number) cos_theta, IN(Number) sigma_sin) {
  Number cos_t = clamp(cos_theta, 0.0, 1.0);
  if (cos_t >= OCEAN_SMITH_MAX_A * sigma_sin) {
    return OCEAN_SMITH_MAX_A;
  }
  return max(cos_t / sigma_sin, OCEAN_SMITH_MIN_A);  // sigma_sin > 0 here.
}

// Smith's Lambda(a) (dimensionless, Bruneton et al. 2010 eq. 8) for a >= 0: 0 for
// a >= OCEAN_SMITH_MAX_A (the zenith; there Lambda < 1e-345), at most 2.8e8 (a raised to
// OCEAN_SMITH_MIN_A) toward the horizon, relative error <= 3e-6 wherever the result is a normal
// double (see OCEAN_SMITH_SPLIT_A).
Number OceanSmithLambda(IN(Number) a) {
  if (a >= OCEAN_SMITH_MAX_A) {
    return 0.0;
  }
  Number a_clamped = max(a, OCEAN_SMITH_MIN_A);
  return 0.5 * exp(-a_clamped * a_clamped) * OceanSmithScaledLambda(a_clamped);
}

// cos theta Lambda(theta) (dimensionless), a = cos theta / sigma_sin, for cos_theta (clamped to
// [0, 1]) and sigma_sin = sqrt(2 sigma_w^2) sin theta > 0 where cos theta < OCEAN_SMITH_MAX_A
// sigma_sin. Finite and exact at the horizon, where it is sigma_sin / (2 sqrt(pi)): below
// OCEAN_SMITH_SPLIT_A it is written exp(-a^2) (sigma_sin / sqrt(pi) - cos theta erfcx(a)) / 2,
// using cos theta / a = sigma_sin, so no 0 * inf appears.
Number OceanSmithCosLambda(IN(Number) cos_theta, IN(Number) sigma_sin) {
  Number cos_t = clamp(cos_theta, 0.0, 1.0);
  if (cos_t >= OCEAN_SMITH_MAX_A * sigma_sin) {
    return 0.0;
  }
  Number a = cos_t / sigma_sin;  // sigma_sin > 0 here.
  Number cos_lambda_scaled = a < OCEAN_SMITH_SPLIT_A ?
      sigma_sin / sqrt(PI) - cos_t * OceanScaledErfcPolynomial(a) :
      cos_t * OceanSmithScaledLambda(a);
  return 0.5 * exp(-a * a) * cos_lambda_scaled;
}

// cos theta (1 + Lambda(theta)) (dimensionless): the area of the facets facing a direction of
// cos theta = cos_theta (clamped to [0, 1]), projected onto the plane normal to it, per unit
// horizontal area (see the top of the file); sigma_sin as for OceanSmithCosLambda. Positive
// wherever sigma_sin > 0: at least max(cos theta, sigma_sin / (2 sqrt(pi))).
Number OceanSmithFacingArea(IN(Number) cos_theta, IN(Number) sigma_sin) {
  return clamp(cos_theta, 0.0, 1.0) + OceanSmithCosLambda(cos_theta, sigma_sin);
}

#endif  // THALASSA_OCEAN_SMITH_GLSL
