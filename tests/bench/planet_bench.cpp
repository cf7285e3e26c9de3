// The CPU work of placing a scene's wakes and calm areas in a frame (place_local_features), as a
// host pays it each frame the camera moves: data/scenes/wake_demo/wake_50m.json (a 12-vertex
// slick with a 150 m fade and a ship's wake) seen from its camera, turned by 1 degree a frame.
// Wall-clock ms per call. Run by hand: build/tests/planet_bench.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "thalassa/planet/local_features.hpp"
#include "thalassa/thalassa.hpp"

namespace {

thalassa::Scene wake_demo() {
  thalassa::SceneBuilder builder;
  builder.load_file(std::string(THALASSA_BENCH_DATA_DIR) + "/scenes/wake_demo/wake_50m.json");
  return builder.build();
}

void PlaceLocalFeatures(benchmark::State& state) {
  thalassa::Scene scene = wake_demo();
  scene.image.width = static_cast<int>(state.range(0));
  scene.image.height = scene.image.width * 9 / 16;
  const thalassa::Planet planet(scene.planet);
  const int samples = static_cast<int>(state.range(1));
  int k = 0;
  std::size_t chart = 0;
  for (auto _ : state) {
    scene.camera.heading = 250.0 + (k++ % 16);
    const thalassa::NadirFrame frame = thalassa::make_nadir_frame(planet, scene.camera);
    const thalassa::ocean::LocalFeatures features =
        thalassa::place_local_features(planet, scene, frame, samples);
    chart = features.calm ? features.calm->scale.size() : 0;
    benchmark::DoNotOptimize(chart);
  }
  state.counters["chart_samples"] = static_cast<double>(chart);
}
BENCHMARK(PlaceLocalFeatures)
    ->Args({320, thalassa::kCalmChartSamples})
    ->Args({1024, thalassa::kCalmChartSamples})
    ->Unit(benchmark::kMillisecond);

// A square calm area of side state.range(0) km at 45 N (scale 0.2, fade 150 m), seen from
// state.range(1) m up over its southern edge, looking north 30 degrees down, at 1024 x 576.
void PlaceSquareCalmArea(benchmark::State& state) {
  const double side = 1e3 * static_cast<double>(state.range(0));
  const thalassa::Planet planet;
  thalassa::Scene scene;
  scene.image.width = 1024;
  scene.image.height = 576;
  const double half_deg = 0.5 * side / 111.2e3;
  const double dlon = half_deg / std::cos(45.0 * 3.14159265358979 / 180.0);
  thalassa::CalmAreaSettings area;
  area.name = "square";
  area.scale = 0.2;
  area.fade = 150.0;
  area.exterior = {{45.0 - half_deg, 10.0 - dlon},
                   {45.0 - half_deg, 10.0 + dlon},
                   {45.0 + half_deg, 10.0 + dlon},
                   {45.0 + half_deg, 10.0 - dlon}};
  scene.calm_areas = {area};
  scene.camera.lat = 45.0 - half_deg;
  scene.camera.lon = 10.0;
  scene.camera.height = static_cast<double>(state.range(1));
  scene.camera.pitch = -30.0;
  int k = 0;
  std::size_t chart = 0;
  for (auto _ : state) {
    scene.camera.heading = (k++ % 16) - 8.0;
    const thalassa::NadirFrame frame = thalassa::make_nadir_frame(planet, scene.camera);
    const thalassa::ocean::LocalFeatures features =
        thalassa::place_local_features(planet, scene, frame);
    chart = features.calm ? features.calm->scale.size() : 0;
    benchmark::DoNotOptimize(chart);
  }
  state.counters["chart_samples"] = static_cast<double>(chart);
}
BENCHMARK(PlaceSquareCalmArea)
    ->Args({2, 2000})
    ->Args({20, 2000})
    ->Args({200, 2000})
    ->Args({200, 100000})
    ->Args({1000, 400000})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
