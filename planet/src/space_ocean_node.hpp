// thalassa — the ocean seen from space as a scene-graph node (internal to the planet module):
// shaders/planet/ocean_space.frag, one full-screen pass, no grid (issue 5, point 2).
#pragma once

#include <memory>

#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/scene_graph.hpp"
#include "thalassa/engine/scene.hpp"
#include "thalassa/ocean/local_features.hpp"

namespace thalassa {

struct SpaceOceanNodeOptions {
  OceanSettings settings;  // the wave set (its total slope variance), Fresnel, deep reflectance
  bool sun_glint = true;
  bool sky = true;
  bool sea = true;
  bool air = true;
  std::shared_ptr<atmosphere::SkyProvider> provider;
  // The wakes and calm areas in view (issue 9): they change the slope variance only.
  std::shared_ptr<const ocean::LocalFeatures> features;
  bool operator==(const SpaceOceanNodeOptions&) const = default;
};

std::unique_ptr<gl::Node> make_space_ocean_node(const SpaceOceanNodeOptions& options);

}  // namespace thalassa
