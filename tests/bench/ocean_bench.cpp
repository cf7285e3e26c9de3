// The paper's performance setting (Bruneton et al. 2010, sec. 7.3): 1024x768, 60 waves from
// 2 cm to 30 m, 8x8-pixel grid cells, the camera looking at the horizon, at heights of 4 m,
// 1,000 m and 8,000 m. Reports the frame and its split into positions + normals + variances
// (ocean.geometry) and lighting (ocean.lighting), with the resolved-wave count. PlanetFrame adds
// the planet's views (issue 5, point 7): both sides of the switch to the view from space (19,990
// and 20,010 m) and orbits of 400 km and 36,000 km, looking 30 degrees down, whose ocean is one
// full-screen pass (ocean.space) instead of the grid's two. ProjectedGridCpu times the projected
// grid alone on the CPU. Timed, never asserted (DESIGN section 6). Run:
// build/tests/ocean_bench [--benchmark_repetitions=N] [--benchmark_filter=ProjectedGridCpu]
// (THALASSA_BACKEND=osmesa picks OSMesa; the default is the headless default).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "thalassa/ocean/projected_grid.hpp"
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

// The projected grid alone (CPU, double; no GL): the same image, cells and view, the node's 2
// margin cells, on the flat sea (arg 0), the sphere of 6371 km (1) and WGS84 at 45 degrees north
// (2). Half the grid lies on the sky's side and is moved onto the horizon.
void ProjectedGridCpu(benchmark::State& state) {
  const double height = double(state.range(1));
  const thalassa::CameraBasis b = thalassa::camera_basis(0.0, 0.0, 0.0);
  const thalassa::ocean::SeaSurface surface =
      state.range(0) == 0   ? thalassa::ocean::flat_sea_surface()
      : state.range(0) == 1 ? thalassa::ocean::spherical_sea_surface(6371e3)
                            : thalassa::planet_sea_surface(thalassa::Planet::wgs84(), 45.0, 0.0);
  const thalassa::ocean::GridCamera camera = thalassa::ocean::make_grid_camera(
      b.right, b.up, b.forward, std::tan(0.5 * 45.0 * 3.14159265358979 / 180.0), height, 1024, 768,
      surface);
  int moved = 0;
  for (auto _ : state) {
    const thalassa::ocean::ProjectedGrid grid = thalassa::ocean::make_projected_grid(camera, 8, 2);
    moved = grid.moved_to_horizon;
    benchmark::DoNotOptimize(grid.rest.data());
  }
  state.counters["moved_to_horizon"] = moved;
}

BENCHMARK(ProjectedGridCpu)
    ->ArgsProduct({{0, 1, 2}, {4, 1000, 8000}})
    ->ArgNames({"sea", "h"})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
