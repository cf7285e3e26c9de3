// PLACEHOLDER SEA of the foundation: the radiance leaving a sea that is flat on average, under the
// placeholder sky (atmosphere/analytic_sky.glsl). It gives the default picture a physically
// sensible sea until the Bruneton et al. 2010 ocean replaces it: no geometry, no waves, only a
// mirror for the sky, a Cox & Munk sun glint and a diffuse upwelling from the water body.
//
// Frame: local east-north-up (x east, y north, z up); the mean sea surface is z = 0 with normal
// +z. Directions are unit vectors pointing away from the surface point: view_dir toward the eye
// (so view_dir.z = cos theta_v >= 0), sun_dir toward the sun. Units: spectral radiance in
// W m^-2 sr^-1 nm^-1, spectral irradiance in W m^-2 nm^-1, per RGB channel (680, 550, 440 nm);
// wind speed in m/s (at 12.5 m, as in Cox & Munk). CPU reference and tests:
// ocean/src/flat_sea_reference.hpp, tests/unit/flat_sea_test.cpp.
//
//   L = R(theta_v) L_sky(reflect) + L_glint + (1 - R(theta_v)) L_deep
//
// R: unpolarised Fresnel reflectance from air onto water (FlatSeaFresnel). L_sky(reflect): the
// analytic sky in the mirror direction (-v.x, -v.y, v.z); the sun's disc is left out of it since
// the glint is its (blurred) reflection. L_deep: the radiance leaving the water body just below
// the surface, see FlatSeaDeepRadiance.
//
// Glint (Cox & Munk 1954, "Measurement of the roughness of the sea surface from photographs of
// the sun's glitter", JOSA 44(11), 838-850, with the Smith masking-shadowing term of Ross, Dion &
// Potvin 2005 in the form used by Bruneton, Neyret & Holzschuch 2010, "Real-time realistic ocean
// lighting using seamless transitions from geometry to BRDF", Computer Graphics Forum 29(2),
// their eq. 5, 8, 9, 13 and 15). The surface is a set of mirror facets z = eta(x, y) whose slopes
// zeta = (eta_x, eta_y) have the pdf p(zeta) per unit slope area and horizontal surface area.
// Only the facets of normal h = normalize(v + s) mirror the sun into the eye; their slopes are
// zeta = -(h.x, h.y) / h.z. Balance power per unit horizontal area: a facet of slope zeta has
// area 1 / cos theta_h per unit horizontal area and receives E (s.h) from the sun (E: irradiance
// on a surface facing the sun), so, without shadowing,
//   L cos theta_v domega_v = R(v.h) E (s.h) p(zeta) dzeta / cos theta_h.
// Slope and normal solid angle: zeta = tan theta_h (cos phi, sin phi) gives
// dzeta = tan theta_h d(tan theta_h) dphi = domega_h / cos^3 theta_h, and reflection gives
// domega_v = 4 (v.h) domega_h with v.h = s.h. Hence, with the masking-shadowing factor G,
//   L_glint = E R(v.h) p(zeta) G / (4 cos^4 theta_h cos theta_v),
//   G = 1 / (1 + Lambda(theta_v) + Lambda(theta_s))                       (paper eq. 5, 15)
// and the BRDF is L_glint / (E cos theta_s).
//
// Masking-shadowing (Smith 1967, "Geometrical shadowing of a random rough surface", IEEE Trans.
// Antennas Propag. 15(5), 668-671). A facet is seen from direction w (zenith angle theta) unless
// the surface rises above the ray beyond it. For a surface of uncorrelated Gaussian heights and
// slopes Smith's Lambda is the mean excess slope beyond the ray's, per unit ray slope:
//   Lambda(theta) = (1 / mu) integral_mu^inf (q - mu) P(q) dq,  mu = cot theta,
// P: the pdf of the slope q along w's azimuth, Gaussian of variance sigma^2 / 2 (half the total
// mean square slope, whatever the azimuth: the pdf is isotropic). With a = mu / (sqrt(2) *
// sqrt(sigma^2 / 2)) = cot theta / sigma, the Gaussian integrals give
//   Lambda(a) = (exp(-a^2) - a sqrt(pi) erfc(a)) / (2 a sqrt(pi))          (paper eq. 8)
// which is the paper's eq. 9 with sigma_x^2 = sigma_y^2 = sigma^2 / 2 (its sigma_x^2 is the
// per-axis variance; its eq. 9 as printed reads "tan theta_i" under the -1/2 power, where the
// dimensions and Smith's definition require tan^2 theta_i, i.e. a = cot theta / sqrt(2 sigma_x^2),
// as in Bruneton's published code). Lambda = 0 for a view from the zenith, Lambda -> inf (as
// 1 / (2 a sqrt(pi))) for a grazing one. The same Gaussian integral gives the identity behind
// the normalisation of paper eq. 10-11, checked numerically by the test:
//   integral max(0, w.n) / n.z p(zeta) dzeta = integral (cos theta - sin theta q)_+ P(q) dq
//                                            = cos theta (1 + Lambda(theta)),
// the area of the facets facing w, projected onto the plane normal to w, per unit horizontal
// area (FlatSeaSmithFacingArea). The erfc, Lambda and the facing area are implemented once, in
// ocean/smith.glsl (shared with the Ross BRDF, ocean/ross_brdf.glsl, whose eq. 11 test checks
// them for anisotropic slopes); this file only supplies a = cot theta / sigma.
//
// Form of G: 1 / (1 + Lambda_v + Lambda_s) is the paper's (eq. 5, from Ross et al.), the
// "height-correlated" Smith masking-shadowing function (Heitz 2014, "Understanding the
// masking-shadowing function in microfacet-based BRDFs", JCGT 3(2)): a facet seen from v and lit
// from s is visible from both if no surface rises above either ray, and a high facet is likely
// visible from both, so the two visibilities are positively correlated and the joint probability
// is larger than the product of the separate ones (the "uncorrelated" form 1 / ((1 + Lambda_v)
// (1 + Lambda_s)), which over-darkens). Chosen because it is the paper's (the future ocean uses
// it) and it keeps the BRDF reciprocal (symmetric in v, s).
//
// Energy: the glint's directional albedo is the facet integral
//   rho(s) = integral R(s.h) (s.h)_+ / (cos theta_h cos theta_s) p(zeta) G(v(zeta), s) dzeta,
// and G <= 1 / (1 + Lambda_s), R <= 1 with the identity above (for w = s) give rho(s) <= 1 for
// every sun elevation (the test checks it up to 89.9 deg from the zenith). Without G, rho
// exceeded 1 for a sun within a few degrees of the horizon (1.4 at 89 deg with wind).
//
// Grazing views. The unshadowed glint grew as 1 / cos theta_v (a clamp of cos theta_v used to
// stop it at 100 times): a white glitter column up to a hard edge at the horizon. With G the
// denominator is cos theta_v (1 + Lambda_v + Lambda_s) = cos theta_v (1 + Lambda_v)
// + cos theta_v Lambda_s, and cos theta_v (1 + Lambda_v) -> sigma / (2 sqrt(pi)) as theta_v ->
// 90 deg (the projected area of the facets facing a horizontal ray: E[max(0, -q)] for a slope q
// of standard deviation sigma / sqrt(2)), while cos theta_v Lambda_s -> 0. So the glint stays
// finite at the horizon, L_glint -> E R p sqrt(pi) / (2 cos^4 theta_h sigma), without any clamp:
// FlatSeaSmithFacingArea evaluates cos theta (1 + Lambda) in a form that is exact at 90 deg.
// The sun at or below the horizon shadows every facet (Lambda_s -> inf): no glint.
//
// Slope pdf: isotropic Gaussian with Cox & Munk's total mean square slope (both directions,
// clean surface, wind speed U in m/s): sigma^2 = <eta_x^2 + eta_y^2> = 0.003 + 5.12e-3 U,
//   p(zeta) = exp(-|zeta|^2 / sigma^2) / (pi sigma^2),
// i.e. variance sigma^2 / 2 per axis. Normalisation: in polar slope coordinates,
// integral 2 pi r exp(-r^2 / sigma^2) dr / (pi sigma^2) = pi sigma^2 / (pi sigma^2) = 1, and
// <r^2> = sigma^2 (the test checks both numerically).

#ifndef THALASSA_OCEAN_FLAT_SEA_GLSL
#define THALASSA_OCEAN_FLAT_SEA_GLSL

#include "common/definitions.glsl"
#include "atmosphere/analytic_sky.glsl"
#include "ocean/smith.glsl"

// Refractive index of sea water relative to air, dimensionless (visible, wavelength-independent
// placeholder).
const Number FLAT_SEA_REFRACTIVE_INDEX = 1.333;

// Cox & Munk (1954) clean-surface total mean square slope: sigma^2 = CALM + PER_WIND_SPEED U.
const Number COX_MUNK_SLOPE_VARIANCE_CALM = 0.003;             // dimensionless
const Number COX_MUNK_SLOPE_VARIANCE_PER_WIND_SPEED = 5.12e-3;  // s/m

// Smallest slope variance the glint accepts, dimensionless: keeps p finite if a caller passes 0
// (Cox & Munk's never goes below 0.003).
const Number FLAT_SEA_MIN_SLOPE_VARIANCE = 1.0e-6;

// Facets steeper than acos(0.01) = 89.4 deg are ignored; this only avoids dividing by h.z ~ 0
// (for v = -s, or v and s both near the horizon), since p(zeta) underflows to 0 long before.
const Number FLAT_SEA_MIN_FACET_COS = 0.01;

// A deep-water reflectance for callers without their own, dimensionless, per channel: the sea
// colour (10, 40, 120) / 255 used in Bruneton et al.'s 2010 ocean demo, scaled by 0.1, i.e.
// 0.4 %, 1.6 %, 4.7 %: the order of magnitude of clear open ocean, chosen by eye. Placeholder.
const vec3 FLAT_SEA_DEFAULT_DEEP_REFLECTANCE = vec3(10.0, 40.0, 120.0) / 255.0 * 0.1;

// Cox & Munk total mean square slope (dimensionless) for a wind speed in m/s; negative speeds
// count as calm.
Number FlatSeaSlopeVariance(IN(Number) wind_speed) {
  return COX_MUNK_SLOPE_VARIANCE_CALM + COX_MUNK_SLOPE_VARIANCE_PER_WIND_SPEED *
         max(wind_speed, 0.0);
}

// Unpolarised Fresnel reflectance (dimensionless) of light arriving from air onto water, for the
// cosine of the angle between the ray and the surface normal (clamped to [0, 1]). The full
// formula (Born & Wolf), the mean of the s and p reflectances:
//   r_s = (cos i - n cos t) / (cos i + n cos t),  r_p = (n cos i - cos t) / (n cos i + cos t),
// with sin t = sin i / n; from air cos t >= sqrt(1 - 1 / n^2) > 0, so no total reflection and no
// zero denominator. R(1) = ((n - 1) / (n + 1))^2 = 0.0204, R(0) = 1.
Number FlatSeaFresnel(IN(Number) cos_incidence) {
  Number n = FLAT_SEA_REFRACTIVE_INDEX;
  Number cos_i = clamp(cos_incidence, 0.0, 1.0);
  Number cos_t = sqrt(1.0 - (1.0 - cos_i * cos_i) / (n * n));
  Number r_s = (cos_i - n * cos_t) / (cos_i + n * cos_t);
  Number r_p = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

// Isotropic Gaussian slope pdf p(zeta), per unit slope area (dimensionless), at the slopes
// (zeta_x, zeta_y) for the total mean square slope slope_variance (see the top of the file).
Number FlatSeaSlopePdf(IN(Number) zeta_x, IN(Number) zeta_y, IN(Number) slope_variance) {
  Number sigma2 = max(slope_variance, FLAT_SEA_MIN_SLOPE_VARIANCE);
  return exp(-(zeta_x * zeta_x + zeta_y * zeta_y) / sigma2) / (PI * sigma2);
}

// sigma sin theta (dimensionless): the denominator of a = cot theta / sigma, for a direction of
// cos theta = cos_theta (clamped to [0, 1]) and the total mean square slope slope_variance.
Number FlatSeaSmithSigmaSin(IN(Number) cos_theta, IN(Number) slope_variance) {
  Number cos_t = clamp(cos_theta, 0.0, 1.0);
  return sqrt(max(slope_variance, FLAT_SEA_MIN_SLOPE_VARIANCE) * (1.0 - cos_t * cos_t));
}

// Smith's Lambda (dimensionless, paper eq. 8) for a direction of cos theta = cos_theta from the
// mean normal (+z; clamped to [0, 1]) over the isotropic Gaussian slopes of total mean square
// slope slope_variance: 0 at the zenith, 2.8e8 at most at the horizon (OCEAN_SMITH_MIN_A).
// a = cot theta / sigma is the anisotropic a of ocean/smith.glsl with sigma_w^2 = sigma^2 / 2.
Number FlatSeaSmithLambda(IN(Number) cos_theta, IN(Number) slope_variance) {
  return OceanSmithLambda(OceanSmithA(cos_theta, FlatSeaSmithSigmaSin(cos_theta, slope_variance)));
}

// cos theta (1 + Lambda(theta)), dimensionless: the area of the facets facing a direction of
// cos theta = cos_theta (clamped to [0, 1]), projected onto the plane normal to it, per unit
// horizontal area (see the top of the file). Finite and exact at the horizon, where it is
// sigma / (2 sqrt(pi)) (OceanSmithFacingArea). Positive: at least max(cos theta, sigma sin theta
// / (2 sqrt(pi))) (for the minimum slope variance, 2.8e-4 at the horizon).
Number FlatSeaSmithFacingArea(IN(Number) cos_theta, IN(Number) slope_variance) {
  return OceanSmithFacingArea(cos_theta, FlatSeaSmithSigmaSin(cos_theta, slope_variance));
}

// Sun glint per unit solar irradiance, sr^-1:
//   R(v.h) p(zeta) / (4 cos^4 theta_h cos theta_v (1 + Lambda_v + Lambda_s)),
// so that L_glint = FlatSeaGlintFactor * E with E the sun's irradiance on a surface facing it
// (the BRDF is this divided by cos theta_s). The denominator's cos theta_v (1 + Lambda_v +
// Lambda_s) is evaluated as FlatSeaSmithFacingArea(v) + cos theta_v Lambda_s, which is finite
// and positive down to cos theta_v = 0 (no clamp; view_dir.z < 0 counts as 0). 0 when the sun is
// at or below the horizon (fully shadowed) or no facet up to 89.4 deg mirrors the sun into the
// eye. Finite for all unit inputs.
Number FlatSeaGlintFactor(IN(vec3) view_dir, IN(vec3) sun_dir, IN(Number) slope_variance) {
  if (sun_dir.z <= 0.0) {
    return 0.0;
  }
  vec3 half_sum = view_dir + sun_dir;  // 2 cos(theta_d) h: not normalised.
  Number half_length = length(half_sum);
  if (half_sum.z <= FLAT_SEA_MIN_FACET_COS * half_length) {
    return 0.0;
  }
  Number cos_h = half_sum.z / half_length;
  // zeta = -(h.x, h.y) / h.z; the normalisation of h cancels in the ratio.
  Number zeta_x = -half_sum.x / half_sum.z;
  Number zeta_y = -half_sum.y / half_sum.z;
  Number fresnel = FlatSeaFresnel(dot(view_dir, half_sum) / half_length);
  Number cos_v = max(view_dir.z, 0.0);
  Number masked_cos_v = FlatSeaSmithFacingArea(cos_v, slope_variance) +
                        cos_v * FlatSeaSmithLambda(sun_dir.z, slope_variance);
  Number cos2_h = cos_h * cos_h;
  return fresnel * FlatSeaSlopePdf(zeta_x, zeta_y, slope_variance) /
         (4.0 * cos2_h * cos2_h * masked_cos_v);
}

// Sun glint radiance, W m^-2 sr^-1 nm^-1, under the analytic sun (its transmitted irradiance,
// 0 once it has set), for a wind speed in m/s.
vec3 FlatSeaSunGlint(IN(vec3) view_dir, IN(vec3) sun_dir, IN(Number) wind_speed) {
  return AnalyticSunTransmittedIrradiance(sun_dir) *
         FlatSeaGlintFactor(view_dir, sun_dir, FlatSeaSlopeVariance(wind_speed));
}

// Radiance leaving the water body (before the (1 - R) of the surface), W m^-2 sr^-1 nm^-1: a
// Lambertian upwelling of irradiance reflectance deep_reflectance (dimensionless, per channel)
// under the downwelling irradiance horizontal_irradiance (sun + sky on a horizontal surface,
// W m^-2 nm^-1): deep_reflectance * E / pi. A constant reflectance rather than a constant
// radiance, so that the water follows the light of the scene and darkens at dusk.
vec3 FlatSeaDeepRadiance(IN(vec3) deep_reflectance, IN(vec3) horizontal_irradiance) {
  return deep_reflectance * horizontal_irradiance / PI;
}

// The sea's radiance, W m^-2 sr^-1 nm^-1, toward view_dir, given the downwelling irradiance
// (sun + sky on a horizontal surface, W m^-2 nm^-1) that the deep-water term uses, so that a
// shader can compute it once per frame (e.g. on the CPU with the reference) instead of per pixel.
vec3 FlatSeaRadianceWithIrradiance(IN(vec3) view_dir, IN(vec3) sun_dir, IN(Number) wind_speed,
                                   IN(vec3) deep_reflectance, IN(vec3) horizontal_irradiance) {
  Number fresnel = FlatSeaFresnel(view_dir.z);
  vec3 mirror_dir = reflect(-view_dir, vec3(0.0, 0.0, 1.0));
  return fresnel * AnalyticSkyRadiance(mirror_dir, sun_dir) +
         FlatSeaSunGlint(view_dir, sun_dir, wind_speed) +
         (1.0 - fresnel) * FlatSeaDeepRadiance(deep_reflectance, horizontal_irradiance);
}

// The sea's radiance, W m^-2 sr^-1 nm^-1, toward view_dir (unit, from the surface toward the eye)
// for the sun along sun_dir, a wind speed in m/s and the water body's irradiance reflectance
// deep_reflectance (e.g. FLAT_SEA_DEFAULT_DEEP_REFLECTANCE). Computes the downwelling irradiance
// itself (12 extra sky evaluations: prefer FlatSeaRadianceWithIrradiance in a shader).
vec3 FlatSeaRadiance(IN(vec3) view_dir, IN(vec3) sun_dir, IN(Number) wind_speed,
                     IN(vec3) deep_reflectance) {
  vec3 horizontal_irradiance =
      AnalyticSunHorizontalIrradiance(sun_dir) + AnalyticSkyIrradiance(sun_dir);
  return FlatSeaRadianceWithIrradiance(view_dir, sun_dir, wind_speed, deep_reflectance,
                                       horizontal_irradiance);
}

#endif  // THALASSA_OCEAN_FLAT_SEA_GLSL
