// The stress suite of issue 7, point 1 (data/suites/stress.json; the suite format is in
// docs/validation.md, loaded by validation/include/thalassa/validation/suite.hpp): it loads with
// the validation loader, its scenes build or are refused as each case says (the cases expecting
// exit status 2 with their error messages), it holds every extreme of the issue, the case "inside
// a wave crest" really puts the camera inside the water of a crest, and a mistake in the file is
// refused with a message naming the file and the case's key. The loader's own checks are in
// tests/unit/validation_suite_test.cpp; the renders in tests/gpu/stress_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "thalassa/ocean/wave_set.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/validation/suite.hpp"

namespace thalassa::validation {
namespace {

const char* kStressSuite = THALASSA_SOURCE_DIR "/data/suites/stress.json";

std::string stress_suite_text() {
  std::ifstream in(kStressSuite);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the SuiteError that loading `text` as "stress.json" throws ("" when it loads).
std::string load_error(const std::string& text) {
  try {
    load_suite_text(text, "stress.json");
  } catch (const SuiteError& e) {
    return e.what();
  }
  return "";
}

// `text` with its first `from` after `after` replaced by `to` (the test fails if there is none).
std::string replace_after(std::string text, const std::string& after, const std::string& from,
                          const std::string& to) {
  const std::size_t start = text.find(after);
  const std::size_t at = start == std::string::npos ? start : text.find(from, start);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no " << from << " after " << after << " in " << kStressSuite;
    return text;
  }
  return text.replace(at, from.size(), to);
}

// The index of the case named `name` in the stress suite (-1 when there is none).
int case_index(const Suite& suite, const std::string& name) {
  for (std::size_t i = 0; i < suite.cases.size(); ++i)
    if (suite.cases[i].name == name) return int(i);
  return -1;
}

// The stress suite is a suite of cases only: each rendered once, by the full method, with no
// reference (so `thalassa validate` checks exit statuses and finite pixels, and measures nothing).
TEST(StressSuite, LoadsWithTheValidationLoader) {
  const Suite suite = load_suite_file(kStressSuite);
  EXPECT_EQ(suite.name, "stress");
  EXPECT_EQ(suite.source, kStressSuite);
  ASSERT_EQ(suite.methods.size(), 1u);
  EXPECT_EQ(suite.methods[0].method, "full");
  EXPECT_TRUE(suite.methods[0].plain());
  EXPECT_EQ(suite.reference_method(), nullptr);
  EXPECT_EQ(suite.base.size(), 2u);  // image.width, image.height
  EXPECT_GT(suite.cases.size(), 60u);
  for (const SuiteCase& c : suite.cases) EXPECT_EQ(c.methods, (std::vector<std::string>{"full"}));
}

// Every case of the stress suite is what it says: a valid scene where it expects exit status 0,
// refused with its message where it expects 2 (the renders are in tests/gpu/stress_test.cpp).
TEST(StressSuite, CasesBuildOrAreRefusedAsTheySay) {
  const Suite suite = load_suite_file(kStressSuite);
  int refused = 0;
  for (const SuiteCase& c : suite.cases) {
    SCOPED_TRACE(c.name);
    const std::optional<std::string> error = case_scene_error(suite, c);
    if (c.expected_exit == 0) {
      EXPECT_FALSE(error.has_value()) << *error;
      continue;
    }
    ++refused;
    ASSERT_TRUE(error.has_value()) << "accepted, expected exit status 2";
    EXPECT_NE(error->find(c.expected_error), std::string::npos) << *error;
    EXPECT_EQ(error->find('\n'), std::string::npos) << *error;  // one line
  }
  EXPECT_GT(refused, 10);
}

// The matrix of issue 7, point 1: each extreme is a case of the suite (by name), so that nobody
// drops one silently.
TEST(StressSuite, HoldsEveryCaseOfTheIssue) {
  const Suite suite = load_suite_file(kStressSuite);
  std::set<std::string> names;
  for (const SuiteCase& c : suite.cases) names.insert(c.name);
  for (const char* name : {"sun_at_zenith",
                           "sun_at_horizon",
                           "sun_1_deg_below",
                           "sun_12_deg_below",
                           "camera_straight_down",
                           "camera_straight_up",
                           "camera_rolled_90",
                           "camera_rolled_180",
                           "fov_1",
                           "fov_150",
                           "camera_at_0_m",
                           "camera_at_1_cm",
                           "camera_below_surface",
                           "camera_inside_crest",
                           "camera_at_20_km",
                           "camera_at_36000_km",
                           "lat_90",
                           "lat_minus_90",
                           "lon_180",
                           "lon_minus_180",
                           "wind_0",
                           "wind_40",
                           "waves_1",
                           "waves_1000",
                           "lambda_min_equals_max",
                           "image_1x1",
                           "image_4096x4096",
                           "time_0",
                           "time_1e9"})
    EXPECT_TRUE(names.count(name)) << name;
}

// The surface height (m, above the sea at rest) at the camera's nadir: the trochoids' displaced
// surface (shaders/ocean/trochoids.glsl) over the nadir, found by solving x + sum t_xy(x) = 0 for
// the rest point x by fixed-point iteration (a contraction: the steepest wave has k h < 0.5).
double surface_height_at_nadir(const Scene& scene) {
  const NadirFrame frame = make_nadir_frame(Planet(scene.planet), scene.camera);
  const ocean::WaveSet waves = ocean::make_wave_set(scene.ocean);
  const std::vector<double> phases = ocean::wrapped_phases(waves, scene.time, frame.wave_origin);
  glm::dvec2 rest(0.0);
  double height = 0.0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    glm::dvec2 horizontal(0.0);
    height = 0.0;
    for (std::size_t i = 0; i < waves.waves.size(); ++i) {
      const ocean::Wave& w = waves.waves[i];
      const glm::dvec2 direction = ocean::chart_direction_in_frame(frame.wave_axes, w.direction);
      const double argument = phases[i] - w.wavenumber * glm::dot(direction, rest);
      horizontal += direction * (w.amplitude * std::sin(argument));
      height += w.amplitude * std::cos(argument);
    }
    rest = -horizontal;
  }
  return height;
}

TEST(StressSuite, TheCrestCaseHasTheCameraInsideTheWater) {
  const Suite suite = load_suite_file(kStressSuite);
  for (const SuiteCase& c : suite.cases) {
    if (c.name != "camera_inside_crest") continue;
    const Scene scene = case_scene(suite, c);
    EXPECT_GT(scene.camera.height, 0.0);  // above the sea at rest...
    const double surface = surface_height_at_nadir(scene);
    std::printf("camera_inside_crest: camera %.3f m, surface %.3f m above the sea at rest\n",
                scene.camera.height, surface);
    EXPECT_GT(surface, scene.camera.height + 0.5);  // ...and half a metre under a crest
    return;
  }
  FAIL() << "no case camera_inside_crest";
}

// A mistake in the stress suite is refused with one line naming the file, the case's key path,
// what was expected and what was found, as a scene file's would be: an unknown key, in a case
// expecting either exit status, and an out-of-range value in a case expected to render.
TEST(StressSuite, AMistakeInTheFileIsRefusedNamingTheCasesKey) {
  const std::string text = stress_suite_text();
  ASSERT_EQ(load_error(text), "");
  const Suite suite = load_suite_text(text, "stress.json");
  const int crest = case_index(suite, "camera_inside_crest");
  ASSERT_GE(crest, 0);
  const std::string at = "stress.json: cases[" + std::to_string(crest) + "].set.";
  EXPECT_EQ(load_error(replace_after(text, "\"camera_inside_crest\"", "\"camera.height\"",
                                     "\"camera.hieght\"")),
            at + "camera.hieght: expected a scene key (docs/scene.md), got an unknown key");
  // A case expected to render is checked with the scene's own range.
  EXPECT_EQ(load_error(replace_after(text, "\"camera_inside_crest\"", "\"ocean.wind_speed\": 20",
                                     "\"ocean.wind_speed\": -20"))
                .rfind(at + "ocean.wind_speed: expected a number in [", 0),
            0u);
  // A case expected to be refused holds a bad value on purpose, but its keys are still checked.
  int refused = -1;
  for (std::size_t i = 0; i < suite.cases.size() && refused < 0; ++i)
    if (suite.cases[i].expected_exit == 2) refused = int(i);
  ASSERT_GE(refused, 0);
  const SuiteCase& c = suite.cases[refused];
  ASSERT_FALSE(c.set.empty());
  const std::string name = "\"" + c.name + "\"";
  const std::string key = "\"" + c.set[0].key + "\"";
  EXPECT_EQ(load_error(replace_after(text, name, key, "\"x" + c.set[0].key + "\"")),
            "stress.json: cases[" + std::to_string(refused) + "].set.x" + c.set[0].key +
                ": expected a scene key (docs/scene.md), got an unknown key");
  EXPECT_EQ(load_error(replace_after(text, name, "\"expect\": 2", "\"expect\": 1")),
            "stress.json: cases[" + std::to_string(refused) + "].expect: expected 0 or 2, got 1");
}

}  // namespace
}  // namespace thalassa::validation
