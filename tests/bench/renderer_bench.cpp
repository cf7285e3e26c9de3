// A host's frame loop: the camera moves every frame (the default scene's camera turning 0.5
// degree and climbing 1 cm a frame, its clock 1/30 s on), drawn by a new Renderer per frame
// (sharing one sky provider, RendererOptions::sky_cache) or by one Renderer given each frame's
// scene (Renderer::set_scene). Wall-clock ms per frame, the frame's drawing included (render()
// waits for its timer queries). Run by hand: build/tests/renderer_bench; THALASSA_BACKEND=osmesa
// or egl picks the backend.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

#include "thalassa/thalassa.hpp"

namespace {

thalassa::GlContext& context() {
  static std::unique_ptr<thalassa::GlContext> instance = [] {
    std::unique_ptr<thalassa::GlContext> c;
    if (const char* name = std::getenv("THALASSA_BACKEND"))
      if (auto backend = thalassa::parse_backend(name)) c = thalassa::create_context(*backend);
    if (!c) c = thalassa::create_headless_context();
    c->make_current();
    return c;
  }();
  return *instance;
}

// The default scene at width x (width * 9 / 16), frame k of the loop.
thalassa::Scene frame_scene(int width, int k) {
  thalassa::SceneBuilder builder;
  builder.set("image.width=" + std::to_string(width));
  builder.set("image.height=" + std::to_string(width * 9 / 16));
  thalassa::Scene scene = builder.build();
  scene.camera.heading += 0.5 * (k % 64);
  scene.camera.height += 0.01 * (k % 64);
  scene.time += k / 30.0;
  return scene;
}

void NewRendererPerFrame(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0));
  thalassa::RendererOptions options;
  options.sky_cache = thalassa::make_sky_provider_cache();
  // The provider made and the programs compiled once before the loop, as a flight's first
  // frame does.
  { thalassa::Renderer(context(), frame_scene(width, 0), options).render(); }
  int k = 1;
  for (auto _ : state) {
    thalassa::Renderer renderer(context(), frame_scene(width, k++), options);
    renderer.render();
  }
  state.SetLabel(thalassa::Renderer(context(), frame_scene(width, 0), options).stats().renderer);
}
BENCHMARK(NewRendererPerFrame)->Arg(320)->Arg(960)->Unit(benchmark::kMillisecond);

void SetScenePerFrame(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0));
  thalassa::Renderer renderer(context(), frame_scene(width, 0));
  renderer.render();
  int k = 1;
  for (auto _ : state) {
    renderer.set_scene(frame_scene(width, k++));
    renderer.render();
  }
  state.counters["frame_ms"] = renderer.stats().frame_ms;  // the last frame's GPU time
  state.SetLabel(renderer.stats().renderer);
}
BENCHMARK(SetScenePerFrame)->Arg(320)->Arg(960)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
