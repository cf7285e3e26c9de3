#include "sky_provider_factory.hpp"

#include <utility>

#include "thalassa/atmosphere/environment_map.hpp"
#include "thalassa/atmosphere/model.hpp"

namespace thalassa {

namespace {
// The radius of the sphere the sky is made for, m: the planet's, or the Earth's mean for WGS84.
double sky_radius(const Scene& scene) {
  return scene.planet.shape == PlanetShape::Sphere ? scene.planet.radius
                                                   : atmosphere::kEarthMeanRadius;
}
}  // namespace

std::shared_ptr<atmosphere::SkyProvider> make_sky_provider(
    const Scene& scene, const RendererOptions& options,
    const atmosphere::SkyMapSettings& settings) {
  const double radius = sky_radius(scene);
  if (!scene.sky.exr.empty()) {
    std::shared_ptr<const atmosphere::EnvironmentMap> map;
    try {
      map = std::make_shared<const atmosphere::EnvironmentMap>(scene.sky.exr);
    } catch (const atmosphere::EnvironmentMapError& e) {
      // A photograph that is not a usable sky is invalid input, like a bad key.
      throw SceneError(std::string("sky.exr: ") + e.what());
    }
    return atmosphere::make_environment_provider(std::move(map), radius, settings);
  }
  atmosphere::PrecomputeOptions precompute;
  precompute.cache_dir = options.cache_dir;
  return atmosphere::make_atmosphere_provider(
      atmosphere::AtmosphereModel::create(atmosphere::AtmosphereParameters::earth(radius),
                                          precompute),
      settings);
}

std::shared_ptr<atmosphere::SkyProvider> SkyProviderCache::provider(
    const GlContext& context, const Scene& scene, const RendererOptions& options,
    const atmosphere::SkyMapSettings& settings, bool& kept) {
  const Key key{.context = &context,
                .exr = scene.sky.exr,
                .radius = sky_radius(scene),
                .cache_dir = options.cache_dir,
                .settings = settings};
  kept = provider_ && key == key_;
  if (!kept) {
    // Let go of the old one first: where no Renderer holds it any more, its textures go before
    // the new one's are made.
    provider_.reset();
    provider_ = make_sky_provider(scene, options, settings);
    key_ = key;
  }
  return provider_;
}

std::shared_ptr<SkyProviderCache> make_sky_provider_cache() {
  return std::make_shared<SkyProviderCache>();
}

}  // namespace thalassa
