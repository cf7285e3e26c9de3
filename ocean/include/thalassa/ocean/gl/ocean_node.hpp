// thalassa — the paper's ocean as a scene-graph node (GL layer, not installed).
//
// Bruneton, Neyret & Holzschuch 2010 per pixel on the sea at rest (shaders/ocean/ocean.frag):
// normals from the waves longer than a pixel, the Ross BRDF widened by the shorter ones, sun,
// sky and refracted light. The projected grid's displacement (issue 3, point 2) comes next.
#pragma once

#include <memory>

#include "thalassa/engine/gl/scene_graph.hpp"
#include "thalassa/engine/scene.hpp"

namespace thalassa::ocean {

struct OceanNodeOptions {
  OceanSettings settings;  // the wave set, filter weights, grid cell and Fresnel reflectance
  bool sun_glint = true;   // the reflected sun (eq. 15); left out when the sun has set
  bool sky = true;         // the reflected sky (eq. 21)
  bool sea = true;         // the light refracted from the water (eq. 28)
};

std::unique_ptr<gl::Node> make_ocean_node(const OceanNodeOptions& options);

}  // namespace thalassa::ocean
