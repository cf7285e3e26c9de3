// thalassa — the sky behind the scene, as a scene-graph node (GL layer, not installed): the sky
// provider's radiance along every pixel's view ray, with the sun's disc (issue 4, point 3f).
#pragma once

#include <memory>

#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/scene_graph.hpp"

namespace thalassa::atmosphere {

struct SkyNodeOptions {
  bool sun_disc = true;  // draw the sun's disc
  bool operator==(const SkyNodeOptions&) const = default;
};

std::unique_ptr<gl::Node> make_sky_node(const SkyNodeOptions& options,
                                        std::shared_ptr<SkyProvider> provider);

}  // namespace thalassa::atmosphere
