// The sky provider a scene asks for (internal to the planet module): the physical atmosphere
// for the planet's radius, or the HDR photograph of `sky.exr`. Shared by the Renderer and the
// sky export, so that `thalassa sky` writes the very sky the renderer draws with.
#pragma once

#include <memory>

#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/scene.hpp"
#include "thalassa/planet/renderer.hpp"

namespace thalassa {

// Needs a current GL context (the provider uploads its tables). The atmosphere's tables are
// loaded from options.cache_dir's cache, or precomputed (tens of seconds) and cached there.
// Throws EnvironmentMapError for a photograph that cannot serve as a sky.
std::shared_ptr<atmosphere::SkyProvider> make_sky_provider(
    const Scene& scene, const RendererOptions& options,
    const atmosphere::SkyMapSettings& settings = {});

}  // namespace thalassa
