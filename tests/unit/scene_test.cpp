// Tests of scene files: defaults, layering, overrides, every class of bad input, the solar
// position for sun.utc, and that docs/scene.md documents every key.
#include "thalassa/engine/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#ifndef THALASSA_SOURCE_DIR
#define THALASSA_SOURCE_DIR ""  // the docs tests then fail and say so
#endif

namespace thalassa {
namespace {

using json = nlohmann::json;

void expect_same(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.image.width, b.image.width);
  EXPECT_EQ(a.image.height, b.image.height);
  EXPECT_EQ(a.image.exposure, b.image.exposure);
  EXPECT_EQ(a.image.exr_type, b.image.exr_type);
  EXPECT_EQ(a.camera.lat, b.camera.lat);
  EXPECT_EQ(a.camera.lon, b.camera.lon);
  EXPECT_EQ(a.camera.height, b.camera.height);
  EXPECT_EQ(a.camera.heading, b.camera.heading);
  EXPECT_EQ(a.camera.pitch, b.camera.pitch);
  EXPECT_EQ(a.camera.roll, b.camera.roll);
  EXPECT_EQ(a.camera.fov_y, b.camera.fov_y);
  EXPECT_EQ(a.sun.zenith, b.sun.zenith);
  EXPECT_EQ(a.sun.azimuth, b.sun.azimuth);
  EXPECT_EQ(a.sun.utc, b.sun.utc);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.planet.shape, b.planet.shape);
  EXPECT_EQ(a.planet.radius, b.planet.radius);
  EXPECT_EQ(a.ocean.wind_speed, b.ocean.wind_speed);
  EXPECT_EQ(a.ocean.wind_direction, b.ocean.wind_direction);
  EXPECT_EQ(a.ocean.spectrum, b.ocean.spectrum);
  EXPECT_EQ(a.ocean.waves, b.ocean.waves);
  EXPECT_EQ(a.ocean.lambda_min, b.ocean.lambda_min);
  EXPECT_EQ(a.ocean.lambda_max, b.ocean.lambda_max);
  EXPECT_EQ(a.ocean.seed, b.ocean.seed);
  EXPECT_EQ(a.ocean.n_min, b.ocean.n_min);
  EXPECT_EQ(a.ocean.n_max, b.ocean.n_max);
  EXPECT_EQ(a.ocean.grid_cell, b.ocean.grid_cell);
  EXPECT_EQ(a.ocean.fresnel_r, b.ocean.fresnel_r);
  EXPECT_EQ(a.sky.model, b.sky.model);
  EXPECT_EQ(a.sky.exr, b.sky.exr);
}

// The message of the SceneError that `f` throws; fails the test when it throws nothing.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
    return msg;
  }
  ADD_FAILURE() << "no SceneError";
  return {};
}

std::string text_error(const std::string& text) {
  return error_of([&] {
    SceneBuilder b;
    b.load_text(text, "s.json");
    b.build();
  });
}

std::string set_error(const std::string& assignment) {
  return error_of([&] {
    SceneBuilder b;
    b.set(assignment);
    b.build();
  });
}

#define EXPECT_HAS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

Scene with_sets(std::initializer_list<std::string> sets) {
  SceneBuilder b;
  for (const auto& s : sets) b.set(s);
  return b.build();
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("thalassa_scene_test_" + name)).string();
}

// --- defaults --------------------------------------------------------------------------------

TEST(SceneDefaults, BuildEqualsHeaderInitializers) {
  const Scene s = SceneBuilder().build();
  expect_same(s, Scene{});
  EXPECT_FALSE(s.sun.utc.has_value());
}

TEST(SceneDefaults, EmbeddedJsonBuildsToDefaults) {
  const json doc = json::parse(default_scene_json());
  EXPECT_FALSE(doc["sun"].contains("utc"));
  SceneBuilder b;
  b.load_text(default_scene_json(), "default");
  expect_same(b.build(), Scene{});
}

TEST(SceneDefaults, EveryKeyHasADefaultExceptUtc) {
  const json doc = json::parse(default_scene_json());
  for (const auto& k : scene_keys()) {
    const auto dot = k.path.find('.');
    const bool present = dot == std::string::npos
                             ? doc.contains(k.path)
                             : doc[k.path.substr(0, dot)].contains(k.path.substr(dot + 1));
    EXPECT_EQ(present, k.path != "sun.utc") << k.path;
    if (present) {
      const json v = dot == std::string::npos ? doc[k.path]
                                              : doc[k.path.substr(0, dot)][k.path.substr(dot + 1)];
      EXPECT_EQ(v.dump(), k.default_value) << k.path;
    } else {
      EXPECT_EQ(k.default_value, "(none)");
    }
  }
}

TEST(SceneDefaults, DataFilesMatch) {
  const std::string root = THALASSA_SOURCE_DIR;
  ASSERT_FALSE(root.empty()) << "THALASSA_SOURCE_DIR is not defined by the build";
  EXPECT_EQ(json::parse(read_text(root + "/data/scenes/default.json")),
            json::parse(default_scene_json()));

  SceneBuilder b;
  b.load_file(root + "/data/scenes/example_utc.json");
  const Scene s = b.build();
  ASSERT_TRUE(s.sun.utc.has_value());
  EXPECT_TRUE(std::isfinite(s.sun.zenith));
  const json doc = json::parse(read_text(root + "/data/scenes/example_utc.json"));
  EXPECT_FALSE(doc["sun"].contains("zenith"));
  EXPECT_FALSE(doc["sun"].contains("azimuth"));
}

// --- files and overrides ---------------------------------------------------------------------

// A copy is a trial: what it is given leaves the original as it was (thalassa view tries a
// frame's changes on one, so that they take together or not at all).
TEST(SceneFile, CopyTakesChangesAlone) {
  SceneBuilder original;
  original.set("camera.height=100");
  SceneBuilder trial = original;
  trial.set("camera.height=2000");
  trial.set("sun.zenith=30");
  EXPECT_THROW(trial.set("camera.lat=95"), SceneError);
  EXPECT_EQ(trial.build().camera.height, 2000.0);
  EXPECT_EQ(trial.build().sun.zenith, 30.0);
  EXPECT_EQ(original.build().camera.height, 100.0);
  EXPECT_EQ(original.build().sun.zenith, Scene{}.sun.zenith);
  EXPECT_EQ(original.source_of("sun.zenith"), "defaults");
  original = trial;
  EXPECT_EQ(original.build().camera.height, 2000.0);
  EXPECT_EQ(original.merged_json(), trial.merged_json());
}

TEST(SceneFile, OverridesSomeKeys) {
  SceneBuilder b;
  b.load_text(R"({"camera": {"height": 20000, "pitch": -90},
                  "ocean": {"spectrum": "omega-2", "seed": 4294967295},
                  "image": {"exr_type": "float", "width": 1},
                  "planet": {"shape": "sphere"},
                  "time": 1e7})",
              "s.json");
  const Scene s = b.build();
  Scene expected;
  expected.camera.height = 20000;
  expected.camera.pitch = -90;
  expected.ocean.spectrum = WaveSpectrum::OmegaMinus2;
  expected.ocean.seed = 4294967295u;
  expected.image.exr_type = ExrPixelType::Float;
  expected.image.width = 1;
  expected.planet.shape = PlanetShape::Sphere;
  expected.time = 1e7;
  expect_same(s, expected);
}

TEST(SceneFile, LoadFileAndLaterLayersWin) {
  const std::string path = temp_path("layers.json");
  {
    std::ofstream out(path);
    out << R"({"camera": {"lat": -33.5, "lon": 151}, "ocean": {"wind_speed": 3}})";
  }
  SceneBuilder b;
  b.load_file(path);
  b.set("ocean.wind_speed=7.5");
  const Scene s = b.build();
  std::filesystem::remove(path);
  EXPECT_EQ(s.camera.lat, -33.5);
  EXPECT_EQ(s.camera.lon, 151.0);
  EXPECT_EQ(s.ocean.wind_speed, 7.5);
}

TEST(SceneFile, MissingAndUnreadableFiles) {
  const std::string missing = temp_path("does_not_exist.json");
  std::string msg = error_of([&] { SceneBuilder().load_file(missing); });
  EXPECT_HAS(msg, missing + ": ");
  EXPECT_HAS(msg, "no such file");

  const std::string dir = temp_path("a_directory.json");
  std::filesystem::create_directories(dir);
  msg = error_of([&] { SceneBuilder().load_file(dir); });
  std::filesystem::remove(dir);
  EXPECT_HAS(msg, dir + ": ");
  EXPECT_HAS(msg, "expected a readable scene file, got a directory");
}

TEST(SceneFile, FailedLoadChangesNothing) {
  SceneBuilder b;
  EXPECT_THROW(b.load_text(R"({"camera": {"height": 50, "pitch": "up"}})", "s.json"), SceneError);
  EXPECT_THROW(b.set("camera.height=1e99"), SceneError);
  expect_same(b.build(), Scene{});
}

TEST(SceneFile, MoveKeepsState) {
  SceneBuilder a;
  a.set("camera.height=123");
  SceneBuilder b(std::move(a));
  SceneBuilder c;
  c = std::move(b);
  EXPECT_EQ(c.build().camera.height, 123.0);
}

TEST(SceneFile, MergedJsonIsSortedCompleteAndRoundTrips) {
  SceneBuilder b;
  b.load_text(R"({"ocean": {"waves": 100}, "camera": {"lat": 10}})", "s.json");
  b.set("sky.exr=skies/noon.exr");
  const std::string merged = b.merged_json();
  const json doc = json::parse(merged);
  EXPECT_EQ(doc["ocean"]["waves"], 100);
  EXPECT_EQ(doc["camera"]["lat"], 10.0);
  EXPECT_EQ(doc["sky"]["exr"], "skies/noon.exr");
  EXPECT_EQ(doc["image"]["width"], 960);
  EXPECT_EQ(doc.dump(), merged);  // nlohmann's json sorts keys: canonical
  // Numbers are canonical whatever their spelling.
  SceneBuilder spelled;
  spelled.load_text(R"({"ocean": {"waves": 1e2}, "camera": {"lat": 10.0}})", "t.json");
  spelled.set("sky.exr=\"skies/noon.exr\"");
  EXPECT_EQ(spelled.merged_json(), merged);

  SceneBuilder again;
  again.load_text(merged, "merged");
  expect_same(again.build(), b.build());

  // With sun.utc the computed angles are left out, so the document still builds.
  SceneBuilder utc;
  utc.set("sun.utc=2024-03-20T12:00:00Z");
  const json with_utc = json::parse(utc.merged_json());
  EXPECT_EQ(with_utc["sun"], json({{"utc", "2024-03-20T12:00:00Z"}}));
  SceneBuilder utc_again;
  utc_again.load_text(utc.merged_json(), "merged");
  expect_same(utc_again.build(), utc.build());
}

TEST(SceneSet, NumbersBareAndQuotedStrings) {
  const Scene s = with_sets({"camera.height=20000", "image.width=64", "ocean.spectrum=omega-2",
                             "planet.shape=\"sphere\"", "sky.exr=/data/sky map.exr", "sun.zenith=0",
                             "time=1e12", "ocean.lambda_min=1e-3"});
  EXPECT_EQ(s.camera.height, 20000.0);
  EXPECT_EQ(s.image.width, 64);
  EXPECT_EQ(s.ocean.spectrum, WaveSpectrum::OmegaMinus2);
  EXPECT_EQ(s.planet.shape, PlanetShape::Sphere);
  EXPECT_EQ(s.sky.exr, "/data/sky map.exr");
  EXPECT_EQ(s.sun.zenith, 0.0);
  EXPECT_EQ(s.time, 1e12);
  EXPECT_EQ(s.ocean.lambda_min, 1e-3);
  // A quoted number is a string: the path "123" must be given as "\"123\"".
  EXPECT_EQ(with_sets({"sky.exr=\"123\""}).sky.exr, "123");
  EXPECT_EQ(with_sets({"sky.exr="}).sky.exr, "");
}

TEST(SceneErrors, FilterWeightsNeedNMinBelowNMax) {
  SceneBuilder b;
  b.set("ocean.n_min=3");
  try {
    b.build();
    FAIL() << "n_min above n_max must be refused";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--set: ocean.n_min: expected a value < ocean.n_max (2.5), got 3");
  }
  SceneBuilder ok;
  ok.set("ocean.n_min=2");
  ok.set("ocean.n_max=4");
  EXPECT_EQ(ok.build().ocean.n_max, 4.0);
}

TEST(SceneErrors, RepeatedKeysAreRefused) {
  // JSON parsers keep the last of two equal keys; a scene names each value once.
  auto error_of = [](const std::string& text) {
    try {
      SceneBuilder b;
      b.load_text(text, "s.json");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of(R"({"camera": {"height": 4, "height": 5}})"),
            "s.json: camera.height: expected each key once, got \"height\" a second time");
  EXPECT_EQ(error_of(R"({"camera": {"height": 4}, "camera": {"pitch": 5}})"),
            "s.json: camera: expected each key once, got \"camera\" a second time");
  // The same name in different sections is not a repeat.
  EXPECT_EQ(error_of(R"({"camera": {"height": 4}, "planet": {"radius": 7e6}})"), "no error");
}

TEST(SceneBuilder, SourceOfNamesWhereAValueCameFrom) {
  SceneBuilder b;
  b.load_text(R"({"camera": {"height": 4}})", "s.json");
  b.set("sun.zenith=10");
  EXPECT_EQ(b.source_of("camera.height"), "s.json");
  EXPECT_EQ(b.source_of("sun.zenith"), "--set");
  EXPECT_EQ(b.source_of("camera.lat"), "defaults");
}

TEST(SceneSet, Errors) {
  std::string msg = set_error("camera.height=abc");
  EXPECT_HAS(msg, "--set");
  EXPECT_HAS(msg, "camera.height");
  EXPECT_HAS(msg, "expected a number in [-11000, 1e9] (m)");
  EXPECT_HAS(msg, "got \"abc\"");

  msg = set_error("camera.height");
  EXPECT_HAS(msg, "--set");
  EXPECT_HAS(msg, "camera.height");
  EXPECT_HAS(msg, "key.path=value");

  msg = set_error("=5");
  EXPECT_HAS(msg, "--set");
  EXPECT_HAS(msg, "key.path=value");

  msg = set_error("camera.hieght=5");
  EXPECT_HAS(msg, "--set: camera.hieght: expected a known key (did you mean camera.height?)");

  msg = set_error("camera=5");
  EXPECT_HAS(msg, "--set: camera: expected a key path such as camera.");

  msg = set_error("zzzzzzzz=1");
  EXPECT_HAS(msg, "--set: zzzzzzzz: expected a known key");
  EXPECT_EQ(msg.find("did you mean"), std::string::npos);

  msg = set_error("image.width=2.5");
  EXPECT_HAS(msg, "--set: image.width: expected an integer in [1, 8192] (pixels), got 2.5");

  msg = set_error("ocean.spectrum=jonswap");
  EXPECT_HAS(msg, "--set: ocean.spectrum: expected one of \"pierson-moskowitz\", \"omega-2\"");
}

// --- bad input in files ----------------------------------------------------------------------

TEST(SceneErrors, MalformedJsonGivesLineAndColumn) {
  const std::string msg = text_error("{\n  \"camera\": {\n    \"height\" 5\n  }\n}");
  EXPECT_HAS(msg, "s.json:3:14: expected valid JSON, got ");
  EXPECT_HAS(text_error(""), "s.json:1:1: expected valid JSON");
  EXPECT_HAS(text_error("{\"time\": 1,}"), "s.json:1:");
}

TEST(SceneErrors, TopLevelAndSectionMustBeObjects) {
  EXPECT_HAS(text_error("[1, 2]"),
             "s.json: expected a JSON object of sections at the top level, "
             "got an array");
  EXPECT_HAS(text_error("{\"camera\": 5}"), "s.json: camera: expected an object");
  EXPECT_HAS(text_error("{\"camera\": [1]}"), "got an array");
}

TEST(SceneErrors, UnknownKeysSuggestTheClosest) {
  EXPECT_HAS(text_error(R"({"camera": {"hieght": 5}})"),
             "s.json: camera.hieght: expected a known key (did you mean camera.height?), got an "
             "unknown key");
  EXPECT_HAS(text_error(R"({"camra": {"height": 5}})"),
             "s.json: camra: expected a known key "
             "(did you mean camera?)");
  EXPECT_HAS(text_error(R"({"wind_speed": 5})"),
             "s.json: wind_speed: expected a known key (did "
             "you mean ocean.wind_speed?)");
  EXPECT_HAS(text_error(R"({"ocean": {"fetch": 5}})"), "s.json: ocean.fetch: expected a known key");
  EXPECT_HAS(text_error(R"({"camera.height": 5})"),
             "s.json: camera.height: expected the key inside its section, {\"camera\": "
             "{\"height\": ...}}, got a dotted name at the top level");
}

TEST(SceneErrors, WrongTypes) {
  std::string msg = text_error(R"({"image": {"width": 2.5}})");
  EXPECT_HAS(msg, "s.json: image.width: expected an integer in [1, 8192] (pixels), got 2.5");
  EXPECT_HAS(text_error(R"({"image": {"width": true}})"), "image.width: expected an integer");
  EXPECT_HAS(text_error(R"({"image": {"width": "960"}})"), "got \"960\"");
  EXPECT_HAS(text_error(R"({"camera": {"height": "high"}})"),
             "s.json: camera.height: expected a number in [-11000, 1e9] (m), got \"high\"");
  EXPECT_HAS(text_error(R"({"camera": {"height": false}})"),
             "camera.height: expected a number in [-11000, 1e9] (m), got false");
  EXPECT_HAS(text_error(R"({"camera": {"height": null}})"), "got null");
  EXPECT_HAS(text_error(R"({"camera": {"height": [4]}})"), "got an array");
  EXPECT_HAS(text_error(R"({"sky": {"exr": 5}})"), "s.json: sky.exr: expected a string, got 5");
  EXPECT_HAS(text_error(R"({"planet": {"shape": 1}})"),
             "s.json: planet.shape: expected one of \"wgs84\", \"sphere\", got 1");
  // An integral number written as a float is accepted for an integer key.
  SceneBuilder b;
  b.load_text(R"({"image": {"width": 1e3}})", "s.json");
  EXPECT_EQ(b.build().image.width, 1000);
}

TEST(SceneErrors, NonFiniteNumbersAreRejected) {
  // nlohmann refuses a literal that overflows a double, without a position.
  EXPECT_HAS(text_error(R"({"time": 1e999})"), "s.json: expected valid JSON, got number overflow");
  EXPECT_HAS(text_error(R"({"camera": {"lat": -1e999}})"), "1e999");
  EXPECT_HAS(set_error("camera.lat=-1e999"), "--set: camera.lat: expected a number");
  EXPECT_HAS(set_error("camera.lat=nan"), "--set: camera.lat: expected a number");
  EXPECT_HAS(set_error("camera.lat=inf"), "got \"inf\"");
  EXPECT_HAS(text_error(R"({"camera": {"lat": NaN}})"), "s.json:1:");
}

TEST(SceneErrors, OutOfRange) {
  EXPECT_HAS(text_error(R"({"camera": {"lat": 90.5}})"),
             "s.json: camera.lat: expected a number in [-90, 90] (degrees), got 90.5");
  EXPECT_HAS(text_error(R"({"image": {"exposure": 0}})"),
             "image.exposure: expected a number in (0, 1e6]");
  EXPECT_HAS(text_error(R"({"image": {"width": 0}})"), "image.width: expected an integer");
  EXPECT_HAS(text_error(R"({"image": {"height": 16385}})"), "image.height: expected an integer");
  EXPECT_HAS(text_error(R"({"ocean": {"waves": 3000000000}})"), "ocean.waves: expected an integer");
  EXPECT_HAS(text_error(R"({"ocean": {"waves": -3000000000}})"), "got -3000000000");
  EXPECT_HAS(text_error(R"({"ocean": {"seed": -1}})"),
             "ocean.seed: expected an integer in [0, 4294967295], got -1");
  EXPECT_HAS(text_error(R"({"ocean": {"seed": 4294967296}})"), "got 4294967296");
  EXPECT_HAS(text_error(R"({"ocean": {"seed": 18446744073709551615}})"), "ocean.seed");
  EXPECT_HAS(text_error(R"({"camera": {"fov_y": 0}})"),
             "camera.fov_y: expected a number in "
             "[0.01, 179] (degrees)");
  EXPECT_HAS(text_error(R"({"planet": {"radius": 6371000000}})"), "planet.radius");
  // The bounds themselves are valid.
  SceneBuilder b;
  b.load_text(R"({"ocean": {"seed": 0, "wind_speed": 60}, "camera": {"lat": -90, "lon": 180}})",
              "s.json");
  EXPECT_EQ(b.build().ocean.seed, 0u);
}

TEST(SceneErrors, EnumValuesListTheAllowedOnes) {
  EXPECT_HAS(text_error(R"({"image": {"exr_type": "double"}})"),
             "s.json: image.exr_type: expected one of \"half\", \"float\", got \"double\"");
  EXPECT_HAS(text_error(R"({"sky": {"model": "hosek"}})"),
             "s.json: sky.model: expected one of \"atmosphere\", got \"hosek\"");
  EXPECT_HAS(text_error(R"({"ocean": {"spectrum": "Omega-2"}})"), "ocean.spectrum");
}

TEST(SceneErrors, LambdaMinAboveLambdaMax) {
  EXPECT_HAS(text_error(R"({"ocean": {"lambda_min": 40}})"),
             "s.json: ocean.lambda_min: expected a value <= ocean.lambda_max (30 m), got 40");
  // Named after the layer that broke it.
  SceneBuilder b;
  b.load_text(R"({"ocean": {"lambda_min": 5}})", "s.json");
  b.set("ocean.lambda_max=1");
  EXPECT_HAS(error_of([&] { b.build(); }),
             "--set: ocean.lambda_min: expected a value <= "
             "ocean.lambda_max (1 m), got 5");
  SceneBuilder equal;
  equal.set("ocean.lambda_min=30");
  EXPECT_EQ(equal.build().ocean.lambda_min, 30.0);
}

TEST(SceneErrors, UtcFormat) {
  for (const char* bad :
       {"2024-03-20 12:00:00Z", "2024-03-20T12:00:00", "2024-03-20T12:00:00+00:00",
        "2024-3-20T12:00:00Z", "2024-02-30T12:00:00Z", "2023-02-29T00:00:00Z",
        "2024-13-01T00:00:00Z", "2024-03-20T24:00:00Z", "2024-03-20T12:60:00Z",
        "2024-03-20T12:00:60Z", "2024-03-20T12:00:00.Z", "2024-03-20T12:00:00.1234567890Z",
        "2024-03-20T12:00:00zZ", "tomorrow", ""}) {
    const std::string msg = text_error(std::string(R"({"sun": {"utc": ")") + bad + "\"}}");
    EXPECT_HAS(msg, "s.json: sun.utc: expected an ISO 8601 UTC time YYYY-MM-DDTHH:MM:SS[.fff]Z");
  }
  EXPECT_HAS(text_error(R"({"sun": {"utc": 1700000000}})"), "sun.utc: expected an ISO 8601");
  // Valid forms.
  EXPECT_EQ(*with_sets({"sun.utc=2024-02-29T23:59:59.999Z"}).sun.utc, "2024-02-29T23:59:59.999Z");
  EXPECT_TRUE(with_sets({"sun.utc=2000-01-01T00:00:00.5Z"}).sun.utc.has_value());
}

TEST(SceneErrors, UtcExcludesZenithAndAzimuth) {
  std::string msg = text_error(R"({"sun": {"utc": "2024-03-20T12:00:00Z", "zenith": 30}})");
  EXPECT_HAS(msg, "s.json: sun.utc: expected either sun.utc or sun.zenith/sun.azimuth, got both");
  EXPECT_HAS(msg, "sun.zenith");

  msg = error_of([] {
    SceneBuilder b;
    b.load_text(R"({"sun": {"utc": "2024-03-20T12:00:00Z"}})", "s.json");
    b.set("sun.azimuth=90");
    b.build();
  });
  EXPECT_HAS(msg, "--set: sun.utc:");
  EXPECT_HAS(msg, "sun.utc (from s.json)");
  EXPECT_HAS(msg, "sun.azimuth (from --set)");

  // The built-in defaults of zenith and azimuth do not count as given...
  const Scene s = with_sets({"sun.utc=2024-03-20T12:00:00Z"});
  EXPECT_NE(s.sun.zenith, Scene{}.sun.zenith);
  // ...but a file that spells them out gives them.
  SceneBuilder b;
  b.load_text(default_scene_json(), "default.json");
  b.set("sun.utc=2024-03-20T12:00:00Z");
  EXPECT_HAS(error_of([&] { b.build(); }), "--set: sun.utc: expected either");
}

// --- the solar position ----------------------------------------------------------------------

struct SunCase {
  const char* utc;
  double lat, lon;         // degrees
  double zenith, azimuth;  // degrees, reference
};

Scene sun_at(const std::string& utc, double lat, double lon) {
  SceneBuilder b;
  b.set("sun.utc=" + utc);
  b.set("camera.lat=" + std::to_string(lat));
  b.set("camera.lon=" + std::to_string(lon));
  return b.build();
}

double angle_diff(double a, double b) {  // degrees, in [0, 180]
  const double d = std::fmod(std::fabs(a - b), 360.0);
  return d > 180.0 ? 360.0 - d : d;
}

TEST(SolarPosition, MatchesReferenceEphemeris) {
  // Geometric (no refraction) topocentric positions from PyEphem 4.1 (VSOP87), a different
  // algorithm from NOAA's; the two agree to about 0.01 degree.
  const SunCase cases[] = {
      {"2024-03-20T12:00:00Z", 0, 0, 1.833, 85.414},
      {"2026-06-21T18:30:00Z", 20, -150, 49.062, 75.842},
      {"2023-11-15T02:30:00Z", -33.87, 151.21, 19.137, 320.870},
      {"2010-06-21T18:06:00Z", 40, -105, 20.321, 140.417},
      {"2025-12-21T11:00:00Z", 60, 10, 83.524, 175.808},
      {"2024-06-21T00:00:00Z", 78.2, 15.6, 77.983, 14.188},
      {"2019-09-01T15:45:30Z", 51.48, -0.0015, 63.044, 247.588},
      {"2031-02-10T21:15:00Z", -17.5, -149.5, 14.138, 78.515},
      {"2010-06-21T06:06:00Z", 40, -105, 115.248, 345.867},
      {"2024-01-01T00:00:00Z", 0, 0, 156.930, 181.808},
  };
  for (const auto& c : cases) {
    const Scene s = sun_at(c.utc, c.lat, c.lon);
    EXPECT_NEAR(s.sun.zenith, c.zenith, 0.1) << c.utc;
    EXPECT_LT(angle_diff(s.sun.azimuth, c.azimuth), 0.1) << c.utc;
    EXPECT_EQ(*s.sun.utc, c.utc);
  }
}

TEST(SolarPosition, KnownGeometry) {
  // March equinox 2024 (03:06 UTC): near 12:00 UTC the sun stands almost overhead at (0, 0)
  // (the equation of time is -7.5 min, so the hour angle is -1.9 degrees).
  EXPECT_LT(sun_at("2024-03-20T12:00:00Z", 0, 0).sun.zenith, 2.5);
  // June solstice 2024 (20:51 UTC) at the Tropic of Cancer, at the longitude whose solar noon
  // it is: overhead.
  EXPECT_LT(sun_at("2024-06-20T20:51:00Z", 23.44, -132.35).sun.zenith, 0.5);
  // At solar noon the zenith angle is |lat - declination|: at 60 N on the June solstice,
  // 60 - 23.44.
  double best = 180.0;
  for (int minute = 0; minute < 60; ++minute) {
    char utc[32];
    std::snprintf(utc, sizeof utc, "2024-06-20T11:%02d:00Z", minute);
    best = std::min(best, sun_at(utc, 60, 0).sun.zenith);
  }
  EXPECT_NEAR(best, 60 - 23.44, 0.05);
  // Midnight at the equator: below the horizon.
  EXPECT_GT(sun_at("2024-01-01T00:00:00Z", 0, 0).sun.zenith, 90.0);
  // On the equinox the sun rises due east and sets due west.
  const Scene rise = sun_at("2024-03-20T06:07:00Z", 45, 0);
  EXPECT_NEAR(rise.sun.zenith, 90.0, 0.5);
  EXPECT_NEAR(rise.sun.azimuth, 90.0, 0.5);
  const Scene set = sun_at("2024-03-20T18:07:00Z", -45, 0);
  EXPECT_NEAR(set.sun.zenith, 90.0, 0.5);
  EXPECT_NEAR(set.sun.azimuth, 270.0, 0.5);
}

TEST(SolarPosition, SymmetricAboutSolarNoon) {
  // Find solar noon (smallest zenith) to the second, then compare +-3 h: the azimuths mirror
  // about the meridian and the zeniths agree (the declination drifts by < 0.1 degree in 6 h).
  for (const double lat : {48.0, -30.0}) {
    const double lon = 30.0;
    auto at = [&](int seconds_of_day) {
      char utc[32];
      std::snprintf(utc, sizeof utc, "2024-05-10T%02d:%02d:%02dZ", seconds_of_day / 3600,
                    seconds_of_day / 60 % 60, seconds_of_day % 60);
      return sun_at(utc, lat, lon).sun;
    };
    int noon = 0;
    double best = 180.0;
    for (int t = 9 * 3600; t < 11 * 3600; t += 10) {
      const double z = at(t).zenith;
      if (z < best) {
        best = z;
        noon = t;
      }
    }
    const auto morning = at(noon - 3 * 3600);
    const auto afternoon = at(noon + 3 * 3600);
    EXPECT_LT(angle_diff(morning.azimuth, 360.0 - afternoon.azimuth), 0.5) << lat;
    EXPECT_NEAR(morning.zenith, afternoon.zenith, 0.5) << lat;
    // North of the tropics the noon sun is due south; south of them, due north.
    EXPECT_LT(angle_diff(at(noon).azimuth, lat > 0 ? 180.0 : 0.0), 1.0) << lat;
    EXPECT_LT(morning.azimuth, 180.0);  // east of the meridian in the morning
  }
}

TEST(SolarPosition, FiniteAtPolesAndAllHours) {
  for (const double lat : {-90.0, -89.999, 0.0, 89.999, 90.0}) {
    for (int hour = 0; hour < 24; hour += 3) {
      char utc[32];
      std::snprintf(utc, sizeof utc, "2024-12-21T%02d:00:00Z", hour);
      for (const double lon : {-180.0, 0.0, 180.0}) {
        const Scene s = sun_at(utc, lat, lon);
        EXPECT_TRUE(std::isfinite(s.sun.zenith) && std::isfinite(s.sun.azimuth)) << utc;
        EXPECT_GE(s.sun.zenith, 0.0);
        EXPECT_LE(s.sun.zenith, 180.0);
        EXPECT_GE(s.sun.azimuth, 0.0);
        EXPECT_LT(s.sun.azimuth, 360.0);
      }
    }
  }
  // At the South Pole on the December solstice the sun is 23.44 degrees up all day.
  EXPECT_NEAR(sun_at("2024-12-21T09:20:00Z", -90, 0).sun.zenith, 90 - 23.44, 0.05);
}

// --- the key list and its documentation ------------------------------------------------------

TEST(SceneKeys, ListsEveryKeyOnce) {
  const std::set<std::string> expected = {"image.width",
                                          "image.height",
                                          "image.exposure",
                                          "image.exr_type",
                                          "camera.lat",
                                          "camera.lon",
                                          "camera.height",
                                          "camera.heading",
                                          "camera.pitch",
                                          "camera.roll",
                                          "camera.fov_y",
                                          "sun.zenith",
                                          "sun.azimuth",
                                          "sun.utc",
                                          "time",
                                          "planet.shape",
                                          "planet.radius",
                                          "ocean.wind_speed",
                                          "ocean.wind_direction",
                                          "ocean.spectrum",
                                          "ocean.waves",
                                          "ocean.lambda_min",
                                          "ocean.lambda_max",
                                          "ocean.seed",
                                          "ocean.n_min",
                                          "ocean.parallax_iterations",
                                          "ocean.n_max",
                                          "ocean.grid_cell",
                                          "ocean.fresnel_r",
                                          "ocean.sky_filter",
                                          "ocean.deep_reflectance_r",
                                          "ocean.deep_reflectance_g",
                                          "ocean.deep_reflectance_b",
                                          "ocean.effective_fresnel",
                                          "ocean.sky_lobe_centre",
                                          "sky.model",
                                          "sky.exr"};
  std::set<std::string> seen;
  for (const auto& k : scene_keys()) {
    EXPECT_TRUE(seen.insert(k.path).second) << "duplicate " << k.path;
    EXPECT_TRUE(k.type == "number" || k.type == "integer" || k.type == "string" || k.type == "enum")
        << k.path;
    EXPECT_FALSE(k.range.empty()) << k.path;
    EXPECT_FALSE(k.doc.empty()) << k.path;
  }
  EXPECT_EQ(seen, expected);
  // Every key can be overridden by --set with its own default.
  for (const auto& k : scene_keys()) {
    if (k.default_value == "(none)") continue;
    SceneBuilder b;
    b.set(k.path + "=" + k.default_value);
    expect_same(b.build(), Scene{});
  }
}

TEST(SceneKeys, DocumentedInDocsSceneMd) {
  const std::string root = THALASSA_SOURCE_DIR;
  ASSERT_FALSE(root.empty()) << "THALASSA_SOURCE_DIR is not defined by the build";
  std::ifstream in(root + "/docs/scene.md");
  ASSERT_TRUE(in) << root << "/docs/scene.md";
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  // Each key has a table row "| `path` | ..." with its range, default and unit.
  for (const auto& k : scene_keys()) {
    const std::string row_start = "| `" + k.path + "` |";
    bool found = false;
    for (const auto& line : lines) {
      if (line.rfind(row_start, 0) == 0) {
        found = true;
        EXPECT_HAS(line, k.range);
        EXPECT_HAS(line, k.default_value);
        if (!k.unit.empty()) {
          EXPECT_HAS(line, k.unit);
        }
      }
    }
    EXPECT_TRUE(found) << "docs/scene.md has no table row for " << k.path;
  }
}

}  // namespace
}  // namespace thalassa
