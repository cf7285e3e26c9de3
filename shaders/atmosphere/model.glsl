// The atmosphere model: Rayleigh and Mie scattering and ozone absorption in a spherical shell,
// with transmittance, single and multiple scattering and ground irradiance precomputed into
// tables, after Bruneton's "Precomputed Atmospheric Scattering" (2008) in the form of its 2017
// reimplementation (precomputed_atmospheric_scattering, functions.glsl): the same table
// parameterisations, written anew here with the derivations in comments.
//
// One source, two languages (common/definitions.glsl): on the GPU these functions render the sky,
// sky maps and aerial perspective from the tables; compiled as C++ in double
// (atmosphere/src/model_reference.hpp) they precompute the tables on the CPU and are the
// reference the tests check against closed forms and brute-force integrals
// (tests/unit/atmosphere_model_test.cpp, tests/gpu/reference_test.cpp).
//
// Frames and units. Positions are relative to the planet's centre, in metres; the atmosphere is
// a spherical shell between bottom_radius (the sea surface) and top_radius. Directions are unit
// vectors. r is a distance to the centre (m); mu the cosine of a view ray's zenith angle at r;
// mu_s the cosine of the sun's zenith angle at r; nu the cosine of the angle between the view ray
// and the sun. Radiance is spectral radiance in W m^-2 sr^-1 nm^-1 and irradiance spectral
// irradiance in W m^-2 nm^-1, per RGB channel at RGB_WAVELENGTHS; scattering and extinction
// coefficients are in m^-1.
//
// Tables (sizes below; texel layout as OpenGL's, texel centres at (i + 0.5) / size):
// - transmittance to the top of the atmosphere T(r, mu), 2D;
// - scattering S(r, mu, mu_s, nu), 4D stored as a 3D texture whose x holds nu and mu_s: the
//   Rayleigh single scattering plus all multiple scattering orders, both *without* the Rayleigh
//   phase function (multiple orders are divided by it at precomputation: they are nearly
//   isotropic, and dividing then multiplying at the same nu is exact at texel centres);
// - single Mie scattering, 4D likewise, without the Mie phase function (kept in its own table
//   rather than packed in an alpha channel, so no extrapolation of its colour is needed);
// - irradiance E(r, mu_s) on a horizontal surface from the sky only (orders >= 1 of scattered
//   light; the direct sun is added analytically from T).
//
// Numerics. Discriminants of ray-sphere intersections are written (R - r)(R + r) + r^2 mu^2
// instead of r^2 (mu^2 - 1) + R^2: R - r is exact when r is near R (Sterbenz), so grazing rays
// from a camera near the sea keep their precision in float; the root that would cancel (the
// ground's near one, the top's far one) is taken in the product-of-roots form (see
// DistanceToTopAtmosphereBoundary; docs/numerics.md, section 6). Every square root and acos
// takes a clamped argument, so no input produces NaN.

#ifndef THALASSA_ATMOSPHERE_MODEL_GLSL
#define THALASSA_ATMOSPHERE_MODEL_GLSL

#include "common/definitions.glsl"

#ifndef THALASSA_CPP
#define TransmittanceTexture sampler2D
#define ScatteringTexture sampler3D
#define IrradianceTexture sampler2D
#endif

// A layer of a density profile: density(h) = exp_term exp(exp_scale h) + linear_term h +
// constant_term, clamped to [0, 1], for altitudes h (m) below `width` (the top layer's width is
// ignored). exp_scale is in m^-1 (minus the inverse scale height), linear_term in m^-1.
struct DensityProfileLayer {
  Number width;
  Number exp_term;
  Number exp_scale;
  Number linear_term;
  Number constant_term;
};

// Two layers: `lower` below lower.width, `upper` above (the ozone's tent needs two; the
// exponential profiles use only the upper one with lower.width = 0).
struct DensityProfile {
  DensityProfileLayer lower;
  DensityProfileLayer upper;
};

struct AtmosphereParameters {
  vec3 solar_irradiance;       // at the top of the atmosphere, W m^-2 nm^-1
  Number sun_angular_radius;   // rad
  Number bottom_radius;        // m, the sea surface
  Number top_radius;           // m
  DensityProfile rayleigh_density;
  vec3 rayleigh_scattering;    // at density 1, m^-1
  DensityProfile mie_density;
  vec3 mie_scattering;         // at density 1, m^-1
  vec3 mie_extinction;         // at density 1, m^-1
  Number mie_phase_g;          // Cornette-Shanks asymmetry parameter
  DensityProfile absorption_density;
  vec3 absorption_extinction;  // ozone, at density 1, m^-1
  vec3 ground_albedo;          // Lambertian
  Number mu_s_min;             // cosine of the largest sun zenith angle the tables hold
};

// Table sizes: Bruneton 2017's defaults for every table (the scattering table holds 1,048,576
// texels of 3 floats, 12.6 MB, as do the single Mie table). The errors they leave against
// direct integration are measured in tests/unit/atmosphere_model_test.cpp (docs/atmosphere.md);
// the effect of other sizes has not been measured.
const int TRANSMITTANCE_TEXTURE_WIDTH = 256;   // mu
const int TRANSMITTANCE_TEXTURE_HEIGHT = 64;   // r
const int SCATTERING_TEXTURE_R_SIZE = 32;
const int SCATTERING_TEXTURE_MU_SIZE = 128;
const int SCATTERING_TEXTURE_MU_S_SIZE = 32;
const int SCATTERING_TEXTURE_NU_SIZE = 8;
const int SCATTERING_TEXTURE_WIDTH = SCATTERING_TEXTURE_NU_SIZE * SCATTERING_TEXTURE_MU_S_SIZE;
const int SCATTERING_TEXTURE_HEIGHT = SCATTERING_TEXTURE_MU_SIZE;
const int SCATTERING_TEXTURE_DEPTH = SCATTERING_TEXTURE_R_SIZE;
const int IRRADIANCE_TEXTURE_WIDTH = 64;       // mu_s
const int IRRADIANCE_TEXTURE_HEIGHT = 16;      // r

// Quadrature sample counts (trapezoid rule along rays; midpoint rule on the sphere). The tests
// bound the resulting error against converged integrals (docs/atmosphere.md).
const int TRANSMITTANCE_SAMPLE_COUNT = 500;
const int SINGLE_SCATTERING_SAMPLE_COUNT = 50;
const int MULTIPLE_SCATTERING_SAMPLE_COUNT = 50;
const int SCATTERING_DENSITY_SAMPLE_COUNT = 16;  // zenith steps; 2x as many azimuth steps
const int INDIRECT_IRRADIANCE_SAMPLE_COUNT = 32; // zenith steps over the hemisphere; 2x azimuth

// ---------------------------------------------------------------------------------------------
// Clamping and ray-sphere distances.

Number ClampCosine(IN(Number) mu) { return clamp(mu, -1.0, 1.0); }
Number ClampDistance(IN(Number) d) { return max(d, 0.0); }
Number SafeSqrt(IN(Number) a) { return sqrt(max(a, 0.0)); }

Number ClampRadius(IN(AtmosphereParameters) atmosphere, IN(Number) r) {
  return clamp(r, atmosphere.bottom_radius, atmosphere.top_radius);
}

// Discriminant (per 4) of |x + d v| = R for |x| = r, v.x = r mu: R^2 - r^2 (1 - mu^2), in the
// cancellation-free form (R - r)(R + r) + (r mu)^2.
Number SphereDiscriminant(IN(Number) r, IN(Number) mu, IN(Number) radius) {
  return (radius - r) * (radius + r) + r * mu * r * mu;
}

// The two roots of |x + d v| = R, d^2 + 2 r mu d + r^2 - R^2 = 0, are -r mu -+ sqrt(disc); their
// product is r^2 - R^2 (Vieta). Of the two, the one whose terms have opposite signs cancels: for
// a camera h above the ground looking down, the near root -r mu - sqrt(disc) ~ h / |mu| is a
// difference of two numbers of size r |mu|, which loses r mu^2 / h ulps (measured in double: 5e8
// ulps at h = 1 cm, 2e5 at 30 m; docs/numerics.md, section 6); so is the top's root
// -r mu + sqrt(disc) ~ (top - r) / mu for a camera just below the top looking up. Each such root
// is computed instead as (r^2 - R^2) / (the other root), whose sum has terms of one sign (the
// product-of-roots form, as ocean/sea_surface.hpp does for the sea), with r^2 - R^2 as
// (r - R)(r + R), exact to one rounding.

// Distance (m) from a point at radius r to the top boundary along a ray of cosine mu (r inside).
Number DistanceToTopAtmosphereBoundary(IN(AtmosphereParameters) atmosphere, IN(Number) r,
                                       IN(Number) mu) {
  Number r_mu = r * mu;
  Number root = SafeSqrt(SphereDiscriminant(r, mu, atmosphere.top_radius));
  // mu > 0: the far root -r mu + root cancels; (top^2 - r^2) / (r mu + root) does not.
  if (r_mu > 0.0) {
    return ClampDistance((atmosphere.top_radius - r) * (atmosphere.top_radius + r) /
                         (r_mu + root));
  }
  return ClampDistance(root - r_mu);
}

// Distance (m) to the ground along a ray that intersects it (see RayIntersectsGround): the near
// root -r mu - sqrt(disc), as (r^2 - bottom^2) / (-r mu + sqrt(disc)), which does not cancel for
// mu < 0. 0 where the far root is not positive (rays that go up or are horizontal).
Number DistanceToBottomAtmosphereBoundary(IN(AtmosphereParameters) atmosphere, IN(Number) r,
                                          IN(Number) mu) {
  Number far_root = SafeSqrt(SphereDiscriminant(r, mu, atmosphere.bottom_radius)) - r * mu;
  if (far_root <= 0.0) return 0.0;
  return ClampDistance((r - atmosphere.bottom_radius) * (r + atmosphere.bottom_radius) / far_root);
}

bool RayIntersectsGround(IN(AtmosphereParameters) atmosphere, IN(Number) r, IN(Number) mu) {
  return mu < 0.0 && SphereDiscriminant(r, mu, atmosphere.bottom_radius) >= 0.0;
}

Number DistanceToNearestAtmosphereBoundary(IN(AtmosphereParameters) atmosphere, IN(Number) r,
                                           IN(Number) mu, bool ray_r_mu_intersects_ground) {
  if (ray_r_mu_intersects_ground) return DistanceToBottomAtmosphereBoundary(atmosphere, r, mu);
  return DistanceToTopAtmosphereBoundary(atmosphere, r, mu);
}

// ---------------------------------------------------------------------------------------------
// Densities and transmittance.

Number GetLayerDensity(IN(DensityProfileLayer) layer, IN(Number) altitude) {
  Number density = layer.exp_term * exp(layer.exp_scale * altitude) +
                   layer.linear_term * altitude + layer.constant_term;
  return clamp(density, 0.0, 1.0);
}

Number GetProfileDensity(IN(DensityProfile) profile, IN(Number) altitude) {
  return altitude < profile.lower.width ? GetLayerDensity(profile.lower, altitude)
                                        : GetLayerDensity(profile.upper, altitude);
}

// Integral of a density profile (m) along the ray from (r, mu) to the top boundary, trapezoid
// rule. The altitude of the sample at distance d is sqrt(d^2 + 2 r mu d + r^2) - R.
Number ComputeOpticalLengthToTopAtmosphereBoundary(IN(AtmosphereParameters) atmosphere,
                                                   IN(DensityProfile) profile, IN(Number) r,
                                                   IN(Number) mu) {
  Number dx = DistanceToTopAtmosphereBoundary(atmosphere, r, mu) /
              Number(TRANSMITTANCE_SAMPLE_COUNT);
  Number result = 0.0;
  for (int i = 0; i <= TRANSMITTANCE_SAMPLE_COUNT; ++i) {
    Number d_i = Number(i) * dx;
    Number r_i = sqrt(d_i * d_i + 2.0 * r * mu * d_i + r * r);
    Number y_i = GetProfileDensity(profile, r_i - atmosphere.bottom_radius);
    Number weight_i = i == 0 || i == TRANSMITTANCE_SAMPLE_COUNT ? 0.5 : 1.0;
    result += y_i * weight_i * dx;
  }
  return result;
}

vec3 ComputeTransmittanceToTopAtmosphereBoundary(IN(AtmosphereParameters) atmosphere,
                                                 IN(Number) r, IN(Number) mu) {
  return exp(-(atmosphere.rayleigh_scattering *
                   ComputeOpticalLengthToTopAtmosphereBoundary(
                       atmosphere, atmosphere.rayleigh_density, r, mu) +
               atmosphere.mie_extinction *
                   ComputeOpticalLengthToTopAtmosphereBoundary(atmosphere,
                                                               atmosphere.mie_density, r, mu) +
               atmosphere.absorption_extinction *
                   ComputeOpticalLengthToTopAtmosphereBoundary(
                       atmosphere, atmosphere.absorption_density, r, mu)));
}

// Texel-centre mappings: a unit-range value x in [0, 1] is stored so that x = 0 and x = 1 fall
// on the first and last texel centres (no extrapolation at the table's edges).
Number GetTextureCoordFromUnitRange(IN(Number) x, IN(int) texture_size) {
  return 0.5 / Number(texture_size) + x * (1.0 - 1.0 / Number(texture_size));
}

Number GetUnitRangeFromTextureCoord(IN(Number) u, IN(int) texture_size) {
  return (u - 0.5 / Number(texture_size)) / (1.0 - 1.0 / Number(texture_size));
}

// Transmittance table parameterisation (Bruneton 2017): with H the distance from the ground to
// the top boundary along the horizontal at the top (sqrt(top^2 - bottom^2)), rho the distance to
// the ground's horizon from r, and d the distance to the top along (r, mu): x_r = rho / H and
// x_mu = (d - d_min) / (d_max - d_min), d_min = top - r, d_max = rho + H. Both are in [0, 1] for
// every ray that does not hit the ground, and resolve the horizon and the ground finely.
vec2 GetTransmittanceTextureUvFromRMu(IN(AtmosphereParameters) atmosphere, IN(Number) r,
                                      IN(Number) mu) {
  Number H = sqrt((atmosphere.top_radius - atmosphere.bottom_radius) *
                  (atmosphere.top_radius + atmosphere.bottom_radius));
  Number rho = SafeSqrt((r - atmosphere.bottom_radius) * (r + atmosphere.bottom_radius));
  Number d = DistanceToTopAtmosphereBoundary(atmosphere, r, mu);
  Number d_min = atmosphere.top_radius - r;
  Number d_max = rho + H;
  Number x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
  Number x_r = rho / H;
  return vec2(GetTextureCoordFromUnitRange(x_mu, TRANSMITTANCE_TEXTURE_WIDTH),
              GetTextureCoordFromUnitRange(x_r, TRANSMITTANCE_TEXTURE_HEIGHT));
}

void GetRMuFromTransmittanceTextureUv(IN(AtmosphereParameters) atmosphere, IN(vec2) uv,
                                      OUT(Number) r, OUT(Number) mu) {
  Number x_mu = GetUnitRangeFromTextureCoord(uv.x, TRANSMITTANCE_TEXTURE_WIDTH);
  Number x_r = GetUnitRangeFromTextureCoord(uv.y, TRANSMITTANCE_TEXTURE_HEIGHT);
  Number H = sqrt((atmosphere.top_radius - atmosphere.bottom_radius) *
                  (atmosphere.top_radius + atmosphere.bottom_radius));
  Number rho = H * x_r;
  r = sqrt(rho * rho + atmosphere.bottom_radius * atmosphere.bottom_radius);
  Number d_min = atmosphere.top_radius - r;
  Number d_max = rho + H;
  Number d = d_min + x_mu * (d_max - d_min);
  // From d^2 + 2 r mu d + r^2 = top^2: mu = (H^2 - rho^2 - d^2) / (2 r d); d = 0 only at the top
  // looking straight up.
  mu = d == 0.0 ? 1.0 : (H * H - rho * rho - d * d) / (2.0 * r * d);
  mu = ClampCosine(mu);
}

vec3 ComputeTransmittanceToTopAtmosphereBoundaryTexture(IN(AtmosphereParameters) atmosphere,
                                                        IN(vec2) frag_coord) {
  const vec2 TRANSMITTANCE_TEXTURE_SIZE =
      vec2(TRANSMITTANCE_TEXTURE_WIDTH, TRANSMITTANCE_TEXTURE_HEIGHT);
  Number r;
  Number mu;
  GetRMuFromTransmittanceTextureUv(atmosphere, frag_coord / TRANSMITTANCE_TEXTURE_SIZE, r, mu);
  return ComputeTransmittanceToTopAtmosphereBoundary(atmosphere, r, mu);
}

vec3 GetTransmittanceToTopAtmosphereBoundary(IN(AtmosphereParameters) atmosphere,
                                             IN(TransmittanceTexture) transmittance_texture,
                                             IN(Number) r, IN(Number) mu) {
  vec2 uv = GetTransmittanceTextureUvFromRMu(atmosphere, r, mu);
  vec4 t = texture(transmittance_texture, uv);
  return vec3(t.x, t.y, t.z);
}

// Transmittance between (r, mu) and the point at distance d along the ray, as a ratio of two
// transmittances to the top (or, for rays that hit the ground, of the reversed rays, whose
// transmittances to the top are defined). Clamped to 1: interpolation can make the ratio exceed
// it by a texel's error.
vec3 GetTransmittance(IN(AtmosphereParameters) atmosphere,
                      IN(TransmittanceTexture) transmittance_texture, IN(Number) r, IN(Number) mu,
                      IN(Number) d, bool ray_r_mu_intersects_ground) {
  Number r_d = ClampRadius(atmosphere, sqrt(d * d + 2.0 * r * mu * d + r * r));
  Number mu_d = ClampCosine((r * mu + d) / r_d);
  if (ray_r_mu_intersects_ground) {
    return min(GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture, r_d,
                                                       -mu_d) /
                   GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture, r,
                                                           -mu),
               vec3(1.0));
  }
  return min(GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture, r, mu) /
                 GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture, r_d,
                                                         mu_d),
             vec3(1.0));
}

// Transmittance of the sun's light to a point at r with sun cosine mu_s, times the visible
// fraction of the sun's disc: the disc is approximated as a band of height 2 alpha_s around the
// horizon's cosine, which fades the sun linearly as it sets behind the planet.
vec3 GetTransmittanceToSun(IN(AtmosphereParameters) atmosphere,
                           IN(TransmittanceTexture) transmittance_texture, IN(Number) r,
                           IN(Number) mu_s) {
  Number sin_theta_h = atmosphere.bottom_radius / r;
  Number cos_theta_h = -SafeSqrt(1.0 - sin_theta_h * sin_theta_h);
  return GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture, r, mu_s) *
         smoothstep(-sin_theta_h * atmosphere.sun_angular_radius,
                    sin_theta_h * atmosphere.sun_angular_radius, mu_s - cos_theta_h);
}

// ---------------------------------------------------------------------------------------------
// Phase functions (sr^-1, normalised to 1 over the sphere).

Number RayleighPhaseFunction(IN(Number) nu) {
  return 3.0 / (16.0 * PI) * (1.0 + nu * nu);
}

// Cornette & Shanks (1992), "Physically reasonable analytic expression for the single-scattering
// phase function", Applied Optics 31(16), eq. 4.
Number MiePhaseFunction(IN(Number) g, IN(Number) nu) {
  Number k = 3.0 / (8.0 * PI) * (1.0 - g * g) / (2.0 + g * g);
  Number denominator = max(1.0 + g * g - 2.0 * g * nu, 1e-12);  // > 0 for |g| < 1
  return k * (1.0 + nu * nu) / (denominator * sqrt(denominator));
}

// ---------------------------------------------------------------------------------------------
// Single scattering.

void ComputeSingleScatteringIntegrand(IN(AtmosphereParameters) atmosphere,
                                      IN(TransmittanceTexture) transmittance_texture,
                                      IN(Number) r, IN(Number) mu, IN(Number) mu_s, IN(Number) nu,
                                      IN(Number) d, bool ray_r_mu_intersects_ground,
                                      OUT(vec3) rayleigh, OUT(vec3) mie) {
  Number r_d = ClampRadius(atmosphere, sqrt(d * d + 2.0 * r * mu * d + r * r));
  Number mu_s_d = ClampCosine((r * mu_s + d * nu) / r_d);
  vec3 transmittance =
      GetTransmittance(atmosphere, transmittance_texture, r, mu, d, ray_r_mu_intersects_ground) *
      GetTransmittanceToSun(atmosphere, transmittance_texture, r_d, mu_s_d);
  rayleigh = transmittance *
             GetProfileDensity(atmosphere.rayleigh_density, r_d - atmosphere.bottom_radius);
  mie = transmittance * GetProfileDensity(atmosphere.mie_density, r_d - atmosphere.bottom_radius);
}

// Single scattering along (r, mu) to the nearest boundary, without phase functions: the
// integral of sun irradiance x transmittances x scattering coefficient, trapezoid rule.
void ComputeSingleScattering(IN(AtmosphereParameters) atmosphere,
                             IN(TransmittanceTexture) transmittance_texture, IN(Number) r,
                             IN(Number) mu, IN(Number) mu_s, IN(Number) nu,
                             bool ray_r_mu_intersects_ground, OUT(vec3) rayleigh, OUT(vec3) mie) {
  Number dx = DistanceToNearestAtmosphereBoundary(atmosphere, r, mu, ray_r_mu_intersects_ground) /
              Number(SINGLE_SCATTERING_SAMPLE_COUNT);
  vec3 rayleigh_sum = vec3(0.0);
  vec3 mie_sum = vec3(0.0);
  for (int i = 0; i <= SINGLE_SCATTERING_SAMPLE_COUNT; ++i) {
    Number d_i = Number(i) * dx;
    vec3 rayleigh_i;
    vec3 mie_i;
    ComputeSingleScatteringIntegrand(atmosphere, transmittance_texture, r, mu, mu_s, nu, d_i,
                                     ray_r_mu_intersects_ground, rayleigh_i, mie_i);
    Number weight_i = (i == 0 || i == SINGLE_SCATTERING_SAMPLE_COUNT) ? 0.5 : 1.0;
    rayleigh_sum += rayleigh_i * weight_i;
    mie_sum += mie_i * weight_i;
  }
  rayleigh = rayleigh_sum * dx * atmosphere.solar_irradiance * atmosphere.rayleigh_scattering;
  mie = mie_sum * dx * atmosphere.solar_irradiance * atmosphere.mie_scattering;
}

// Scattering table parameterisation (Bruneton 2017). r as for transmittance. mu: rays that hit
// the ground use the lower half of the axis (distance to the ground, from the horizon's r - R
// to rho), the others the upper half (distance to the top, from top - r to rho + H), so the
// discontinuity at the horizon falls between texels. mu_s: through the distance to the top along
// the sun's direction at the ground, normalised so that mu_s_min maps to 1 (finer near the
// horizon). nu: linear.
vec4 GetScatteringTextureUvwzFromRMuMuSNu(IN(AtmosphereParameters) atmosphere, IN(Number) r,
                                          IN(Number) mu, IN(Number) mu_s, IN(Number) nu,
                                          bool ray_r_mu_intersects_ground) {
  Number H = sqrt((atmosphere.top_radius - atmosphere.bottom_radius) *
                  (atmosphere.top_radius + atmosphere.bottom_radius));
  Number rho = SafeSqrt((r - atmosphere.bottom_radius) * (r + atmosphere.bottom_radius));
  Number u_r = GetTextureCoordFromUnitRange(rho / H, SCATTERING_TEXTURE_R_SIZE);

  Number r_mu = r * mu;
  Number discriminant = SphereDiscriminant(r, mu, atmosphere.bottom_radius);
  Number u_mu;
  if (ray_r_mu_intersects_ground) {
    Number d = DistanceToBottomAtmosphereBoundary(atmosphere, r, mu);  // no cancellation
    Number d_min = r - atmosphere.bottom_radius;
    Number d_max = rho;
    u_mu = 0.5 - 0.5 * GetTextureCoordFromUnitRange(
                           d_max == d_min ? 0.0 : (d - d_min) / (d_max - d_min),
                           SCATTERING_TEXTURE_MU_SIZE / 2);
  } else {
    Number d = -r_mu + SafeSqrt(discriminant + H * H);
    Number d_min = atmosphere.top_radius - r;
    Number d_max = rho + H;
    u_mu = 0.5 + 0.5 * GetTextureCoordFromUnitRange((d - d_min) / (d_max - d_min),
                                                    SCATTERING_TEXTURE_MU_SIZE / 2);
  }

  Number d = DistanceToTopAtmosphereBoundary(atmosphere, atmosphere.bottom_radius, mu_s);
  Number d_min = atmosphere.top_radius - atmosphere.bottom_radius;
  Number d_max = H;
  Number a = (d - d_min) / (d_max - d_min);
  Number D = DistanceToTopAtmosphereBoundary(atmosphere, atmosphere.bottom_radius,
                                             atmosphere.mu_s_min);
  Number A = (D - d_min) / (d_max - d_min);
  // a in [0, A] for mu_s in [1, mu_s_min]; (1 - a / A) / (1 + a) maps it onto [1, 0],
  // stretched near the horizon. Sun zeniths beyond mu_s_min clamp to the last texel.
  Number u_mu_s =
      GetTextureCoordFromUnitRange(max(1.0 - a / A, 0.0) / (1.0 + a), SCATTERING_TEXTURE_MU_S_SIZE);
  Number u_nu = (nu + 1.0) / 2.0;
  return vec4(u_nu, u_mu_s, u_mu, u_r);
}

void GetRMuMuSNuFromScatteringTextureUvwz(IN(AtmosphereParameters) atmosphere, IN(vec4) uvwz,
                                          OUT(Number) r, OUT(Number) mu, OUT(Number) mu_s,
                                          OUT(Number) nu, OUT(bool) ray_r_mu_intersects_ground) {
  Number H = sqrt((atmosphere.top_radius - atmosphere.bottom_radius) *
                  (atmosphere.top_radius + atmosphere.bottom_radius));
  Number rho = H * GetUnitRangeFromTextureCoord(uvwz.w, SCATTERING_TEXTURE_R_SIZE);
  r = sqrt(rho * rho + atmosphere.bottom_radius * atmosphere.bottom_radius);

  if (uvwz.z < 0.5) {
    Number d_min = r - atmosphere.bottom_radius;
    Number d_max = rho;
    Number d = d_min + (d_max - d_min) * GetUnitRangeFromTextureCoord(
                                             1.0 - 2.0 * uvwz.z, SCATTERING_TEXTURE_MU_SIZE / 2);
    mu = d == 0.0 ? -1.0 : ClampCosine(-(rho * rho + d * d) / (2.0 * r * d));
    ray_r_mu_intersects_ground = true;
  } else {
    Number d_min = atmosphere.top_radius - r;
    Number d_max = rho + H;
    Number d = d_min + (d_max - d_min) * GetUnitRangeFromTextureCoord(
                                             2.0 * uvwz.z - 1.0, SCATTERING_TEXTURE_MU_SIZE / 2);
    mu = d == 0.0 ? 1.0 : ClampCosine((H * H - rho * rho - d * d) / (2.0 * r * d));
    ray_r_mu_intersects_ground = false;
  }

  Number x_mu_s = GetUnitRangeFromTextureCoord(uvwz.y, SCATTERING_TEXTURE_MU_S_SIZE);
  Number d_min = atmosphere.top_radius - atmosphere.bottom_radius;
  Number d_max = H;
  Number D = DistanceToTopAtmosphereBoundary(atmosphere, atmosphere.bottom_radius,
                                             atmosphere.mu_s_min);
  Number A = (D - d_min) / (d_max - d_min);
  Number a = (A - x_mu_s * A) / (1.0 + x_mu_s * A);
  Number d = d_min + min(a, A) * (d_max - d_min);
  mu_s = d == 0.0 ? 1.0
                  : ClampCosine((H * H - d * d) / (2.0 * atmosphere.bottom_radius * d));
  nu = ClampCosine(uvwz.x * 2.0 - 1.0);
}

// The (r, mu, mu_s, nu) of a scattering-table texel (frag_coord: texel centre, (i + 0.5)). nu
// is clamped to the range that mu and mu_s allow (|angle(view, sun)| between the difference and
// the sum of their zenith angles), so every texel is a realisable geometry.
void GetRMuMuSNuFromScatteringTextureFragCoord(IN(AtmosphereParameters) atmosphere,
                                               IN(vec3) frag_coord, OUT(Number) r, OUT(Number) mu,
                                               OUT(Number) mu_s, OUT(Number) nu,
                                               OUT(bool) ray_r_mu_intersects_ground) {
  Number frag_coord_nu = floor(frag_coord.x / Number(SCATTERING_TEXTURE_MU_S_SIZE));
  Number frag_coord_mu_s = mod(frag_coord.x, Number(SCATTERING_TEXTURE_MU_S_SIZE));
  vec4 uvwz = vec4(frag_coord_nu / Number(SCATTERING_TEXTURE_NU_SIZE - 1),
                   frag_coord_mu_s / Number(SCATTERING_TEXTURE_MU_S_SIZE),
                   frag_coord.y / Number(SCATTERING_TEXTURE_MU_SIZE),
                   frag_coord.z / Number(SCATTERING_TEXTURE_R_SIZE));
  GetRMuMuSNuFromScatteringTextureUvwz(atmosphere, uvwz, r, mu, mu_s, nu,
                                       ray_r_mu_intersects_ground);
  nu = clamp(nu, mu * mu_s - SafeSqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s)),
             mu * mu_s + SafeSqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s)));
}

void ComputeSingleScatteringTexture(IN(AtmosphereParameters) atmosphere,
                                    IN(TransmittanceTexture) transmittance_texture,
                                    IN(vec3) frag_coord, OUT(vec3) rayleigh, OUT(vec3) mie) {
  Number r;
  Number mu;
  Number mu_s;
  Number nu;
  bool ray_r_mu_intersects_ground;
  GetRMuMuSNuFromScatteringTextureFragCoord(atmosphere, frag_coord, r, mu, mu_s, nu,
                                            ray_r_mu_intersects_ground);
  ComputeSingleScattering(atmosphere, transmittance_texture, r, mu, mu_s, nu,
                          ray_r_mu_intersects_ground, rayleigh, mie);
}

// A 4D lookup: linear in nu between the two slices of the 3D texture that bracket it.
vec3 GetScattering(IN(AtmosphereParameters) atmosphere, IN(ScatteringTexture) scattering_texture,
                   IN(Number) r, IN(Number) mu, IN(Number) mu_s, IN(Number) nu,
                   bool ray_r_mu_intersects_ground) {
  vec4 uvwz = GetScatteringTextureUvwzFromRMuMuSNu(atmosphere, r, mu, mu_s, nu,
                                                   ray_r_mu_intersects_ground);
  Number tex_coord_x = uvwz.x * Number(SCATTERING_TEXTURE_NU_SIZE - 1);
  Number tex_x = floor(tex_coord_x);
  Number lerp = tex_coord_x - tex_x;
  vec3 uvw0 = vec3((tex_x + uvwz.y) / Number(SCATTERING_TEXTURE_NU_SIZE), uvwz.z, uvwz.w);
  vec3 uvw1 = vec3((tex_x + 1.0 + uvwz.y) / Number(SCATTERING_TEXTURE_NU_SIZE), uvwz.z, uvwz.w);
  vec4 s = texture(scattering_texture, uvw0) * (1.0 - lerp) +
           texture(scattering_texture, uvw1) * lerp;
  return vec3(s.x, s.y, s.z);
}

// ---------------------------------------------------------------------------------------------
// Irradiance.

// Irradiance table parameterisation: linear in r and in mu_s over [-1, 1] (the ground receives
// sky light after sunset).
vec2 GetIrradianceTextureUvFromRMuS(IN(AtmosphereParameters) atmosphere, IN(Number) r,
                                    IN(Number) mu_s) {
  Number x_r = (r - atmosphere.bottom_radius) /
               (atmosphere.top_radius - atmosphere.bottom_radius);
  Number x_mu_s = mu_s * 0.5 + 0.5;
  return vec2(GetTextureCoordFromUnitRange(x_mu_s, IRRADIANCE_TEXTURE_WIDTH),
              GetTextureCoordFromUnitRange(x_r, IRRADIANCE_TEXTURE_HEIGHT));
}

void GetRMuSFromIrradianceTextureUv(IN(AtmosphereParameters) atmosphere, IN(vec2) uv,
                                    OUT(Number) r, OUT(Number) mu_s) {
  Number x_mu_s = GetUnitRangeFromTextureCoord(uv.x, IRRADIANCE_TEXTURE_WIDTH);
  Number x_r = GetUnitRangeFromTextureCoord(uv.y, IRRADIANCE_TEXTURE_HEIGHT);
  r = atmosphere.bottom_radius + x_r * (atmosphere.top_radius - atmosphere.bottom_radius);
  mu_s = ClampCosine(2.0 * x_mu_s - 1.0);
}

// Direct sun irradiance on a horizontal surface at r, with the sun's disc partly below the
// horizon (a linear ramp of the cosine factor over the disc's angular radius).
vec3 ComputeDirectIrradiance(IN(AtmosphereParameters) atmosphere,
                             IN(TransmittanceTexture) transmittance_texture, IN(Number) r,
                             IN(Number) mu_s) {
  Number alpha_s = atmosphere.sun_angular_radius;
  Number average_cosine_factor =
      mu_s < -alpha_s ? 0.0
                      : (mu_s > alpha_s ? mu_s : (mu_s + alpha_s) * (mu_s + alpha_s) /
                                                     (4.0 * alpha_s));
  return atmosphere.solar_irradiance *
         GetTransmittanceToTopAtmosphereBoundary(atmosphere, transmittance_texture, r, mu_s) *
         average_cosine_factor;
}

vec3 ComputeDirectIrradianceTexture(IN(AtmosphereParameters) atmosphere,
                                    IN(TransmittanceTexture) transmittance_texture,
                                    IN(vec2) frag_coord) {
  Number r;
  Number mu_s;
  GetRMuSFromIrradianceTextureUv(
      atmosphere, frag_coord / vec2(IRRADIANCE_TEXTURE_WIDTH, IRRADIANCE_TEXTURE_HEIGHT), r,
      mu_s);
  return ComputeDirectIrradiance(atmosphere, transmittance_texture, r, mu_s);
}

vec3 GetIrradiance(IN(AtmosphereParameters) atmosphere, IN(IrradianceTexture) irradiance_texture,
                   IN(Number) r, IN(Number) mu_s) {
  vec2 uv = GetIrradianceTextureUvFromRMuS(atmosphere, r, mu_s);
  vec4 e = texture(irradiance_texture, uv);
  return vec3(e.x, e.y, e.z);
}

// ---------------------------------------------------------------------------------------------
// Multiple scattering.

// Radiance of order `scattering_order - 1` arriving at (r, mu) from direction (mu, mu_s, nu),
// phase functions applied: from the single-scattering tables at order 2, from the previous
// order's multiple-scattering table (stored with phase functions already applied) beyond.
vec3 GetScatteringOfOrder(IN(AtmosphereParameters) atmosphere,
                          IN(ScatteringTexture) single_rayleigh_scattering_texture,
                          IN(ScatteringTexture) single_mie_scattering_texture,
                          IN(ScatteringTexture) multiple_scattering_texture, IN(Number) r,
                          IN(Number) mu, IN(Number) mu_s, IN(Number) nu,
                          bool ray_r_mu_intersects_ground, IN(int) scattering_order) {
  if (scattering_order == 1) {
    vec3 rayleigh = GetScattering(atmosphere, single_rayleigh_scattering_texture, r, mu, mu_s,
                                  nu, ray_r_mu_intersects_ground);
    vec3 mie = GetScattering(atmosphere, single_mie_scattering_texture, r, mu, mu_s, nu,
                             ray_r_mu_intersects_ground);
    return rayleigh * RayleighPhaseFunction(nu) +
           mie * MiePhaseFunction(atmosphere.mie_phase_g, nu);
  }
  return GetScattering(atmosphere, multiple_scattering_texture, r, mu, mu_s, nu,
                       ray_r_mu_intersects_ground);
}

// Directions of the sphere quadrature of the scattering density: cell (l, m) of a midpoint rule
// with SCATTERING_DENSITY_SAMPLE_COUNT zenith steps (l) and twice as many azimuth steps (m), in
// a frame whose z is the local zenith and whose xz half-plane (x > 0) holds the sun. `domega` is
// the cell's solid angle (sr).
vec3 ScatteringDensityDirection(IN(int) l, IN(int) m, OUT(Number) domega) {
  const Number dtheta = PI / Number(SCATTERING_DENSITY_SAMPLE_COUNT);
  const Number dphi = PI / Number(SCATTERING_DENSITY_SAMPLE_COUNT);
  Number theta = (Number(l) + 0.5) * dtheta;
  Number phi = (Number(m) + 0.5) * dphi;
  domega = dtheta * dphi * sin(theta);
  return vec3(cos(phi) * sin(theta), sin(phi) * sin(theta), cos(theta));
}

// The sun's direction in that frame, for a sun cosine mu_s.
vec3 ScatteringDensitySunDirection(IN(Number) mu_s) {
  return vec3(SafeSqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
}

// A view direction of cosine mu and cosine nu with the sun, in that frame (the one with y >= 0).
vec3 ScatteringDensityViewDirection(IN(Number) mu, IN(Number) mu_s, IN(Number) nu) {
  Number sin_s = SafeSqrt(1.0 - mu_s * mu_s);
  Number x = sin_s == 0.0 ? SafeSqrt(1.0 - mu * mu) : clamp((nu - mu * mu_s) / sin_s, -1.0, 1.0);
  return vec3(x, SafeSqrt(1.0 - x * x - mu * mu), mu);
}

// Radiance (W m^-2 sr^-1 nm^-1) of order `scattering_order - 1` arriving at radius r from the
// direction omega_i (in the frame above, for the sun cosine mu_s): scattered light of that order,
// plus, for directions that hit the ground, the light the ground reflects (transmittance to the
// ground x albedo / pi x the ground's irradiance of the order before, which includes the direct
// sun at order 2). By the atmosphere's spherical symmetry it depends on r, mu_s and omega_i only,
// which the precomputation uses: it evaluates it once per (r, mu_s) of the table rather than once
// per texel (atmosphere/src/precompute.cpp).
vec3 ComputeIncidentRadiance(IN(AtmosphereParameters) atmosphere,
                             IN(TransmittanceTexture) transmittance_texture,
                             IN(ScatteringTexture) single_rayleigh_scattering_texture,
                             IN(ScatteringTexture) single_mie_scattering_texture,
                             IN(ScatteringTexture) multiple_scattering_texture,
                             IN(IrradianceTexture) irradiance_texture, IN(Number) r,
                             IN(Number) mu_s, IN(vec3) omega_i, IN(int) scattering_order) {
  vec3 omega_s = ScatteringDensitySunDirection(mu_s);
  bool ray_r_theta_intersects_ground = RayIntersectsGround(atmosphere, r, omega_i.z);
  vec3 incident_radiance = GetScatteringOfOrder(
      atmosphere, single_rayleigh_scattering_texture, single_mie_scattering_texture,
      multiple_scattering_texture, r, omega_i.z, mu_s, ClampCosine(dot(omega_s, omega_i)),
      ray_r_theta_intersects_ground, scattering_order - 1);
  if (ray_r_theta_intersects_ground) {
    Number distance_to_ground = DistanceToBottomAtmosphereBoundary(atmosphere, r, omega_i.z);
    vec3 transmittance_to_ground = GetTransmittance(atmosphere, transmittance_texture, r,
                                                    omega_i.z, distance_to_ground, true);
    vec3 ground_point = vec3(0.0, 0.0, r) + distance_to_ground * omega_i;
    vec3 ground_normal = normalize(ground_point);
    vec3 ground_irradiance =
        GetIrradiance(atmosphere, irradiance_texture, atmosphere.bottom_radius,
                      ClampCosine(dot(ground_normal, omega_s)));
    incident_radiance +=
        transmittance_to_ground * atmosphere.ground_albedo * (1.0 / PI) * ground_irradiance;
  }
  return incident_radiance;
}

// The fraction of incident radiance from omega_i scattered toward -omega per unit length and
// solid angle (m^-1 sr^-1) at radius r: scattering coefficients times phase functions.
vec3 ScatteringDensityKernel(IN(AtmosphereParameters) atmosphere, IN(Number) r,
                             IN(Number) cos_angle) {
  Number rayleigh_density =
      GetProfileDensity(atmosphere.rayleigh_density, r - atmosphere.bottom_radius);
  Number mie_density = GetProfileDensity(atmosphere.mie_density, r - atmosphere.bottom_radius);
  return atmosphere.rayleigh_scattering * rayleigh_density * RayleighPhaseFunction(cos_angle) +
         atmosphere.mie_scattering * mie_density *
             MiePhaseFunction(atmosphere.mie_phase_g, cos_angle);
}

// The scattering density J (W m^-3 sr^-1 nm^-1) of order `scattering_order` at radius r toward
// the view direction of (mu, mu_s, nu): the incident radiance of the previous order from every
// direction times the kernel above, midpoint rule over the sphere.
vec3 ComputeScatteringDensity(IN(AtmosphereParameters) atmosphere,
                              IN(TransmittanceTexture) transmittance_texture,
                              IN(ScatteringTexture) single_rayleigh_scattering_texture,
                              IN(ScatteringTexture) single_mie_scattering_texture,
                              IN(ScatteringTexture) multiple_scattering_texture,
                              IN(IrradianceTexture) irradiance_texture, IN(Number) r,
                              IN(Number) mu, IN(Number) mu_s, IN(Number) nu,
                              IN(int) scattering_order) {
  vec3 omega = ScatteringDensityViewDirection(mu, mu_s, nu);
  vec3 density = vec3(0.0);
  for (int l = 0; l < SCATTERING_DENSITY_SAMPLE_COUNT; ++l) {
    for (int m = 0; m < 2 * SCATTERING_DENSITY_SAMPLE_COUNT; ++m) {
      Number domega_i;
      vec3 omega_i = ScatteringDensityDirection(l, m, domega_i);
      density += ComputeIncidentRadiance(atmosphere, transmittance_texture,
                                         single_rayleigh_scattering_texture,
                                         single_mie_scattering_texture,
                                         multiple_scattering_texture, irradiance_texture, r, mu_s,
                                         omega_i, scattering_order) *
                 ScatteringDensityKernel(atmosphere, r, dot(omega, omega_i)) * domega_i;
    }
  }
  return density;
}

// Multiple scattering of one order along (r, mu): the integral of the scattering density times
// the transmittance to the camera, trapezoid rule.
vec3 ComputeMultipleScattering(IN(AtmosphereParameters) atmosphere,
                               IN(TransmittanceTexture) transmittance_texture,
                               IN(ScatteringTexture) scattering_density_texture, IN(Number) r,
                               IN(Number) mu, IN(Number) mu_s, IN(Number) nu,
                               bool ray_r_mu_intersects_ground) {
  Number dx = DistanceToNearestAtmosphereBoundary(atmosphere, r, mu, ray_r_mu_intersects_ground) /
              Number(MULTIPLE_SCATTERING_SAMPLE_COUNT);
  vec3 rayleigh_mie_sum = vec3(0.0);
  for (int i = 0; i <= MULTIPLE_SCATTERING_SAMPLE_COUNT; ++i) {
    Number d_i = Number(i) * dx;
    Number r_i = ClampRadius(atmosphere, sqrt(d_i * d_i + 2.0 * r * mu * d_i + r * r));
    Number mu_i = ClampCosine((r * mu + d_i) / r_i);
    Number mu_s_i = ClampCosine((r * mu_s + d_i * nu) / r_i);
    vec3 rayleigh_mie_i =
        GetScattering(atmosphere, scattering_density_texture, r_i, mu_i, mu_s_i, nu,
                      ray_r_mu_intersects_ground) *
        GetTransmittance(atmosphere, transmittance_texture, r, mu, d_i,
                         ray_r_mu_intersects_ground) *
        dx;
    Number weight_i = (i == 0 || i == MULTIPLE_SCATTERING_SAMPLE_COUNT) ? 0.5 : 1.0;
    rayleigh_mie_sum += rayleigh_mie_i * weight_i;
  }
  return rayleigh_mie_sum;
}

// Indirect irradiance of order `scattering_order` on a horizontal surface at r: the previous
// order's radiance over the upper hemisphere, cosine-weighted, midpoint rule.
vec3 ComputeIndirectIrradiance(IN(AtmosphereParameters) atmosphere,
                               IN(ScatteringTexture) single_rayleigh_scattering_texture,
                               IN(ScatteringTexture) single_mie_scattering_texture,
                               IN(ScatteringTexture) multiple_scattering_texture, IN(Number) r,
                               IN(Number) mu_s, IN(int) scattering_order) {
  const Number dphi = PI / Number(INDIRECT_IRRADIANCE_SAMPLE_COUNT);
  const Number dtheta = PI / 2.0 / Number(INDIRECT_IRRADIANCE_SAMPLE_COUNT);
  vec3 result = vec3(0.0);
  vec3 omega_s = vec3(SafeSqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
  for (int j = 0; j < INDIRECT_IRRADIANCE_SAMPLE_COUNT; ++j) {
    Number theta = (Number(j) + 0.5) * dtheta;
    for (int i = 0; i < 2 * INDIRECT_IRRADIANCE_SAMPLE_COUNT; ++i) {
      Number phi = (Number(i) + 0.5) * dphi;
      vec3 omega = vec3(cos(phi) * sin(theta), sin(phi) * sin(theta), cos(theta));
      Number domega = dtheta * dphi * sin(theta);
      Number nu = dot(omega, omega_s);
      result += GetScatteringOfOrder(atmosphere, single_rayleigh_scattering_texture,
                                     single_mie_scattering_texture, multiple_scattering_texture,
                                     r, omega.z, mu_s, nu, false, scattering_order) *
                omega.z * domega;
    }
  }
  return result;
}

// ---------------------------------------------------------------------------------------------
// Rendering: sky radiance, aerial perspective, irradiance, from the precomputed tables.

// Moves `position` (m, planet-centred), if outside the atmosphere, to where `view_ray` enters it,
// and gives its radius r and r mu (m). False when the ray misses the atmosphere. The discriminant
// is written (top - r)(top + r) + (r mu)^2, as SphereDiscriminant, rather than r mu^2 - r^2 +
// top^2, whose two large squares cancel in float.
bool MoveIntoAtmosphere(IN(AtmosphereParameters) atmosphere, IN(vec3) view_ray,
                        INOUT(vec3) position, OUT(Number) r, OUT(Number) rmu) {
  r = length(position);
  rmu = dot(position, view_ray);
  if (r <= atmosphere.top_radius) return true;
  Number discriminant =
      rmu * rmu + (atmosphere.top_radius - r) * (atmosphere.top_radius + r);
  Number distance = -rmu - sqrt(max(discriminant, 0.0));
  if (discriminant < 0.0 || distance <= 0.0) return false;
  position = position + view_ray * distance;
  r = atmosphere.top_radius;
  rmu += distance;
  return true;
}

// The sky's radiance (without the sun's disc) seen from `camera` (m, planet-centred) along
// `view_ray`, and the transmittance to the top of the atmosphere or the ground along it. A
// camera outside the atmosphere is first moved to where the ray enters it; a ray that misses
// the atmosphere gets zero radiance and transmittance 1.
vec3 GetSkyRadiance(IN(AtmosphereParameters) atmosphere,
                    IN(TransmittanceTexture) transmittance_texture,
                    IN(ScatteringTexture) scattering_texture,
                    IN(ScatteringTexture) single_mie_scattering_texture, IN(vec3) camera,
                    IN(vec3) view_ray, IN(vec3) sun_direction, OUT(vec3) transmittance) {
  vec3 position = camera;
  Number r;
  Number rmu;
  if (!MoveIntoAtmosphere(atmosphere, view_ray, position, r, rmu)) {
    transmittance = vec3(1.0);
    return vec3(0.0);
  }
  Number mu = ClampCosine(rmu / r);
  Number mu_s = ClampCosine(dot(position, sun_direction) / r);
  Number nu = ClampCosine(dot(view_ray, sun_direction));
  bool ray_r_mu_intersects_ground = RayIntersectsGround(atmosphere, r, mu);

  transmittance = ray_r_mu_intersects_ground
                      ? vec3(0.0)
                      : GetTransmittanceToTopAtmosphereBoundary(atmosphere,
                                                                transmittance_texture, r, mu);
  vec3 scattering = GetScattering(atmosphere, scattering_texture, r, mu, mu_s, nu,
                                  ray_r_mu_intersects_ground);
  vec3 single_mie_scattering = GetScattering(atmosphere, single_mie_scattering_texture, r, mu,
                                             mu_s, nu, ray_r_mu_intersects_ground);
  return scattering * RayleighPhaseFunction(nu) +
         single_mie_scattering * MiePhaseFunction(atmosphere.mie_phase_g, nu);
}

// Aerial perspective: the radiance scattered toward `camera` between it and `point` (m,
// planet-centred), and the transmittance between them, as the difference of the scattering
// seen from the camera and from the point along the same ray (times the transmittance between).
vec3 GetSkyRadianceToPoint(IN(AtmosphereParameters) atmosphere,
                           IN(TransmittanceTexture) transmittance_texture,
                           IN(ScatteringTexture) scattering_texture,
                           IN(ScatteringTexture) single_mie_scattering_texture, IN(vec3) camera,
                           IN(vec3) point, IN(vec3) sun_direction, OUT(vec3) transmittance) {
  // A point at the camera has nothing in between (and no direction: normalize would give NaN).
  Number point_distance = length(point - camera);
  if (point_distance == 0.0) {
    transmittance = vec3(1.0);
    return vec3(0.0);
  }
  vec3 view_ray = (point - camera) / point_distance;
  vec3 position = camera;
  Number r;
  Number rmu;
  if (!MoveIntoAtmosphere(atmosphere, view_ray, position, r, rmu)) {
    transmittance = vec3(1.0);
    return vec3(0.0);
  }
  Number mu = ClampCosine(rmu / r);
  Number mu_s = ClampCosine(dot(position, sun_direction) / r);
  Number nu = ClampCosine(dot(view_ray, sun_direction));
  Number d = length(point - position);
  bool ray_r_mu_intersects_ground = RayIntersectsGround(atmosphere, r, mu);

  transmittance =
      GetTransmittance(atmosphere, transmittance_texture, r, mu, d, ray_r_mu_intersects_ground);

  vec3 scattering = GetScattering(atmosphere, scattering_texture, r, mu, mu_s, nu,
                                  ray_r_mu_intersects_ground);
  vec3 single_mie_scattering = GetScattering(atmosphere, single_mie_scattering_texture, r, mu,
                                             mu_s, nu, ray_r_mu_intersects_ground);

  Number r_p = ClampRadius(atmosphere, sqrt(d * d + 2.0 * r * mu * d + r * r));
  Number mu_p = ClampCosine((r * mu + d) / r_p);
  Number mu_s_p = ClampCosine((r * mu_s + d * nu) / r_p);
  vec3 scattering_p = GetScattering(atmosphere, scattering_texture, r_p, mu_p, mu_s_p, nu,
                                    ray_r_mu_intersects_ground);
  vec3 single_mie_scattering_p = GetScattering(atmosphere, single_mie_scattering_texture, r_p,
                                               mu_p, mu_s_p, nu, ray_r_mu_intersects_ground);
  // The difference can dip below zero by the tables' interpolation error: clamp.
  scattering = max(scattering - transmittance * scattering_p, vec3(0.0));
  single_mie_scattering =
      max(single_mie_scattering - transmittance * single_mie_scattering_p, vec3(0.0));
  return scattering * RayleighPhaseFunction(nu) +
         single_mie_scattering * MiePhaseFunction(atmosphere.mie_phase_g, nu);
}

// Sun and sky irradiance (W m^-2 nm^-1) on a surface at `point` (m, planet-centred) with unit
// `normal`: the sky part from the horizontal-surface table scaled by (1 + n.up) / 2 (the part of
// the sky a tilted surface sees, for an isotropic sky), the sun part with the visible fraction of
// its disc.
vec3 GetSunAndSkyIrradiance(IN(AtmosphereParameters) atmosphere,
                            IN(TransmittanceTexture) transmittance_texture,
                            IN(IrradianceTexture) irradiance_texture, IN(vec3) point,
                            IN(vec3) normal, IN(vec3) sun_direction,
                            OUT(vec3) sky_irradiance) {
  Number r = length(point);
  Number mu_s = ClampCosine(dot(point, sun_direction) / r);
  // max: for a normal facing straight down, 1 + n.up rounds to -1e-16, not 0.
  sky_irradiance = GetIrradiance(atmosphere, irradiance_texture, r, mu_s) *
                   max(1.0 + dot(normal, point) / r, 0.0) * 0.5;
  return atmosphere.solar_irradiance *
         GetTransmittanceToSun(atmosphere, transmittance_texture, r, mu_s) *
         max(dot(normal, sun_direction), 0.0);
}

#endif  // THALASSA_ATMOSPHERE_MODEL_GLSL
