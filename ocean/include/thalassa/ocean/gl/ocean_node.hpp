// thalassa — the paper's ocean as a scene-graph node (GL layer, not installed).
//
// Bruneton, Neyret & Holzschuch 2010: the projected grid displaced by the waves longer than a
// grid cell (ocean.vert), per-pixel normals from the waves longer than a pixel and the unresolved
// slope variance of the shorter ones (ocean_geometry.frag), then the Ross BRDF lit by the sun,
// the sky and the refracted light from the sky provider, seen through the aerial perspective
// (ocean_lighting.frag).
#pragma once

#include <memory>

#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/scene_graph.hpp"
#include "thalassa/engine/scene.hpp"

namespace thalassa::ocean {

struct OceanNodeOptions {
  OceanSettings settings;  // the wave set, filter weights, grid cell and Fresnel reflectance
  bool sun_glint = true;   // the reflected sun (eq. 15); left out when the sun has set
  bool sky = true;         // the reflected sky (eq. 21)
  bool sea = true;         // the light refracted from the water (eq. 28)
  bool air = true;         // the in-scattered light between the camera and the sea
  // Eq. 27's single anisotropic fetch (false) or the average of nine samples (true).
  bool sky_nine_samples = false;
  // Ramamoorthi & Hanrahan 2002's frequency-space prefiltering instead (overrides
  // sky_nine_samples): the sky term reads glossy sky maps (atmosphere/gl/sky_shrm.hpp) and L_sea
  // takes the sky's irradiance from the same SH projection.
  bool sky_shrm = false;
  // All sky light: the sky map, sun radiance, irradiance and aerial perspective.
  std::shared_ptr<atmosphere::SkyProvider> provider;
};

std::unique_ptr<gl::Node> make_ocean_node(const OceanNodeOptions& options);

}  // namespace thalassa::ocean
