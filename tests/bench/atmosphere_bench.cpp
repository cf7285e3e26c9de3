// The atmosphere's costs (issue 4, point 7): the CPU precomputation of its tables and loading
// them from the cache; the CPU queries of AtmosphereModel; and on the GL device the sky map, the
// sun-zenith array of sky maps, the per-frame sky pass and the aerial perspective. Timed, never
// asserted (DESIGN section 6); docs/atmosphere.md reports a run. On llvmpipe quote ratios, not
// absolute GPU times.
//
// Run: build/tests/atmosphere_bench [--benchmark_filter=...] with THALASSA_CACHE_DIR set (the
// cache to load; the precomputation benchmark bypasses it). THALASSA_BACKEND=osmesa picks OSMesa;
// the default is the headless default.
#include <benchmark/benchmark.h>
#include <glad/gl.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/atmosphere/model.hpp"
#include "thalassa/engine/gl/hdr_target.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/thalassa.hpp"

namespace {

using thalassa::atmosphere::AtmosphereModel;
using thalassa::atmosphere::AtmosphereParameters;
using thalassa::atmosphere::PrecomputeOptions;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

// The Earth model from the cache (computed and cached on the first run).
const std::shared_ptr<const AtmosphereModel>& model() {
  static const std::shared_ptr<const AtmosphereModel> instance =
      AtmosphereModel::create(AtmosphereParameters::earth());
  return instance;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---------------------------------------------------------------------------------------------
// CPU.

void Precompute(benchmark::State& state) {
  PrecomputeOptions options;
  options.use_cache = false;
  options.threads = static_cast<int>(state.range(0));
  double seconds = 0.0;
  for (auto _ : state) {
    const auto m = AtmosphereModel::create(AtmosphereParameters::earth(), options);
    seconds = m->precompute_seconds();
  }
  state.counters["precompute_s"] = seconds;
  state.counters["threads"] = static_cast<double>(state.range(0));
}
BENCHMARK(Precompute)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

void LoadCache(benchmark::State& state) {
  model();  // make sure the cache file exists
  for (auto _ : state) {
    // Not the tables of model() already in memory: the file's read is what is timed.
    const auto m = AtmosphereModel::create(AtmosphereParameters::earth(),
                                           PrecomputeOptions{.share_in_process = false});
    if (m->cache_status() != "loaded") state.SkipWithError("the cache was not loaded");
    benchmark::DoNotOptimize(m.get());
  }
}
BENCHMARK(LoadCache)->Iterations(5)->Unit(benchmark::kMillisecond)->UseRealTime();

// 256 view directions over the sphere and a camera 2 m above the sea, sun 60 degrees from the
// zenith.
struct QueryInputs {
  glm::dvec3 camera;
  glm::dvec3 sun;
  std::vector<glm::dvec3> views;
};

const QueryInputs& inputs() {
  static const QueryInputs q = [] {
    QueryInputs q;
    q.camera = glm::dvec3(0.0, 0.0, model()->parameters().bottom_radius + 2.0);
    q.sun = glm::dvec3(std::sin(60.0 * kDegree), 0.0, std::cos(60.0 * kDegree));
    for (int i = 0; i < 256; ++i) {
      const double z = 1.0 - (i + 0.5) / 128.0;  // uniform in cos(zenith)
      const double phi = i * 2.399963;           // golden angle, rad
      const double s = std::sqrt(1.0 - z * z);
      q.views.emplace_back(s * std::cos(phi), s * std::sin(phi), z);
    }
    return q;
  }();
  return q;
}

void SkyRadiance(benchmark::State& state) {
  const QueryInputs& q = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(model()->sky_radiance(q.camera, q.views[i++ & 255], q.sun));
  }
}
BENCHMARK(SkyRadiance);

void SkyRadianceToPoint(benchmark::State& state) {
  const QueryInputs& q = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    const glm::dvec3 point = q.camera + 5000.0 * q.views[i++ & 255];
    benchmark::DoNotOptimize(model()->sky_radiance_to_point(q.camera, point, q.sun));
  }
}
BENCHMARK(SkyRadianceToPoint);

void SunAndSkyIrradiance(benchmark::State& state) {
  const QueryInputs& q = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    glm::dvec3 sky;
    benchmark::DoNotOptimize(
        model()->sun_and_sky_irradiance(q.camera, q.views[i++ & 255], q.sun, &sky));
  }
}
BENCHMARK(SunAndSkyIrradiance);

void SunRadiance(benchmark::State& state) {
  const QueryInputs& q = inputs();
  for (auto _ : state) benchmark::DoNotOptimize(model()->sun_radiance(q.camera, q.sun));
}
BENCHMARK(SunRadiance);

// ---------------------------------------------------------------------------------------------
// GL.

thalassa::GlContext& context() {
  static std::unique_ptr<thalassa::GlContext> instance = [] {
    std::unique_ptr<thalassa::GlContext> c;
    const char* name = std::getenv("THALASSA_BACKEND");
    if (name != nullptr) {
      if (auto backend = thalassa::parse_backend(name)) c = thalassa::create_context(*backend);
    }
    if (!c) c = thalassa::create_headless_context();
    c->make_current();
    // This program's own GL table, for the aerial-perspective pass and glFinish.
    if (gladLoadGL(reinterpret_cast<GLADloadfunc>(c->proc_address())) == 0) {
      throw std::runtime_error("glad could not load GL");
    }
    return c;
  }();
  return *instance;
}

// The bench's shaders (tests/bench/shaders) before the library's.
thalassa::gl::ShaderLibrary& shaders() {
  static thalassa::gl::ShaderLibrary library({THALASSA_BENCH_SHADER_DIR});
  return library;
}

void SkyMap(benchmark::State& state) {
  context();
  thalassa::atmosphere::SkyMapSettings settings;
  settings.size = static_cast<int>(state.range(0));
  const auto provider = thalassa::atmosphere::make_atmosphere_provider(model(), settings);
  int k = 0;
  for (auto _ : state) {
    // Another sun each time, so that the map is rebuilt.
    const double zenith = (30.0 + (k++ % 16)) * kDegree;
    const glm::dvec3 sun(std::sin(zenith), 0.0, std::cos(zenith));
    const auto start = std::chrono::steady_clock::now();
    provider->sky_map(2.0, sun, shaders(), nullptr);
    glFinish();
    state.SetIterationTime(seconds_since(start));
  }
  state.SetLabel(reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
}
BENCHMARK(SkyMap)->Arg(512)->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);

void SkyMapArray(benchmark::State& state) {
  context();
  for (auto _ : state) {
    const auto provider = thalassa::atmosphere::make_atmosphere_provider(model());
    const auto start = std::chrono::steady_clock::now();
    provider->sky_map_array(shaders(), nullptr);
    glFinish();
    state.SetIterationTime(seconds_since(start));
    state.counters["layers"] = provider->sky_map_settings().array_layers;
  }
}
BENCHMARK(SkyMapArray)->Iterations(2)->UseManualTime()->Unit(benchmark::kMillisecond);

// A frame of the default scene at 1024 x 768, looking up (sky only: the sky pass) or at the sea
// (the ocean's passes, whose lighting includes the aerial perspective, and the sky above the
// horizon). GPU pass times from the renderer's statistics.
void Frame(benchmark::State& state) {
  thalassa::SceneBuilder builder;
  builder.set("image.width=1024");
  builder.set("image.height=768");
  builder.set("camera.pitch=" + std::to_string(state.range(0)));
  thalassa::Renderer renderer(context(), builder.build());
  for (auto _ : state) renderer.render();
  const thalassa::RenderStats stats = renderer.stats();
  state.counters["frame_ms"] = stats.frame_ms;
  for (const auto& [name, ms] : stats.passes) state.counters[name + "_ms"] = ms;
  state.SetLabel(state.range(0) > 0 ? "sky only" : "sea");
}
BENCHMARK(Frame)->Arg(60)->Arg(-5)->Iterations(3)->Unit(benchmark::kMillisecond);

// The aerial perspective alone over a 1024 x 768 full-screen pass (one evaluation per pixel, as
// the ocean's lighting does).
void AerialPerspective(benchmark::State& state) {
  context();
  const auto provider = thalassa::atmosphere::make_atmosphere_provider(model());
  const glm::dvec3 sun(std::sin(60.0 * kDegree), 0.0, std::cos(60.0 * kDegree));
  provider->sky_map(2.0, sun, shaders(), nullptr);
  thalassa::gl::HdrTarget target(1024, 768);
  const GLuint program = shaders().program(
      {"engine/fullscreen.vert", "bench/aerial_perspective.frag", "", provider->defines()});
  GLuint vertex_array = 0;
  glCreateVertexArrays(1, &vertex_array);
  const double radius = provider->planet_radius();
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    target.begin();
    glUseProgram(program);
    provider->bind();
    glUniform3f(glGetUniformLocation(program, "camera_position"), 0.0f, 0.0f,
                static_cast<float>(radius + 2.0));
    glUniform3f(glGetUniformLocation(program, "sun_direction"), static_cast<float>(sun.x),
                static_cast<float>(sun.y), static_cast<float>(sun.z));
    glUniform1f(glGetUniformLocation(program, "planet_radius"), static_cast<float>(radius));
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    state.SetIterationTime(seconds_since(start));
  }
  glBindVertexArray(0);
  glDeleteVertexArrays(1, &vertex_array);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}
BENCHMARK(AerialPerspective)->Iterations(5)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
