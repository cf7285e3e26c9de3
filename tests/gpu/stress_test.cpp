// The stress suite of issue 7, point 1 (data/suites/stress.json; the suite format and its loader,
// thalassa::validation::load_suite_file, are in docs/validation.md), rendered in-process through
// the library: every case that expects exit status 0 renders, and every pixel of its EXR, written
// as the command line writes it (scene.image.exr_type, half by default) and read back, is finite.
// (The cases that expect 2 are checked, with their error messages, without GL in
// tests/unit/stress_suite_test.cpp.) The cases are split into a few shards, one gtest (hence one
// ctest entry) each, so that ctest -j runs them in parallel.
//
// A case larger than kCiPixelBudget (image_4096x4096: a frame of that size takes tens of seconds
// on llvmpipe, docs/numerics.md) is rendered in CI as two surrogates that hold exactly its own
// rays: its central kStripPixels rows (an image kStripPixels high whose fov_y is narrowed so that
// its pixel centres are those of the full image's central rows) and its central kStripPixels
// columns. `thalassa validate` renders the full image, and so does this test with the environment
// variable THALASSA_STRESS_FULL=1 (about three minutes on llvmpipe, 1.4 GB of memory).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace thalassa {
namespace {

constexpr const char* kSuitePath = THALASSA_SOURCE_DIR "/data/suites/stress.json";
// Largest image rendered whole in CI, pixels (a 1024 x 1024 frame: about a second on llvmpipe).
constexpr long kCiPixelBudget = 1L << 20;
// Rows (columns) of the surrogates of a larger case.
constexpr int kStripPixels = 16;

constexpr double kDegree = M_PI / 180.0;

// The suite, loaded once; empty when it cannot be loaded (StressSuite.Loads then fails).
const validation::Suite& stress_suite() {
  static const validation::Suite suite = [] {
    try {
      return validation::load_suite_file(kSuitePath);
    } catch (const validation::SuiteError&) {
      return validation::Suite{};
    }
  }();
  return suite;
}

std::vector<std::string> rendered_case_names() {
  std::vector<std::string> names;
  for (const validation::SuiteCase& c : stress_suite().cases)
    if (c.expected_exit == 0) names.push_back(c.name);
  return names;
}

// The scene's central `strip` rows (rows = true) or columns, as a scene of their own: the same
// camera with the image cut to `strip` pixels across that axis and tan(fov_y / 2) scaled so that
// the remaining pixels' rays are exactly the full image's (pixel centre v = (H - 2 y - 1) / H
// tan(fov_y / 2) in both).
Scene central_strip(const Scene& scene, bool rows, int strip) {
  Scene cut = scene;
  const double tan_half = std::tan(0.5 * scene.camera.fov_y * kDegree);
  if (rows) {
    cut.image.height = strip;
    cut.camera.fov_y = 2.0 * std::atan(tan_half * strip / scene.image.height) / kDegree;
  } else {
    cut.image.width = strip;  // fov_y, hence every row's ray, unchanged
  }
  return cut;
}

TEST(StressSuite, Loads) {
  EXPECT_NO_THROW(validation::load_suite_file(kSuitePath));
  EXPECT_GT(rendered_case_names().size(), 20u);
  // Each case is rendered once, plainly, with the full hierarchy (no `methods` in the file).
  ASSERT_EQ(stress_suite().methods.size(), 1u);
  EXPECT_EQ(stress_suite().methods[0].method, "full");
  EXPECT_TRUE(stress_suite().methods[0].plain());
}

// Renders one case of the suite with `method` (its scene and shading method, as `thalassa
// validate` renders it) and checks its EXR.
void check_case(GlContext& context, const validation::SuiteCase& c,
                const validation::SuiteMethod& method) {
  SCOPED_TRACE(c.name + " (" + method.name + ")");
  const Scene scene = validation::case_scene(stress_suite(), c, &method);
  RendererOptions options;
  const std::optional<ocean::OceanMethod> shading = ocean::parse_method(method.method);
  ASSERT_TRUE(shading.has_value()) << method.method;
  options.method = *shading;
  std::vector<Scene> renders;
  const char* full = std::getenv("THALASSA_STRESS_FULL");
  const bool whole = full != nullptr && std::string(full) == "1";
  if (!whole && long(scene.image.width) * scene.image.height > kCiPixelBudget) {
    renders = {central_strip(scene, true, kStripPixels), central_strip(scene, false, kStripPixels)};
  } else {
    renders = {scene};
  }
  for (const Scene& s : renders) {
    Renderer renderer(context, s, options);
    const RenderStats stats = renderer.stats();
    const std::string path = test::output_dir() + "/stress_" + c.name + ".exr";
    write_exr(path, renderer.image(), s.image.exr_type);
    const Image image = read_image(path);
    std::filesystem::remove(path);
    ASSERT_EQ(image.width, s.image.width);
    ASSERT_EQ(image.height, s.image.height);
    long non_finite = 0, negative = 0;
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
      if (i % 4 == 3) continue;  // alpha
      const float v = image.rgba[i];
      if (!std::isfinite(v)) {
        ++non_finite;
        continue;
      }
      negative += v < 0.0f;
      low = std::min(low, double(v));
      high = std::max(high, double(v));
    }
    std::printf("stress %-34s %4dx%-4d %-7s min %.3g max %.3g non-finite %ld\n", c.name.c_str(),
                s.image.width, s.image.height, stats.mode.c_str(), low, high, non_finite);
    EXPECT_EQ(non_finite, 0) << "pixels (channels) not finite";
    // Radiance is never negative either (a negative value is as wrong as a NaN).
    EXPECT_EQ(negative, 0) << "channels below 0";
  }
}

// The cases are dealt round-robin to kShards tests (ctest entries), which ctest -j runs in
// parallel: one process per shard rather than per case saves each case a process start (a GL
// context, the atmosphere's tables loaded, the shaders compiled: about 0.5 s of CPU on llvmpipe).
// THALASSA_STRESS_CASE=name renders that case only (in its shard), to debug one case.
constexpr int kShards = 4;

class Stress : public ::testing::TestWithParam<int> {};

TEST_P(Stress, RendersFiniteImages) {
  const char* only = std::getenv("THALASSA_STRESS_CASE");
  auto context = test::make_test_context();
  const std::vector<std::string> names = rendered_case_names();
  ASSERT_FALSE(names.empty());
  for (std::size_t i = GetParam(); i < names.size(); i += kShards) {
    if (only != nullptr && names[i] != only) continue;
    for (const validation::SuiteCase& c : stress_suite().cases) {
      if (c.name != names[i]) continue;
      ASSERT_FALSE(c.methods.empty()) << c.name;
      for (const std::string& m : c.methods)
        check_case(*context, c, *stress_suite().find_method(m));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, Stress, ::testing::Range(0, kShards),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return "shard_" + std::to_string(info.param) + "_of_" +
                                  std::to_string(kShards);
                         });

// Each light term alone (`thalassa render --terms sun`, ...; the energy checks render them so), at
// the surface, in the grid's hand-over to the sun-zenith array (above 10 km) and from space. The
// view from space without the sky term failed to compile (ocean_space.frag includes
// sky_array_reflection.glsl, whose array lookup needs SKY_MAP_ARRAY, defined with the sky term
// only): fixed there, in sky_array_reflection.glsl.
TEST(StressTerms, EachLightTermAloneRendersAFiniteImage) {
  auto context = test::make_test_context();
  const LightTerms alone[] = {{.sun = true, .sky = false, .sea = false, .air = false},
                              {.sun = false, .sky = true, .sea = false, .air = false},
                              {.sun = false, .sky = false, .sea = true, .air = false},
                              {.sun = false, .sky = false, .sea = false, .air = true},
                              {.sun = false, .sky = false, .sea = false, .air = false}};
  for (const double height : {4.0, 15000.0, 400000.0}) {
    SceneBuilder builder;
    builder.load_text(R"({"image": {"width": 48, "height": 32}, "camera": {"pitch": -30},
                         "sun": {"zenith": 30, "azimuth": 0}})",
                      "terms");
    builder.set("camera.height=" + std::to_string(height));
    const Scene scene = builder.build();
    for (const LightTerms& terms : alone) {
      SCOPED_TRACE(::testing::Message()
                   << "height " << height << " m, terms sun " << terms.sun << " sky " << terms.sky
                   << " sea " << terms.sea << " air " << terms.air);
      RendererOptions options;
      options.terms = terms;
      std::unique_ptr<Renderer> renderer;
      ASSERT_NO_THROW(renderer = std::make_unique<Renderer>(*context, scene, options));
      const Image image = renderer->image();
      double sum = 0.0;
      for (float v : image.rgba) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, 0.0f);
        sum += v;
      }
      EXPECT_GT(sum, 0.0);  // the sky's pixels at least, and alpha
    }
  }
}

}  // namespace
}  // namespace thalassa
