#include "sky_provider_factory.hpp"

#include <utility>

#include "thalassa/atmosphere/environment_map.hpp"
#include "thalassa/atmosphere/model.hpp"

namespace thalassa {

std::shared_ptr<atmosphere::SkyProvider> make_sky_provider(
    const Scene& scene, const RendererOptions& options,
    const atmosphere::SkyMapSettings& settings) {
  const double radius = scene.planet.shape == PlanetShape::Sphere ? scene.planet.radius
                                                                  : atmosphere::kEarthMeanRadius;
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

}  // namespace thalassa
