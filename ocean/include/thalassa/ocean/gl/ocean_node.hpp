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
  OceanSettings settings;
  bool sun_glint = true;  // left out when the sun is below the horizon
  double n_min = 1.0;     // N_min of the filter weights (sec. 3.2 and 7.1)
  double n_max = 2.5;     // N_max
  double fresnel_r = 0.02;  // R, Fresnel reflectance at normal incidence (eq. 14)
};

std::unique_ptr<gl::Node> make_ocean_node(const OceanNodeOptions& options);

}  // namespace thalassa::ocean
