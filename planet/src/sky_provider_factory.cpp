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
    auto map = std::make_shared<const atmosphere::EnvironmentMap>(scene.sky.exr);
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
