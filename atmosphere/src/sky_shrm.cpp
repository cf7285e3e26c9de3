// thalassa — the provider's sky in SH and the glossy sky maps on the GPU (contracts in
// thalassa/atmosphere/gl/sky_shrm.hpp).

#include "thalassa/atmosphere/gl/sky_shrm.hpp"

#include <chrono>
#include <cmath>

#include "thalassa/engine/gl/gpu_timer.hpp"
#include "thalassa/engine/gl/objects.hpp"

namespace thalassa::atmosphere {

SkyRadianceFunction ocean_sky(const SkyProvider& provider, double height, const glm::dvec3& sun) {
  const glm::dvec3 below = provider.below_horizon_radiance(height, sun);
  return [&provider, height, sun, below](const glm::dvec3& d) -> glm::dvec3 {
    return d.z >= 0.0 ? provider.sky_radiance(height, d, sun) : below;
  };
}

IrradianceSh sky_irradiance_sh(const SkyProvider& provider, double height, const glm::dvec3& sun,
                               const SkyProjectionGrid& grid) {
  constexpr int kOrder = 2;
  const std::vector<double> samples = sample_sky(ocean_sky(provider, height, sun), grid);
  return irradiance_sh(project_sky(samples, grid, kOrder), kOrder);
}

GlossySkyMaps::GlossySkyMaps(const GlossySkySettings& settings) : settings_(settings) {}

const GlossySky& GlossySkyMaps::update(const SkyProvider& provider, double height,
                                       const glm::dvec3& sun, gl::GpuTimer* timer) {
  if (built_ && height == height_ && sun == sun_) return sky_;
  if (kernels_.levels.empty()) {
    const auto kernels_start = std::chrono::steady_clock::now();
    kernels_ = glossy_sky_kernels(settings_);
    kernels_ms_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - kernels_start)
            .count();
  }
  const auto start = std::chrono::steady_clock::now();
  sky_ = glossy_sky(ocean_sky(provider, height, sun), settings_, kernels_);
  if (!texture_) {
    texture_ = gl::make_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(texture_.get(), 1, GL_RGBA32F, sky_.width, sky_.height,
                       static_cast<GLsizei>(sky_.levels.size()));
    // The maps are already filtered by the BRDF (their finest lobe spans ~2 texels): bilinear
    // within a layer; the shader interpolates between layers itself.
    // s: the azimuth; t: the zenith angle.
    gl::set_sampling(texture_.get(), {.wrap_s = GL_REPEAT});
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage3D(texture_.get(), 0, 0, 0, 0, sky_.width, sky_.height,
                      static_cast<GLsizei>(sky_.levels.size()), GL_RGBA, GL_FLOAT,
                      sky_.rgba.data());
  if (timer) timer->end_pass("sky.shrm");
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  built_ = true;
  height_ = height;
  sun_ = sun;
  ++build_count_;
  return sky_;
}

void GlossySkyMaps::bind() const { glBindTextureUnit(kSkyShrmUnit, texture_.get()); }

std::vector<std::string> GlossySkyMaps::built() const {
  if (!built_) return {};
  return {"sky.shrm_maps (" + std::to_string(sky_.levels.size()) +
          " levels, F = " + std::to_string(sky_.levels.front().orders.order_l) + ".." +
          std::to_string(sky_.levels.back().orders.order_l) + ")"};
}

glm::dvec2 GlossySkyMaps::level_mapping() const {
  const double s0 = glossy_sky_slope_variance(settings_, 0);
  const double s1 = glossy_sky_slope_variance(settings_, 1);
  return {std::log(s0), 1.0 / std::log(s1 / s0)};
}

}  // namespace thalassa::atmosphere
