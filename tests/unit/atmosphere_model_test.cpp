// Tests of the physical atmosphere (issue 4, point 2): the double-precision model of
// shaders/atmosphere/model.glsl compiled as C++ and its precomputed tables, against closed forms
// (vertical transmittance of exponential and tent profiles, Bodhaine's Rayleigh optical depth),
// brute-force integrals (single scattering along the ray, the ground's irradiance over the
// hemisphere) and identities (the factored scattering density, the sun's vertical plane as a
// mirror), plus the order-by-order convergence of multiple scattering, finiteness everywhere,
// the table cache and parameter validation.
//
// Frames and units: positions planet-centred in metres; r a radius, mu / mu_s / nu cosines of
// the view zenith, sun zenith and view-sun angles (model.glsl); radiance in
// W m^-2 sr^-1 nm^-1, irradiance in W m^-2 nm^-1, RGB at 680, 550, 440 nm.
//
// Every test shares one model with the Earth defaults (Model()), loaded from the cache of
// $THALASSA_CACHE_DIR (ctest's fixture `atmosphere_tables` precomputes it first; see
// tests/CMakeLists.txt). Each bound is a measured value with a margin, the measurement in the
// comment beside it; docs/atmosphere.md collects them.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "gauss_legendre.hpp"
#include "model_cache.hpp"
#include "model_tables.hpp"
#include "precompute.hpp"
#include "reference_test_support.hpp"
#include "thalassa/atmosphere/model.hpp"

namespace thalassa::atmosphere {
namespace {

using glsl::vec3;
using glsl::test::IsFiniteNonNegative;
using glsl::test::RelativeDifference;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

// The one model of this process: the Earth defaults, from the cache (or precomputed and cached).
const AtmosphereModel& Model() {
  static const std::shared_ptr<const AtmosphereModel> model =
      AtmosphereModel::create(AtmosphereParameters::earth());
  return *model;
}

// The shared code's parameters of that model.
const glsl::AtmosphereParameters& Atmosphere() {
  static const glsl::AtmosphereParameters atmosphere = to_glsl(Model().parameters());
  return atmosphere;
}

const ModelTables& Tables() { return Model().tables(); }

double MaxComponent(const vec3& v) { return std::max({v.x, v.y, v.z}); }

double MaxRelativeDifference(const vec3& a, const vec3& b) {
  return std::max(
      {RelativeDifference(a.x, b.x), RelativeDifference(a.y, b.y), RelativeDifference(a.z, b.z)});
}

// |a - b| / max(|b|, floor), componentwise maximum: a relative error that does not blow up where
// the reference is negligible (floor: a radiance below which errors do not matter).
double FlooredRelativeDifference(const vec3& a, const vec3& b, double floor) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    worst = std::max(worst, std::abs(a[c] - b[c]) / std::max(std::abs(b[c]), floor));
  }
  return worst;
}

// ---------------------------------------------------------------------------------------------
// Closed forms of the vertical optical depth.

// The ozone tent of parameters.cpp: density 0 below 10 km, rising linearly to 1 at 25 km and
// back to 0 at 40 km (m). The test below checks the model's profile against it.
constexpr double kOzoneBottom = 10000.0;
constexpr double kOzonePeak = 25000.0;
constexpr double kOzoneTop = 40000.0;

// Integral of the tent from altitude 0 to x (m): (x - 10 km)^2 / 30 km on the rising side, the
// full rising half (7.5 km) plus the part of the falling half below x above the peak.
double OzoneTentIntegral(double x) {
  const double half_width = kOzonePeak - kOzoneBottom;
  if (x <= kOzoneBottom) return 0.0;
  if (x <= kOzonePeak) return (x - kOzoneBottom) * (x - kOzoneBottom) / (2.0 * half_width);
  if (x <= kOzoneTop) {
    return half_width / 2.0 +
           (half_width * half_width - (kOzoneTop - x) * (kOzoneTop - x)) / (2.0 * half_width);
  }
  return half_width;
}

// Vertical optical depth from altitude h (m) to the top Z of an exponential profile of scale
// height H with coefficient beta at density 1: beta H (exp(-h / H) - exp(-Z / H)).
vec3 ExponentialColumn(const vec3& beta, double scale_height, double h, double top) {
  return beta * scale_height * (std::exp(-h / scale_height) - std::exp(-top / scale_height));
}

// The closed-form optical depth (all species) from altitude h to the top along the zenith.
vec3 VerticalOpticalDepth(const glsl::AtmosphereParameters& a, double h) {
  const double top = a.top_radius - a.bottom_radius;
  const double rayleigh_scale_height = -1.0 / a.rayleigh_density.upper.exp_scale;
  const double mie_scale_height = -1.0 / a.mie_density.upper.exp_scale;
  return ExponentialColumn(a.rayleigh_scattering, rayleigh_scale_height, h, top) +
         ExponentialColumn(a.mie_extinction, mie_scale_height, h, top) +
         a.absorption_extinction * (OzoneTentIntegral(top) - OzoneTentIntegral(h));
}

vec3 Exp(const vec3& v) { return vec3(std::exp(v.x), std::exp(v.y), std::exp(v.z)); }

TEST(AtmosphereTables, Precompute) {
  // The fixture of ctest (atmosphere_tables): builds or loads the shared tables once, before
  // every other test that needs them.
  const AtmosphereModel& model = Model();
  EXPECT_TRUE(model.cache_status() == "loaded" || model.cache_status() == "computed")
      << model.cache_status();
  EXPECT_TRUE(std::filesystem::exists(model.cache_path())) << model.cache_path();
  for (const std::vector<float>* data :
       {&Tables().transmittance.data(), &Tables().scattering.data(),
        &Tables().single_mie_scattering.data(), &Tables().irradiance.data()}) {
    ASSERT_FALSE(data->empty());
    EXPECT_TRUE(std::all_of(data->begin(), data->end(),
                            [](float v) { return std::isfinite(v) && v >= 0.0f; }));
  }
}

TEST(AtmosphereTransmittance, ProfilesAreTheDocumentedOnes) {
  // The closed forms below assume these shapes: exponential Rayleigh and Mie (one layer), the
  // ozone tent of 10-25-40 km.
  const glsl::AtmosphereParameters& a = Atmosphere();
  for (double h : {0.0, 1000.0, 8000.0, 30000.0}) {
    EXPECT_NEAR(glsl::GetProfileDensity(a.rayleigh_density, h), std::exp(-h / 8000.0), 1e-15);
    EXPECT_NEAR(glsl::GetProfileDensity(a.mie_density, h), std::exp(-h / 1200.0), 1e-15);
  }
  EXPECT_EQ(glsl::GetProfileDensity(a.absorption_density, 5000.0), 0.0);
  EXPECT_NEAR(glsl::GetProfileDensity(a.absorption_density, kOzoneBottom), 0.0, 1e-15);
  EXPECT_NEAR(glsl::GetProfileDensity(a.absorption_density, 17500.0), 0.5, 1e-15);
  EXPECT_NEAR(glsl::GetProfileDensity(a.absorption_density, kOzonePeak), 1.0, 1e-15);
  EXPECT_NEAR(glsl::GetProfileDensity(a.absorption_density, 32500.0), 0.5, 1e-15);
  EXPECT_NEAR(glsl::GetProfileDensity(a.absorption_density, kOzoneTop), 0.0, 1e-15);
  EXPECT_EQ(glsl::GetProfileDensity(a.absorption_density, 50000.0), 0.0);
}

TEST(AtmosphereTransmittance, VerticalPathMatchesClosedForm) {
  const glsl::AtmosphereParameters& a = Atmosphere();
  double worst_direct = 0.0;
  double worst_table = 0.0;
  for (double h : {0.0, 1000.0, 10000.0, 50000.0}) {
    const double r = a.bottom_radius + h;
    const vec3 expected = Exp(-VerticalOpticalDepth(a, h));
    const vec3 direct = glsl::ComputeTransmittanceToTopAtmosphereBoundary(a, r, 1.0);
    const vec3 table =
        glsl::GetTransmittanceToTopAtmosphereBoundary(a, Tables().transmittance, r, 1.0);
    worst_direct = std::max(worst_direct, MaxRelativeDifference(direct, expected));
    worst_table = std::max(worst_table, MaxRelativeDifference(table, expected));
  }
  std::printf("[ measured ] vertical transmittance: direct %.3g, table %.3g\n", worst_direct,
              worst_table);
  // The 500-step trapezoid's error, about (dx / H)^2 / 12 of the optical depth.
  EXPECT_LT(worst_direct, 1.5e-5);  // measured 9.0e-6
  // The table adds float storage and the linear interpolation in r between texel rows.
  EXPECT_LT(worst_table, 6e-5);  // measured 3.9e-5
}

TEST(AtmosphereTransmittance, RayleighOpticalDepthIsBodhaines) {
  // Bodhaine et al. (1999), eq. 30, lambda in micrometres, at 1013.25 hPa.
  auto bodhaine = [](double lambda) {
    const double l2 = lambda * lambda;
    return 0.0021520 * (1.0455996 - 341.29061 / l2 - 0.90230850 * l2) /
           (1.0 + 0.0027059889 / l2 - 85.968563 * l2);
  };
  const glsl::AtmosphereParameters& a = Atmosphere();
  const vec3 expected(bodhaine(glsl::RGB_WAVELENGTHS.x / 1000.0),
                      bodhaine(glsl::RGB_WAVELENGTHS.y / 1000.0),
                      bodhaine(glsl::RGB_WAVELENGTHS.z / 1000.0));
  const double top = a.top_radius - a.bottom_radius;
  const vec3 closed_form = ExponentialColumn(a.rayleigh_scattering, 8000.0, 0.0, top);
  const vec3 model = a.rayleigh_scattering * glsl::ComputeOpticalLengthToTopAtmosphereBoundary(
                                                 a, a.rayleigh_density, a.bottom_radius, 1.0);
  std::printf("[ measured ] Rayleigh optical depth vs Bodhaine: closed form %.3g, model %.3g\n",
              MaxRelativeDifference(closed_form, expected), MaxRelativeDifference(model, expected));
  // parameters.cpp quotes the formula's values to 6 significant digits.
  EXPECT_LT(MaxRelativeDifference(closed_form, expected), 2e-6);  // measured 9.6e-7
  // Plus the trapezoid's error.
  EXPECT_LT(MaxRelativeDifference(model, expected), 3e-5);  // measured 1.9e-5
}

TEST(AtmosphereTransmittance, TableMatchesDirectOffTexelCentres) {
  // (r, mu) on a grid between texel centres (fractions 0.3 and 0.7 of a texel), every ray that
  // does not hit the ground (the table's domain), compared with the 500-step direct integral.
  const glsl::AtmosphereParameters& a = Atmosphere();
  const int width = glsl::TRANSMITTANCE_TEXTURE_WIDTH;
  const int height = glsl::TRANSMITTANCE_TEXTURE_HEIGHT;
  double worst = 0.0;
  double worst_above = 0.0;  // rays with a transmittance above 1e-2 in every channel
  double worst_mu = 0.0, worst_r = 0.0;
  for (int y = 0; y + 1 < height; y += 3) {
    for (int x = 0; x + 1 < width; x += 5) {
      for (double f : {0.3, 0.7}) {
        const glsl::vec2 uv((x + 0.5 + f) / width, (y + 1.5 - f) / height);
        double r, mu;
        glsl::GetRMuFromTransmittanceTextureUv(a, uv, r, mu);
        if (glsl::RayIntersectsGround(a, r, mu)) continue;
        const vec3 direct = glsl::ComputeTransmittanceToTopAtmosphereBoundary(a, r, mu);
        const vec3 table =
            glsl::GetTransmittanceToTopAtmosphereBoundary(a, Tables().transmittance, r, mu);
        const double e = MaxRelativeDifference(table, direct);
        if (e > worst) {
          worst = e;
          worst_mu = mu;
          worst_r = r;
        }
        if (std::min({direct.x, direct.y, direct.z}) > 1e-2) worst_above = std::max(worst_above, e);
      }
    }
  }
  std::printf(
      "[ measured ] transmittance table vs direct: %.3g (at h %.0f m, mu %.5f), %.3g "
      "where T > 1e-2\n",
      worst, worst_r - a.bottom_radius, worst_mu, worst_above);
  // Worst near the horizon seen from high up, where T is ~1e-4 and varies fastest with mu.
  EXPECT_LT(worst, 0.1);          // measured 0.070 (h 55 km, mu -0.128)
  EXPECT_LT(worst_above, 0.008);  // measured 0.0051
}

// ---------------------------------------------------------------------------------------------
// Single scattering against a brute-force integral.

// Extinction (m^-1) at an altitude (m): Rayleigh + Mie + ozone.
vec3 ExtinctionAt(const glsl::AtmosphereParameters& a, double altitude) {
  return a.rayleigh_scattering * glsl::GetProfileDensity(a.rayleigh_density, altitude) +
         a.mie_extinction * glsl::GetProfileDensity(a.mie_density, altitude) +
         a.absorption_extinction * glsl::GetProfileDensity(a.absorption_density, altitude);
}

// Optical depth from radius r to the top of the atmosphere along a ray of cosine mu, or a
// negative value if the ray hits the ground (the planet's shadow). Independent of the model's
// trapezoid: Gauss-Legendre on the pieces between the distances where the ray crosses the
// ozone's kinks (10, 25, 40 km) and its point nearest to the centre, each piece split in two, so
// that every piece's integrand is smooth.
constexpr int kSunPathGaussPoints = 8;
vec3 OpticalDepthToTop(const glsl::AtmosphereParameters& a, double r, double mu) {
  if (mu < 0.0 && r * r * (mu * mu - 1.0) + a.bottom_radius * a.bottom_radius >= 0.0) {
    return vec3(-1.0);
  }
  static const test::Quadrature1d gauss = test::gauss_legendre(kSunPathGaussPoints);
  const double rmu = r * mu;
  const double length =
      -rmu + std::sqrt(std::max(rmu * rmu - r * r + a.top_radius * a.top_radius, 0.0));
  std::vector<double> breaks = {0.0, length};
  if (-rmu > 0.0 && -rmu < length) breaks.push_back(-rmu);  // nearest point to the centre
  for (double altitude : {kOzoneBottom, kOzonePeak, kOzoneTop}) {
    const double radius = a.bottom_radius + altitude;
    const double discriminant = rmu * rmu - r * r + radius * radius;
    if (discriminant < 0.0) continue;
    for (double d : {-rmu - std::sqrt(discriminant), -rmu + std::sqrt(discriminant)}) {
      if (d > 0.0 && d < length) breaks.push_back(d);
    }
  }
  std::sort(breaks.begin(), breaks.end());
  vec3 depth(0.0);
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    for (int half = 0; half < 2; ++half) {
      const double d0 = breaks[i] + 0.5 * half * (breaks[i + 1] - breaks[i]);
      const double d1 = d0 + 0.5 * (breaks[i + 1] - breaks[i]);
      const double mid = 0.5 * (d0 + d1), half_length = 0.5 * (d1 - d0);
      for (std::size_t k = 0; k < gauss.x.size(); ++k) {
        const double d = mid + half_length * gauss.x[k];
        const double r_d = std::sqrt(d * d + 2.0 * rmu * d + r * r);
        depth += ExtinctionAt(a, r_d - a.bottom_radius) * (gauss.w[k] * half_length);
      }
    }
  }
  return depth;
}

struct SingleScatteringSample {
  vec3 rayleigh;  // without phase function, W m^-2 sr^-1 nm^-1 x sr (as the model's tables)
  vec3 mie;
};

// Single scattering along (r, mu) to the nearest boundary with the sun at (mu_s, nu), in the
// model's convention (no phase functions): E_sun beta_s(x) T(camera, x) T_sun(x) integrated
// over the ray, trapezoid rule with `steps` steps; T along the view ray accumulated with the same
// rule, T to the sun from OpticalDepthToTop (0 in the planet's shadow: a point sun).
SingleScatteringSample BruteForceSingleScattering(const glsl::AtmosphereParameters& a, double r,
                                                  double mu, double mu_s, double nu, int steps) {
  const bool ground = glsl::RayIntersectsGround(a, r, mu);
  const double length = glsl::DistanceToNearestAtmosphereBoundary(a, r, mu, ground);
  const double dx = length / steps;
  vec3 view_depth(0.0);
  vec3 previous_extinction(0.0);
  vec3 rayleigh(0.0), mie(0.0);
  for (int i = 0; i <= steps; ++i) {
    const double d = i * dx;
    const double r_d = std::sqrt(d * d + 2.0 * r * mu * d + r * r);
    const double altitude = r_d - a.bottom_radius;
    const vec3 extinction = ExtinctionAt(a, altitude);
    if (i > 0) view_depth += 0.5 * (previous_extinction + extinction) * dx;
    previous_extinction = extinction;
    const double mu_s_d = std::clamp((r * mu_s + d * nu) / r_d, -1.0, 1.0);
    const vec3 sun_depth = OpticalDepthToTop(a, r_d, mu_s_d);
    if (sun_depth.x < 0.0) continue;
    const vec3 t = Exp(-(view_depth + sun_depth));
    const double weight = (i == 0 || i == steps) ? 0.5 : 1.0;
    rayleigh += t * glsl::GetProfileDensity(a.rayleigh_density, altitude) * weight;
    mie += t * glsl::GetProfileDensity(a.mie_density, altitude) * weight;
  }
  return {rayleigh * dx * a.solar_irradiance * a.rayleigh_scattering,
          mie * dx * a.solar_irradiance * a.mie_scattering};
}

// The worst errors of a set of geometries.
struct SingleScatteringErrors {
  double rayleigh = 0.0;          // ComputeSingleScattering's Rayleigh, relative (floored)
  double mie = 0.0;               // ComputeSingleScattering's Mie, relative (floored)
  double mie_table = 0.0;         // the single Mie table, relative (floored)
  double mie_table_in_sky = 0.0;  // the table's Mie error over the single-scattered radiance
};

TEST(AtmosphereSingleScattering, MatchesBruteForce) {
  const glsl::AtmosphereParameters& a = Atmosphere();
  // Converged: 20000 steps and 16 Gauss points per piece of the sun's path give the same worst
  // errors below to 3 digits as 2000 and 8 (measured).
  constexpr int kSteps = 4000;
  // Floors of the relative errors (the model's units, no phase function): below them an error
  // is invisible next to the sky's single scattering, ~1e-1 for Rayleigh at the zenith.
  constexpr double kRayleighFloor = 1e-3;
  constexpr double kMieFloor = 1e-4;
  SingleScatteringErrors day, twilight;  // sun zenith < 90 degrees, and 90 to 100
  int count = 0;
  for (double h : {0.0, 1000.0, 10000.0, 59000.0}) {
    const double r = a.bottom_radius + h;
    for (double view_zenith : {0.0, 60.0, 85.0, 90.0, 92.0, 95.0, 120.0, 180.0}) {
      const double mu = std::cos(view_zenith * kDegree);
      const bool ground = glsl::RayIntersectsGround(a, r, mu);
      if (glsl::DistanceToNearestAtmosphereBoundary(a, r, mu, ground) == 0.0) continue;
      for (double sun_zenith : {0.0, 60.0, 85.0, 90.0, 95.0, 100.0}) {
        const double mu_s = std::cos(sun_zenith * kDegree);
        for (double azimuth : {0.0, 120.0}) {
          // The view and the sun `azimuth` degrees apart around the zenith.
          const double nu =
              std::sqrt((1.0 - mu * mu) * (1.0 - mu_s * mu_s)) * std::cos(azimuth * kDegree) +
              mu * mu_s;
          const SingleScatteringSample brute =
              BruteForceSingleScattering(a, r, mu, mu_s, nu, kSteps);
          vec3 rayleigh, mie;
          glsl::ComputeSingleScattering(a, Tables().transmittance, r, mu, mu_s, nu, ground,
                                        rayleigh, mie);
          const vec3 mie_table =
              glsl::GetScattering(a, Tables().single_mie_scattering, r, mu, mu_s, nu, ground);
          const double rayleigh_phase = glsl::RayleighPhaseFunction(nu);
          const double mie_phase = glsl::MiePhaseFunction(a.mie_phase_g, nu);
          const vec3 sky = brute.rayleigh * rayleigh_phase + brute.mie * mie_phase;
          SingleScatteringErrors& e = sun_zenith < 90.0 ? day : twilight;
          e.rayleigh = std::max(
              e.rayleigh, FlooredRelativeDifference(rayleigh, brute.rayleigh, kRayleighFloor));
          e.mie = std::max(e.mie, FlooredRelativeDifference(mie, brute.mie, kMieFloor));
          e.mie_table =
              std::max(e.mie_table, FlooredRelativeDifference(mie_table, brute.mie, kMieFloor));
          e.mie_table_in_sky = std::max(
              e.mie_table_in_sky,
              FlooredRelativeDifference(mie_table * mie_phase + brute.rayleigh * rayleigh_phase,
                                        sky, kRayleighFloor * rayleigh_phase));
          ++count;
        }
      }
    }
  }
  for (const auto& [name, e] : {std::pair{"day", day}, std::pair{"twilight", twilight}}) {
    std::printf(
        "[ measured ] single scattering (%d geometries), %s: Rayleigh %.3g, Mie %.3g, "
        "Mie table %.3g (%.3g of the sky)\n",
        count, name, e.rayleigh, e.mie, e.mie_table, e.mie_table_in_sky);
  }
  // ComputeSingleScattering's 50-step trapezoid: on paths through the whole atmosphere (looking
  // down from 59 km) a step is about the Mie scale height (1.2 km), hence Mie's larger error.
  EXPECT_LT(day.rayleigh, 0.035);  // measured 0.025
  EXPECT_LT(day.mie, 0.11);        // measured 0.086
  // The table adds the interpolation between its 32 r layers, across which the Mie density of
  // near-horizontal rays changes by a factor of ~4 (h 10 km), and in mu, mu_s, nu.
  EXPECT_LT(day.mie_table, 0.17);          // measured 0.132
  EXPECT_LT(day.mie_table_in_sky, 0.085);  // measured 0.066
  // Twilight adds the sun's disc fading over the horizon (the model) against a point sun (the
  // brute force) near the planet's shadow.
  EXPECT_LT(twilight.rayleigh, 0.15);          // measured 0.118
  EXPECT_LT(twilight.mie, 0.25);               // measured 0.192
  EXPECT_LT(twilight.mie_table, 0.25);         // measured 0.196
  EXPECT_LT(twilight.mie_table_in_sky, 0.18);  // measured 0.141
}

// ---------------------------------------------------------------------------------------------
// Multiple scattering.

TEST(AtmosphereMultipleScattering, FactoredDensityEqualsSharedFunction) {
  // precompute.cpp evaluates the incident radiance once per (r, mu_s) slice; the shared
  // ComputeScatteringDensity evaluates it per texel. Any tables work as inputs for this identity:
  // the model's final ones stand in for the previous order's.
  const glsl::AtmosphereParameters& a = Atmosphere();
  const ModelTables& t = Tables();
  double worst = 0.0;
  for (int order : {2, 3}) {
    for (const auto& [z, j] : {std::pair{0, 3}, std::pair{12, 17}, std::pair{31, 31}}) {
      const std::vector<vec3> slice =
          compute_density_slice(Model().parameters(), t.transmittance, t.scattering,
                                t.single_mie_scattering, t.scattering, t.irradiance, order, z, j);
      for (int y : {0, 31, 63, 64, 100, 127}) {
        for (int k : {0, 4, 7}) {
          const int x = k * glsl::SCATTERING_TEXTURE_MU_S_SIZE + j;
          double r, mu, mu_s, nu;
          bool ground;
          glsl::GetRMuMuSNuFromScatteringTextureFragCoord(a, vec3(x + 0.5, y + 0.5, z + 0.5), r, mu,
                                                          mu_s, nu, ground);
          const vec3 expected = glsl::ComputeScatteringDensity(
              a, t.transmittance, t.scattering, t.single_mie_scattering, t.scattering, t.irradiance,
              r, mu, mu_s, nu, order);
          ASSERT_GT(MaxComponent(expected), 0.0);
          worst = std::max(worst, MaxRelativeDifference(
                                      slice[y * glsl::SCATTERING_TEXTURE_NU_SIZE + k], expected));
        }
      }
    }
  }
  std::printf("[ measured ] factored density vs ComputeScatteringDensity: %.3g\n", worst);
  EXPECT_LT(worst, 1e-12);  // measured 9.8e-16
}

TEST(AtmosphereMultipleScattering, OrdersConverge) {
  // A second model with 3 orders (cached beside the first): at the texels of the zenith seen from
  // the sea, the default model's scattering table minus this one's is the 4th order alone, and
  // this one's minus the single Rayleigh scattering (recomputed at the texel exactly as the
  // precomputation did) is orders 2 and 3. The 4th order must be smaller than half of orders 2
  // and 3 together (it would be if each order were smaller than the one before) and those
  // smaller than the single scattering. Likewise for the ground's irradiance (orders 1 to 2 of
  // scattered light against the 3rd).
  AtmosphereParameters three_orders = AtmosphereParameters::earth();
  three_orders.scattering_orders = 3;
  const std::shared_ptr<const AtmosphereModel> model3 = AtmosphereModel::create(three_orders);
  const glsl::AtmosphereParameters& a = Atmosphere();
  const ModelTables& t4 = Tables();
  const ModelTables& t3 = model3->tables();
  const int y = glsl::SCATTERING_TEXTURE_MU_SIZE / 2;  // the zenith (d = d_min)
  double worst_order4 = 0.0, worst_orders23 = 0.0;
  for (int j = 0; j < glsl::SCATTERING_TEXTURE_MU_S_SIZE; ++j) {
    const int x = j;  // nu is clamped to mu_s at the zenith: any nu slice
    double r, mu, mu_s, nu;
    bool ground;
    glsl::GetRMuMuSNuFromScatteringTextureFragCoord(a, vec3(x + 0.5, y + 0.5, 0.5), r, mu, mu_s, nu,
                                                    ground);
    ASSERT_NEAR(mu, 1.0, 1e-12);
    if (mu_s < 0.1) continue;  // daylight (sun zenith < 84 degrees)
    vec3 single_rayleigh, single_mie;
    glsl::ComputeSingleScattering(a, t4.transmittance, r, mu, mu_s, nu, ground, single_rayleigh,
                                  single_mie);
    const vec3 single = single_rayleigh * glsl::RayleighPhaseFunction(nu) +
                        single_mie * glsl::MiePhaseFunction(a.mie_phase_g, nu);
    const vec3 orders23 =
        (t3.scattering.get(x, y, 0) - single_rayleigh) * glsl::RayleighPhaseFunction(nu);
    const vec3 order4 =
        (t4.scattering.get(x, y, 0) - t3.scattering.get(x, y, 0)) * glsl::RayleighPhaseFunction(nu);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(order4[c], 0.0) << "mu_s " << mu_s;
      worst_order4 = std::max(worst_order4, order4[c] / orders23[c]);
      worst_orders23 = std::max(worst_orders23, orders23[c] / single[c]);
    }
  }
  // Irradiance at the sea for the same suns: E(1..2) from the 3-order model, E(3) the difference.
  double worst_irradiance = 0.0;
  for (double mu_s : {0.1, 0.5, 1.0}) {
    const vec3 e12 = glsl::GetIrradiance(a, t3.irradiance, a.bottom_radius, mu_s);
    const vec3 e3 = glsl::GetIrradiance(a, t4.irradiance, a.bottom_radius, mu_s) - e12;
    for (int c = 0; c < 3; ++c) worst_irradiance = std::max(worst_irradiance, e3[c] / e12[c]);
  }
  std::printf(
      "[ measured ] zenith sky: order 4 / orders 2-3 %.3g, orders 2-3 / single %.3g; "
      "ground irradiance: order 3 / orders 1-2 %.3g\n",
      worst_order4, worst_orders23, worst_irradiance);
  EXPECT_LT(worst_order4, 0.5);      // measured 0.078
  EXPECT_LT(worst_orders23, 1.0);    // measured 0.48
  EXPECT_LT(worst_irradiance, 0.5);  // measured 0.081
}

// ---------------------------------------------------------------------------------------------
// Queries of AtmosphereModel.

// An orthonormal east-north-up frame at a planet-centred position (not on the polar axis).
struct LocalFrame {
  glm::dvec3 east, north, up;
};

LocalFrame FrameAt(const glm::dvec3& position) {
  LocalFrame f;
  f.up = glm::normalize(position);
  f.east = glm::normalize(glm::cross(glm::dvec3(0.0, 0.0, 1.0), f.up));
  f.north = glm::cross(f.up, f.east);
  return f;
}

// The direction of a zenith angle and an azimuth (clockwise from north), both in radians.
glm::dvec3 DirectionIn(const LocalFrame& f, double zenith, double azimuth) {
  return std::cos(zenith) * f.up +
         std::sin(zenith) * (std::cos(azimuth) * f.north + std::sin(azimuth) * f.east);
}

TEST(AtmosphereSky, SymmetricAboutTheSunsVerticalPlane) {
  // A camera at a general position (so that no coordinate is zero) and a sun at azimuth 37
  // degrees: the view at azimuth 37 + delta and its mirror image at 37 - delta must see the same
  // sky (mu, mu_s and nu are equal; only rounding differs).
  const AtmosphereModel& model = Model();
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const double sun_azimuth = 37.0 * kDegree;
  constexpr double kFloor = 1e-10;
  double worst = 0.0;
  for (double h : {0.0, 1000.0, 20000.0, 100000.0, 36.0e6}) {
    const glm::dvec3 camera = axis * (model.parameters().bottom_radius + h);
    const LocalFrame f = FrameAt(camera);
    for (double sun_zenith : {0.0, 45.0, 89.0, 95.0, 101.0}) {
      const glm::dvec3 sun = DirectionIn(f, sun_zenith * kDegree, sun_azimuth);
      for (double view_zenith : {10.0, 60.0, 89.5, 90.0, 93.0, 100.0, 150.0, 179.0}) {
        for (double delta : {5.0, 45.0, 90.0, 170.0}) {
          glm::dvec3 t1, t2;
          const glm::dvec3 l1 = model.sky_radiance(
              camera, DirectionIn(f, view_zenith * kDegree, sun_azimuth + delta * kDegree), sun,
              &t1);
          const glm::dvec3 l2 = model.sky_radiance(
              camera, DirectionIn(f, view_zenith * kDegree, sun_azimuth - delta * kDegree), sun,
              &t2);
          // Floor: 1e-10 (radiance ~1e-9 of the daylight sky's ~0.1, and transmittances of rays
          // grazing the ground from above, ~exp(-50), whose rounding is amplified by their
          // optical depth).
          worst = std::max({worst, FlooredRelativeDifference(l1, l2, kFloor),
                            FlooredRelativeDifference(t1, t2, kFloor)});
        }
      }
    }
  }
  std::printf("[ measured ] mirror symmetry: %.3g\n", worst);
  // Worst from 100 km along a ray that enters the atmosphere and grazes the planet: the entry
  // point's rounding (~1e-9 m) is amplified by the ray's optical depth (~14 in blue).
  EXPECT_LT(worst, 5e-12);  // measured 1.0e-12 (below 1e-13 from inside the atmosphere)
}

TEST(AtmosphereSky, FiniteAndNonNegativeEverywhere) {
  const AtmosphereModel& model = Model();
  const double bottom = model.parameters().bottom_radius;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(-0.2, 0.6, 0.7));
  int checked = 0;
  auto check = [&](const glm::dvec3& v, const char* what, double h, double vz, double sz) {
    ++checked;
    EXPECT_TRUE(IsFiniteNonNegative(v))
        << what << " at h " << h << " view zenith " << vz << " sun zenith " << sz << ": " << v.x
        << ' ' << v.y << ' ' << v.z;
  };
  for (double h : {0.0, 0.01, 1.0, 1000.0, 59900.0, 60000.0, 100000.0, 36.0e6}) {
    const double r = bottom + h;
    const glm::dvec3 camera = axis * r;
    const LocalFrame f = FrameAt(camera);
    // The view zeniths (rad): straight up, oblique, exactly horizontal, grazing the ground (the
    // horizon's dip from r), just below it, steeply down and straight down.
    const double horizon = kPi - std::asin(std::min(bottom / r, 1.0));
    std::vector<double> view_zeniths = {
        0.0, 0.5, kPi / 2.0, horizon, horizon - 1e-9, horizon + 1e-9, 2.5, kPi};
    for (double sun_zenith_deg = 0.0; sun_zenith_deg <= 180.0; sun_zenith_deg += 15.0) {
      for (double sz : {sun_zenith_deg, sun_zenith_deg + 0.01}) {
        const glm::dvec3 sun = DirectionIn(f, sz * kDegree, 0.3);
        for (double vz : view_zeniths) {
          for (double azimuth : {0.3, 2.0}) {
            const glm::dvec3 view = DirectionIn(f, vz, azimuth);
            glm::dvec3 t;
            check(model.sky_radiance(camera, view, sun, &t), "sky_radiance", h, vz, sz);
            check(t, "sky_radiance transmittance", h, vz, sz);
            for (double d : {0.0, 1.0, 1000.0, 100000.0}) {
              check(model.sky_radiance_to_point(camera, camera + d * view, sun, &t),
                    "sky_radiance_to_point", h, vz, sz);
              check(t, "sky_radiance_to_point transmittance", h, vz, sz);
            }
          }
        }
        // A point below the ground, straight down and sideways.
        for (const glm::dvec3& point :
             {axis * (bottom - 1000.0), FrameAt(camera).east * bottom * 0.5}) {
          glm::dvec3 t;
          check(model.sky_radiance_to_point(camera, point, sun, &t), "to a point underground", h,
                -1.0, sz);
          check(t, "to a point underground: transmittance", h, -1.0, sz);
        }
        check(model.sun_transmittance(camera, sun), "sun_transmittance", h, -1.0, sz);
        check(model.sun_radiance(camera, sun), "sun_radiance", h, -1.0, sz);
        for (const glm::dvec3& normal : {f.up, -f.up, f.east, sun}) {
          glm::dvec3 sky;
          check(model.sun_and_sky_irradiance(camera, normal, sun, &sky), "sun irradiance", h, -1.0,
                sz);
          check(sky, "sky irradiance", h, -1.0, sz);
        }
      }
    }
  }
  EXPECT_GT(checked, 10000);
}

TEST(AtmosphereIrradiance, TableMatchesHemisphereIntegralOfSkyRadiance) {
  // E = integral over the upper hemisphere of L cos(theta): Gauss-Legendre in cos(theta), the
  // midpoint rule in azimuth, from sky_radiance at the sea. The table holds the scattered orders
  // 1 to 3 (the 4th order's irradiance would need a 5th pass), sky_radiance all 4 orders, so the
  // table is expected lower by the 4th order's share.
  const AtmosphereModel& model = Model();
  const double bottom = model.parameters().bottom_radius;
  const glm::dvec3 camera(0.0, 0.0, bottom);
  const LocalFrame f{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  constexpr int kZenithPoints = 48;
  constexpr int kAzimuthSteps = 96;
  const test::Quadrature1d gauss = test::gauss_legendre(kZenithPoints);
  double worst = 0.0;
  for (double sun_zenith : {0.0, 60.0}) {
    const glm::dvec3 sun = DirectionIn(f, sun_zenith * kDegree, 0.0);
    glm::dvec3 integral(0.0);
    for (int i = 0; i < kZenithPoints; ++i) {
      const double mu = 0.5 * (gauss.x[i] + 1.0);  // cos(theta) on [0, 1]
      for (int k = 0; k < kAzimuthSteps; ++k) {
        const double phi = (k + 0.5) * 2.0 * kPi / kAzimuthSteps;
        const glm::dvec3 view = DirectionIn(f, std::acos(mu), phi);
        integral += model.sky_radiance(camera, view, sun) * mu * (0.5 * gauss.w[i]) *
                    (2.0 * kPi / kAzimuthSteps);
      }
    }
    glm::dvec3 table;
    model.sun_and_sky_irradiance(camera, f.up, sun, &table);
    const double e = MaxRelativeDifference(table, integral);
    std::printf(
        "[ measured ] sky irradiance, sun zenith %.0f: table %.4g %.4g %.4g, integral "
        "%.4g %.4g %.4g (%.3g)\n",
        sun_zenith, table.x, table.y, table.z, integral.x, integral.y, integral.z, e);
    worst = std::max(worst, e);
  }
  // Mostly the 4th order, missing from the table (blue, where multiple scattering matters most).
  EXPECT_LT(worst, 0.035);  // measured 0.024 (sun zenith 60), 0.021 (sun at the zenith)
}

TEST(AtmosphereIrradiance, NoDirectSunBelowTheHorizon) {
  const AtmosphereModel& model = Model();
  const glm::dvec3 point(0.0, 0.0, model.parameters().bottom_radius);
  const LocalFrame f{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  for (double sun_zenith : {90.5, 91.0, 95.0, 102.0, 150.0, 180.0}) {
    const glm::dvec3 sun = DirectionIn(f, sun_zenith * kDegree, 1.0);
    // Facing the sun (the cosine factor is positive) and horizontal.
    for (const glm::dvec3& normal : {sun, f.up}) {
      glm::dvec3 sky;
      EXPECT_EQ(model.sun_and_sky_irradiance(point, normal, sun, &sky), glm::dvec3(0.0))
          << sun_zenith;
    }
    EXPECT_EQ(model.sun_radiance(point, sun), glm::dvec3(0.0)) << sun_zenith;
  }
  // And some just above it: the disc (angular radius 0.27 degrees) is partly visible.
  const glm::dvec3 low_sun = DirectionIn(f, 89.9 * kDegree, 1.0);
  glm::dvec3 sky;
  EXPECT_GT(model.sun_and_sky_irradiance(point, low_sun, low_sun, &sky).x, 0.0);
}

// ---------------------------------------------------------------------------------------------
// The cache and the parameters.

bool SameTables(const ModelTables& a, const ModelTables& b) {
  auto same = [](const std::vector<float>& x, const std::vector<float>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) == 0;
  };
  return same(a.transmittance.data(), b.transmittance.data()) &&
         same(a.scattering.data(), b.scattering.data()) &&
         same(a.single_mie_scattering.data(), b.single_mie_scattering.data()) &&
         same(a.irradiance.data(), b.irradiance.data());
}

// A fresh folder for one test, removed at the end.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name)
      : path_(std::filesystem::path(::testing::TempDir()) /
              ("thalassa-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(AtmosphereCache, ModelsAliveInTheProcessShareTheirTables) {
  // Parameters of their own (another ground albedo: another key), with a cache file of their own
  // in a scratch folder (the default tables stored under that key: the content does not matter
  // here), so that no other model of this process is involved.
  const ScratchFolder folder("atmosphere-share");
  AtmosphereParameters p = AtmosphereParameters::earth();
  p.ground_albedo = glm::dvec3(0.123);
  const std::string key = cache_key(p);
  ASSERT_EQ(store_cache((folder.path() / cache_file_name(key)).string(), key, Model().tables()),
            "");
  PrecomputeOptions options;
  options.cache_dir = folder.path().string();
  {
    const auto first = AtmosphereModel::create(p, options);
    EXPECT_EQ(first->cache_status(), "loaded");
    const auto second = AtmosphereModel::create(p, options);
    EXPECT_EQ(second->cache_status(), "shared");
    EXPECT_EQ(&second->tables(), &first->tables());  // the same memory, not a copy
    EXPECT_EQ(second->load_seconds(), 0.0);
    EXPECT_EQ(second->precompute_seconds(), 0.0);
    EXPECT_EQ(second->cache_path(), first->cache_path());
    // The models are apart; only the tables are shared.
    EXPECT_NE(second.get(), first.get());
    EXPECT_EQ(second->parameters().ground_albedo, p.ground_albedo);
    // Told not to share: read from the file again.
    PrecomputeOptions apart = options;
    apart.share_in_process = false;
    const auto third = AtmosphereModel::create(p, apart);
    EXPECT_EQ(third->cache_status(), "loaded");
    EXPECT_NE(&third->tables(), &first->tables());
    EXPECT_TRUE(SameTables(third->tables(), first->tables()));
  }
  // Once no model holds them the tables are gone (the map is weak): the next model reads the file.
  const auto later = AtmosphereModel::create(p, options);
  EXPECT_EQ(later->cache_status(), "loaded");
}

TEST(AtmosphereCache, LoadingGivesTheSameTablesBitForBit) {
  const AtmosphereModel& model = Model();
  // Another model of the same parameters reads the file the first one read or wrote (when told
  // not to share the first one's tables in memory).
  const std::shared_ptr<const AtmosphereModel> again =
      AtmosphereModel::create(model.parameters(), PrecomputeOptions{.share_in_process = false});
  EXPECT_EQ(again->cache_status(), "loaded");
  EXPECT_EQ(again->cache_path(), model.cache_path());
  EXPECT_TRUE(SameTables(again->tables(), model.tables()));
  // A round trip through store_cache and load_cache in a fresh folder.
  const ScratchFolder folder("atmosphere-cache");
  const std::string key = cache_key(model.parameters());
  const std::string path = (folder.path() / cache_file_name(key)).string();
  ASSERT_EQ(store_cache(path, key, model.tables()), "");
  ModelTables loaded;
  ASSERT_TRUE(load_cache(path, key, loaded));
  EXPECT_TRUE(SameTables(loaded, model.tables()));
  // Only the file itself is left (the temporary was renamed).
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder.path())) {
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(AtmosphereCache, DamagedFilesAreRejected) {
  const AtmosphereModel& model = Model();
  const std::string key = cache_key(model.parameters());
  const ScratchFolder folder("atmosphere-damaged");
  const std::string good = (folder.path() / "good.bin").string();
  ASSERT_EQ(store_cache(good, key, model.tables()), "");
  const std::uintmax_t size = std::filesystem::file_size(good);
  // Offsets in the file (model_cache.hpp): magic, key length, key, then the first table's count.
  const std::uintmax_t key_offset = 8 + 8;
  const std::uintmax_t first_float = key_offset + key.size() + 8;

  auto damaged = [&](const std::string& name, const auto& damage) {
    const std::string path = (folder.path() / name).string();
    std::filesystem::copy_file(good, path);
    damage(path);
    ModelTables tables;
    return load_cache(path, key, tables);
  };
  auto overwrite = [](const std::string& path, std::uintmax_t offset, const void* bytes,
                      std::size_t count) {
    std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(static_cast<std::streamoff>(offset));
    file.write(static_cast<const char*>(bytes), static_cast<std::streamsize>(count));
  };
  ModelTables tables;
  EXPECT_TRUE(load_cache(good, key, tables));
  EXPECT_FALSE(load_cache((folder.path() / "missing.bin").string(), key, tables));
  EXPECT_FALSE(load_cache(good, key + "x", tables)) << "another key";
  EXPECT_FALSE(damaged("truncated.bin", [&](const std::string& p) {
    std::filesystem::resize_file(p, size - 1000);
  }));
  EXPECT_FALSE(damaged("header_only.bin", [&](const std::string& p) {
    std::filesystem::resize_file(p, first_float);
  }));
  EXPECT_FALSE(
      damaged("empty.bin", [&](const std::string& p) { std::filesystem::resize_file(p, 0); }));
  EXPECT_FALSE(damaged("longer.bin", [&](const std::string& p) {
    std::ofstream(p, std::ios::app | std::ios::binary).put('\0');
  }));
  EXPECT_FALSE(damaged("magic.bin", [&](const std::string& p) { overwrite(p, 0, "X", 1); }));
  EXPECT_FALSE(damaged(
      "key.bin", [&](const std::string& p) { overwrite(p, key_offset + key.size() / 2, "#", 1); }));
  EXPECT_FALSE(damaged("nan.bin", [&](const std::string& p) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    overwrite(p, first_float + 4 * 1000, &nan, sizeof nan);
  }));
  EXPECT_FALSE(damaged("negative.bin", [&](const std::string& p) {
    const float negative = -1.0f;
    overwrite(p, size - sizeof(float), &negative, sizeof negative);
  }));
  EXPECT_FALSE(damaged("count.bin", [&](const std::string& p) {
    const std::uint64_t count = 12;
    overwrite(p, first_float - 8, &count, sizeof count);
  }));
}

TEST(AtmosphereParameters, InvalidValuesThrowNamingTheField) {
  auto expect_throw = [](const char* field, const auto& change) {
    AtmosphereParameters p = AtmosphereParameters::earth();
    change(p);
    try {
      p.validate();
      ADD_FAILURE() << field << ": no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
    // create() validates before reading the cache or computing anything.
    EXPECT_THROW(AtmosphereModel::create(p, PrecomputeOptions{.use_cache = false}),
                 std::invalid_argument)
        << field;
  };
  EXPECT_NO_THROW(AtmosphereParameters::earth().validate());
  expect_throw("rayleigh_scattering",
               [](AtmosphereParameters& p) { p.rayleigh_scattering.y = -1e-6; });
  expect_throw("mie_scattering", [](AtmosphereParameters& p) { p.mie_scattering.z = -1e-6; });
  expect_throw("absorption_extinction",
               [](AtmosphereParameters& p) { p.absorption_extinction.x = -1e-9; });
  expect_throw("top_radius", [](AtmosphereParameters& p) { p.top_radius = p.bottom_radius; });
  expect_throw("top_radius", [](AtmosphereParameters& p) { p.top_radius = p.bottom_radius - 1.0; });
  expect_throw("mie_phase_g", [](AtmosphereParameters& p) { p.mie_phase_g = 1.0; });
  expect_throw("mie_phase_g", [](AtmosphereParameters& p) { p.mie_phase_g = 1.5; });
  expect_throw("solar_irradiance", [](AtmosphereParameters& p) {
    p.solar_irradiance.x = std::numeric_limits<double>::quiet_NaN();
  });
  expect_throw("ground_albedo", [](AtmosphereParameters& p) { p.ground_albedo.y = 1.5; });
  expect_throw("scattering_orders", [](AtmosphereParameters& p) { p.scattering_orders = 0; });
}

}  // namespace
}  // namespace thalassa::atmosphere
