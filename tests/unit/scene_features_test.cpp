// Tests of the scene keys `wakes` and `calm_areas` (issue 9, point 3; docs/scene.md "Wakes and
// calm areas"): inline entries and GeoJSON files (LineString tracks with per-vertex times, Point
// ships, Polygon and MultiPolygon areas) arrive in the Scene; bad geometry is refused with one
// line naming the file, the entry or feature (index and name) and what was expected; the merged
// scene holds the features inline and builds to the same Scene.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "thalassa/engine/scene.hpp"

namespace thalassa {
namespace {

namespace fs = std::filesystem;

std::string error_of_text(const std::string& text, const std::string& source = "s.json") {
  try {
    SceneBuilder b;
    b.load_text(text, source);
    b.build();
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    return msg;
  }
  ADD_FAILURE() << "no SceneError for " << text;
  return {};
}

#define EXPECT_HAS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

// A folder of its own under the temporary directory, removed at the end.
struct TempDir {
  fs::path path;
  TempDir() {
    path =
        fs::temp_directory_path() /
        ("thalassa_features_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

TEST(SceneFeatures, NoneByDefault) {
  const Scene s = SceneBuilder().build();
  EXPECT_TRUE(s.wakes.empty());
  EXPECT_TRUE(s.calm_areas.empty());
  EXPECT_EQ(std::string(default_scene_json()).find("wakes"), std::string::npos);
}

TEST(SceneFeatures, InlineWakesAndCalmAreas) {
  SceneBuilder b;
  b.load_text(R"({
    "wakes": [
      {"name": "ferry", "track": [{"lat": 43.29, "lon": 5.36, "time": 0},
                                  {"lat": 43.28, "lon": 5.35, "time": 200}], "amplitude": 0.5},
      {"lat": -12, "lon": 179.99, "heading": 95, "speed": 12, "time": 30, "length": 5000}
    ],
    "calm_areas": [
      {"name": "slick", "scale": 0.1, "fade": 250,
       "polygon": [{"lat": 43.2, "lon": 5.3}, {"lat": 43.2, "lon": 5.4}, {"lat": 43.3, "lon": 5.4},
                   {"lat": 43.3, "lon": 5.3}, {"lat": 43.2, "lon": 5.3}],
       "holes": [[{"lat": 43.24, "lon": 5.34}, {"lat": 43.26, "lon": 5.34}, {"lat": 43.25, "lon": 5.36}]]}
    ]})",
              "s.json");
  const Scene s = b.build();
  ASSERT_EQ(s.wakes.size(), 2u);
  EXPECT_EQ(s.wakes[0].name, "ferry");
  ASSERT_EQ(s.wakes[0].track.size(), 2u);
  EXPECT_EQ(s.wakes[0].track[1].time, 200.0);
  EXPECT_EQ(s.wakes[0].track[1].lon, 5.35);
  EXPECT_EQ(s.wakes[0].amplitude, 0.5);
  EXPECT_EQ(s.wakes[0].draft, WakeSettings{}.draft);
  EXPECT_EQ(s.wakes[1].name, "");
  EXPECT_TRUE(s.wakes[1].track.empty());
  EXPECT_EQ(s.wakes[1].heading, 95.0);
  EXPECT_EQ(s.wakes[1].speed, 12.0);
  EXPECT_EQ(s.wakes[1].time, 30.0);
  EXPECT_EQ(s.wakes[1].length, 5000.0);
  ASSERT_EQ(s.calm_areas.size(), 1u);
  EXPECT_EQ(s.calm_areas[0].exterior.size(), 4u);  // the repeated closing vertex is dropped
  ASSERT_EQ(s.calm_areas[0].holes.size(), 1u);
  EXPECT_EQ(s.calm_areas[0].holes[0].size(), 3u);
  EXPECT_EQ(s.calm_areas[0].scale, 0.1);
  EXPECT_EQ(s.calm_areas[0].fade, 250.0);
  // The merged scene holds them inline and builds to the same features.
  SceneBuilder again;
  again.load_text(b.merged_json(), "merged");
  const Scene t = again.build();
  ASSERT_EQ(t.wakes.size(), 2u);
  EXPECT_EQ(t.wakes[0].track[0].lat, 43.29);
  EXPECT_EQ(t.calm_areas[0].holes[0][2].lon, 5.36);
  EXPECT_EQ(again.merged_json(), b.merged_json());
  // A later layer replaces the whole array.
  b.set(R"(wakes=[])");
  EXPECT_TRUE(b.build().wakes.empty());
  EXPECT_EQ(b.source_of("wakes"), "--set");
}

TEST(SceneFeatures, GeoJsonFilesRelativeToTheScene) {
  const TempDir dir;
  dir.write("tracks.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"name": "ferry", "times": [0, 100, 250], "draft": 4},
     "geometry": {"type": "LineString", "coordinates": [[5.36, 43.29], [5.35, 43.285, 0], [5.34, 43.28]]}},
    {"type": "Feature", "id": 7, "properties": {"heading": 270, "speed": 9, "time": 10},
     "geometry": {"type": "Point", "coordinates": [179.99, -12]}}]})");
  dir.write("slicks.geojson", R"({"type": "Feature", "properties": {"name": "slicks", "scale": 0.3},
     "geometry": {"type": "MultiPolygon", "coordinates": [
       [[[5.3, 43.2], [5.4, 43.2], [5.4, 43.3], [5.3, 43.3], [5.3, 43.2]]],
       [[[179.5, -0.5], [-179.5, -0.5], [-179.5, 0.5], [179.5, 0.5], [179.5, -0.5]],
        [[179.9, -0.1], [-179.9, -0.1], [-179.9, 0.1], [179.9, 0.1], [179.9, -0.1]]]]}})");
  const std::string scene = dir.write("scene.json", R"({
    "wakes": [{"geojson": "tracks.geojson", "amplitude": 0.8}],
    "calm_areas": [{"geojson": "slicks.geojson", "fade": 40}]})");
  SceneBuilder b;
  b.load_file(scene);
  const Scene s = b.build();
  ASSERT_EQ(s.wakes.size(), 2u);
  EXPECT_EQ(s.wakes[0].name, "ferry");
  ASSERT_EQ(s.wakes[0].track.size(), 3u);
  EXPECT_EQ(s.wakes[0].track[1].lat, 43.285);
  EXPECT_EQ(s.wakes[0].track[2].time, 250.0);
  EXPECT_EQ(s.wakes[0].draft, 4.0);      // the feature's property
  EXPECT_EQ(s.wakes[0].amplitude, 0.8);  // the entry's default
  EXPECT_EQ(s.wakes[1].name, "7");
  EXPECT_EQ(s.wakes[1].lon, 179.99);
  EXPECT_EQ(s.wakes[1].heading, 270.0);
  EXPECT_EQ(s.wakes[1].time, 10.0);
  ASSERT_EQ(s.calm_areas.size(), 2u);  // one per polygon of the MultiPolygon
  EXPECT_EQ(s.calm_areas[1].name, "slicks");
  EXPECT_EQ(s.calm_areas[1].holes.size(), 1u);
  EXPECT_EQ(s.calm_areas[1].scale, 0.3);
  EXPECT_EQ(s.calm_areas[1].fade, 40.0);
  // --set takes a bare path (relative to the working directory) as the whole array.
  SceneBuilder c;
  c.set("calm_areas=" + (dir.path / "slicks.geojson").string());
  EXPECT_EQ(c.build().calm_areas.size(), 2u);
}

TEST(SceneFeatures, BadGeometryIsRefusedNamingTheFeature) {
  const TempDir dir;
  const auto geojson_error = [&](const std::string& geometry,
                                 const std::string& properties = R"({"name": "bad one"})") {
    dir.write("f.geojson", R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {"name": "fine", "times": [0, 10]},
       "geometry": {"type": "LineString", "coordinates": [[0, 0], [0.001, 0]]}},
      {"type": "Feature", "properties": )" +
                               properties + R"(, "geometry": )" + geometry + "}]}");
    const std::string scene = dir.write("s.json", R"({"wakes": [{"geojson": "f.geojson"}]})");
    std::string msg;
    try {
      SceneBuilder b;
      b.load_file(scene);
    } catch (const SceneError& e) {
      msg = e.what();
    }
    EXPECT_FALSE(msg.empty()) << geometry;
    return msg;
  };
  const std::string file = (dir.path / "f.geojson").string();
  // Non-increasing times (feature 1 is the bad one; feature 0 is fine).
  std::string m =
      geojson_error(R"({"type": "LineString", "coordinates": [[0, 0], [0.001, 0], [0.002, 0]]})",
                    R"({"name": "bad one", "times": [0, 10, 10]})");
  EXPECT_HAS(
      m, file + ": features[1] (\"bad one\").geometry.coordinates[2]: expected a time later than");
  EXPECT_HAS(m, "got 10 s");
  // Too few points.
  m = geojson_error(R"({"type": "LineString", "coordinates": [[0, 0]]})",
                    R"({"name": "bad one", "times": [0]})");
  EXPECT_HAS(
      m, "features[1] (\"bad one\").geometry.coordinates: expected a track of at least 2 points");
  // Times missing or of the wrong count.
  m = geojson_error(R"({"type": "LineString", "coordinates": [[0, 0], [0.001, 0]]})",
                    R"({"id": "x"})");
  EXPECT_HAS(m, "features[1] (\"x\").properties.times: expected an array of times");
  // Latitude out of range ([lon, lat] order).
  m = geojson_error(R"({"type": "LineString", "coordinates": [[0, 0], [0.001, 91]]})",
                    R"({"name": "bad one", "times": [0, 10]})");
  EXPECT_HAS(m,
             "features[1] (\"bad one\").geometry.coordinates[1]: expected a position [lon, lat] "
             "with lon in");
  // A ship faster than 100 m/s.
  m = geojson_error(R"({"type": "LineString", "coordinates": [[0, 0], [1, 0]]})",
                    R"({"name": "bad one", "times": [0, 10]})");
  EXPECT_HAS(m, "coordinates[1]: expected a ship speed from point 0 of at most 100 m/s");
  // A polygon among wakes.
  m = geojson_error(R"({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]})");
  EXPECT_HAS(
      m, "features[1] (\"bad one\").geometry.type: expected \"LineString\" (a track) or \"Point\"");
  // The file is read as strictly as a scene: a syntax error at its line and column, and a
  // property given twice (JSON would keep the last silently).
  m = geojson_error(R"({"type": "LineString", "coordinates": [[0, 0], [0.001, 0]],})");
  EXPECT_HAS(m, file + ":4:133:");
  EXPECT_HAS(m, ": expected valid JSON, got ");
  m = geojson_error(R"({"type": "LineString", "coordinates": [[0, 0], [0.001, 0]]})",
                    R"({"name": "bad one", "times": [0, 10], "times": [0, 20]})");
  EXPECT_HAS(m, file + ": features[1].properties.times: expected each key once");

  // Calm areas.
  const auto area_error = [&](const std::string& coordinates) {
    dir.write("a.geojson", R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {"name": "ok"}, "geometry": {"type": "Polygon",
       "coordinates": [[[0, 0], [0.1, 0], [0.1, 0.1], [0, 0]]]}},
      {"type": "Feature", "properties": {"name": "slick B"}, "geometry": {"type": "Polygon",
       "coordinates": )" + coordinates +
                               "}}]}");
    const std::string scene = dir.write("s2.json", R"({"calm_areas": [{"geojson": "a.geojson"}]})");
    std::string msg;
    try {
      SceneBuilder b;
      b.load_file(scene);
    } catch (const SceneError& e) {
      msg = e.what();
    }
    EXPECT_FALSE(msg.empty()) << coordinates;
    return msg;
  };
  const std::string afile = (dir.path / "a.geojson").string();
  m = area_error("[[[0, 0], [1, 0], [1, 1], [0, 1]]]");
  EXPECT_HAS(m,
             afile + ": features[1] (\"slick B\").geometry.coordinates[0]: expected a closed ring");
  m = area_error("[[[0, 0], [1, 0], [0, 0]]]");
  EXPECT_HAS(m, "coordinates[0]: expected a linear ring of at least 4 positions");
  m = area_error("[[[0, 0], [1, 0], [1, 0], [0, 0]]]");
  EXPECT_HAS(m, "expected a ring of at least 3 distinct vertices");
  m = area_error("[[[0, 0], [1, 1], [1, 0], [0, 1], [0, 0]]]");  // a bow tie
  EXPECT_HAS(
      m, "coordinates[0]: expected a ring that does not cross itself, got edge 0 crossing edge 2");
  m = area_error(
      "[[[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], [[0.2, 0.2], [0.4, 0.2], [0.3, \"x\"], [0.2, "
      "0.2]]]");
  EXPECT_HAS(m, "coordinates[1][2]: expected a position of numbers");
  m = area_error("[[[-40, -40], [0, 60], [40, -40], [-40, -40]]]");
  EXPECT_HAS(m, "expected a polygon within 4500 km of its centre");
  m = area_error("[]");
  EXPECT_HAS(m, "expected an array of linear rings");
}

TEST(SceneFeatures, BadInlineEntries) {
  EXPECT_EQ(error_of_text(R"({"wakes": {"lat": 1}})"),
            "s.json: wakes: expected an array of wakes (or a GeoJSON file's path), got an object");
  EXPECT_EQ(error_of_text(R"({"wakes": [{"name": "tug", "track": [{"lat": 0, "lon": 0, "time": 5},
                                                                  {"lat": 0, "lon": 0.001, "time": 4}]}]})"),
            "s.json: wakes[0].track[1]: expected a time later than point 0's (5 s): times must "
            "increase strictly, got 4 s");
  EXPECT_EQ(error_of_text(R"({"wakes": [{"track": [{"lat": 0, "lon": 0, "time": 0}]}]})"),
            "s.json: wakes[0].track: expected a track of at least 2 points, got a track of 1");
  EXPECT_EQ(error_of_text(R"({"wakes": [{"lat": 95, "lon": 0, "heading": 0, "speed": 3}]})"),
            "s.json: wakes[0].lat: expected a number in [-90, 90] (degrees), got 95");
  EXPECT_EQ(error_of_text(R"({"wakes": [{"lat": "NaN", "lon": 0, "heading": 0, "speed": 3}]})"),
            "s.json: wakes[0].lat: expected a number in [-90, 90] (degrees), got \"NaN\"");
  EXPECT_EQ(error_of_text(R"({"wakes": [{"lat": 1, "lon": 0, "speed": 3}]})"),
            "s.json: wakes[0].heading: expected a number (a ship given by position needs lat, "
            "lon, heading and speed), got nothing");
  EXPECT_HAS(
      error_of_text(R"({"wakes": [{"lat": 1, "lon": 0, "heading": 0, "speed": 3, "sped": 1}]})"),
      "s.json: wakes[0].sped: expected a known key of a wake (name, track, lat, lon");
  EXPECT_HAS(error_of_text(R"({"wakes": [{"track": [], "lat": 1}]})"),
             "s.json: wakes[0]: expected either a track or a position");
  EXPECT_EQ(error_of_text(
                R"({"calm_areas": [{"polygon": [{"lat": 0, "lon": 0}, {"lat": 0, "lon": 1}]}]})"),
            "s.json: calm_areas[0].polygon: expected a ring of at least 3 distinct vertices, got a "
            "ring of 2");
  EXPECT_EQ(
      error_of_text(R"({"calm_areas": [{"polygon": [{"lat": 0, "lon": 0}, {"lat": 1, "lon": 1},
                                                          {"lat": 0, "lon": 1}, {"lat": 1, "lon": 0}]}]})"),
      "s.json: calm_areas[0].polygon: expected a ring that does not cross itself, got edge "
      "0 crossing edge 2");
  EXPECT_EQ(
      error_of_text(R"({"calm_areas": [{"polygon": [{"lat": 0, "lon": 0}, {"lat": 0, "lon": 1},
                                                          {"lat": 1, "lon": 1}], "scale": 2}]})"),
      "s.json: calm_areas[0].scale: expected a number in [0, 1], got 2");
  EXPECT_EQ(error_of_text(R"({"calm_areas": [{"geojson": "nowhere.geojson"}]})", "dir/s.json"),
            "dir/s.json: calm_areas[0].geojson: expected a GeoJSON file, got no such file "
            "\"dir/nowhere.geojson\"");
  EXPECT_EQ(
      error_of_text(R"({"calm_area": []})"),
      "s.json: calm_area: expected a known key (did you mean calm_areas?), got an unknown key");
  // Inside a flight's scene the key path has the prefix.
  try {
    SceneBuilder b;
    b.load_text(R"({"wakes": [{"lat": 95, "lon": 0, "heading": 0, "speed": 3}]})", "f.json",
                "scene.");
    ADD_FAILURE();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "f.json: scene.wakes[0].lat: expected a number in [-90, 90] (degrees), got 95");
  }
}

// The antimeridian and the poles are valid places: a ring across 180 and one around a pole pass
// the self-crossing check.
TEST(SceneFeatures, AntimeridianAndPolarRingsAreAccepted) {
  SceneBuilder b;
  b.load_text(R"({"calm_areas": [
    {"polygon": [{"lat": -0.5, "lon": 179.5}, {"lat": -0.5, "lon": -179.5},
                 {"lat": 0.5, "lon": -179.5}, {"lat": 0.5, "lon": 179.5}]},
    {"polygon": [{"lat": 89, "lon": -180}, {"lat": 89, "lon": -60}, {"lat": 89, "lon": 60}]}]})",
              "s.json");
  EXPECT_EQ(b.build().calm_areas.size(), 2u);
}

// docs/scene.md has a row for every field, with the defaults of WakeSettings / CalmAreaSettings.
TEST(SceneFeatures, DocumentedInDocsSceneMd) {
  std::ifstream in(std::string(THALASSA_SOURCE_DIR) + "/docs/scene.md");
  ASSERT_TRUE(in);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto row = [&](const std::string& field) {
    for (const auto& line : lines)
      if (line.rfind("| `" + field + "` |", 0) == 0) return line;
    ADD_FAILURE() << "docs/scene.md has no row for " << field;
    return std::string();
  };
  const auto number = [](double x) {
    std::ostringstream s;
    s << x;
    return "`" + s.str() + "`";
  };
  for (const char* f : {"name", "track", "lat", "lon", "heading", "speed", "time", "geojson"})
    row(std::string("wakes[].") + f);
  EXPECT_HAS(row("wakes[].amplitude"), number(WakeSettings{}.amplitude));
  EXPECT_HAS(row("wakes[].draft"), number(WakeSettings{}.draft));
  EXPECT_HAS(row("wakes[].length"), number(WakeSettings{}.length));
  for (const char* f : {"name", "polygon", "holes", "geojson"})
    row(std::string("calm_areas[].") + f);
  EXPECT_HAS(row("calm_areas[].scale"), number(CalmAreaSettings{}.scale));
  EXPECT_HAS(row("calm_areas[].fade"), number(CalmAreaSettings{}.fade));
}

}  // namespace
}  // namespace thalassa
