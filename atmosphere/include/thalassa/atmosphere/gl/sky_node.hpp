// thalassa — the sky behind the scene, as a scene-graph node (GL layer, not installed).
//
// Until the atmosphere model (issue 4) lands, this draws the foundation's placeholder: the
// closed-form single-scattering Rayleigh sky of shaders/atmosphere/analytic_sky.glsl.
#pragma once

#include <memory>

#include "thalassa/engine/gl/scene_graph.hpp"

namespace thalassa::atmosphere {

struct SkyNodeOptions {
  bool sun_disc = true;  // draw the sun's disc (left out when the sun is below the horizon)
};

std::unique_ptr<gl::Node> make_sky_node(const SkyNodeOptions& options);

}  // namespace thalassa::atmosphere
