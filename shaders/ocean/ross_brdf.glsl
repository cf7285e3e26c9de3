// The Ross et al. ocean BRDF and the lighting terms built on it, as used by Bruneton, Neyret &
// Holzschuch 2010, "Real-time realistic ocean lighting using seamless transitions from geometry
// to BRDF", Computer Graphics Forum 29(2) (../shared/papers/000_911981a54ad14c3e.txt), sections
// 4 and 5, eq. 5-27 and Algorithm 5.1; after Ross, Dion & Potvin 2005, "Detailed analytical
// approach to the Gaussian surface bidirectional reflectance distribution function
// specular component applied to the sea surface", JOSA A 22(11), 2442-2453 ([RDP05]).
// CPU reference: ocean/src/ross_brdf_reference.hpp; identity tests: tests/unit/ross_brdf_test.cpp;
// the error of the effective Fresnel fit: docs/ocean_fresnel.md.
//
// FRAME. Unless a function says otherwise, vectors are in the TANGENT FRAME of the mean surface
// (Algorithm 5.1's t_x, t_y, n): x along the wind (the axis of slope variance sigma_x^2), y
// across it (sigma_y^2), z the mean normal n. Directions are unit vectors pointing away from the
// surface: v toward the eye, l toward the light, so cos theta_v = v.z. OceanToTangentFrame takes
// a world (or camera-relative) vector into this frame. Slopes zeta = (zeta_x, zeta_y) =
// (dz/dx, dz/dy) of a facet are dimensionless; a facet of slopes zeta has the unit normal
//   f(zeta) = (-zeta_x, -zeta_y, 1) / sqrt(1 + |zeta|^2)                            (eq. 6)
// (OceanFacetNormal). Slope variances sigma_x^2, sigma_y^2 are dimensionless PER-AXIS variances
// (eq. 4, 7), passed as a vec2 slope_variance = (sigma_x^2, sigma_y^2); Cox & Munk's total mean
// square slope is their sum. BRDFs are in sr^-1, everything else here is dimensionless.
//
// THE MODEL (sec. 4). Slopes are Gaussian (eq. 7, OceanSlopePdf). The probability density, per
// unit slope area, of seeing from v a facet of slopes zeta that is also lit from l is (eq. 5,
// OceanVisibleSlopePdf)
//   q_vn(zeta, v, l) = p(zeta) max(v.f, 0) H(l.f) / ((1 + Lambda(a_v) + Lambda(a_l)) f_z cos theta_v)
// with Smith's Lambda (eq. 8, ocean/smith.glsl). Without a light (eq. 10, OceanVisibleSlopePdfE)
//   q_vn^e(zeta, v) = p(zeta) max(v.f, 0) / ((1 + Lambda(a_v)) f_z cos theta_v),
// which integrates to 1 over the slope plane (eq. 11): that is the identity the tests check,
// because max(v.f, 0) / f_z = (cos theta_v - v_x zeta_x - v_y zeta_y)_+ and its Gaussian average
// is cos theta_v (1 + Lambda(a_v)) exactly when a_v is right (ocean/smith.glsl, top). Note
// max(v.f, 0) / f_z: the division by f_z cancels the normalisation of f, so q_vn is evaluated
// without any square root.
//
// TYPO 1, eq. 9. The paper (and the slides) print
//   a_i = (2 (sigma_x^2 cos^2 phi_i + sigma_y^2 sin^2 phi_i) tan theta_i)^(-1/2),
// which is dimensionally inconsistent with Smith's definition: a = mu / sqrt(2 sigma_w^2) with
// mu = cot theta, the slope of the ray, so tan^2 theta belongs where tan theta stands:
//   a_i = 1 / (sqrt(2 sigma_w^2) tan theta_i),  sigma_w^2 = sigma_x^2 cos^2 phi_i + sigma_y^2 sin^2 phi_i.
// The identity eq. 11 decides: with the corrected a the integral of q_vn^e is 1 to the accuracy
// of Lambda (measured: 7e-8, see the test), with the printed a it is not (both forms
// agree only at theta = 45 deg, where tan = tan^2 = 1; the test measures the integral with the
// printed form at 1.048, 1.282 and 5.03 for theta_v = 70, 80 and 89 deg, sigma_x^2 = sigma_y^2 =
// 0.1, and asserts that it fails).
// Bruneton's published code uses the corrected form. In the tangent frame, with w a unit vector
// and sin theta cos phi = w_x, sin theta sin phi = w_y, it needs no angle at all:
//   a = w_z / sqrt(2 (sigma_x^2 w_x^2 + sigma_y^2 w_y^2))                       (OceanSmithAToward)
// which for sigma_x^2 = sigma_y^2 = sigma^2 / 2 is the isotropic cot theta / sigma.
//
// TYPO 2, eq. 12. The paper prints the change of variables d^2 zeta = d^2 omega_l / (4 h_z^2
// v.h); the slides print h_z^3, which is right: a slope zeta = tan theta_h (cos phi, sin phi)
// has d^2 zeta = tan theta_h d(tan theta_h) dphi = d^2 omega_h / cos^3 theta_h, and the mirror
// reflection gives d^2 omega_l = 4 (v.h) d^2 omega_h. Eq. 13 (h_z^3) and eq. 15 (h_z^4) are
// consistent with h_z^3. The test "the BRDF's albedo equals the same reflection counted on the
// facets" integrates the BRDF over light directions and q_vn F over slopes: they agree with h_z^3
// and differ by a factor h_z inside the integral (1 % at sigma^2 = 0.01 per axis, 6-8 % at
// 0.09) with h_z^2.
//
// THE BRDF (eq. 13, OceanRossBrdf). With f = h at zeta = zeta_h (the slopes of the half vector,
// OceanHalfVectorSlopes), v.f = v.h = l.h > 0 and f_z = h_z, eq. 13 simplifies to
//   brdf(v, l) = p(zeta_h) F(v.h) / (4 h_z^4 cos theta_v cos theta_l (1 + Lambda_v + Lambda_l)),
// symmetric in v and l (reciprocal). The reflected sun (eq. 15, OceanReflectedSun) is
// brdf cos theta_l per unit L_sun Omega_sun. Both denominators are evaluated through
// cos theta (1 + Lambda) and cos theta Lambda (ocean/smith.glsl), which are finite at the horizon:
//   cos_v cos_l (1 + L_v + L_l) = cos_v cos_l + cos_l (cos_v L_v) + cos_v (cos_l L_l),
//   cos_v (1 + L_v + L_l)       = cos_v (1 + L_v) + cos_v L_l,
// so a horizontal view gives a finite BRDF and a finite sun glint, without any clamp of cos
// theta_v (the paper's code clamps it to 0.01).
//
// Degenerate inputs: v below the mean surface (v.z < 0), a light at or below the horizon
// (l.z <= 0, every facet is shadowed: Lambda_l -> inf) and pairs with no mirroring facet within
// OCEAN_MIN_FACET_COS of the vertical (v = -l included) give 0; slope variances are raised to
// OCEAN_MIN_SLOPE_VARIANCE. Every function returns finite values for all unit inputs and every
// slope variance in [0, 1] (tested down to 1e-8 and, through the floor, 0).

#ifndef THALASSA_OCEAN_ROSS_BRDF_GLSL
#define THALASSA_OCEAN_ROSS_BRDF_GLSL

#include "common/definitions.glsl"
#include "ocean/smith.glsl"

// Smallest slope variance (per axis, dimensionless) that any function here accepts: a floor
// against 0 and negative inputs only (p(zeta) <= 1 / (2 pi 1e-10) = 1.6e9 stays finite in single
// precision); the sun term raises its variances much further (OCEAN_SUN_MIN_SLOPE_VARIANCE).
const Number OCEAN_MIN_SLOPE_VARIANCE = 1.0e-10;

// The sun's mean angular radius, radians: 0.2666 deg (its apparent diameter, 31.99 arcmin, at
// 1 AU; it varies by +-1.7 % over the year).
const Number OCEAN_SUN_ANGULAR_RADIUS = 4.653e-3;

// The "minimum variance for the sun's disc" of sec. 5.1, per axis, dimensionless: eq. 15 treats
// the BRDF as constant over the sun's solid angle, which for a flat sea (a Dirac BRDF) would draw
// a point instead of a disc, so the paper clamps sigma_x^2 and sigma_y^2 to a minimum in eq. 15.
// The value makes the Gaussian glint of a flat sea have the second moments of the sun's disc:
// the eye sees the sun reflected by the facets whose normal h bisects v and a point l of the
// disc; near normal incidence, moving l by an angle e moves h, hence the slope, by e / 2, so the
// disc (radius delta, uniform, per-axis variance delta^2 / 4) becomes a disc of radius delta / 2
// in slope space, per-axis variance delta^2 / 16 = 1.35e-6 (sigma = 1.16e-3). It is exact in
// the second moment at normal incidence only (the mapping is anisotropic at oblique incidence),
// but conserves the reflected energy at every incidence (the test checks it). A renderer whose
// pixels are wider than the sun's image may raise it (Bruneton's demo code uses 2e-5).
const Number OCEAN_SUN_MIN_SLOPE_VARIANCE =
    OCEAN_SUN_ANGULAR_RADIUS * OCEAN_SUN_ANGULAR_RADIUS / 16.0;

// Facets steeper than acos(0.01) = 89.4 deg are ignored (no mirroring facet: 0): this only
// avoids dividing by h_z ~ 0 (for v = -l, or v and l both near the horizon), since p(zeta_h)
// with |zeta_h| >= 100 underflows to 0 long before for slope variances up to 1 per axis.
const Number OCEAN_MIN_FACET_COS = 0.01;

// The Fresnel reflectance of water at normal incidence, R of Schlick's eq. 14 (dimensionless):
// the paper's and the issue's default (for n = 1.333, ((n - 1) / (n + 1))^2 = 0.0204).
const Number OCEAN_DEFAULT_FRESNEL_R = 0.02;

// The constants of the paper's effective Fresnel fit, eq. 26 (dimensionless, fitted by the
// authors, see Fig. 7): the exponent 5 exp(-DECAY sigma_v) and the denominator
// 1 + SCALE sigma_v^1.5, sigma_v the slope standard deviation toward the view (eq. 25).
const Number OCEAN_EFFECTIVE_FRESNEL_EXPONENT_DECAY = 2.69;
const Number OCEAN_EFFECTIVE_FRESNEL_SCALE = 22.7;

// The table of eq. 24 that replaces the fit where a scene asks for it (ocean.effective_fresnel =
// "table"; ocean/effective_fresnel.hpp builds it, shaders/ocean/effective_fresnel.glsl reads it):
// COS_SIZE x SIGMA_SIZE samples of the visible facets' mean Schlick factor for isotropic slopes and
// its derivative in the variance across the view (OceanEffectiveFresnelFromTable), on a grid
// uniform in sqrt(cos theta_v) (x) and sqrt(sigma_v / MAX_SIGMA) (y), which puts samples where the
// factor changes fastest: at grazing views, where it falls from Schlick's value over
// cos theta_v ~ sigma_v for small sigma_v. Measured errors in docs/ocean_fresnel.md. sigma_v is
// held at MAX_SIGMA (slope variance 1 toward the view, the range every function here accepts).
const int OCEAN_EFFECTIVE_FRESNEL_TABLE_COS_SIZE = 128;
const int OCEAN_EFFECTIVE_FRESNEL_TABLE_SIGMA_SIZE = 64;
const Number OCEAN_EFFECTIVE_FRESNEL_TABLE_MAX_SIGMA = 1.0;

// The largest radius (in units of the horizon circle's) that the stereographic sky-map mapping
// returns, dimensionless. The mapping U(r) = (r_x, r_y) / (1 + r_z) sends the nadir r = (0, 0, -1)
// to infinity; rays within 2 / OCEAN_SKY_MAP_MAX_RADIUS rad (0.11 deg) of the nadir are mapped to
// this radius instead, along (r_x, r_y), and the nadir itself to (OCEAN_SKY_MAP_MAX_RADIUS, 0).
// Any point this far outside the unit circle reads the same clamped edge texels of a sky map
// that covers the upper hemisphere, so the choice does not show; it keeps U and its derivatives
// finite (|dU/dzeta| <= ~4 (2 / MAX_RADIUS^2)^(-3/2) = 1.4e10) in single precision.
const Number OCEAN_SKY_MAP_MAX_RADIUS = 1000.0;

// ---------------------------------------------------------------------------------------------
// Frames, slopes and the slope distribution.

// The components of w (any frame) in the tangent frame (t_x, t_y, n) given in that same frame:
// (w.t_x, w.t_y, w.n). t_x, t_y, n must be orthonormal (Algorithm 5.1's inputs).
vec3 OceanToTangentFrame(IN(vec3) w, IN(vec3) t_x, IN(vec3) t_y, IN(vec3) n) {
  return vec3(dot(w, t_x), dot(w, t_y), dot(w, n));
}

// slope_variance raised to OCEAN_MIN_SLOPE_VARIANCE, per axis.
vec2 OceanClampedSlopeVariance(IN(vec2) slope_variance) {
  return max(slope_variance, OCEAN_MIN_SLOPE_VARIANCE);
}

// The unit normal f(zeta) of a facet of slopes zeta, tangent frame (eq. 6).
vec3 OceanFacetNormal(IN(vec2) zeta) {
  return vec3(-zeta.x, -zeta.y, 1.0) / sqrt(1.0 + zeta.x * zeta.x + zeta.y * zeta.y);
}

// The anisotropic Gaussian slope pdf p(zeta), per unit slope area (dimensionless), eq. 7:
//   p = exp(-(zeta_x^2 / sigma_x^2 + zeta_y^2 / sigma_y^2) / 2) / (2 pi sigma_x sigma_y).
Number OceanSlopePdf(IN(vec2) zeta, IN(vec2) slope_variance) {
  vec2 s2 = OceanClampedSlopeVariance(slope_variance);
  Number q = zeta.x * zeta.x / s2.x + zeta.y * zeta.y / s2.y;
  return exp(-0.5 * q) / (2.0 * PI * sqrt(s2.x * s2.y));
}

// The slope variance in the azimuth of w (tangent frame, any length), dimensionless, eq. 25:
//   sigma_w^2 = sigma_x^2 cos^2 phi_w + sigma_y^2 sin^2 phi_w
// = (sigma_x^2 w_x^2 + sigma_y^2 w_y^2) / (w_x^2 + w_y^2). For a vertical w (no azimuth) it is
// the azimuthal mean (sigma_x^2 + sigma_y^2) / 2, the value that matters at the zenith, where
// q_vn^e = p and eq. 24 depends on both variances alike.
Number OceanSlopeVarianceToward(IN(vec3) w, IN(vec2) slope_variance) {
  vec2 s2 = OceanClampedSlopeVariance(slope_variance);
  Number sin2 = w.x * w.x + w.y * w.y;
  if (sin2 > 0.0) {
    return (s2.x * w.x * w.x + s2.y * w.y * w.y) / sin2;
  }
  return 0.5 * (s2.x + s2.y);
}

// sqrt(2 sigma_w^2) sin theta_w = sqrt(2 (sigma_x^2 w_x^2 + sigma_y^2 w_y^2)) (dimensionless),
// for a unit w in the tangent frame: the denominator of a = cos theta / sigma_sin (eq. 9
// corrected, see the top of the file). Positive unless w is vertical.
Number OceanSmithSigmaSin(IN(vec3) w, IN(vec2) slope_variance) {
  vec2 s2 = OceanClampedSlopeVariance(slope_variance);
  return sqrt(2.0 * (s2.x * w.x * w.x + s2.y * w.y * w.y));
}

// Smith's a for the unit direction w (tangent frame), eq. 9 corrected:
//   a = w_z / sqrt(2 (sigma_x^2 w_x^2 + sigma_y^2 w_y^2)) = 1 / (sqrt(2 sigma_w^2) tan theta_w),
// held in [OCEAN_SMITH_MIN_A, OCEAN_SMITH_MAX_A] (w_z <= 0 gives OCEAN_SMITH_MIN_A).
Number OceanSmithAToward(IN(vec3) w, IN(vec2) slope_variance) {
  if (w.z <= 0.0) {
    return OCEAN_SMITH_MIN_A;
  }
  return OceanSmithA(w.z, OceanSmithSigmaSin(w, slope_variance));
}

// Smith's Lambda(a_w) (dimensionless, eq. 8-9) for the unit direction w (tangent frame): 0 at
// the zenith, 2.8e8 (OCEAN_SMITH_MIN_A) at and below the horizon.
Number OceanSmithLambdaToward(IN(vec3) w, IN(vec2) slope_variance) {
  return OceanSmithLambda(OceanSmithAToward(w, slope_variance));
}

// cos theta_w Lambda(a_w) (dimensionless) for the unit direction w (tangent frame), w_z clamped
// to [0, 1]: finite at the horizon (sigma_sin / (2 sqrt(pi))).
Number OceanSmithCosLambdaToward(IN(vec3) w, IN(vec2) slope_variance) {
  return OceanSmithCosLambda(w.z, OceanSmithSigmaSin(w, slope_variance));
}

// cos theta_w (1 + Lambda(a_w)) (dimensionless), the facing area of ocean/smith.glsl, for the
// unit direction w (tangent frame), w_z clamped to [0, 1]: positive for every w whose z is >= 0,
// at least sqrt(2 OCEAN_MIN_SLOPE_VARIANCE) / (2 sqrt(pi)) = 4e-6.
Number OceanSmithFacingAreaToward(IN(vec3) w, IN(vec2) slope_variance) {
  return OceanSmithFacingArea(w.z, OceanSmithSigmaSin(w, slope_variance));
}

// The slopes zeta_h of the facet that mirrors l into v (tangent frame): h = normalize(v + l),
// zeta_h = -(h_x, h_y) / h_z (Algorithm 5.1; the normalisation cancels). h_z is held at
// OCEAN_MIN_FACET_COS |v + l| or above (and |v + l| at 1e-30 or above), so the result is finite
// for every input; callers skip the facets steeper than that (OceanMirrorFacetTerm).
vec2 OceanHalfVectorSlopes(IN(vec3) v, IN(vec3) l) {
  vec3 sum = v + l;
  Number h_z = max(sum.z, max(OCEAN_MIN_FACET_COS * length(sum), 1.0e-30));
  return vec2(-sum.x, -sum.y) / h_z;
}

// ---------------------------------------------------------------------------------------------
// Visible-slope distributions (sec. 4).

// q_vn(zeta, v, l) of eq. 5, per unit slope area (dimensionless): the density of the facets of
// slopes zeta seen from v and lit from l (unit, tangent frame). max(v.f, 0) / f_z is
// (v_z - v_x zeta_x - v_y zeta_y)_+ and H(l.f) is 1 where l_z - l_x zeta_x - l_y zeta_y > 0; the
// denominator cos theta_v (1 + Lambda_v + Lambda_l) is the facing area of v plus cos theta_v
// Lambda_l, positive down to cos theta_v = 0. 0 for v_z < 0 or l_z <= 0.
Number OceanVisibleSlopePdf(IN(vec2) zeta, IN(vec3) v, IN(vec3) l, IN(vec2) slope_variance) {
  if (v.z < 0.0 || l.z <= 0.0) {
    return 0.0;
  }
  Number lit = l.z - l.x * zeta.x - l.y * zeta.y;
  if (lit <= 0.0) {
    return 0.0;
  }
  Number facing = max(v.z - v.x * zeta.x - v.y * zeta.y, 0.0);
  Number masked_cos_v = OceanSmithFacingAreaToward(v, slope_variance) +
                        v.z * OceanSmithLambdaToward(l, slope_variance);
  return OceanSlopePdf(zeta, slope_variance) * facing / masked_cos_v;
}

// q_vn^e(zeta, v) of eq. 10, per unit slope area (dimensionless): the density of the facets of
// slopes zeta seen from v (unit, tangent frame), without a light; integrates to 1 (eq. 11).
// 0 for v_z < 0.
Number OceanVisibleSlopePdfE(IN(vec2) zeta, IN(vec3) v, IN(vec2) slope_variance) {
  if (v.z < 0.0) {
    return 0.0;
  }
  Number facing = max(v.z - v.x * zeta.x - v.y * zeta.y, 0.0);
  return OceanSlopePdf(zeta, slope_variance) * facing /
         OceanSmithFacingAreaToward(v, slope_variance);
}

// ---------------------------------------------------------------------------------------------
// Fresnel, the BRDF and the sun.

// Schlick's approximation of the Fresnel reflectance (dimensionless), eq. 14:
//   F = R + (1 - R) (1 - cos)^5, cos = cos_incidence clamped to [0, 1], R = fresnel_r.
Number OceanSchlickFresnel(IN(Number) cos_incidence, IN(Number) fresnel_r) {
  Number x = 1.0 - clamp(cos_incidence, 0.0, 1.0);
  Number x2 = x * x;
  return fresnel_r + (1.0 - fresnel_r) * x2 * x2 * x;
}

// F(v.h) / (4 h_z^4) (dimensionless), the numerator common to eq. 13 and 15 without the slope
// density, and the slopes zeta_h of the facet that mirrors l into v, for unit v and l in the
// tangent frame; 0 (and zeta_h = 0) when no facet within OCEAN_MIN_FACET_COS of the vertical
// does (v = -l included).
Number OceanMirrorFacetFactor(IN(vec3) v, IN(vec3) l, IN(Number) fresnel_r, OUT(vec2) zeta_h) {
  vec3 sum = v + l;  // 2 (v.h) h: not normalised.
  Number sum_length = length(sum);
  if (sum.z <= OCEAN_MIN_FACET_COS * sum_length) {
    zeta_h = vec2(0.0);
    return 0.0;
  }
  Number h_z = sum.z / sum_length;
  zeta_h = vec2(-sum.x, -sum.y) / sum.z;
  Number fresnel = OceanSchlickFresnel(dot(v, sum) / sum_length, fresnel_r);
  Number h_z2 = h_z * h_z;
  return fresnel / (4.0 * h_z2 * h_z2);
}

// p(zeta_h) F(v.h) / (4 h_z^4) (dimensionless), the numerator common to eq. 13 and 15, for unit
// v and l in the tangent frame; 0 when no facet within OCEAN_MIN_FACET_COS of the vertical
// mirrors l into v (v = -l included).
Number OceanMirrorFacetTerm(IN(vec3) v, IN(vec3) l, IN(vec2) slope_variance,
                            IN(Number) fresnel_r) {
  vec2 zeta_h;
  Number factor = OceanMirrorFacetFactor(v, l, fresnel_r, zeta_h);
  return factor > 0.0 ? OceanSlopePdf(zeta_h, slope_variance) * factor : 0.0;
}

// The Ross BRDF (sr^-1), eq. 13, for unit v and l in the tangent frame, slope variances
// (sigma_x^2, sigma_y^2) and Schlick's R = fresnel_r:
//   brdf = p(zeta_h) F(v.h) / (4 h_z^4 cos theta_v cos theta_l (1 + Lambda_v + Lambda_l))
// (eq. 13 with eq. 5 at zeta = zeta_h, see the top of the file). Reciprocal. 0 for v_z < 0,
// l_z < 0 or no mirroring facet; finite for a horizontal v or l (not both: then 0).
Number OceanRossBrdf(IN(vec3) v, IN(vec3) l, IN(vec2) slope_variance, IN(Number) fresnel_r) {
  if (v.z < 0.0 || l.z < 0.0) {
    return 0.0;
  }
  Number masked_cos_vl = v.z * l.z + l.z * OceanSmithCosLambdaToward(v, slope_variance) +
                         v.z * OceanSmithCosLambdaToward(l, slope_variance);
  if (masked_cos_vl <= 0.0) {
    return 0.0;  // v and l both horizontal: every facet is masked or shadowed.
  }
  return OceanMirrorFacetTerm(v, l, slope_variance, fresnel_r) / masked_cos_vl;
}

// cos theta_v (1 + Lambda_v + Lambda_l) written as the facing area of v plus cos theta_v
// Lambda_l (dimensionless), eq. 15's denominator: finite and positive down to a horizontal view
// for unit v (v_z >= 0) and l (l_z > 0) in the tangent frame, slope variances s2 (per axis).
Number OceanSunMaskedCosView(IN(vec3) v, IN(vec3) l, IN(vec2) s2) {
  return OceanSmithFacingAreaToward(v, s2) + v.z * OceanSmithLambdaToward(l, s2);
}

// The reflected sun radiance per unit sun radiance and solid angle, L_sun Omega_sun
// (dimensionless, i.e. sr^-1 times sr), eq. 15: brdf(v, l) cos theta_l with the slope variances
// raised to OCEAN_SUN_MIN_SLOPE_VARIANCE (sec. 5.1: the sun's disc; the only place the paper
// clamps them), for unit v and l (toward the sun's centre) in the tangent frame:
//   I_sun / (L_sun Omega_sun) = p(zeta_h) F(v.h) / (4 h_z^4 cos theta_v (1 + Lambda_v + Lambda_l)).
// The denominator is the facing area of v plus cos theta_v Lambda_l: finite and positive down to
// a horizontal view. 0 for v_z < 0, a sun at or below the horizon, or no mirroring facet.
Number OceanReflectedSun(IN(vec3) v, IN(vec3) l, IN(vec2) slope_variance,
                         IN(Number) fresnel_r) {
  if (v.z < 0.0 || l.z <= 0.0) {
    return 0.0;
  }
  vec2 s2 = max(slope_variance, OCEAN_SUN_MIN_SLOPE_VARIANCE);
  return OceanMirrorFacetTerm(v, l, s2, fresnel_r) / OceanSunMaskedCosView(v, l, s2);
}

// ---------------------------------------------------------------------------------------------
// The sun over a pixel.
//
// Eq. 15 gives the sun's light for one view direction, but a pixel's light is its average over
// the pixel's solid angle, over which the mirror slope zeta_h moves. Where the lobe p is narrower
// than that motion (a calm sea, a low sun, a far view: on a 3 m/s sea seen from 1 km with the sun
// 10 degrees high, 128 pixels over 80 degrees, zeta_h moves across the wind by 4.8 standard
// deviations from one side of a pixel to the other) the pixel's centre samples the lobe's flank
// or misses it: a glitter path narrower than a pixel drew 0.08 to 0.57 of the reference's light
// in a row, and more or less as the camera turned (docs/validation.md, "The sun's lobe across a pixel
// (stop 36)"). Over a pixel zeta_h is linear in the pixel's coordinates (u, w) in [-1/2, 1/2]^2:
// zeta_h = zeta_c + u d_x + w d_y, d_x and d_y its changes across the pixel, so the pixel's
// average of p is the integral of eq. 7's Gaussian over a parallelogram, which
// OceanPixelSlopePdf evaluates. The other factors of eq. 15 (Fresnel, h_z^-4, the masking) change
// little across a pixel and stay at its centre's values.

// Below this half-width (in standard deviations) the box average of the normal density is its
// Taylor series, whose next term is below 1e-3 of the value for |x| <= 5; above it, a difference
// of upper tails, whose relative cancellation 2 h |x| is then mild.
const Number OCEAN_BOX_AVERAGE_TAYLOR_HALF_WIDTH = 0.25;

// The upper tail of the standard normal distribution, Q(x) = erfc(x / sqrt(2)) / 2, for x >= 0,
// as exp(-x^2 / 2) times A&S 7.1.26's scaled erfc (OceanScaledErfcPolynomial, smith.glsl), whose
// relative error stays small in the tail (the box averages built on it: 0.4 % to 6 standard
// deviations, 1.4 % to 9; ross_brdf_test.cpp), so that differences of tails far out keep their
// relative precision (the absolute-error form OceanErfc would not: 1.5e-7 is phi(5.3)).
Number OceanNormalUpperTail(IN(Number) x) {
  return 0.5 * exp(-0.5 * x * x) * OceanScaledErfcPolynomial(x * sqrt(0.5));
}

// The average of the standard normal density phi over [x - h, x + h] (dimensionless), h >= 0:
// (Phi(x + h) - Phi(x - h)) / (2 h); phi(x) at h = 0. Symmetric in x. Finite for all inputs.
Number OceanNormalBoxAverage(IN(Number) x, IN(Number) h) {
  Number ax = abs(x);
  if (h < OCEAN_BOX_AVERAGE_TAYLOR_HALF_WIDTH) {
    // phi(x) (1 + (x^2 - 1) h^2 / 6 + (x^4 - 6 x^2 + 3) h^4 / 120): phi's derivatives averaged.
    Number x2 = ax * ax;
    Number h2 = h * h;
    return exp(-0.5 * x2) / sqrt(2.0 * PI) *
           max(1.0 + (x2 - 1.0) * h2 / 6.0 + (x2 * x2 - 6.0 * x2 + 3.0) * h2 * h2 / 120.0, 0.0);
  }
  Number low = ax - h;
  Number high = ax + h;
  Number mass = low >= 0.0 ? OceanNormalUpperTail(low) - OceanNormalUpperTail(high)
                           : 1.0 - OceanNormalUpperTail(-low) - OceanNormalUpperTail(high);
  return max(mass, 0.0) / (2.0 * h);
}

// The average over a pixel of eq. 7's slope density p (per unit slope area, dimensionless), for
// the mirror slope zeta_c at the pixel's centre, its changes d_x and d_y across the pixel (tangent
// frame) and the slope variances s2 (per axis, raised to OCEAN_MIN_SLOPE_VARIANCE):
//   (1 / |pixel|) integral over the pixel of p(zeta_c + u d_x + w d_y) du dw.
// In units of the standard deviations (z = zeta / sigma per axis) p is the standard normal
// density phi2(z) / (sigma_x sigma_y), and the pixel a parallelogram spanned by D_x = d_x / sigma,
// D_y = d_y / sigma. Along the longer of the two, D_1 (length L, unit e), the integral is exact
// (OceanNormalBoxAverage); the other, D_2 = a e + b e_perp, moves the point by b across e, which
// weighs the pixel's rows w by phi(s0 + w b), s0 = z_c.e_perp, and by a along e. The rows are
// then taken at their weighted mean w-bar with their spread along e, a^2 Var(w), added to the
// box's Gaussian (the conditioning approximation of a multivariate normal's rectangle
// probability, Mendell & Elston 1974, Biometrics 30):
//   average = B(s0, b / 2) B((t0 + a w-bar) / r, L / (2 r)) / r,  r = sqrt(1 + a^2 Var(w)),
// B = OceanNormalBoxAverage, t0 = z_c.e. Exact where D_x and D_y are orthogonal (a = 0: among
// others a pixel whose motions lie along the wind's axes) and for a segment (D_2 = 0); as the
// pixel shrinks it tends to p(zeta_c). Along e the pixels partition the plane exactly: summed
// over pixels one D_1 apart it is their strip's integral, wherever the lobe falls (the tests
// check the energy over a lattice of pixels, and the result against the parallelogram's
// integral: ross_brdf_test.cpp).
Number OceanPixelSlopePdf(IN(vec2) zeta_c, IN(vec2) d_x, IN(vec2) d_y, IN(vec2) slope_variance) {
  vec2 sigma = sqrt(OceanClampedSlopeVariance(slope_variance));
  vec2 z = zeta_c / sigma;
  vec2 motion_x = d_x / sigma;
  vec2 motion_y = d_y / sigma;
  bool x_longer = dot(motion_x, motion_x) >= dot(motion_y, motion_y);
  vec2 primary = x_longer ? motion_x : motion_y;
  vec2 secondary = x_longer ? motion_y : motion_x;
  Number length_1 = length(primary);
  vec2 e = length_1 > 1.0e-12 ? primary / length_1 : vec2(1.0, 0.0);
  vec2 e_perp = vec2(-e.y, e.x);
  Number a = dot(secondary, e);
  Number b = dot(secondary, e_perp);
  Number t0 = dot(z, e);
  Number s0 = dot(z, e_perp);
  if (b < 0.0) {  // orient e_perp along the secondary's perpendicular part: b >= 0
    b = -b;
    s0 = -s0;
  }
  // The rows' weights phi(s0 + w b) on w in [-1/2, 1/2]: their mass, mean and variance.
  Number row_weight = OceanNormalBoxAverage(s0, 0.5 * b);
  Number w_mean = 0.0;
  Number w_variance = 1.0 / 12.0;  // uniform rows (b -> 0)
  if (b >= OCEAN_BOX_AVERAGE_TAYLOR_HALF_WIDTH) {
    // The standard normal truncated to [s_low, s_high]: mean and variance (of s = s0 + w b).
    Number s_low = s0 - 0.5 * b;
    Number s_high = s0 + 0.5 * b;
    Number mass = row_weight * b;
    if (mass > 1.0e-30) {
      Number phi_low = exp(-0.5 * s_low * s_low) / sqrt(2.0 * PI);
      Number phi_high = exp(-0.5 * s_high * s_high) / sqrt(2.0 * PI);
      Number s_mean = clamp((phi_low - phi_high) / mass, s_low, s_high);
      Number s_variance =
          1.0 + (s_low * phi_low - s_high * phi_high) / mass - s_mean * s_mean;
      w_mean = (s_mean - s0) / b;
      w_variance = clamp(s_variance / (b * b), 0.0, 1.0 / 12.0);
    }
  } else {
    w_mean = -s0 * b / 12.0;  // first order in b: weights 1 - s0 b w
  }
  Number r = sqrt(1.0 + a * a * w_variance);
  Number along = OceanNormalBoxAverage((t0 + a * w_mean) / r, 0.5 * length_1 / r) / r;
  return row_weight * along / (sigma.x * sigma.y);
}

// OceanReflectedSun (eq. 15) averaged over a pixel: the same, with p(zeta_h) replaced by its
// average over the pixel (OceanPixelSlopePdf), for unit v (toward the eye through the pixel's
// centre) and l in the tangent frame, and zeta_dx, zeta_dy the changes of zeta_h (relative to
// the sea at rest) across the pixel (shaders/ocean/pixel_mirror_slopes.glsl). Equal to
// OceanReflectedSun for zeta_dx = zeta_dy = 0.
Number OceanReflectedSunOverPixel(IN(vec3) v, IN(vec3) l, IN(vec2) slope_variance,
                                  IN(Number) fresnel_r, IN(vec2) zeta_dx, IN(vec2) zeta_dy) {
  if (v.z < 0.0 || l.z <= 0.0) {
    return 0.0;
  }
  vec2 s2 = max(slope_variance, OCEAN_SUN_MIN_SLOPE_VARIANCE);
  vec2 zeta_h;
  Number factor = OceanMirrorFacetFactor(v, l, fresnel_r, zeta_h);
  if (factor <= 0.0) {
    return 0.0;
  }
  return OceanPixelSlopePdf(zeta_h, zeta_dx, zeta_dy, s2) * factor /
         OceanSunMaskedCosView(v, l, s2);
}

// ---------------------------------------------------------------------------------------------
// Sky and sea light (sec. 5.2, 5.3).

// The effective Fresnel reflectance F-bar (dimensionless), the paper's fit eq. 26 of eq. 24
// (the Schlick reflectance averaged over the visible facets, q_vn^e):
//   F-bar = R + (1 - R) (1 - cos theta_v)^(5 exp(-2.69 sigma_v)) / (1 + 22.7 sigma_v^1.5),
// for cos theta_v = cos_theta_v (clamped to [0, 1]) and sigma_v^2 = view_slope_variance (eq. 25,
// OceanSlopeVarianceToward; negative counts as 0). Schlick's eq. 14 at sigma_v = 0. Its error
// against eq. 24 is tabulated in docs/ocean_fresnel.md. The sea's refracted term (eq. 28) is
// L_sea (1 - F-bar).
Number OceanEffectiveFresnel(IN(Number) cos_theta_v, IN(Number) view_slope_variance,
                             IN(Number) fresnel_r) {
  Number sigma_v = sqrt(max(view_slope_variance, 0.0));
  Number x = 1.0 - clamp(cos_theta_v, 0.0, 1.0);
  // The exponent is held at 1e-6 or above: for sigma_v > 38 (far outside the fit's range, slope
  // variances <= 1) 5 exp(-2.69 sigma_v) underflows to 0 in float (at 278 in double), and
  // pow(0, 0) at normal incidence is undefined in GLSL (llvmpipe returns 0, C++ 1: a jump of
  // the result by (1 - R) / (1 + 22.7 sigma_v^1.5) between the two). With the floor x^exponent
  // is 0 at x = 0 for every sigma_v, continuous with its value at all smaller sigma_v.
  Number exponent = max(5.0 * exp(-OCEAN_EFFECTIVE_FRESNEL_EXPONENT_DECAY * sigma_v), 1.0e-6);
  return fresnel_r + (1.0 - fresnel_r) * pow(x, exponent) /
         (1.0 + OCEAN_EFFECTIVE_FRESNEL_SCALE * sigma_v * sqrt(sigma_v));
}

// The position of (cos theta_v, sigma_v^2 = view_slope_variance) in the effective Fresnel table,
// in samples (x in [0, COS_SIZE - 1], y in [0, SIGMA_SIZE - 1]; clamped to the table): the
// sample (i, j) holds cos theta_v = (i / (COS_SIZE - 1))^2 and
// sigma_v = MAX_SIGMA (j / (SIGMA_SIZE - 1))^2 (OceanEffectiveFresnelTableNode).
vec2 OceanEffectiveFresnelTablePosition(IN(Number) cos_theta_v, IN(Number) view_slope_variance) {
  Number sigma_v = sqrt(max(view_slope_variance, 0.0));
  Number x = sqrt(clamp(cos_theta_v, 0.0, 1.0));
  Number y = sqrt(min(sigma_v / OCEAN_EFFECTIVE_FRESNEL_TABLE_MAX_SIGMA, 1.0));
  return vec2(x * Number(OCEAN_EFFECTIVE_FRESNEL_TABLE_COS_SIZE - 1),
              y * Number(OCEAN_EFFECTIVE_FRESNEL_TABLE_SIGMA_SIZE - 1));
}

// (cos theta_v, sigma_v) of the table's sample (i, j), the inverse of
// OceanEffectiveFresnelTablePosition at the samples.
vec2 OceanEffectiveFresnelTableNode(IN(Number) i, IN(Number) j) {
  Number x = i / Number(OCEAN_EFFECTIVE_FRESNEL_TABLE_COS_SIZE - 1);
  Number y = j / Number(OCEAN_EFFECTIVE_FRESNEL_TABLE_SIGMA_SIZE - 1);
  return vec2(x * x, OCEAN_EFFECTIVE_FRESNEL_TABLE_MAX_SIGMA * y * y);
}

// F-bar (dimensionless) from the table's bilinear sample (I, dI/db) at (cos theta_v, along), for
// slope variances `along` and `across` the view's azimuth and Schlick's R = fresnel_r: eq. 24's
// average I carried from isotropic slopes to b = across to first order, held to [0, 1]. Both
// variances are held to [0, 1], as the table's are (beyond it the difference would be float
// rounding of large numbers).
Number OceanEffectiveFresnelFromTable(IN(vec2) table_sample, IN(Number) along, IN(Number) across,
                                      IN(Number) fresnel_r) {
  Number change = clamp(across, 0.0, 1.0) - clamp(along, 0.0, 1.0);
  Number average = clamp(table_sample.x + table_sample.y * change, 0.0, 1.0);
  return fresnel_r + (1.0 - fresnel_r) * average;
}

// The mean slope toward the view's azimuth of the visible facets weighted by their Schlick
// reflectance, E_q[F zeta.e] / E_q[F] (dimensionless, F = R + (1 - R) (1 - v.f)^5, e the view's
// horizontal direction), from the table's sample (I, dI/db, E_q[zeta.e] / sin theta_v,
// E_q[(1 - v.f)^5 zeta.e] / sin theta_v: both vanish as sin theta_v at normal view, and their
// ratios to it are smooth there), sin theta_v = sin_theta_v and R = fresnel_r: where eq. 21's
// product F-bar L-bar centres the sky's lobe (eq. 27's mirror direction of the mean normal,
// slope 0), the light the facets send is centred here.
Number OceanFresnelWeightedMeanSlope(IN(vec4) table_sample, IN(Number) sin_theta_v,
                                     IN(Number) fresnel_r) {
  Number weight = fresnel_r + (1.0 - fresnel_r) * table_sample.x;
  return sin_theta_v * (fresnel_r * table_sample.z + (1.0 - fresnel_r) * table_sample.w) / weight;
}

// 1 + r_z (dimensionless), the denominator of the stereographic mapping, for a unit r. Near the
// nadir (r_z -> -1) the sum 1 + r_z ~ eps^2 / 2 (eps the angle from the nadir) cancels: an error
// of r_z's last bit (6e-8 in float, 1.1e-16 in double) becomes a relative error 2 ulp / eps^2 of
// U (3 % in float at eps = 4e-3, measured by tests/gpu/numerics_test.cpp where r is computed
// by a reflection). For r_z < 0 it is written (1 - r_z)(1 + r_z) / (1 - r_z) = (r_x^2 + r_y^2)
// / (1 - r_z) (|r| = 1): no cancellation (1 - r_z >= 1), and r_x, r_y carry the direction with
// a relative error ulp / eps only. Both forms are equal for a unit r and agree at r_z = 0.
Number OceanStereographicDenominator(IN(vec3) r) {
  return r.z >= 0.0 ? 1.0 + r.z : (r.x * r.x + r.y * r.y) / (1.0 - r.z);
}

// The stereographic sky-map coordinates U(r) = (r_x, r_y) / (1 + r_z) (dimensionless, sec. 5.2)
// of the unit direction r in the sky map's frame (z up: the zenith maps to (0, 0), the horizon to
// the unit circle, the lower hemisphere outside it), 1 + r_z from OceanStereographicDenominator
// (stable near the nadir). Near the nadir, where 1 + r_z < 2 / OCEAN_SKY_MAP_MAX_RADIUS^2, the
// radius is held at OCEAN_SKY_MAP_MAX_RADIUS along (r_x, r_y), and the nadir itself maps to
// (OCEAN_SKY_MAP_MAX_RADIUS, 0) (see that constant).
vec2 OceanStereographic(IN(vec3) r) {
  Number d = OceanStereographicDenominator(r);
  if (d >= 2.0 / (OCEAN_SKY_MAP_MAX_RADIUS * OCEAN_SKY_MAP_MAX_RADIUS)) {
    return vec2(r.x, r.y) / d;
  }
  Number r_xy = sqrt(r.x * r.x + r.y * r.y);
  if (r_xy > 0.0) {
    return vec2(r.x, r.y) * (OCEAN_SKY_MAP_MAX_RADIUS / r_xy);
  }
  return vec2(OCEAN_SKY_MAP_MAX_RADIUS, 0.0);
}

// The derivative of U (OceanStereographic) along dr = dr/ds at r, for any parameter s:
//   dU = (dr_x, dr_y) / d - (r_x, r_y) dr_z / d^2,  d = 1 + r_z (OceanStereographicDenominator),
// with d held at 2 / OCEAN_SKY_MAP_MAX_RADIUS^2 or above (near the nadir: large but finite).
vec2 OceanStereographicDerivative(IN(vec3) r, IN(vec3) dr) {
  Number d = max(OceanStereographicDenominator(r),
                 2.0 / (OCEAN_SKY_MAP_MAX_RADIUS * OCEAN_SKY_MAP_MAX_RADIUS));
  return vec2(dr.x, dr.y) / d - vec2(r.x, r.y) * (dr.z / (d * d));
}

// u(v, zeta) = U(r(v, zeta)) (Algorithm 5.1's procedure U): the sky-map coordinates of the view
// vector v reflected by the facet of slopes zeta, r = 2 (v.f) f - v (eq. 18), with
// f = f_x t_x + f_y t_y + f_z n from eq. 6. v, t_x, t_y, n are unit vectors in the SKY MAP'S
// frame (world or east-north-up, z up), (t_x, t_y, n) the orthonormal tangent frame of the
// surface (wind, cross-wind, mean normal). For the 9-sample elliptical average and tests.
vec2 OceanSkyMapCoordinates(IN(vec3) v, IN(vec3) t_x, IN(vec3) t_y, IN(vec3) n,
                            IN(vec2) zeta) {
  vec3 f_tangent = OceanFacetNormal(zeta);
  vec3 f = f_tangent.x * t_x + f_tangent.y * t_y + f_tangent.z * n;
  vec3 r = 2.0 * dot(f, v) * f - v;
  return OceanStereographic(r);
}

// u0 = u(v, 0) and the analytic derivatives du/dzeta_x, du/dzeta_y at zeta = 0 (dimensionless;
// arguments as for OceanSkyMapCoordinates). Eq. 27's texture gradients are
// 2 sigma_x du_dzeta_x and 2 sigma_y du_dzeta_y (Algorithm 5.1 takes them by finite differences
// with epsilon = 1e-3; these are exact). At zeta = 0, f = n and, since |-zeta_x t_x - zeta_y t_y
// + n| = 1 + O(zeta^2), df/dzeta_x = -t_x, df/dzeta_y = -t_y; then r = 2 (v.n) n - v and
//   dr/dzeta_x = 2 (df.v) f + 2 (f.v) df = -2 ((v.t_x) n + (v.n) t_x)   (likewise for y).
void OceanSkyMapGradients(IN(vec3) v, IN(vec3) t_x, IN(vec3) t_y, IN(vec3) n, OUT(vec2) u0,
                          OUT(vec2) du_dzeta_x, OUT(vec2) du_dzeta_y) {
  Number v_n = dot(v, n);
  vec3 r = 2.0 * v_n * n - v;
  vec3 dr_x = -2.0 * (dot(v, t_x) * n + v_n * t_x);
  vec3 dr_y = -2.0 * (dot(v, t_y) * n + v_n * t_y);
  u0 = OceanStereographic(r);
  du_dzeta_x = OceanStereographicDerivative(r, dr_x);
  du_dzeta_y = OceanStereographicDerivative(r, dr_y);
}

// ---------------------------------------------------------------------------------------------
// Refracted light (sec. 5.3, eq. 28): I_sea = L_sea (1 - F-bar).

// The default deep-water irradiance reflectance, dimensionless, per channel (the scene keys
// ocean.deep_reflectance_r/g/b): the sea colour (10, 40, 120) / 255 of Bruneton et al.'s 2010
// ocean demo scaled by 0.1 and rounded, 0.4 %, 1.6 %, 4.7 %: the order of magnitude of clear
// open ocean (irradiance reflectances of 2-5 % in the blue, under 0.5 % in the red), chosen by
// eye rather than from a water model.
const vec3 OCEAN_DEFAULT_DEEP_REFLECTANCE = vec3(0.004, 0.016, 0.047);

// L_sea, the radiance reaching the surface from the water body, W m^-2 sr^-1 nm^-1: diffuse and
// proportional to the total sun and sky irradiance, as sec. 5.3 assumes; here a Lambertian
// upwelling of irradiance reflectance deep_reflectance (dimensionless, per channel) under the
// downwelling irradiance horizontal_irradiance (sun + sky on a horizontal surface,
// W m^-2 nm^-1): deep_reflectance * E / pi, so that the water darkens at dusk with the light.
vec3 OceanDeepRadiance(IN(vec3) deep_reflectance, IN(vec3) horizontal_irradiance) {
  return deep_reflectance * horizontal_irradiance / PI;
}

#endif  // THALASSA_OCEAN_ROSS_BRDF_GLSL
