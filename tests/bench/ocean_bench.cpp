// The paper's performance setting (Bruneton et al. 2010, sec. 7.3): 1024x768, 60 waves from
// 2 cm to 30 m, 8x8-pixel grid cells, the camera looking at the horizon, at heights of 4 m,
// 1,000 m and 8,000 m. Reports the frame and its split into positions + normals + variances
// (ocean.geometry) and lighting (ocean.lighting), with the resolved-wave count. PlanetFrame adds
// the planet's views (issue 5, point 7): both sides of the switch to the view from space (19,990
// and 20,010 m) and orbits of 400 km and 36,000 km, looking 30 degrees down, whose ocean is one
// full-screen pass (ocean.space) instead of the grid's two. Timed, never
// asserted (DESIGN section 6). Run: build/tests/ocean_bench [--benchmark_repetitions=N]
// (THALASSA_BACKEND=osmesa picks OSMesa; the default is the headless default).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "thalassa/thalassa.hpp"

namespace {

thalassa::GlContext& context() {
  static std::unique_ptr<thalassa::GlContext> instance = [] {
    const char* name = std::getenv("THALASSA_BACKEND");
    if (name != nullptr) {
      if (auto backend = thalassa::parse_backend(name)) return thalassa::create_context(*backend);
    }
    return thalassa::create_headless_context();
  }();
  return *instance;
}

void OceanFrame(benchmark::State& state) {
  thalassa::SceneBuilder builder;
  builder.set("image.width=1024");
  builder.set("image.height=768");
  builder.set("camera.height=" + std::to_string(state.range(0)));
  builder.set("camera.pitch=0");  // the horizon across the middle of the image
  builder.set("ocean.waves=60");
  builder.set("ocean.lambda_min=0.02");
  builder.set("ocean.lambda_max=30");
  builder.set("ocean.grid_cell=8");
  thalassa::Renderer renderer(context(), builder.build());
  for (auto _ : state) renderer.render();
  const thalassa::RenderStats stats = renderer.stats();
  state.counters["frame_ms"] = stats.frame_ms;
  for (const auto& [name, ms] : stats.passes) state.counters[name + "_ms"] = ms;
  state.counters["resolved_waves"] = stats.resolved_waves;
  state.SetLabel(stats.renderer + ", " + stats.timing);
}

BENCHMARK(OceanFrame)->Arg(4)->Arg(1000)->Arg(8000)->Unit(benchmark::kMillisecond)->Iterations(3);

void PlanetFrame(benchmark::State& state) {
  thalassa::SceneBuilder builder;
  builder.set("image.width=1024");
  builder.set("image.height=768");
  builder.set("camera.height=" + std::to_string(state.range(0)));
  builder.set("camera.pitch=" + std::string(state.range(0) > 1000000 ? "-90" : "-30"));
  builder.set("camera.fov_y=" + std::string(state.range(0) > 1000000 ? "25" : "45"));
  thalassa::Renderer renderer(context(), builder.build());
  for (auto _ : state) renderer.render();
  const thalassa::RenderStats stats = renderer.stats();
  state.counters["frame_ms"] = stats.frame_ms;
  for (const auto& [name, ms] : stats.passes) state.counters[name + "_ms"] = ms;
  state.SetLabel(stats.mode + ", " + stats.renderer + ", " + stats.timing);
}

BENCHMARK(PlanetFrame)
    ->Arg(19990)
    ->Arg(20010)
    ->Arg(400000)
    ->Arg(36000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
