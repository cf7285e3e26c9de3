#include "thalassa/planet/sky_export.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "elapsed_ms.hpp"
#include "sky_provider_factory.hpp"
#include "thalassa/atmosphere/environment_map.hpp"
#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/hdr_target.hpp"
#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/scene_graph.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/engine/gl/state_guard.hpp"
#include "thalassa/engine/gl_info.hpp"
#include "thalassa/planet/camera_frame.hpp"

namespace thalassa {
namespace {

using Clock = std::chrono::steady_clock;

void check_options(const SkyExportOptions& options) {
  if (options.map_size < 1 || options.map_size > kSkyExportMaxSize)
    throw std::invalid_argument("sky map size " + std::to_string(options.map_size) +
                                ": expected an integer in [1, " +
                                std::to_string(kSkyExportMaxSize) + "]");
  const int w = options.panorama_width;
  if (w != 0 && (w < 2 || w > kSkyExportMaxSize || w % 2 != 0))
    throw std::invalid_argument("panorama width " + std::to_string(w) +
                                ": expected an even integer in [2, " +
                                std::to_string(kSkyExportMaxSize) + "]");
}

// The provider's map texture read back as an Image: GL's row 0 is t = 0 (south), the Image's
// row 0 is north.
Image read_map(GLuint texture, int size) {
  Image image;
  image.width = image.height = size;
  image.rgba = gl::read_texture_rgba_top_down(texture, size, size, "sky map read-back");
  return image;
}

// Draws shaders/atmosphere/sky_panorama.frag into a width x width / 2 float target and reads it
// back, top row (the zenith) first.
Image render_panorama(atmosphere::SkyProvider& provider, gl::ShaderLibrary& shaders, int width,
                      double height, const glm::dvec3& sun) {
  const int panorama_height = width / 2;
  gl::HdrTarget target(width, panorama_height);
  {
    const gl::StateGuard guard;
    gl::Defines defines = provider.defines();
    // The disc while any of it is above the horizon, as the Renderer decides for the sky pass.
    const double radius = provider.sun_angular_radius();
    if (sun.z > -std::sin(radius)) defines["SUN_DISC"] = "1";
    const GLuint program = shaders.program({.vertex = "engine/fullscreen.vert",
                                            .fragment = "atmosphere/sky_panorama.frag",
                                            .defines = defines});
    const glm::dvec3 disc = provider.sun_disc_radiance();
    const auto location = [&](const char* name) { return glGetUniformLocation(program, name); };
    glProgramUniform3f(program, location("camera_position"), 0.0f, 0.0f,
                       float(provider.planet_radius() + height));
    glProgramUniform3f(program, location("sun_direction"), float(sun.x), float(sun.y),
                       float(sun.z));
    glProgramUniform3f(program, location("sun_disc_radiance"), float(disc.x), float(disc.y),
                       float(disc.z));
    glProgramUniform1f(program, location("sun_cos_angular_radius"), float(std::cos(radius)));
    glProgramUniform1f(program, location("sun_angular_radius"), float(radius));
    glProgramUniform2f(program, location("panorama_size"), float(width), float(panorama_height));
    target.begin();
    const gl::VertexArray vertex_array = gl::make_vertex_array();  // gl_VertexID only
    glBindVertexArray(vertex_array.get());
    glUseProgram(program);
    provider.bind();
    gl::draw_fullscreen_pass();
    gl::check_error("sky panorama");
  }
  Image image;
  image.width = width;
  image.height = panorama_height;
  image.rgba = target.read_rgba_top_down();
  return image;
}

}  // namespace

SkyExport render_sky(GlContext& context, const Scene& scene, const SkyExportOptions& options,
                     const RendererOptions& renderer_options) {
  check_options(options);
  check_drawable(scene);
  context.make_current();
  const GlInfo info = query_gl_info();
  if (!info.missing.empty()) {
    std::string missing;
    for (const auto& name : info.missing) missing += (missing.empty() ? "" : ", ") + name;
    throw gl::GlError("this OpenGL context lacks what thalassa needs: " + missing);
  }
  gl::ShaderLibrary shaders(std::vector<std::filesystem::path>(
      renderer_options.shader_roots.begin(), renderer_options.shader_roots.end()));

  SkyExport result;
  SkyExportStats& stats = result.stats;
  const auto provider_start = Clock::now();
  atmosphere::SkyMapSettings settings;
  settings.size = options.map_size;
  const std::shared_ptr<atmosphere::SkyProvider> provider =
      make_sky_provider(scene, renderer_options, settings);
  stats.setup_ms.emplace_back("sky.provider", elapsed_ms(provider_start));
  for (const auto& item : provider->setup_ms()) stats.setup_ms.push_back(item);

  glm::dvec3 sun = sun_direction(scene.sun.zenith, scene.sun.azimuth);
  if (const auto photograph_sun = provider->sun_direction()) {
    sun = *photograph_sun;
    result.sun_from_provider = true;
  }
  result.sun_direction = {sun.x, sun.y, sun.z};

  // The map the ocean reflects: seen from the sea surface at the camera's nadir.
  result.map = read_map(provider->sky_map(0.0, sun, shaders, nullptr), options.map_size);
  result.map_extent = atmosphere::kSkyMapExtent;
  stats.setup_ms.emplace_back("sky.map", provider->sky_map_ms());
  stats.built.push_back("planet.sky_export.map." + std::to_string(options.map_size) + "x" +
                        std::to_string(options.map_size));

  if (options.panorama_width > 0) {
    // Below the sea surface the sky is the one seen from the surface above.
    result.panorama_height = std::max(scene.camera.height, 0.0);
    const auto start = Clock::now();
    result.panorama =
        render_panorama(*provider, shaders, options.panorama_width, result.panorama_height, sun);
    stats.setup_ms.emplace_back("sky.panorama", elapsed_ms(start));
    stats.built.push_back("planet.sky_export.panorama." + std::to_string(result.panorama.width) +
                          "x" + std::to_string(result.panorama.height));
  }

  stats.backend = std::string(backend_name(context.backend()));
  stats.renderer = info.renderer;
  stats.sky_provider = provider->kind();
  stats.map_size = options.map_size;
  stats.panorama_width = result.panorama.width;
  stats.panorama_height = result.panorama.height;
  for (const auto& item : provider->built()) stats.built.push_back(item);
  for (const auto& program : shaders.built_programs()) stats.built.push_back("shader:" + program);
  return result;
}

}  // namespace thalassa
