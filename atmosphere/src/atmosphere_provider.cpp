// The sky provider of the physical atmosphere: the model's tables on the GPU, stereographic sky
// maps rendered from them (atmosphere/sky_map.frag), and the CPU answers through the same code.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "model_tables.hpp"
#include "sky_map_texture.hpp"
#include "thalassa/atmosphere/environment_map.hpp"
#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/gpu_timer.hpp"
#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/scene_graph.hpp"
#include "thalassa/engine/gl/state_guard.hpp"

namespace thalassa::atmosphere {
namespace {

gl::Texture upload_2d(const glsl::Texture2D& table) {
  gl::Texture texture = gl::make_texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.get(), 1, GL_RGBA32F, table.width(), table.height());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage2D(texture.get(), 0, 0, 0, table.width(), table.height(), GL_RGB, GL_FLOAT,
                      table.data().data());
  gl::set_sampling(texture.get(), {});
  return texture;
}

gl::Texture upload_3d(const glsl::Texture3D& table) {
  gl::Texture texture = gl::make_texture(GL_TEXTURE_3D);
  glTextureStorage3D(texture.get(), 1, GL_RGBA32F, table.width(), table.height(), table.depth());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage3D(texture.get(), 0, 0, 0, 0, table.width(), table.height(), table.depth(),
                      GL_RGB, GL_FLOAT, table.data().data());
  gl::set_sampling(texture.get(), {.wrap_r = GL_CLAMP_TO_EDGE});
  return texture;
}

class AtmosphereProvider final : public SkyProvider {
 public:
  AtmosphereProvider(std::shared_ptr<const AtmosphereModel> model, const SkyMapSettings& settings)
      : model_(std::move(model)), settings_(settings) {
    check_sky_map_settings(settings_);
    const ModelTables& tables = model_->tables();
    transmittance_ = upload_2d(tables.transmittance);
    scattering_ = upload_3d(tables.scattering);
    single_mie_ = upload_3d(tables.single_mie_scattering);
    irradiance_ = upload_2d(tables.irradiance);
    vertex_array_ = gl::make_vertex_array();
  }

  std::string kind() const override { return "atmosphere"; }

  std::vector<std::string> built() const override {
    std::vector<std::string> list = {"atmosphere.model (" + model_->cache_status() + ")"};
    if (sky_map_) list.push_back("atmosphere.sky_map");
    if (sky_map_array_) list.push_back("atmosphere.sky_map_array");
    return list;
  }

  gl::Defines defines() const override {
    gl::Defines defines = sky_map_array_defines(settings_);
    defines["SKY_PROVIDER_ATMOSPHERE"] = "1";
    defines["ATMOSPHERE"] = glsl_constructor(model_->parameters());
    defines["SKY_MAP_EXTENT"] = glsl_float_literal(kSkyMapExtent);
    return defines;
  }

  void bind() const override {
    glBindTextureUnit(kSkyMapUnit, sky_map_.get());
    glBindTextureUnit(kSkyTransmittanceUnit, transmittance_.get());
    glBindTextureUnit(kSkyScatteringUnit, scattering_.get());
    glBindTextureUnit(kSkySingleMieUnit, single_mie_.get());
    glBindTextureUnit(kSkyIrradianceUnit, irradiance_.get());
    if (sky_map_array_) glBindTextureUnit(kSkyMapArrayUnit, sky_map_array_.get());
  }

  GLuint sky_map(double height, const glm::dvec3& sun, gl::ShaderLibrary& shaders,
                 gl::GpuTimer* timer) override {
    if (sky_map_ && height == map_height_ && sun == map_sun_) return sky_map_.get();
    const auto start = std::chrono::steady_clock::now();
    if (!sky_map_) {
      sky_map_ = gl::make_texture(GL_TEXTURE_2D);
      glTextureStorage2D(sky_map_.get(), sky_map_mip_levels(settings_.size), GL_RGBA32F,
                         settings_.size, settings_.size);
      set_sky_map_sampling(sky_map_.get());
    }
    render_map(shaders, sky_map_.get(), -1, height, sun);
    glGenerateTextureMipmap(sky_map_.get());
    if (timer) timer->end_pass("sky.map");
    glFinish();
    sky_map_ms_ = elapsed_ms(start);
    ++sky_map_builds_;
    map_height_ = height;
    map_sun_ = sun;
    return sky_map_.get();
  }

  GLuint sky_map_array(gl::ShaderLibrary& shaders, gl::GpuTimer* timer) override {
    if (sky_map_array_) return sky_map_array_.get();
    const auto start = std::chrono::steady_clock::now();
    sky_map_array_ = gl::make_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(sky_map_array_.get(), sky_map_mip_levels(settings_.size), GL_RGBA32F,
                       settings_.size, settings_.size, settings_.array_layers);
    set_sky_map_sampling(sky_map_array_.get());
    for (int layer = 0; layer < settings_.array_layers; ++layer) {
      const double zenith = sky_map_array_zenith(settings_, layer);
      render_map(shaders, sky_map_array_.get(), layer, 0.0,
                 glm::dvec3(0.0, std::sin(zenith), std::cos(zenith)));
    }
    glGenerateTextureMipmap(sky_map_array_.get());
    if (timer) timer->end_pass("sky.map_array");
    glFinish();
    sky_map_array_ms_ = elapsed_ms(start);
    return sky_map_array_.get();
  }

  const SkyMapSettings& sky_map_settings() const override { return settings_; }
  double sky_map_ms() const override { return sky_map_ms_; }
  int sky_map_builds() const override { return sky_map_builds_; }
  double sky_map_array_ms() const override { return sky_map_array_ms_; }
  std::vector<std::pair<std::string, double>> setup_ms() const override {
    if (model_->precompute_seconds() > 0.0)
      return {{"atmosphere.precompute", 1e3 * model_->precompute_seconds()}};
    return {{"atmosphere.load", 1e3 * model_->load_seconds()}};
  }

  glm::dvec3 sun_radiance(double height, const glm::dvec3& sun) const override {
    return model_->sun_radiance(position(height), sun);
  }
  double sun_angular_radius() const override { return model_->parameters().sun_angular_radius; }
  glm::dvec3 sun_disc_radiance() const override {
    const AtmosphereParameters& p = model_->parameters();
    return p.solar_irradiance / (2.0 * glsl::PI * (1.0 - std::cos(p.sun_angular_radius)));
  }
  glm::dvec3 sun_irradiance(double height, const glm::dvec3& sun) const override {
    return model_->sun_and_sky_irradiance(position(height), {0.0, 0.0, 1.0}, sun, nullptr);
  }
  glm::dvec3 sky_irradiance(double height, const glm::dvec3& sun) const override {
    glm::dvec3 sky;
    model_->sun_and_sky_irradiance(position(height), {0.0, 0.0, 1.0}, sun, &sky);
    return sky;
  }
  glm::dvec3 below_horizon_radiance(double height, const glm::dvec3& sun) const override {
    return mean_water_fresnel() / glsl::PI * sky_irradiance(height, sun);
  }
  glm::dvec3 sky_radiance(double height, const glm::dvec3& view,
                          const glm::dvec3& sun) const override {
    return model_->sky_radiance(position(height), view, sun);
  }
  glm::dvec3 aerial_perspective(double height, const glm::dvec3& offset, const glm::dvec3& sun,
                                glm::dvec3* transmittance) const override {
    const glm::dvec3 camera = position(height);
    const glm::dvec3 point = glm::dvec3(0.0, 0.0, planet_radius()) + offset;
    return model_->sky_radiance_to_point(camera, point, sun, transmittance);
  }
  std::optional<glm::dvec3> sun_direction() const override { return std::nullopt; }
  double planet_radius() const override { return model_->parameters().bottom_radius; }

 private:
  glm::dvec3 position(double height) const {
    return glm::dvec3(0.0, 0.0, planet_radius() + height);
  }

  static double elapsed_ms(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  }

  // Renders the sky seen from `height` into level 0 of `texture` (a layer of it if layer >= 0).
  void render_map(gl::ShaderLibrary& shaders, GLuint texture, int layer, double height,
                  const glm::dvec3& sun) {
    gl::StateGuard guard;
    gl::Framebuffer framebuffer = gl::make_framebuffer();
    if (layer < 0) {
      glNamedFramebufferTexture(framebuffer.get(), GL_COLOR_ATTACHMENT0, texture, 0);
    } else {
      glNamedFramebufferTextureLayer(framebuffer.get(), GL_COLOR_ATTACHMENT0, texture, 0, layer);
    }
    if (glCheckNamedFramebufferStatus(framebuffer.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw gl::GlError("sky map: framebuffer incomplete");
    const GLuint program = shaders.program({.vertex = "engine/fullscreen.vert",
                                            .fragment = "atmosphere/sky_map.frag",
                                            .defines = defines()});
    const glm::dvec3 observer = position(height);
    const glm::dvec3 below = below_horizon_radiance(height, sun);
    glProgramUniform3f(program, glGetUniformLocation(program, "observer"), float(observer.x),
                       float(observer.y), float(observer.z));
    glProgramUniform3f(program, glGetUniformLocation(program, "sun_direction"), float(sun.x),
                       float(sun.y), float(sun.z));
    glProgramUniform3f(program, glGetUniformLocation(program, "below_horizon_radiance"),
                       float(below.x), float(below.y), float(below.z));
    glProgramUniform1f(program, glGetUniformLocation(program, "map_size"), float(settings_.size));
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glViewport(0, 0, settings_.size, settings_.size);
    gl::set_pass_state();
    glBindVertexArray(vertex_array_.get());  // full-screen passes draw from gl_VertexID
    glUseProgram(program);
    // The map itself must not be bound while it is the target.
    glBindTextureUnit(kSkyMapUnit, 0);
    glBindTextureUnit(kSkyTransmittanceUnit, transmittance_.get());
    glBindTextureUnit(kSkyScatteringUnit, scattering_.get());
    glBindTextureUnit(kSkySingleMieUnit, single_mie_.get());
    glBindTextureUnit(kSkyIrradianceUnit, irradiance_.get());
    gl::draw_fullscreen_pass();
  }

  std::shared_ptr<const AtmosphereModel> model_;
  SkyMapSettings settings_;
  gl::Texture transmittance_, scattering_, single_mie_, irradiance_;
  gl::Texture sky_map_, sky_map_array_;
  gl::VertexArray vertex_array_;
  double map_height_ = 0.0;
  glm::dvec3 map_sun_{0.0};
  double sky_map_ms_ = 0.0, sky_map_array_ms_ = 0.0;
  int sky_map_builds_ = 0;
};

}  // namespace

double sky_map_array_zenith(const SkyMapSettings& s, double layer) {
  const double k = s.array_knee_layer, last = s.array_layers - 1;
  layer = std::clamp(layer, 0.0, last);
  if (layer <= k) return s.array_knee_zenith * layer / k;
  return s.array_knee_zenith +
         (s.array_max_sun_zenith - s.array_knee_zenith) * (layer - k) / (last - k);
}

double sky_map_array_layer(const SkyMapSettings& s, double zenith) {
  const double k = s.array_knee_layer, last = s.array_layers - 1;
  zenith = std::clamp(zenith, 0.0, s.array_max_sun_zenith);
  if (zenith <= s.array_knee_zenith) return k * zenith / s.array_knee_zenith;
  return k + (last - k) * (zenith - s.array_knee_zenith) /
                 (s.array_max_sun_zenith - s.array_knee_zenith);
}

std::shared_ptr<SkyProvider> make_atmosphere_provider(std::shared_ptr<const AtmosphereModel> model,
                                                      const SkyMapSettings& settings) {
  if (!model) throw std::invalid_argument("make_atmosphere_provider: no model");
  return std::make_shared<AtmosphereProvider>(std::move(model), settings);
}

}  // namespace thalassa::atmosphere
