// The sky provider a scene asks for (internal to the planet module): the physical atmosphere
// for the planet's radius, or the HDR photograph of `sky.exr`. Shared by the Renderer and the
// sky export, so that `thalassa sky` writes the very sky the renderer draws with.
#pragma once

#include <memory>
#include <string>

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

// RendererOptions::sky_cache (renderer.hpp): the last provider made, and what it was made for.
class SkyProviderCache {
 public:
  // The cached provider when `scene`'s sky, options.cache_dir, `settings` and `context` are what
  // it was made for (kept = true), else a new one from make_sky_provider, which replaces it.
  std::shared_ptr<atmosphere::SkyProvider> provider(const GlContext& context, const Scene& scene,
                                                    const RendererOptions& options,
                                                    const atmosphere::SkyMapSettings& settings,
                                                    bool& kept);

 private:
  struct Key {
    const GlContext* context = nullptr;
    std::string exr;        // sky.exr; empty: the atmosphere
    double radius = 0.0;    // the planet's radius the sky is made for, m
    std::string cache_dir;  // the atmosphere's table cache
    atmosphere::SkyMapSettings settings;
    bool operator==(const Key&) const = default;
  };
  Key key_;
  std::shared_ptr<atmosphere::SkyProvider> provider_;
};

}  // namespace thalassa
