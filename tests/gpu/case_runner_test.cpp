// The validation's case runner as a library user calls it (validation/runner.hpp), without the
// command line: a case rendered, written and measured, its progress told as render_count says,
// a variant measured against its own reference, and a case refused before rendering.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "thalassa/validation/runner.hpp"

namespace thalassa {
namespace {

namespace fs = std::filesystem;

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
  // Its own folder: the backends' runs of this test may run at once.
  const fs::path dir =
      fs::temp_directory_path() / ("thalassa_case_runner_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "images");
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

}  // namespace
}  // namespace thalassa
