#include "thalassa/planet/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>

#include "sky_provider_factory.hpp"
#include "space_ocean_node.hpp"
#include "thalassa/atmosphere/gl/sky_node.hpp"
#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/gpu_timer.hpp"
#include "thalassa/engine/gl/hdr_target.hpp"
#include "thalassa/engine/gl/scene_graph.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/engine/gl/state_guard.hpp"
#include "thalassa/engine/gl_info.hpp"
#include "thalassa/ocean/gl/ocean_node.hpp"
#include "thalassa/ocean/projected_grid.hpp"
#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/nadir_frame.hpp"

namespace thalassa {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
// Lowest camera height drawn, m: 1 mm, below anything a pixel of the sea can show from there
// (the issue 7 stress cases go down to 0.01 m).
constexpr double kSurfaceCameraHeight = 1e-3;

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

gl::FrameInputs frame_inputs(const Scene& scene, const NadirFrame& frame) {
  gl::FrameInputs inputs;
  inputs.width = scene.image.width;
  inputs.height = scene.image.height;
  const CameraBasis basis =
      camera_basis(scene.camera.heading, scene.camera.pitch, scene.camera.roll);
  inputs.camera_right = basis.right;
  inputs.camera_up = basis.up;
  inputs.camera_forward = basis.forward;
  inputs.tan_half_fov_y = std::tan(0.5 * scene.camera.fov_y * kDegree);
  // A camera exactly on the sea is above it (the scene allows height 0): it sees the sea from
  // kSurfaceCameraHeight, since the sea's quadric meets rays from a positive height only.
  inputs.camera_height = scene.camera.height >= 0.0
                             ? std::max(scene.camera.height, kSurfaceCameraHeight)
                             : scene.camera.height;
  inputs.sun_direction = sun_direction(scene.sun.zenith, scene.sun.azimuth);
  inputs.time = scene.time;
  inputs.sea_curvature = frame.sea_surface.curvature;
  inputs.wave_origin = frame.wave_origin;
  inputs.wave_axes = frame.wave_axes;
  return inputs;
}

// Which of the sky and the sea the image sees: the image's rays against the sea at rest (the
// planet's quadric), decided exactly by the projected grid's tests (projected_grid.hpp).
void horizon_visibility(const gl::FrameInputs& inputs, bool& sky_visible, bool& sea_visible) {
  // Below the surface the sea fills the whole image with deep-water light.
  if (inputs.camera_height < 0.0) {
    sea_visible = true;
    sky_visible = false;
    return;
  }
  const ocean::GridCamera camera = ocean::make_grid_camera(
      inputs.camera_right, inputs.camera_up, inputs.camera_forward, inputs.tan_half_fov_y,
      inputs.camera_height, inputs.width, inputs.height, ocean::SeaSurface{inputs.sea_curvature});
  const glm::dvec2 lo(-1.0), hi(1.0);  // the whole image
  sea_visible = ocean::image_sees_sea(camera, lo, hi);
  sky_visible = ocean::image_sees_sky(camera, lo, hi);
}

}  // namespace

void check_drawable(const Scene& scene, const std::string& source) {
  std::error_code error;
  if (!scene.sky.exr.empty() && !std::filesystem::is_regular_file(scene.sky.exr, error))
    throw SceneError(source + ": sky.exr: expected an HDR image file, got \"" + scene.sky.exr +
                     "\" (no such file)");
}

struct Renderer::Impl {
  GlContext& context;
  Scene scene;
  NadirFrame nadir;
  gl::FrameInputs inputs;
  gl::ShaderLibrary shaders;
  gl::HdrTarget target;
  gl::SceneGraph graph;
  GlInfo info;
  std::vector<double> frame_ms;
  std::map<std::string, std::vector<double>> pass_ms;
  std::vector<std::string> pass_order;
  gl::VertexArray present_vao;
  gl::GpuTimer timer;
  std::shared_ptr<atmosphere::SkyProvider> provider;
  double provider_ms = 0.0;  // creating the provider: tables computed or loaded, uploaded

  Impl(GlContext& context_, const Scene& scene_, const RendererOptions& options)
      : context(context_),
        scene(scene_),
        nadir(make_nadir_frame(Planet(scene_.planet), scene_.camera, options.wave_anchor)),
        inputs(frame_inputs(scene_, nadir)),
        shaders([&] {
          std::vector<std::filesystem::path> roots(options.shader_roots.begin(),
                                                   options.shader_roots.end());
          return roots;
        }()),
        target(scene_.image.width, scene_.image.height),
        info(query_gl_info()),
        timer(gl::GpuTimer::source_for_renderer(info.renderer)) {
    check_drawable(scene);
    if (!info.missing.empty()) {
      std::string missing;
      for (const auto& name : info.missing) missing += (missing.empty() ? "" : ", ") + name;
      throw gl::GlError("this OpenGL context lacks what thalassa needs: " + missing);
    }
    const auto provider_start = std::chrono::steady_clock::now();
    provider = make_sky_provider(scene, options);
    provider_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - provider_start)
            .count();
    // A photograph's sun is where the photograph has it.
    if (const auto sun = provider->sun_direction()) inputs.sun_direction = *sun;
    bool sky_visible = false, sea_visible = false;
    horizon_visibility(inputs, sky_visible, sea_visible);
    // The sun's disc and glint while any of the disc is above the horizon (the provider fades
    // them as it sets).
    const bool sun_up = inputs.sun_direction.z > -std::sin(provider->sun_angular_radius());
    if (sky_visible) graph.add(atmosphere::make_sky_node({.sun_disc = sun_up}, provider));
    const bool space = scene.camera.height >= kSpaceModeHeight;
    if (sea_visible && space)
      graph.add(make_space_ocean_node({.settings = scene.ocean,
                                       .sun_glint = sun_up && options.terms.sun,
                                       .sky = options.terms.sky,
                                       .sea = options.terms.sea,
                                       .air = options.terms.air,
                                       .provider = provider}));
    else if (sea_visible)
      graph.add(
          ocean::make_ocean_node({.settings = scene.ocean,
                                  .sun_glint = sun_up && options.terms.sun,
                                  .sky = options.terms.sky,
                                  .sea = options.terms.sea,
                                  .air = options.terms.air,
                                  .sky_nine_samples = scene.ocean.sky_filter == "nine_samples",
                                  .sky_shrm = scene.ocean.sky_filter == "shrm",
                                  .provider = provider}));
  }
};

Renderer::Renderer(GlContext& context, const Scene& scene, RendererOptions options)
    : impl_(std::make_unique<Impl>(context, scene, options)) {
  // A first frame compiles every shader, so that no timed frame includes compilation.
  render();
  impl_->frame_ms.clear();
  impl_->pass_ms.clear();
}

// GL objects are deleted in the renderer's own context (a no-op for a host's context, which
// the host must keep current).
Renderer::~Renderer() {
  try {
    if (impl_) impl_->context.make_current();
  } catch (const ContextError&) {
    // A context that cannot be made current any more has lost its objects with it.
  }
}

void Renderer::render() {
  Impl& m = *impl_;
  m.context.make_current();
  gl::PassTime frame;
  {
    const gl::StateGuard guard;  // a host's context gets its state back
    m.graph.render(m.inputs, m.target, m.shaders, m.timer);
  }
  const auto passes = m.timer.resolve(frame);
  const bool wall = m.timer.source() == gl::TimingSource::FinishWallClock;
  m.frame_ms.push_back(wall ? frame.wall_ms : frame.query_ms);
  m.pass_order.clear();
  for (const auto& pass : passes) {
    m.pass_order.push_back(pass.name);
    m.pass_ms[pass.name].push_back(wall ? pass.wall_ms : pass.query_ms);
  }
}

Image Renderer::image() const {
  impl_->context.make_current();
  Image image;
  image.width = impl_->target.width();
  image.height = impl_->target.height();
  image.rgba = impl_->target.read_rgba_top_down();
  return image;
}

unsigned Renderer::hdr_texture() const { return impl_->target.color_texture(); }
unsigned Renderer::hdr_framebuffer() const { return impl_->target.framebuffer(); }

void Renderer::present(unsigned framebuffer, int width, int height) {
  Impl& m = *impl_;
  m.context.make_current();
  if (!m.present_vao) m.present_vao = gl::make_vertex_array();
  const GLuint program =
      m.shaders.program({.vertex = "engine/fullscreen.vert", .fragment = "engine/tonemap.frag"});
  const gl::StateGuard guard;
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  gl::set_pass_state();
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program);
  glBindTextureUnit(0, m.target.color_texture());
  glProgramUniform1f(program, glGetUniformLocation(program, "exposure"),
                     static_cast<float>(m.scene.image.exposure));
  glBindVertexArray(m.present_vao.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  gl::check_error("present");
}

RenderStats Renderer::stats() const {
  const Impl& m = *impl_;
  RenderStats stats;
  stats.backend = std::string(backend_name(m.context.backend()));
  stats.renderer = m.info.renderer;
  stats.width = m.target.width();
  stats.height = m.target.height();
  stats.mode = m.scene.camera.height >= kSpaceModeHeight ? "space" : "surface";
  stats.frames = static_cast<int>(m.frame_ms.size());
  stats.frame_ms = median(m.frame_ms);
  stats.timing = m.timer.source() == gl::TimingSource::FinishWallClock ? "finish_wall_clock"
                                                                       : "gl_timestamp_query";
  for (const auto& name : m.pass_order) {
    auto it = m.pass_ms.find(name);
    if (it != m.pass_ms.end()) stats.passes.emplace_back(name, median(it->second));
  }
  for (const auto& node : m.graph.nodes())
    stats.resolved_waves = std::max(stats.resolved_waves, node->resolved_waves());
  stats.built.push_back("engine.hdr_target.rgba32f+depth32f." + std::to_string(stats.width) + "x" +
                        std::to_string(stats.height));
  for (const auto& item : m.provider->built()) stats.built.push_back(item);
  for (const auto& node : m.graph.nodes())
    for (const auto& item : node->built()) stats.built.push_back(item);
  stats.sky_provider = m.provider->kind();
  stats.setup_ms.emplace_back("sky.provider", m.provider_ms);
  for (const auto& [name, ms] : m.provider->setup_ms()) stats.setup_ms.emplace_back(name, ms);
  if (m.provider->sky_map_ms() > 0.0)
    stats.setup_ms.emplace_back("sky.map", m.provider->sky_map_ms());
  if (m.provider->sky_map_array_ms() > 0.0)
    stats.setup_ms.emplace_back("sky.map_array", m.provider->sky_map_array_ms());
  for (const auto& program : m.shaders.built_programs()) stats.built.push_back("shader:" + program);
  return stats;
}

const Scene& Renderer::scene() const { return impl_->scene; }

}  // namespace thalassa
