// The validation's case runner as a library user calls it (validation/runner.hpp), without the
// command line: a case rendered, written and measured, its progress told as render_count says,
// a variant measured against its own reference, a method drawn at a multiple of the reference's
// pixels, and a case refused before rendering.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "thalassa/planet/renderer.hpp"
#include "thalassa/validation/metrics.hpp"
#include "thalassa/validation/runner.hpp"

namespace thalassa {
namespace {

namespace fs = std::filesystem;

// An empty folder of the test's own, with its images/ folder: the backends' runs of a test may
// run at once.
fs::path fresh_folder(const std::string& stem) {
  const fs::path dir = fs::temp_directory_path() / (stem + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "images");
  return dir;
}

TEST(CaseRunner, RendersMeasuresAndTellsItsProgressAsCounted) {
  const validation::Suite suite = validation::load_suite_text(R"({
    "suite": "runner",
    "base": {"image.width": 16, "image.height": 10, "camera.height": 100, "camera.pitch": -20},
    "methods": ["reference", "full",
                {"name": "full_waves30", "method": "full", "set": {"ocean.waves": 30},
                 "own_reference": true}],
    "terms": ["sky", "sun"],
    "flicker": {"frames": 2, "dt": 0.04, "terms": ["sky"]},
    "timing": {"width": 32, "height": 20, "frames": 2},
    "reference": {"pixel_samples": 4, "sun_normal_samples": 256, "check_convergence": true},
    "cases": [{"name": "near", "set": {}},
              {"name": "refused", "set": {"sky.exr": "no_such_sky.exr"}, "expect": 2,
               "error": "no_such_sky.exr"}]
  })",
                                                              "runner.json");
  const fs::path dir = fresh_folder("thalassa_case_runner_test");
  auto context = test::make_test_context();
  int done = 0, skipped = 0;
  validation::CaseRunOptions options;
  options.dir = dir.string();
  options.write_exr = false;
  options.progress.done = [&](const std::string& name, const std::string&, double seconds) {
    EXPECT_EQ(name, "near");
    EXPECT_GE(seconds, 0.0);
    ++done;
  };
  options.progress.skipped = [&](const std::string&, const std::string&) { ++skipped; };

  const validation::SuiteCase& near = suite.cases[0];
  const validation::CaseResult result = validation::run_case(suite, *context, near, options);
  EXPECT_EQ(result.exit_status, validation::kCaseRendered) << result.message;
  EXPECT_TRUE(result.passed());
  // The case's reference, the variant's own, full and the variant: 2 terms each, the sky over
  // 2 frames; full and the variant timed apart.
  EXPECT_EQ(done, validation::render_count(suite, near));
  EXPECT_EQ(done, 4 * (2 + 1) + 2);
  EXPECT_EQ(skipped, 0);
  ASSERT_EQ(result.methods.size(), 4u);
  EXPECT_EQ(result.methods[0].name, "reference");
  EXPECT_EQ(result.methods[1].name, "reference_full_waves30");
  EXPECT_EQ(result.methods[1].reference, "reference_full_waves30");
  EXPECT_EQ(result.methods[3].name, "full_waves30");
  EXPECT_EQ(result.methods[3].reference, "reference_full_waves30");
  for (const validation::MethodResult& m : result.methods) {
    ASSERT_EQ(m.terms.size(), 2u) << m.name;
    for (const validation::TermResult& t : m.terms) {
      EXPECT_TRUE(fs::is_regular_file(dir / t.png)) << t.png;
      EXPECT_TRUE(t.exr.empty());  // write_exr false
      // The sky on every sea pixel; the sun on the rows the reference's coarse lattice (16^2
      // cells a footprint) resolves, which may be none.
      if (t.term == "sky") {
        EXPECT_GT(t.metrics.error.pixels, 0) << m.name;
      }
      EXPECT_EQ(t.flicker.has_value(), t.term == "sky") << m.name << " " << t.term;
    }
    // The reference measured against itself: no error; full on the sky, some.
    if (m.method == "reference") {
      EXPECT_EQ(m.terms[0].metrics.error.relative_l1.l, 0.0) << m.name;
      EXPECT_FALSE(m.convergence.empty()) << m.name;
    } else {
      ASSERT_TRUE(m.timing_ms.has_value()) << m.name;
      EXPECT_GT(*m.timing_ms, 0.0);
      EXPECT_GT(m.terms[0].metrics.error.relative_l1.l, 0.0) << m.name;
      EXPECT_TRUE(std::isfinite(m.terms[0].metrics.row_error)) << m.name;
    }
  }
  EXPECT_TRUE(result.timing == suite.timing);

  // Timed again at the same settings: retime_count says there is nothing to do.
  EXPECT_EQ(validation::retime_count(suite, result), 0);

  // A case whose scene cannot be drawn is refused before any render, as it expects.
  const validation::CaseResult refused =
      validation::run_case(suite, *context, suite.cases[1], options);
  EXPECT_EQ(refused.exit_status, validation::kCaseInvalidInput);
  EXPECT_NE(refused.message.find("no_such_sky.exr"), std::string::npos) << refused.message;
  EXPECT_TRUE(refused.passed());
  EXPECT_TRUE(refused.methods.empty());
  EXPECT_EQ(skipped, validation::render_count(suite, suite.cases[1]));
  fs::remove_all(dir);
}

// A method with "supersample": k is the case drawn at k times its width and height and averaged
// to the reference's pixels: its image as written is the larger render box-filtered, its row
// totals those of the sea alone of each sea pixel's block (supersampled_for_comparison), and they
// are not the method's at the case's own pixels (a pixel a quarter the size resolves more of the
// waves in its normal).
TEST(CaseRunner, SupersampledMethodIsItsLargerRenderAveragedToTheReferencesPixels) {
  const validation::Suite suite = validation::load_suite_text(R"({
    "suite": "supersample",
    "base": {"image.width": 24, "image.height": 14, "camera.height": 100, "camera.pitch": -19},
    "methods": ["reference", "full", {"name": "full_x2", "method": "full", "supersample": 2}],
    "terms": ["sky"],
    "flicker": {"frames": 0, "terms": ["sky"]},
    "timing": {"width": 16, "height": 10, "frames": 1},
    "reference": {"pixel_samples": 1, "pixel_samples_without_sun": 1,
                  "check_convergence": false},
    "cases": [{"name": "near", "set": {}}]
  })",
                                                              "supersample.json");
  const fs::path dir = fresh_folder("thalassa_case_runner_x2_test");
  auto context = test::make_test_context();
  std::vector<std::string> details;
  validation::CaseRunOptions options;
  options.dir = dir.string();
  options.write_exr = true;
  options.progress.done = [&](const std::string&, const std::string& detail, double) {
    details.push_back(detail);
  };
  const validation::SuiteCase& near = suite.cases[0];
  const validation::CaseResult result = validation::run_case(suite, *context, near, options);
  ASSERT_EQ(result.exit_status, validation::kCaseRendered) << result.message;
  ASSERT_EQ(result.methods.size(), 3u);
  const validation::MethodResult& full = result.methods[1];
  const validation::MethodResult& x2 = result.methods[2];
  ASSERT_EQ(x2.name, "full_x2");
  EXPECT_TRUE(full.plain);
  EXPECT_FALSE(x2.plain);  // not a curve of the rows plots: a variant
  ASSERT_EQ(x2.terms.size(), 1u);

  // The same method and term drawn here at 48 x 28.
  const Scene scene = validation::case_scene(suite, near, suite.find_method("full_x2"));
  ASSERT_EQ(scene.image.width, 48);
  ASSERT_EQ(scene.image.height, 28);
  RendererOptions render_options;
  render_options.terms = {.sun = false, .sky = true, .sea = false, .air = false};
  Renderer renderer(*context, scene, render_options);
  renderer.render();

  // Written averaged 2 x 2, at the reference's size.
  const Image written = read_image((dir / x2.terms[0].exr).string());
  const Image averaged = validation::box_filter(renderer.image(), 2);
  ASSERT_EQ(written.width, 24);
  ASSERT_EQ(written.height, 14);
  for (std::size_t i = 0; i < written.rgba.size(); ++i)
    ASSERT_NEAR(written.rgba[i], averaged.rgba[i], 1e-6f * (1.0f + std::abs(averaged.rgba[i])))
        << i;
  // Measured on the sea alone of each sea pixel's block: at the pixels the horizon crosses the
  // plain average holds sky, brighter than the sea.
  const validation::ViewGeometry view(validation::case_scene(suite, near));
  const validation::ViewGeometry fine_view(scene);
  const std::vector<validation::ChannelValues> expected =
      validation::row_totals(validation::supersampled_for_comparison(
                                 renderer.image(), 2, fine_view.sea_mask(), view.sea_mask()),
                             &view.sea_mask());
  const std::vector<validation::ChannelValues> with_sky =
      validation::row_totals(averaged, &view.sea_mask());
  bool sky_in_a_row = false;
  for (std::size_t y = 0; y < expected.size(); ++y)
    sky_in_a_row = sky_in_a_row ||
                   (std::isfinite(expected[y].l) && with_sky[y].l > expected[y].l * (1.0 + 1e-3));
  EXPECT_TRUE(sky_in_a_row);
  const std::vector<validation::ChannelValues>& measured = x2.terms[0].metrics.row_totals;
  const std::vector<validation::ChannelValues>& own = full.terms[0].metrics.row_totals;
  ASSERT_EQ(measured.size(), 14u);
  ASSERT_EQ(own.size(), 14u);
  int sea_rows = 0;
  double largest_change = 0.0;
  for (std::size_t y = 0; y < expected.size(); ++y) {
    if (!std::isfinite(expected[y].l)) {
      EXPECT_FALSE(std::isfinite(measured[y].l)) << "row " << y;
      continue;
    }
    ++sea_rows;
    EXPECT_NEAR(measured[y].l, expected[y].l, 1e-5 * expected[y].l) << "row " << y;
    largest_change = std::max(largest_change, std::abs(measured[y].l / own[y].l - 1.0));
  }
  EXPECT_GE(sea_rows, 5);
  EXPECT_GT(largest_change, 1e-3);
  // Timed at twice the timing's width and height.
  bool timed_larger = false;
  for (const std::string& detail : details)
    timed_larger = timed_larger || detail.find("full_x2, timed at 32x20") != std::string::npos;
  EXPECT_TRUE(timed_larger);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thalassa
