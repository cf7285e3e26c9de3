// Precomputation of the atmosphere's tables on CPU threads, in double precision with the shared
// code of shaders/atmosphere/model.glsl, in the order of Bruneton 2017 (Precompute()):
// transmittance; direct irradiance; single scattering; then for each order n >= 2 the scattering
// density of order n, the indirect irradiance of order n - 1 and the multiple scattering of
// order n. CPU threads rather than GPU passes: the tables come out bit-identical on every
// machine and GL driver (DESIGN section 4, determinism), and tests need no GL context.
#include <atomic>
#include <cstdio>
#include <exception>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "model_tables.hpp"
#include "precompute.hpp"
#include "sky_map_texture.hpp"

namespace thalassa::atmosphere {
namespace {

using glsl::Texture2D;
using glsl::Texture3D;
using glsl::vec2;
using glsl::vec3;

// Runs body(i) for i in [0, count) on `threads` threads (rows or layers of a table: every i
// writes its own texels). The first exception is rethrown on the calling thread.
template <typename Body>
void parallel_for(int count, int threads, const Body& body) {
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    for (int i = next++; i < count; i = next++) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = count;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

// Calls texel(x, y, z, frag_coord) for every texel of a scattering-sized 3D table, one r layer
// per task.
template <typename Texel>
void for_each_scattering_texel(int threads, const Texel& texel) {
  parallel_for(glsl::SCATTERING_TEXTURE_DEPTH, threads, [&](int z) {
    for (int y = 0; y < glsl::SCATTERING_TEXTURE_HEIGHT; ++y) {
      for (int x = 0; x < glsl::SCATTERING_TEXTURE_WIDTH; ++x) {
        texel(x, y, z, vec3(x + 0.5, y + 0.5, z + 0.5));
      }
    }
  });
}

template <typename Texel>
void for_each_irradiance_texel(int threads, const Texel& texel) {
  parallel_for(glsl::IRRADIANCE_TEXTURE_HEIGHT, threads, [&](int y) {
    for (int x = 0; x < glsl::IRRADIANCE_TEXTURE_WIDTH; ++x) texel(x, y, vec2(x + 0.5, y + 0.5));
  });
}

// The scattering density of order `order` for every texel of layer z whose mu_s index is j, in
// double: element y * NU_SIZE + k is the texel (k * MU_S_SIZE + j, y, z).
std::vector<vec3> density_slice(const glsl::AtmosphereParameters& atmosphere,
                                const Texture2D& transmittance, const Texture3D& delta_rayleigh,
                                const Texture3D& delta_mie, const Texture3D& delta_multiple,
                                const Texture2D& delta_irradiance, int order, int z, int j) {
  constexpr int kZenith = glsl::SCATTERING_DENSITY_SAMPLE_COUNT;
  constexpr int kAzimuth = 2 * glsl::SCATTERING_DENSITY_SAMPLE_COUNT;
  // r and mu_s of the slice, from any of its texels.
  double r, mu, mu_s, nu;
  bool intersects_ground;
  glsl::GetRMuMuSNuFromScatteringTextureFragCoord(atmosphere, vec3(j + 0.5, 0.5, z + 0.5), r, mu,
                                                  mu_s, nu, intersects_ground);
  std::vector<vec3> directions(kZenith * kAzimuth);
  std::vector<vec3> weighted_incident(kZenith * kAzimuth);  // L_in domega
  for (int l = 0; l < kZenith; ++l) {
    for (int m = 0; m < kAzimuth; ++m) {
      double domega;
      const vec3 omega_i = glsl::ScatteringDensityDirection(l, m, domega);
      directions[l * kAzimuth + m] = omega_i;
      weighted_incident[l * kAzimuth + m] =
          glsl::ComputeIncidentRadiance(atmosphere, transmittance, delta_rayleigh, delta_mie,
                                        delta_multiple, delta_irradiance, r, mu_s, omega_i, order) *
          domega;
    }
  }
  // ScatteringDensityKernel with its densities (functions of r alone) hoisted out of the loop.
  const vec3 rayleigh =
      atmosphere.rayleigh_scattering *
      glsl::GetProfileDensity(atmosphere.rayleigh_density, r - atmosphere.bottom_radius);
  const vec3 mie = atmosphere.mie_scattering *
                   glsl::GetProfileDensity(atmosphere.mie_density, r - atmosphere.bottom_radius);
  std::vector<vec3> slice(glsl::SCATTERING_TEXTURE_HEIGHT * glsl::SCATTERING_TEXTURE_NU_SIZE);
  for (int y = 0; y < glsl::SCATTERING_TEXTURE_HEIGHT; ++y) {
    for (int k = 0; k < glsl::SCATTERING_TEXTURE_NU_SIZE; ++k) {
      const int x = k * glsl::SCATTERING_TEXTURE_MU_S_SIZE + j;
      double r_t, mu_s_t;
      glsl::GetRMuMuSNuFromScatteringTextureFragCoord(atmosphere, vec3(x + 0.5, y + 0.5, z + 0.5),
                                                      r_t, mu, mu_s_t, nu, intersects_ground);
      const vec3 omega = glsl::ScatteringDensityViewDirection(mu, mu_s, nu);
      vec3 density(0.0);
      for (std::size_t i = 0; i < directions.size(); ++i) {
        const double cos_angle = glsl::dot(omega, directions[i]);
        density += weighted_incident[i] *
                   (rayleigh * glsl::RayleighPhaseFunction(cos_angle) +
                    mie * glsl::MiePhaseFunction(atmosphere.mie_phase_g, cos_angle));
      }
      slice[y * glsl::SCATTERING_TEXTURE_NU_SIZE + k] = density;
    }
  }
  return slice;
}

Texture3D scattering_table() {
  return Texture3D(glsl::SCATTERING_TEXTURE_WIDTH, glsl::SCATTERING_TEXTURE_HEIGHT,
                   glsl::SCATTERING_TEXTURE_DEPTH);
}

std::string glsl_vec3(const glm::dvec3& v) {
  return "vec3(" + glsl_float_literal(v.x) + ", " + glsl_float_literal(v.y) + ", " +
         glsl_float_literal(v.z) + ")";
}

std::string glsl_layer(const DensityLayer& l) {
  return "DensityProfileLayer(" + glsl_float_literal(l.width) + ", " +
         glsl_float_literal(l.exp_term) + ", " + glsl_float_literal(l.exp_scale) + ", " +
         glsl_float_literal(l.linear_term) + ", " + glsl_float_literal(l.constant_term) + ")";
}

std::string glsl_profile(const DensityProfile& p) {
  return "DensityProfile(" + glsl_layer(p.lower) + ", " + glsl_layer(p.upper) + ")";
}

}  // namespace

std::vector<vec3> compute_density_slice(const AtmosphereParameters& parameters,
                                        const Texture2D& transmittance,
                                        const Texture3D& delta_rayleigh, const Texture3D& delta_mie,
                                        const Texture3D& delta_multiple,
                                        const Texture2D& delta_irradiance, int order, int z,
                                        int j) {
  return density_slice(to_glsl(parameters), transmittance, delta_rayleigh, delta_mie,
                       delta_multiple, delta_irradiance, order, z, j);
}

std::string glsl_constructor(const AtmosphereParameters& a) {
  const glsl::AtmosphereParameters g = to_glsl(a);
  return "AtmosphereParameters(" + glsl_vec3(g.solar_irradiance) + ", " +
         glsl_float_literal(g.sun_angular_radius) + ", " + glsl_float_literal(g.bottom_radius) +
         ", " + glsl_float_literal(g.top_radius) + ", " + glsl_profile(a.rayleigh_density) + ", " +
         glsl_vec3(g.rayleigh_scattering) + ", " + glsl_profile(a.mie_density) + ", " +
         glsl_vec3(g.mie_scattering) + ", " + glsl_vec3(g.mie_extinction) + ", " +
         glsl_float_literal(g.mie_phase_g) + ", " + glsl_profile(a.absorption_density) + ", " +
         glsl_vec3(g.absorption_extinction) + ", " + glsl_vec3(g.ground_albedo) + ", " +
         glsl_float_literal(g.mu_s_min) + ")";
}

void precompute_tables(const AtmosphereParameters& parameters, int threads, ModelTables& tables) {
  const glsl::AtmosphereParameters atmosphere = to_glsl(parameters);

  // Transmittance.
  tables.transmittance =
      Texture2D(glsl::TRANSMITTANCE_TEXTURE_WIDTH, glsl::TRANSMITTANCE_TEXTURE_HEIGHT);
  parallel_for(glsl::TRANSMITTANCE_TEXTURE_HEIGHT, threads, [&](int y) {
    for (int x = 0; x < glsl::TRANSMITTANCE_TEXTURE_WIDTH; ++x) {
      tables.transmittance.set(x, y,
                               glsl::ComputeTransmittanceToTopAtmosphereBoundaryTexture(
                                   atmosphere, vec2(x + 0.5, y + 0.5)));
    }
  });
  const Texture2D& transmittance = tables.transmittance;

  // Direct irradiance (order 0, only to light the ground at order 2); the stored irradiance is
  // the sky's alone.
  Texture2D delta_irradiance(glsl::IRRADIANCE_TEXTURE_WIDTH, glsl::IRRADIANCE_TEXTURE_HEIGHT);
  tables.irradiance = Texture2D(glsl::IRRADIANCE_TEXTURE_WIDTH, glsl::IRRADIANCE_TEXTURE_HEIGHT);
  for_each_irradiance_texel(threads, [&](int x, int y, const vec2& frag_coord) {
    delta_irradiance.set(
        x, y, glsl::ComputeDirectIrradianceTexture(atmosphere, transmittance, frag_coord));
  });

  // Single scattering.
  Texture3D delta_rayleigh = scattering_table();
  Texture3D delta_mie = scattering_table();
  for_each_scattering_texel(threads, [&](int x, int y, int z, const vec3& frag_coord) {
    vec3 rayleigh;
    vec3 mie;
    glsl::ComputeSingleScatteringTexture(atmosphere, transmittance, frag_coord, rayleigh, mie);
    delta_rayleigh.set(x, y, z, rayleigh);
    delta_mie.set(x, y, z, mie);
  });
  tables.scattering = delta_rayleigh;
  tables.single_mie_scattering = delta_mie;

  // Multiple scattering, order by order.
  Texture3D delta_multiple = scattering_table();
  Texture3D delta_density = scattering_table();
  for (int order = 2; order <= parameters.scattering_orders; ++order) {
    // Scattering density of order n (ComputeScatteringDensity), factored: the incident radiance
    // depends on r, mu_s and the direction only, and r and mu_s are shared by every texel of a
    // (layer, mu_s) slice, so it is evaluated once per slice on the quadrature's directions and
    // each texel only sums it against its kernel: the shared function's sum up to rounding (a
    // test checks them equal) with 500 times fewer table lookups.
    parallel_for(glsl::SCATTERING_TEXTURE_DEPTH * glsl::SCATTERING_TEXTURE_MU_S_SIZE, threads,
                 [&](int task) {
                   const int z = task / glsl::SCATTERING_TEXTURE_MU_S_SIZE;
                   const int j = task % glsl::SCATTERING_TEXTURE_MU_S_SIZE;
                   const std::vector<vec3> slice =
                       density_slice(atmosphere, transmittance, delta_rayleigh, delta_mie,
                                     delta_multiple, delta_irradiance, order, z, j);
                   for (int y = 0; y < glsl::SCATTERING_TEXTURE_HEIGHT; ++y) {
                     for (int k = 0; k < glsl::SCATTERING_TEXTURE_NU_SIZE; ++k) {
                       delta_density.set(k * glsl::SCATTERING_TEXTURE_MU_S_SIZE + j, y, z,
                                         slice[y * glsl::SCATTERING_TEXTURE_NU_SIZE + k]);
                     }
                   }
                 });

    Texture2D next_irradiance(glsl::IRRADIANCE_TEXTURE_WIDTH, glsl::IRRADIANCE_TEXTURE_HEIGHT);
    for_each_irradiance_texel(threads, [&](int x, int y, const vec2& frag_coord) {
      double r, mu_s;
      glsl::GetRMuSFromIrradianceTextureUv(
          atmosphere,
          frag_coord / vec2(glsl::IRRADIANCE_TEXTURE_WIDTH, glsl::IRRADIANCE_TEXTURE_HEIGHT), r,
          mu_s);
      const vec3 e = glsl::ComputeIndirectIrradiance(atmosphere, delta_rayleigh, delta_mie,
                                                     delta_multiple, r, mu_s, order - 1);
      next_irradiance.set(x, y, e);
      tables.irradiance.set(x, y, tables.irradiance.get(x, y) + e);
    });
    delta_irradiance = std::move(next_irradiance);

    for_each_scattering_texel(threads, [&](int x, int y, int z, const vec3& frag_coord) {
      double r, mu, mu_s, nu;
      bool intersects_ground;
      glsl::GetRMuMuSNuFromScatteringTextureFragCoord(atmosphere, frag_coord, r, mu, mu_s, nu,
                                                      intersects_ground);
      const vec3 s = glsl::ComputeMultipleScattering(atmosphere, transmittance, delta_density, r,
                                                     mu, mu_s, nu, intersects_ground);
      delta_multiple.set(x, y, z, s);
      tables.scattering.set(x, y, z,
                            tables.scattering.get(x, y, z) + s / glsl::RayleighPhaseFunction(nu));
    });
  }
}

}  // namespace thalassa::atmosphere
