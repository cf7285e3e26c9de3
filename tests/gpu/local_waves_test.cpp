// Wakes and calm areas on the GPU (issue 9; docs/wakes.md "On the GPU"):
// - shaders/ocean/kelvin_wake.glsl in float against ocean::kelvin_wake_at in double over a grid
//   of points of the ship frame (amplitudes, arguments, wave vectors, the linear height);
// - a scene with calm areas and a wake renders them, lists them in `built`, and a scene without
//   them compiles none of their code.
// - geodetic placement (issue 9, point 4): a mirror-flat calm area placed by latitude and
//   longitude appears where the camera projects it, the projection computed with GeographicLib's
//   own conversions, from 2 m, 2 km and 400 km, across the antimeridian and near a pole.
//   THALASSA_TEST_BACKEND=egl build/tests/gpu_tests --gtest_filter='LocalWaves*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include "test_support.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/ocean/gl/local_features_gpu.hpp"
#include "thalassa/ocean/kelvin_wake.hpp"
#include "thalassa/ocean/local_features.hpp"
#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/flight.hpp"

namespace thalassa {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double RoundToFloat(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}

// |a - b| of two angles, modulo 2 pi, rad.
double AngleDifference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), kTwoPi);
  return std::min(d, kTwoPi - d);
}

class LocalWavesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = test::make_test_context();
    library_ = std::make_unique<gl::ShaderLibrary>(
        std::vector<std::filesystem::path>{THALASSA_SOURCE_DIR "/tests/gpu/shaders"});
  }

  // KelvinWake at each (b, y) (width x height texels), OUTPUT 1 or 2; rows bottom first.
  std::vector<glm::vec4> evaluate(int output, const std::vector<glm::vec4>& inputs, int width,
                                  int height, const glm::dvec4& params,
                                  const ocean::LocalFeatureBuffers* features = nullptr) {
    const GLuint program = library_->program({.vertex = "engine/fullscreen.vert",
                                              .fragment = "kelvin_wake_eval.frag",
                                              .defines = {{"OUTPUT", std::to_string(output)}}});
    glProgramUniform4f(program, glGetUniformLocation(program, "params"), float(params.x),
                       float(params.y), float(params.z), float(params.w));
    if (features) {
      features->set_uniforms(program);
      features->bind();
    }
    return test::evaluate_fragment(program, inputs, width, height);
  }

  std::unique_ptr<GlContext> context_;
  std::unique_ptr<gl::ShaderLibrary> library_;
};

// The float shader against the double reference on a 96 x 64 grid: b from 0 to 1.05 length
// (the ship, the fade in, the far field, the tail, beyond), y / b from -0.45 to 0.45 (both
// sides, the cusp lines at +-0.354 and Airy's tail beyond), for a slow and a fast ship.
TEST_F(LocalWavesTest, KelvinWakeMatchesTheDoubleReference) {
  constexpr int kWidth = 96, kHeight = 64;
  for (const ocean::KelvinWakeParams params :
       {ocean::KelvinWakeParams{.speed = 5.0, .amplitude = 0.3, .draft = 2.0, .length = 2000.0},
        ocean::KelvinWakeParams{.speed = 12.0, .amplitude = 0.5, .draft = 4.0, .length = 5000.0}}) {
    std::vector<glm::vec4> inputs;
    for (int j = 0; j < kHeight; ++j)
      for (int i = 0; i < kWidth; ++i) {
        const double b = RoundToFloat(1.05 * params.length * (i + 0.5) / kWidth);
        const double y = RoundToFloat(b * (-0.45 + 0.9 * (j + 0.5) / kHeight));
        inputs.emplace_back(float(b), float(y), 0.0f, 0.0f);
      }
    const glm::dvec4 gpu_params = ocean::kelvin_wake_gpu_params(params);
    const std::vector<glm::vec4> waves = evaluate(1, inputs, kWidth, kHeight, gpu_params);
    const std::vector<glm::vec4> vectors = evaluate(2, inputs, kWidth, kHeight, gpu_params);
    double worst_amplitude = 0.0, worst_argument = 0.0, worst_vector = 0.0, worst_height = 0.0;
    int compared = 0;
    for (std::size_t n = 0; n < inputs.size(); ++n) {
      const ocean::KelvinWakeSample cpu = ocean::kelvin_wake_at(params, inputs[n].x, inputs[n].y);
      const glm::vec4 w = waves[n], k = vectors[n];
      for (float value : {w.x, w.y, w.z, w.w, k.x, k.y, k.z, k.w})
        ASSERT_TRUE(std::isfinite(value)) << "b " << inputs[n].x << ", y " << inputs[n].y;
      const ocean::WakeWave* branch[2] = {&cpu.transverse, &cpu.divergent};
      const double gpu_h[2] = {w.x, w.z}, gpu_theta[2] = {w.y, w.w};
      const glm::dvec2 gpu_k[2] = {{k.x, k.y}, {k.z, k.w}};
      double gpu_height = 0.0;
      for (int b = 0; b < 2; ++b) {
        const ocean::WakeWave& c = *branch[b];
        // Amplitudes relative to a_ref; arguments and wave vectors where the wave is visible
        // (above 1e-4 a_ref: the fades' ends and Airy's tail are continuous, so their arguments
        // matter only through their amplitude).
        worst_amplitude =
            std::max(worst_amplitude, std::abs(gpu_h[b] - c.amplitude) / params.amplitude);
        gpu_height += gpu_h[b] * std::cos(gpu_theta[b]);
        if (c.amplitude > 1e-4 * params.amplitude) {
          ++compared;
          worst_argument = std::max(worst_argument, AngleDifference(gpu_theta[b], c.argument));
          worst_vector =
              std::max(worst_vector, glm::length(gpu_k[b] - c.wave_vector) / c.wavenumber);
        }
      }
      worst_height =
          std::max(worst_height, std::abs(gpu_height - cpu.linear_height()) / params.amplitude);
    }
    std::printf(
        "KelvinWake float vs double, U = %.0f m/s, %d branches: amplitude %.2g a_ref, "
        "argument %.2g rad, wave vector %.2g relative, linear height %.2g a_ref\n",
        params.speed, compared, worst_amplitude, worst_argument, worst_vector, worst_height);
    EXPECT_GT(compared, kWidth * kHeight / 2);
    EXPECT_LE(worst_amplitude, 2e-6);
    EXPECT_LE(worst_argument, 1e-3);
    EXPECT_LE(worst_vector, 2e-6);
    EXPECT_LE(worst_height, 1e-4);
  }
}

// The shader's search for a wake's ship frame along its track (LocalWakeFrame) against its
// double reference ocean::wake_frame_coordinates: a track with two turns, 96 x 64 points over
// 5 km x 3.4 km around it. Both agree on presence away from the wake's edges and on (b, y) to
// float's resolution of km-sized numbers.
TEST_F(LocalWavesTest, WakeFrameAlongATrackMatchesTheDoubleReference) {
  constexpr int kWidth = 96, kHeight = 64;
  ocean::LocalFeatures features;
  ocean::WakeInFrame wake;
  wake.params = {.speed = 8.0, .amplitude = 0.5, .draft = 2.0, .length = 4000.0};
  wake.track = {{300.0, 900.0}, {0.0, 0.0}, {-600.0, -700.0}, {-600.0, -2500.0}};
  features.wakes = {wake};
  const ocean::LocalFeatureBuffers buffers(features);
  std::vector<glm::vec4> inputs;
  for (int j = 0; j < kHeight; ++j)
    for (int i = 0; i < kWidth; ++i)
      inputs.emplace_back(float(-2500.0 + 5000.0 * (i + 0.5) / kWidth),
                          float(-2500.0 + 3400.0 * (j + 0.5) / kHeight), 0.0f, 0.0f);
  const std::vector<glm::vec4> out =
      evaluate(3, inputs, kWidth, kHeight, glm::dvec4(0.0), &buffers);
  double worst_b = 0.0, worst_y = 0.0;
  int present = 0, disagree = 0;
  for (std::size_t n = 0; n < inputs.size(); ++n) {
    const ocean::WakeFrameCoordinates c =
        ocean::wake_frame_coordinates(wake, glm::dvec2(inputs[n].x, inputs[n].y));
    if ((out[n].x > 0.5f) != c.present) {
      ++disagree;
      continue;
    }
    if (!c.present) continue;
    ++present;
    worst_b = std::max(worst_b, std::abs(out[n].y - c.behind));
    worst_y = std::max(worst_y, std::abs(out[n].z - c.lateral));
  }
  std::printf(
      "LocalWakeFrame float vs double: %d points in the wake, %d disagree on presence, "
      "|b| %.2g m, |y| %.2g m\n",
      present, disagree, worst_b, worst_y);
  EXPECT_GT(present, kWidth * kHeight / 4);
  EXPECT_LE(disagree, 2);
  EXPECT_LE(worst_b, 1e-3);
  EXPECT_LE(worst_y, 1e-3);
}

double Luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

// Issue 9, point 4. The scene's camera looks at a point P ahead along its heading; a calm area
// of scale 0 (a mirror) is a geodesic square around P (corners from GeographicLib's Direct
// problem), lit so that the rough sea's glint covers it. The pixels whose radiance the area
// changes are the square seen by the renderer; their centroid is compared with the centroid of
// the square's corners projected through GeographicLib (geodetic -> ECEF -> the camera's local
// east-north-up, LocalCartesian) and the camera model (camera_basis). The square is small on
// screen (about 10 to 30 pixels), so its projected centroid is the quadrilateral's to well under
// a pixel, and the fade (a tenth of the half-side) is symmetric. Tolerances: 1 pixel where the
// area changes only normals and BRDF (2 km, 400 km: the mask is the square to a pixel); from 2 m
// it changes the projected grid's geometry too, whose vertices are kGridCell = 8 pixels apart,
// so the changed region is the square grown by up to a cell, raggedly, with the random waves
// (1.5 m/s) displacing its edges: 2 pixels (a quarter of a cell).
TEST(LocalWavesPlacement, CalmAreaAppearsWhereGeographicLibProjectsIt) {
  auto context = test::make_test_context();
  const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
  struct Case {
    const char* name;
    double lat, lon, height, heading, pitch;
    double ahead;  // m: geodesic distance from the nadir to the square's centre
    double half;   // m: half the square's side
  };
  const Case cases[] = {
      {"2 m, antimeridian", -35.0, 179.99999, 2.0, 90.0, -25.0, 4.3, 0.6},
      {"2 km, antimeridian", -35.0, 179.995, 2000.0, 90.0, -30.0, 3460.0, 150.0},
      {"400 km, antimeridian", -35.0, 178.0, 400000.0, 90.0, -60.0, 225000.0, 15000.0},
      {"2 m, near the north pole", 89.99, 30.0, 2.0, 10.0, -25.0, 4.3, 0.6},
      {"2 km, near the north pole", 89.99, 30.0, 2000.0, 10.0, -30.0, 3460.0, 150.0},
      {"400 km, near the north pole", 89.5, 30.0, 400000.0, 10.0, -60.0, 225000.0, 15000.0},
  };
  constexpr int kWidth = 160, kHeight = 120;
  // A pixel counts as showing the area where its luminance changes by more than this (relative).
  constexpr double kChanged = 0.05;
  for (const Case& c : cases) {
    // The square's centre and corners (degrees).
    double lat_c, lon_c, azi;
    geodesic.Direct(c.lat, c.lon, c.heading, c.ahead, lat_c, lon_c, azi);
    double corners[4][2];
    for (int k = 0; k < 4; ++k)
      geodesic.Direct(lat_c, lon_c, azi + 45.0 + 90.0 * k, c.half * std::sqrt(2.0), corners[k][0],
                      corners[k][1]);
    char json[2048];
    // The sun ahead, kSunOffset degrees higher than the elevation of the centre's reflection:
    // the rough sea's glint covers the square, the mirror does not show the sun's disc.
    constexpr double kSunOffset = 15.0;
    const double sun_zenith = std::clamp(90.0 + c.pitch - kSunOffset, 5.0, 85.0);
    std::snprintf(json, sizeof json,
                  R"({"image": {"width": %d, "height": %d},
                      "camera": {"lat": %.10f, "lon": %.10f, "height": %.3f, "heading": %.3f,
                                 "pitch": %.3f},
                      "sun": {"zenith": %.3f, "azimuth": %.3f},
                      "ocean": {"wind_speed": 1.5}})",
                  kWidth, kHeight, c.lat, c.lon, c.height, c.heading, c.pitch, sun_zenith,
                  c.heading);
    const Scene plain = test::scene_from(json);
    Scene calm = plain;
    CalmAreaSettings area;
    area.scale = 0.0;
    area.fade = 0.1 * c.half;
    for (const auto& corner : corners) area.exterior.push_back({corner[0], corner[1]});
    calm.calm_areas = {area};
    Image images[2];
    for (int i = 0; i < 2; ++i) {
      Renderer renderer(*context, i == 0 ? plain : calm);
      renderer.render();
      images[i] = renderer.image();
    }
    // The relative change of each pixel's luminance.
    std::vector<double> change(std::size_t(kWidth) * kHeight);
    for (std::size_t p = 0; p < change.size(); ++p) {
      const double before = Luminance(&images[0].rgba[4 * p]);
      change[p] = std::abs(Luminance(&images[1].rgba[4 * p]) - before) / std::max(before, 1e-6);
    }
    double sx = 0.0, sy = 0.0;
    int count = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (change[std::size_t(y) * kWidth + x] > kChanged) {
          sx += x + 0.5;
          sy += y + 0.5;
          ++count;
        }
    const glm::dvec2 measured(sx / count, sy / count);

    // GeographicLib's projection of the corners into the image (pixels, row 0 at the top).
    const GeographicLib::LocalCartesian camera(c.lat, c.lon, c.height,
                                               GeographicLib::Geocentric::WGS84());
    const CameraBasis basis = camera_basis(c.heading, c.pitch, 0.0);
    const double tan_half = std::tan(0.5 * plain.camera.fov_y * std::numbers::pi / 180.0);
    const double aspect = double(kWidth) / kHeight;
    glm::dvec2 projected[4];
    for (int k = 0; k < 4; ++k) {
      glm::dvec3 d;
      camera.Forward(corners[k][0], corners[k][1], 0.0, d.x, d.y, d.z);
      const double along = glm::dot(d, basis.forward);
      const double u = glm::dot(d, basis.right) / (along * tan_half * aspect);
      const double v = glm::dot(d, basis.up) / (along * tan_half);
      projected[k] = {0.5 * (u + 1.0) * kWidth, 0.5 * (1.0 - v) * kHeight};
    }
    // The quadrilateral's area centroid (shoelace).
    double area2 = 0.0;
    glm::dvec2 centroid(0.0);
    for (int k = 0; k < 4; ++k) {
      const glm::dvec2 a = projected[k], b = projected[(k + 1) % 4];
      const double cross = a.x * b.y - b.x * a.y;
      area2 += cross;
      centroid += (a + b) * cross;
    }
    centroid /= 3.0 * area2;
    const double error = glm::length(measured - centroid);
    std::printf(
        "%-28s %4d pixels changed (quadrilateral %.0f), centroid (%.2f, %.2f), "
        "GeographicLib (%.2f, %.2f): %.2f px\n",
        c.name, count, 0.5 * std::abs(area2), measured.x, measured.y, centroid.x, centroid.y,
        error);
    ASSERT_GT(count, 30) << c.name;
    const double tolerance = c.height < 100.0 ? 2.0 : 1.0;
    EXPECT_LE(error, tolerance) << c.name;
    if (error > tolerance || std::getenv("THALASSA_TEST_WRITE_IMAGES")) {
      std::string base = test::output_dir() + "/placement_" + c.name;
      std::replace(base.begin(), base.end(), ' ', '_');
      write_png(base + ".plain.png", images[0], 10.0);
      write_png(base + ".calm.png", images[1], 10.0);
    }
  }
}

// Whether any of `built` contains `part`.
bool Built(const RenderStats& stats, const std::string& part) {
  return std::any_of(stats.built.begin(), stats.built.end(),
                     [&](const std::string& item) { return item.find(part) != std::string::npos; });
}

// Issue 9, point 5: only what a scene needs. Features in view are built (statistics and shader
// defines); features out of view (1000 km away, or behind the camera) and scenes without any
// compile none of their code.
TEST(LocalWavesLeaveOut, FeaturesAreBuiltOnlyWhenInView) {
  auto context = test::make_test_context();
  const std::string base = R"({"image": {"width": 48, "height": 32},
      "camera": {"lat": 10, "lon": 20, "height": 50, "pitch": -20, "heading": 0}})";
  const std::string near =
      R"({"wakes": [{"lat": 10.01, "lon": 20, "heading": 0, "speed": 8, "length": 500}],
      "calm_areas": [{"polygon": [{"lat": 10.001, "lon": 19.999}, {"lat": 10.001, "lon": 20.001},
                                  {"lat": 10.002, "lon": 20.0}]}]})";
  const std::string far = R"({"wakes": [{"lat": 19, "lon": 20, "heading": 0, "speed": 8}],
      "calm_areas": [{"polygon": [{"lat": 10, "lon": 29.9}, {"lat": 10, "lon": 30},
                                  {"lat": 10.1, "lon": 30}]}]})";
  // The same features behind the camera (looking south): within the horizon, not in the image.
  const std::string behind = near.substr(0, near.size() - 1) + R"(, "camera": {"heading": 180}})";
  for (const auto& [extra, expected] :
       {std::pair<std::string, bool>{"{}", false}, {near, true}, {far, false}, {behind, false}}) {
    SceneBuilder builder;
    builder.load_text(base, "base");
    builder.load_text(extra, "features");
    Renderer renderer(*context, builder.build());
    renderer.render();
    const RenderStats stats = renderer.stats();
    EXPECT_EQ(Built(stats, "ocean.calm_areas"), expected) << extra;
    EXPECT_EQ(Built(stats, "ocean.kelvin_wakes"), expected) << extra;
    EXPECT_EQ(Built(stats, "CALM_AREAS"), expected) << extra;
    EXPECT_EQ(Built(stats, "KELVIN_WAKES"), expected) << extra;
  }
}

// Issue 9, point 6: the demo's scenes and flight parse, and render their wake and slick (small
// images; the first and last frames of the flight).
TEST(LocalWavesDemo, DemoScenesAndFlightRenderTheirFeatures) {
  auto context = test::make_test_context();
  auto check = [&](const Scene& scene, const std::string& name) {
    Renderer renderer(*context, scene);
    renderer.render();
    const RenderStats stats = renderer.stats();
    EXPECT_TRUE(Built(stats, "ocean.calm_areas.1")) << name;
    EXPECT_TRUE(Built(stats, "ocean.kelvin_wakes.1")) << name;
    for (float v : renderer.image().rgba) ASSERT_TRUE(std::isfinite(v)) << name;
  };
  for (const char* name : {"wake_50m", "wake_2km", "wake_400km"}) {
    SceneBuilder builder;
    builder.load_file(std::string(THALASSA_SOURCE_DIR "/data/scenes/wake_demo/") + name + ".json");
    builder.set("image.width=64");
    builder.set("image.height=36");
    check(builder.build(), name);
  }
  Flight flight = Flight::load_file(THALASSA_SOURCE_DIR "/data/flights/wake_demo.json");
  flight.set("image.width=64");
  flight.set("image.height=36");
  for (int frame : {0, flight.frame_count() - 1})
    check(flight.frame_scene(frame), "wake_demo frame " + std::to_string(frame));
}

}  // namespace
}  // namespace thalassa
