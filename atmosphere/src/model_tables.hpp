// The atmosphere's precomputed tables (internal): what AtmosphereModel holds and the GL side
// uploads. Layouts and parameterisations: shaders/atmosphere/model.glsl.
#pragma once

#include "model_reference.hpp"
#include "thalassa/atmosphere/model.hpp"

namespace thalassa::atmosphere {

struct ModelTables {
  glsl::Texture2D transmittance;          // T to the top, (mu, r)
  glsl::Texture3D scattering;             // Rayleigh single + multiple, no phase function
  glsl::Texture3D single_mie_scattering;  // no phase function
  glsl::Texture2D irradiance;             // sky only (orders >= 1), horizontal surface
};

namespace {
// The shared code's parameter struct from the public one. (In an anonymous namespace, as the
// shared code's types are: each translation unit has its own.)
[[maybe_unused]] glsl::DensityProfileLayer to_glsl(const DensityLayer& l) {
  return {l.width, l.exp_term, l.exp_scale, l.linear_term, l.constant_term};
}
[[maybe_unused]] glsl::DensityProfile to_glsl(const DensityProfile& p) {
  return {to_glsl(p.lower), to_glsl(p.upper)};
}
[[maybe_unused]] glsl::AtmosphereParameters to_glsl(const AtmosphereParameters& a) {
  glsl::AtmosphereParameters g;
  g.solar_irradiance = a.solar_irradiance;
  g.sun_angular_radius = a.sun_angular_radius;
  g.bottom_radius = a.bottom_radius;
  g.top_radius = a.top_radius;
  g.rayleigh_density = to_glsl(a.rayleigh_density);
  g.rayleigh_scattering = a.rayleigh_scattering;
  g.mie_density = to_glsl(a.mie_density);
  g.mie_scattering = a.mie_scattering;
  g.mie_extinction = a.mie_extinction;
  g.mie_phase_g = a.mie_phase_g;
  g.absorption_density = to_glsl(a.absorption_density);
  g.absorption_extinction = a.absorption_extinction;
  g.ground_albedo = a.ground_albedo;
  g.mu_s_min = std::cos(a.max_sun_zenith);
  return g;
}
}  // namespace

// The GLSL expression of `parameters` as an AtmosphereParameters constructor, for the shaders'
// ATMOSPHERE define (full float precision).
std::string glsl_constructor(const AtmosphereParameters& parameters);

// Precomputes every table on `threads` CPU threads.
void precompute_tables(const AtmosphereParameters& parameters, int threads, ModelTables& tables);

}  // namespace thalassa::atmosphere
