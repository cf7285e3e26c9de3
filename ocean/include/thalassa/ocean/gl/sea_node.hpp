// thalassa — the sea surface as a scene-graph node (GL layer, not installed).
//
// Until the Bruneton-Neyret-Holzschuch ocean (issue 3) lands, this draws the foundation's
// placeholder: a flat sea whose roughness is an isotropic Cox-Munk slope distribution
// (shaders/ocean/flat_sea.glsl), reflecting the same analytic sky the sky node draws.
#pragma once

#include <glm/glm.hpp>

#include <memory>

#include "thalassa/engine/gl/scene_graph.hpp"

namespace thalassa::ocean {

struct SeaNodeOptions {
  double wind_speed = 10.0;  // m/s; sets the slope variance
  bool sun_glint = true;     // left out when the sun is below the horizon
};

std::unique_ptr<gl::Node> make_sea_node(const SeaNodeOptions& options);

}  // namespace thalassa::ocean
