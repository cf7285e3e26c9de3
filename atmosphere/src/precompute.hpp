// The factored scattering density of the precomputation (internal), exposed for the test that
// checks it against the shared ComputeScatteringDensity (tests/unit/atmosphere_model_test.cpp).
#pragma once

#include <vector>

#include "model_reference.hpp"
#include "thalassa/atmosphere/model.hpp"

namespace thalassa::atmosphere {

// The scattering density J of order `order` (W m^-3 sr^-1 nm^-1, in double) of every texel of
// the scattering table's layer z (r index) whose mu_s index is j: element y * NU_SIZE + k is
// the texel (k * MU_S_SIZE + j, y, z). The inputs are the previous order's tables as
// ComputeScatteringDensity takes them (shaders/atmosphere/model.glsl).
std::vector<glsl::vec3> compute_density_slice(const AtmosphereParameters& parameters,
                                              const glsl::Texture2D& transmittance,
                                              const glsl::Texture3D& delta_rayleigh,
                                              const glsl::Texture3D& delta_mie,
                                              const glsl::Texture3D& delta_multiple,
                                              const glsl::Texture2D& delta_irradiance, int order,
                                              int z, int j);

}  // namespace thalassa::atmosphere
