// The command line as users and scripts see it (DESIGN section 5): exit statuses 0, 1, 2, one
// clear message on stderr for bad input with nothing written, the default outputs, --set, and
// the statistics JSON.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

#include "thalassa/engine/image.hpp"
#include "thalassa/planet/sea_state.hpp"

namespace {

namespace fs = std::filesystem;

struct Result {
  int status = -1;
  std::string err;
};

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("thalassa_cli_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs the program in dir_ with `args` (shell words), capturing stderr.
  Result run(const std::string& args, const std::string& prefix = "") {
    const std::string command = "cd '" + dir_.string() + "' && " + prefix + "'" THALASSA_EXE "' " +
                                args + " 2> stderr.txt > stdout.txt";
    const int raw = std::system(command.c_str());
    Result result;
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    std::ifstream in(dir_ / "stderr.txt");
    std::stringstream text;
    text << in.rdbuf();
    result.err = text.str();
    fs::remove(dir_ / "stderr.txt");
    fs::remove(dir_ / "stdout.txt");
    return result;
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  // The JSON file at `name` in dir_ (a report's results.json, a --stats file).
  nlohmann::json read_json(const std::string& name) const {
    std::ifstream in(dir_ / name);
    return nlohmann::json::parse(in);
  }
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

const std::string kSmall = "--set image.width=32 --set image.height=24";

TEST_F(Cli, DefaultRenderWritesExrAndPng) {
  const Result r = run("render " + kSmall);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"thalassa.exr", "thalassa.png"}));
  thalassa::Metadata metadata;
  const thalassa::Image image = thalassa::read_image((dir_ / "thalassa.exr").string(), &metadata);
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(image.height, 24);
  std::map<std::string, std::string> meta(metadata.begin(), metadata.end());
  ASSERT_TRUE(meta.count("thalassa:scene"));
  EXPECT_EQ(nlohmann::json::parse(meta["thalassa:scene"])["image"]["width"], 32);
  EXPECT_TRUE(meta.count("thalassa:camera"));
  EXPECT_EQ(meta["thalassa:sun"], "zenith=60 azimuth=180");
  EXPECT_TRUE(meta.count("thalassa:frame_ms"));
  for (float v : image.rgba) ASSERT_TRUE(std::isfinite(v));
}

TEST_F(Cli, StatsJsonHasTheContractKeys) {
  const Result r = run("render " + kSmall + " -o out.exr --no-png --stats stats.json --repeat 3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"out.exr", "stats.json"}));
  std::ifstream in(dir_ / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  for (const char* key : {"backend", "renderer", "width", "height", "mode", "frame_ms", "passes",
                          "resolved_waves", "built"})
    EXPECT_TRUE(stats.contains(key)) << key;
  // What the frame times are to be read with: the driver's version and how the context was made.
  EXPECT_NE(stats["gl_version"].get<std::string>().find("4."), std::string::npos);
  EXPECT_FALSE(stats["context"].get<std::string>().empty());
  EXPECT_EQ(stats["width"], 32);
  EXPECT_EQ(stats["mode"], "surface");
  EXPECT_EQ(stats["frames"], 3);
  EXPECT_GT(stats["frame_ms"].get<double>(), 0.0);
  // Every frame's timestamps usable (on llvmpipe the wall clock is used, and none is counted).
  EXPECT_EQ(stats["timing_fallback_frames"], 0);
  EXPECT_TRUE(stats["passes"].contains("sky"));
  // The ocean's two passes, timed apart as in the paper's sec. 7.3.
  EXPECT_TRUE(stats["passes"].contains("ocean.geometry"));
  EXPECT_TRUE(stats["passes"].contains("ocean.lighting"));
  // What was built follows from the scene: the default looks at sky and sea under a risen sun.
  const auto built = stats["built"].get<std::vector<std::string>>();
  auto has = [&](const std::string& item) {
    return std::find(built.begin(), built.end(), item) != built.end();
  };
  EXPECT_TRUE(has("sky.background"));
  // A ground view builds one sky map for the sea, not the array of the view from space.
  EXPECT_TRUE(has("atmosphere.sky_map"));
  EXPECT_FALSE(has("atmosphere.sky_map_array"));
  EXPECT_TRUE(has("ocean.ross_brdf"));
  EXPECT_TRUE(has("ocean.sun_glint"));
  EXPECT_TRUE(has("ocean.waves.60"));
  // The paper's default: 60 waves from 2 cm to 30 m; a 32x24 image resolves some of them.
  EXPECT_GT(stats["resolved_waves"].get<int>(), 0);
  EXPECT_LE(stats["resolved_waves"].get<int>(), 60);
  // The sky: which provider, and its one-off costs (tables loaded or computed, the sky map the
  // ocean reflects).
  EXPECT_EQ(stats["sky_provider"], "atmosphere");
  ASSERT_TRUE(stats["setup_ms"].is_object());
  EXPECT_TRUE(stats["setup_ms"].contains("sky.provider"));
  EXPECT_TRUE(stats["setup_ms"].contains("atmosphere.load") ||
              stats["setup_ms"].contains("atmosphere.precompute"));
  EXPECT_GT(stats["setup_ms"]["sky.map"].get<double>(), 0.0);
}

TEST_F(Cli, OnlyWhatTheSceneNeedsIsBuilt) {
  // Looking up: no sea. Sun set: no glint and no sun disc.
  ASSERT_EQ(run("render " + kSmall + " --set camera.pitch=60 --no-png --stats s.json").status, 0);
  std::ifstream in(dir_ / "s.json");
  const auto built = nlohmann::json::parse(in)["built"].get<std::vector<std::string>>();
  for (const auto& item : built) {
    EXPECT_EQ(item.find("ocean"), std::string::npos) << item;
    // No sea, so no sky map to reflect.
    EXPECT_EQ(item.find("sky_map"), std::string::npos) << item;
  }
  ASSERT_EQ(run("render " + kSmall + " --set sun.zenith=100 --no-png --stats t.json").status, 0);
  std::ifstream in2(dir_ / "t.json");
  const auto built2 = nlohmann::json::parse(in2)["built"].get<std::vector<std::string>>();
  for (const auto& item : built2) {
    EXPECT_EQ(item.find("sun_glint"), std::string::npos) << item;
    EXPECT_EQ(item.find("sun_disc"), std::string::npos) << item;
  }
  // A camera exactly at the surface is above it: it sees the sky and the sea.
  ASSERT_EQ(run("render " + kSmall + " --set camera.height=0 --no-png --stats z.json").status, 0);
  std::ifstream in_z(dir_ / "z.json");
  const auto built_z = nlohmann::json::parse(in_z)["built"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(built_z.begin(), built_z.end(), "sky.background"), built_z.end());
  EXPECT_NE(std::find(built_z.begin(), built_z.end(), "ocean.ross_brdf"), built_z.end());
  EXPECT_EQ(run("render " + kSmall + " --set camera.height=25000 --no-png --stats u.json").status,
            0);
  std::ifstream in3(dir_ / "u.json");
  EXPECT_EQ(nlohmann::json::parse(in3)["mode"], "space");
}

// The light terms add up: sun + sky + sea rendered apart sum to the frame rendered with all
// three (the sky behind the sea is the same in every render, so it is counted once).
TEST_F(Cli, LightTermsAddUp) {
  for (const char* terms : {"sun,sky,sea,air", "sun", "sky", "sea", "air"})
    ASSERT_EQ(run("render " + kSmall + " --float --no-png --terms " + std::string(terms) + " -o " +
                  std::string(terms) + ".exr")
                  .status,
              0)
        << terms;
  const auto all = thalassa::read_image((dir_ / "sun,sky,sea,air.exr").string());
  const auto sun = thalassa::read_image((dir_ / "sun.exr").string());
  const auto sky = thalassa::read_image((dir_ / "sky.exr").string());
  const auto sea = thalassa::read_image((dir_ / "sea.exr").string());
  const auto air = thalassa::read_image((dir_ / "air.exr").string());
  int sea_pixels = 0;
  for (std::size_t i = 0; i < all.rgba.size(); i += 4) {
    // Sky pixels are identical in all four renders; sea pixels hold the terms.
    if (sun.rgba[i] == sky.rgba[i] && sky.rgba[i] == sea.rgba[i] && sea.rgba[i] == air.rgba[i])
      continue;
    ++sea_pixels;
    for (int c = 0; c < 3; ++c) {
      const double sum =
          double(sun.rgba[i + c]) + sky.rgba[i + c] + sea.rgba[i + c] + air.rgba[i + c];
      EXPECT_NEAR(all.rgba[i + c], sum, 1e-5 * sum + 1e-7) << "pixel " << i / 4;
    }
  }
  EXPECT_GT(sea_pixels, 100);
}

// Every method renders, says which it was in the statistics and the EXR, and the reference says
// how many samples it averaged.
TEST_F(Cli, MethodsRenderAndSayWhichTheyAre) {
  for (const char* method : {"full", "basic", "normals", "reference"}) {
    const std::string name(method);
    // (--sun-cells 32: the reference's sun at the default 256^2 cells per pixel costs two
    // minutes here for nothing this test looks at.)
    ASSERT_EQ(run("render " + kSmall + " --no-png --method " + name +
                  " --samples 4 --sun-cells 32 -o " + name + ".exr --stats " + name + ".json")
                  .status,
              0)
        << method;
    std::ifstream in(dir_ / (name + ".json"));
    const auto stats = nlohmann::json::parse(in);
    EXPECT_EQ(stats["method"], name);
    EXPECT_EQ(stats["samples"], name == "reference" ? 4 : 1);
    const auto built = stats["built"].get<std::vector<std::string>>();
    EXPECT_EQ(std::find(built.begin(), built.end(), "ocean.method." + name) != built.end(),
              name != "full")
        << method;
  }
  const auto full = thalassa::read_image((dir_ / "full.exr").string());
  const auto reference = thalassa::read_image((dir_ / "reference.exr").string());
  EXPECT_NE(full.rgba, reference.rgba);
  // The reference's sun is scattered from a lattice by default and reports the lattice's
  // measures; gathered, it reports none.
  std::ifstream scattered_in(dir_ / "reference.json");
  const auto scattered = nlohmann::json::parse(scattered_in);
  EXPECT_EQ(scattered["reference_sun"], "scattered");
  EXPECT_GT(scattered["sun_lattice_ms"].get<double>(), 0.0);
  EXPECT_TRUE(scattered.contains("sun_lattice_row_change"));
  EXPECT_TRUE(scattered.contains("sun_lattice_rows"));
  // Per image row: the change where the lattice counted the row, null where it did not; as
  // many counted as sun_lattice_rows, the largest sun_lattice_row_change.
  ASSERT_TRUE(scattered.contains("sun_lattice_row_changes"));
  const auto& per_row = scattered["sun_lattice_row_changes"];
  EXPECT_EQ(per_row.size(), scattered["height"].get<std::size_t>());
  int counted = 0;
  double largest = 0.0;
  for (const auto& change : per_row)
    if (!change.is_null()) {
      ++counted;
      largest = std::max(largest, change.get<double>());
    }
  EXPECT_EQ(counted, scattered["sun_lattice_rows"].get<int>());
  EXPECT_DOUBLE_EQ(largest, scattered["sun_lattice_row_change"].get<double>());
  EXPECT_EQ(scattered["sun_lattice_refine"], 4);  // the default refinement, within the budget
  EXPECT_GE(scattered["sun_lattice_segment"].get<int>(), 1);  // cells per scatter invocation
  EXPECT_GE(scattered["sun_lattice_block_rows"].get<int>(), 1);  // and rows
  // The refined cells' queue (the default, the most), the lattice's cells, those refined and
  // those of them refined in place (none: the queue held them).
  EXPECT_EQ(scattered["sun_lattice_refined_queue"].get<double>(),
            65535.0 * 64.0);  // ocean::kReferenceMaxSunRefinedQueue
  EXPECT_GT(scattered["sun_lattice_scattered_cells"].get<double>(), 0.0);
  EXPECT_GE(scattered["sun_lattice_refined_cells"].get<double>(), 0.0);
  EXPECT_LE(scattered["sun_lattice_refined_cells"].get<double>(),
            scattered["sun_lattice_scattered_cells"].get<double>());
  EXPECT_EQ(scattered["sun_lattice_refined_in_place"].get<double>(), 0.0);
  // The lattice as drawn: undoubled by default.
  EXPECT_EQ(scattered["sun_lattice_cells_per_wavelength"], 16.0);
  EXPECT_EQ(scattered["sun_lattice_cells"], 32);
  EXPECT_EQ(scattered["sun_lattice_doublings"], 0);
  ASSERT_EQ(run("render " + kSmall +
                " --no-png --method reference --samples 4 --reference-sun gathered --sun-cells 8 "
                "-o gathered.exr --stats gathered.json")
                .status,
            0);
  std::ifstream gathered_in(dir_ / "gathered.json");
  const auto gathered = nlohmann::json::parse(gathered_in);
  EXPECT_EQ(gathered["reference_sun"], "gathered");
  EXPECT_FALSE(gathered.contains("sun_lattice_ms"));
  std::ifstream full_in(dir_ / "full.json");
  EXPECT_FALSE(nlohmann::json::parse(full_in).contains("reference_sun"));
  const Result wrong = run("render " + kSmall + " --method reference --reference-sun both");
  EXPECT_EQ(wrong.status, 2);
  EXPECT_NE(wrong.err.find("--reference-sun"), std::string::npos) << wrong.err;
  // A lattice may only double up from where it starts.
  const Result down = run("render " + kSmall +
                          " --method reference --sun-cells-per-wavelength 16 "
                          "--sun-max-cells-per-wavelength 8 -o down.exr");
  EXPECT_EQ(down.status, 2);
  EXPECT_NE(down.err.find("--sun-max-cells-per-wavelength: expected 0 or at least "
                          "--sun-cells-per-wavelength (16), got 8"),
            std::string::npos)
      << down.err;
  EXPECT_FALSE(fs::exists(dir_ / "down.exr"));
  // The limits of ocean/method.hpp: past them, refused before anything renders.
  for (const std::string& past : std::vector<std::string>{
           "--sun-cells-per-wavelength 129", "--sun-max-cells-per-wavelength 129",
           "--sun-cells 16385", "--sun-segment 16385", "--sun-segment -1", "--sun-block-rows 9",
           "--sun-refined-queue -2", "--sun-refined-queue 4194241", "--reference-grid-cell 0.1",
           "--reference-grid-cell 2"}) {
    const Result refused = run("render " + kSmall + " --method reference " + past + " -o past.exr");
    EXPECT_EQ(refused.status, 2) << past;
    EXPECT_NE(refused.err.find(past.substr(0, past.find(' '))), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir_ / "past.exr")) << past;
  }
}

// --fixed-samples draws exactly --samples (as validate draws a flicker frame after the first);
// --sun-sums writes the scattered sun's per-pixel sums as a float EXR of the image's size, whose
// solid angles cover the sea; the statistics count the samples that were not finite (none).
// Both are refused where they mean nothing, before anything renders.
TEST_F(Cli, ReferenceFixedSamplesAndSunSums) {
  ASSERT_EQ(run("render " + kSmall +
                " --no-png --method reference --samples 64 --fixed-samples --sun-cells 32 "
                "-o fixed.exr --sun-sums sums.exr --stats fixed.json")
                .status,
            0);
  std::ifstream in(dir_ / "fixed.json");
  const auto stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["samples"], 64);
  EXPECT_EQ(stats["reference_nonfinite_samples"], 0);
  EXPECT_EQ(stats["reference_nonfinite_pixels"], 0);
  EXPECT_FALSE(stats.contains("reference_first_nonfinite"));
  thalassa::Metadata metadata;
  const auto sums = thalassa::read_image((dir_ / "sums.exr").string(), &metadata);
  EXPECT_EQ(sums.width, 32);
  EXPECT_EQ(sums.height, 24);
  int sea = 0;
  for (std::size_t i = 0; i < sums.rgba.size(); i += 4) {
    for (int c = 0; c < 4; ++c) EXPECT_GE(sums.rgba[i + c], 0.0f);
    if (sums.rgba[i + 1] > 0.0f) {
      ++sea;
      EXPECT_TRUE(std::isfinite(sums.rgba[i] / sums.rgba[i + 1]));
    }
  }
  EXPECT_GT(sea, 32 * 24 / 4);  // the default view's sea: the lower half and more
  EXPECT_TRUE(std::any_of(metadata.begin(), metadata.end(),
                          [](const auto& m) { return m.first == "thalassa:channels"; }));
  for (const std::string& pointless :
       {std::string("--method full"), std::string("--method reference --terms sky"),
        std::string("--method reference --reference-sun gathered")}) {
    const Result refused =
        run("render " + kSmall + " " + pointless + " --sun-sums pointless.exr -o p.exr");
    EXPECT_EQ(refused.status, 2) << pointless;
    EXPECT_NE(refused.err.find("--sun-sums"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir_ / "pointless.exr")) << pointless;
    EXPECT_FALSE(fs::exists(dir_ / "p.exr")) << pointless;
  }
}

TEST_F(Cli, SceneFileAndSetOverride) {
  write("scene.json", R"({"image": {"width": 20, "height": 10}, "camera": {"pitch": 10}})");
  ASSERT_EQ(run("render scene.json --set image.height=12 -o a.exr --png b.png").status, 0);
  const thalassa::Image image = thalassa::read_image((dir_ / "b.png").string());
  EXPECT_EQ(image.width, 20);
  EXPECT_EQ(image.height, 12);
}

// Invalid input: status 2, one line naming the source, the key and the expectation; no file.
void expect_invalid(const Result& r, const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const auto& fragment : fragments)
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << r.err;
}

TEST_F(Cli, InvalidSceneFilesExitWith2AndWriteNothing) {
  write("malformed.json", "{\"camera\": {\"height\": 4,}}");
  expect_invalid(run("render malformed.json"), {"malformed.json", "JSON"});
  write("unknown.json", R"({"camera": {"hieght": 4}})");
  expect_invalid(run("render unknown.json"), {"unknown.json", "camera.hieght", "camera.height"});
  write("type.json", R"({"camera": {"height": "high"}})");
  expect_invalid(run("render type.json"), {"type.json", "camera.height", "number"});
  write("range.json", R"({"camera": {"lat": 91}})");
  expect_invalid(run("render range.json"), {"range.json", "camera.lat", "[-90, 90]"});
  write("enum.json", R"({"planet": {"shape": "cube"}})");
  expect_invalid(run("render enum.json"), {"enum.json", "planet.shape", "wgs84"});
  expect_invalid(run("render missing.json"), {"missing.json"});
  std::vector<std::string> left = files();
  std::vector<std::string> inputs = {"enum.json", "malformed.json", "range.json", "type.json",
                                     "unknown.json"};
  EXPECT_EQ(left, inputs);  // no output, no temporary
}

TEST_F(Cli, InvalidOverridesAndOptionsExitWith2) {
  expect_invalid(run("render --set camera.height=abc"), {"--set", "camera.height"});
  expect_invalid(run("render --set image.width=0"), {"--set", "image.width"});
  expect_invalid(run("render --set nothing.here=1"), {"--set", "nothing.here"});
  expect_invalid(run("render -o out.png"), {"-o", ".exr"});
  expect_invalid(run("render -o nowhere/out.exr"), {"nowhere"});
  expect_invalid(run("render -o a.exr --stats a.exr"), {"--stats", "same file"});
  fs::create_directory(dir_ / "folder.png");
  expect_invalid(run("render -o a.exr --png folder.png"), {"--png", "folder"});
  fs::remove(dir_ / "folder.png");
  expect_invalid(run("render --set sky.exr=noon.exr"), {"--set: sky.exr", "noon.exr"});
  expect_invalid(run("render --terms sun,moon"), {"--terms", "moon"});
  expect_invalid(run("render --terms ,"), {"--terms"});
  expect_invalid(run("render --method reference --set camera.height=30000"),
                 {"--method reference", "below 20000 m", "camera.height"});
  EXPECT_EQ(run("render --backend vulkan").status, 2);
  EXPECT_EQ(run("render --method photon-mapping").status, 2);
  EXPECT_EQ(run("frobnicate").status, 2);
  EXPECT_EQ(files(), std::vector<std::string>{});
}

// ---- thalassa validate ----

// A small suite: two methods on one case that renders and one that must be refused. The report
// holds every file docs/validation.md lists, and the reference's own metrics are exact.
TEST_F(Cli, ValidateWritesTheReport) {
  write("suite.json", R"({
    "suite": "tiny",
    "base": {"image.width": 24, "image.height": 16, "camera.height": 100, "camera.pitch": -20},
    "methods": ["reference", "full"],
    "terms": ["sun", "sky", "all"],
    "flicker": {"frames": 2, "dt": 0.04, "terms": ["all"]},
    "reference": {"pixel_samples": 4, "pixel_samples_without_sun": 8, "sun_normal_samples": 1024},
    "cases": [
      {"name": "near", "set": {"ocean.wind_speed": 8}},
      {"name": "bad_lat", "set": {"camera.lat": 95}, "expect": 2, "error": "camera.lat"}
    ]
  })");
  // --reference-samples replaces the suite's reference.pixel_samples (4); the sky alone keeps
  // reference.pixel_samples_without_sun (8).
  // --reference-sun-max-cells-per-wavelength replaces the suite's most cells (here the start,
  // 16: no doubling, and nothing to pay for it); --reference-sun-cells the suite's
  // sun_normal_samples (1024) with its square.
  const Result r =
      run("validate suite.json -o report --reference-samples 2 "
          "--reference-sun-max-cells-per-wavelength 16 --reference-sun-cells 16");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* file : {"index.html", "results.json", "metrics.csv", "rows.csv", "horizon.csv",
                           "cases.csv", "images/near_reference_sun.exr", "images/near_full_all.png",
                           "plots/near_sun_rows.png", "plots/near_error_time.png"})
    EXPECT_TRUE(fs::is_regular_file(dir_ / "report" / file)) << file;
  std::ifstream in(dir_ / "report" / "results.json");
  const auto results = nlohmann::json::parse(in);
  EXPECT_EQ(results["cases"].size(), 2u);
  EXPECT_EQ(results["cases"][1]["exit_status"], 2);
  EXPECT_EQ(results["reference"]["pixel_samples"], 2);
  EXPECT_EQ(results["reference"]["sun_max_cells_per_wavelength"], 16.0);
  EXPECT_EQ(results["reference"]["sun_normal_samples"], 256);
  EXPECT_EQ(results["cases"][0]["methods"][0]["lattice_cells_per_wavelength"]["sun"], 16.0);
  const auto& reference_terms = results["cases"][0]["methods"][0]["terms"];
  EXPECT_EQ(reference_terms[0]["samples"], 2);                             // sun
  EXPECT_EQ(reference_terms[1]["samples"], 8);                             // sky
  EXPECT_EQ(reference_terms[2]["samples"], 2);                             // all
  EXPECT_EQ(results["cases"][0]["methods"][1]["terms"][0]["samples"], 1);  // full's
  // What each term and the case cost, wall-clock: every term some time, together no more than
  // the case (which also times full apart); none for the refused case.
  double terms_seconds = 0.0;
  for (const auto& m : results["cases"][0]["methods"])
    for (const auto& t : m["terms"]) {
      ASSERT_TRUE(t.contains("seconds")) << m["name"] << " " << t["term"];
      EXPECT_GT(t["seconds"].get<double>(), 0.0);
      terms_seconds += t["seconds"].get<double>();
    }
  EXPECT_LE(terms_seconds, results["cases"][0]["seconds"].get<double>());
  EXPECT_FALSE(results["cases"][1].contains("seconds"));
  // Above the sky's own cap, --reference-samples raises it too (the sky alone: cheap).
  write("sky.json", R"({"suite": "sky", "base": {"image.width": 24, "image.height": 16},
    "methods": ["reference"], "terms": ["sky"], "flicker": {"frames": 1, "terms": ["sky"]},
    "reference": {"pixel_samples": 4, "pixel_samples_without_sun": 8},
    "cases": [{"name": "near", "set": {}}]})");
  ASSERT_EQ(run("validate sky.json -o report16 --reference-samples 16").status, 0);
  std::ifstream in16(dir_ / "report16" / "results.json");
  const auto results16 = nlohmann::json::parse(in16);
  EXPECT_EQ(results16["reference"]["pixel_samples_without_sun"], 16);
  EXPECT_EQ(results16["cases"][0]["methods"][0]["terms"][0]["samples"], 16);
  // With check_convergence and a doubling (16 to 32) the reference reports each row's change as
  // its uncertainty; a row the test did not count (the top rows see only sky) takes the largest.
  write("sky32.json", R"({"suite": "sky", "base": {"image.width": 24, "image.height": 16},
    "methods": ["reference"], "terms": ["sky"], "flicker": {"frames": 1, "terms": ["sky"]},
    "reference": {"pixel_samples": 32, "check_convergence": true},
    "cases": [{"name": "near", "set": {}}]})");
  ASSERT_EQ(run("validate sky32.json -o report32").status, 0);
  std::ifstream in32(dir_ / "report32" / "results.json");
  const auto results32 = nlohmann::json::parse(in32);
  const auto& reference32 = results32["cases"][0]["methods"][0];
  ASSERT_TRUE(reference32["row_uncertainty"].contains("sky"));
  const auto& rows32 = reference32["row_uncertainty"]["sky"];
  ASSERT_EQ(rows32.size(), 16u);
  double largest = 0.0, smallest = 1e300;
  for (const auto& u : rows32) {
    ASSERT_FALSE(u.is_null());
    largest = std::max(largest, u.get<double>());
    smallest = std::min(smallest, u.get<double>());
  }
  EXPECT_DOUBLE_EQ(largest, reference32["convergence"]["sky"].get<double>());
  EXPECT_DOUBLE_EQ(rows32[0].get<double>(), largest);  // the top row: sky only
  EXPECT_LT(smallest, largest);                        // the rows of sea: each its own
  // The reference says on how many rows of the sea its sun resolved every wave: 2 cm waves seen
  // from 100 m at 24 x 16 are resolved on none (the sky's rows, resolved, are not the sea's), so
  // no row is compared and the sun's ratio plot says so instead of failing.
  const auto& resolved = results["cases"][0]["methods"][0]["resolved_rows"];
  ASSERT_TRUE(resolved.contains("sun"));
  EXPECT_EQ(resolved["sun"].get<int>(), 0);
}

// A variant that changes the sea (30 waves where the case has 60) is measured against a
// reference of its own sea, rendered with its overrides and reported as a method of the case; the
// other methods keep the case's reference.
TEST_F(Cli, ValidateMeasuresASeaChangingVariantAgainstItsOwnReference) {
  write("own.json", R"({"suite": "own",
    "base": {"image.width": 24, "image.height": 16, "camera.pitch": -20, "ocean.waves": 60},
    "methods": ["reference", "full",
      {"name": "full_waves30", "method": "full", "set": {"ocean.waves": 30},
       "own_reference": true}],
    "terms": ["sky"], "flicker": {"frames": 1, "terms": ["sky"]},
    "reference": {"pixel_samples": 4},
    "cases": [{"name": "near", "set": {}}]})");
  const Result r = run("validate own.json -o report");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "report" / "images/near_reference_full_waves30_sky.exr"));
  std::ifstream in(dir_ / "report" / "results.json");
  const auto results = nlohmann::json::parse(in);
  const auto& methods = results["cases"][0]["methods"];
  ASSERT_EQ(methods.size(), 4u);
  EXPECT_EQ(methods[0]["name"], "reference");
  EXPECT_EQ(methods[1]["name"], "reference_full_waves30");
  EXPECT_EQ(methods[1]["method"], "reference");
  EXPECT_EQ(methods[1]["reference"], "reference_full_waves30");  // against itself
  EXPECT_EQ(methods[2]["name"], "full");
  EXPECT_EQ(methods[2]["reference"], "");
  EXPECT_EQ(methods[3]["name"], "full_waves30");
  EXPECT_EQ(methods[3]["reference"], "reference_full_waves30");
  const auto l1 = [&](int m) {
    return methods[m]["terms"][0]["error"]["relative_l1"]["l"].get<double>();
  };
  EXPECT_EQ(l1(1), 0.0);  // its own reference against itself
  EXPECT_GT(l1(2), 0.0);
  EXPECT_GT(l1(3), 0.0);
  // metrics.csv names the reference each line was measured against.
  std::ifstream csv(dir_ / "report" / "metrics.csv");
  const std::string text{std::istreambuf_iterator<char>(csv), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("near_full_waves30_sky.png,reference_full_waves30"), std::string::npos);
  EXPECT_NE(text.find("near_full_sky.png,reference\n"), std::string::npos);
  EXPECT_NE(text.find("near_reference_full_waves30_sky.png,reference_full_waves30"),
            std::string::npos);
}

// --seas N draws each selected case over N seas (its ocean.seed and the next ones), as cases of
// their own, and the report sums their rows and pools their horizon bands (seas.csv,
// seas_horizon.csv; validation::summarize_seas).
TEST_F(Cli, ValidateDrawsTheSelectedCasesOverTheirSeas) {
  write("seas.json", R"({
    "suite": "seas",
    "base": {"image.width": 16, "image.height": 10, "camera.height": 100, "camera.pitch": -20},
    "methods": ["reference", "basic", "full"],
    "terms": ["sun"],
    "flicker": {"frames": 0, "terms": ["sun"]},
    "reference": {"pixel_samples": 4, "sun_normal_samples": 256},
    "cases": [{"name": "near", "set": {"ocean.seed": 5}}, {"name": "far", "set": {}}]
  })");
  const Result r = run("validate seas.json -o report --seas 2 --case near");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(dir_ / "report" / "results.json");
  const auto results = nlohmann::json::parse(in);
  ASSERT_EQ(results["cases"].size(), 2u);
  EXPECT_EQ(results["suite_cases"], 4);
  for (int k = 0; k < 2; ++k) {
    const auto& c = results["cases"][k];
    EXPECT_EQ(c["name"], "near_sea" + std::to_string(k + 1));
    EXPECT_EQ(c["sea_of"], "near");
    EXPECT_EQ(c["sea"], k + 1);
    EXPECT_EQ(c["set"]["ocean.seed"], 5 + k);
  }
  std::ifstream csv(dir_ / "report" / "seas.csv");
  const std::string text{std::istreambuf_iterator<char>(csv), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("\nnear,basic,sun,2,"), std::string::npos) << text;
  EXPECT_NE(text.find("\nnear,full,sun,2,"), std::string::npos) << text;
  // The horizon band pooled over the two seas, bin by bin from the horizon down.
  std::ifstream bins(dir_ / "report" / "seas_horizon.csv");
  const std::string bins_text{std::istreambuf_iterator<char>(bins),
                              std::istreambuf_iterator<char>()};
  EXPECT_NE(bins_text.find("\nnear,full,sun,2,0,0.5,"), std::string::npos) << bins_text;
}

TEST_F(Cli, ValidateRefusesBadSuitesAndReportsUnexpectedEnds) {
  write("bad.json", R"({"suite": "bad", "cases": [{"name": "x", "set": {"camera.hieght": 4}}]})");
  expect_invalid(run("validate bad.json -o out"), {"bad.json", "camera.hieght"});
  // An option out of its range: CLI11's message (and its "Run with --help" line), status 2.
  // Past ocean/method.hpp's limits too.
  for (const std::string& past : std::vector<std::string>{
           "--reference-samples 0", "--reference-samples 16385",
           "--reference-sun-max-cells-per-wavelength 129", "--reference-sun-cells 0",
           "--reference-sun-cells 16385", "--seas 0", "--seas 65"}) {
    const Result range = run("validate -o out " + past);
    EXPECT_EQ(range.status, 2) << range.err;
    EXPECT_NE(range.err.find(past.substr(0, past.find(' '))), std::string::npos) << range.err;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
  }
  // The sun's lattice may only double up from where the suite starts it (16 per wavelength).
  expect_invalid(run("validate -o out --reference-sun-max-cells-per-wavelength 8"),
                 {"--reference-sun-max-cells-per-wavelength: expected at least the suite's "
                  "reference.sun_cells_per_wavelength (16), got 8"});
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  // A case that expects to be refused but renders: the run ends with status 1.
  write("wrong.json", R"({"suite": "wrong", "base": {"image.width": 16, "image.height": 8},
    "cases": [{"name": "fine", "set": {"camera.lat": 45}, "expect": 2, "error": "lat"}]})");
  const Result r = run("validate wrong.json -o out2");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("case fine"), std::string::npos) << r.err;
}

// --case runs a part of a suite (names or shell patterns), says so in the report, and keeps the
// messages naming each case's place in the file. Refused cases cost no render.
TEST_F(Cli, ValidateRunsOnlyTheChosenCases) {
  write("part.json", R"({"suite": "part", "base": {"image.width": 16, "image.height": 8},
    "cases": [
      {"name": "fine", "set": {}},
      {"name": "bad_lat", "set": {"camera.lat": 91}, "expect": 2, "error": "camera.lat"},
      {"name": "bad_lon", "set": {"camera.lon": 181}, "expect": 2, "error": "camera.lon"}
    ]})");
  expect_invalid(run("validate part.json -o none --case nope"), {"--case", "nope", "bad_lat"});
  EXPECT_FALSE(fs::exists(dir_ / "none"));
  const Result r = run("validate part.json -o out --case 'bad_*'");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto results = read_json("out/results.json");
  EXPECT_EQ(results["suite_cases"], 3);
  ASSERT_EQ(results["cases"].size(), 2u);
  EXPECT_EQ(results["cases"][0]["name"], "bad_lat");
  EXPECT_EQ(results["cases"][1]["name"], "bad_lon");
  const std::string message = results["cases"][1]["message"];
  EXPECT_EQ(message.rfind("part.json: cases[2].set: camera.lon: expected", 0), 0u) << message;
  std::ifstream html(dir_ / "out" / "index.html");
  const std::string page{std::istreambuf_iterator<char>(html), std::istreambuf_iterator<char>()};
  EXPECT_NE(page.find("2 of its 3 cases were run"), std::string::npos);

  // --method and --term narrow the methods and terms (validation::narrow_suite); an unknown one
  // is refused before anything is written.
  write("two.json", R"({"suite": "two", "base": {"image.width": 16, "image.height": 8},
    "methods": ["basic", "full"], "terms": ["sky", "all"], "flicker": {"frames": 0},
    "cases": [{"name": "fine", "set": {}}]})");
  expect_invalid(run("validate two.json -o none --method fulll"), {"--method", "fulll", "basic"});
  expect_invalid(run("validate two.json -o none --term sun"), {"--term", "sun", "sky, all"});
  EXPECT_FALSE(fs::exists(dir_ / "none"));
  const Result narrowed = run("validate two.json -o narrowed --method full --term sky");
  ASSERT_EQ(narrowed.status, 0) << narrowed.err;
  const auto narrowed_results = read_json("narrowed/results.json");
  const auto& methods = narrowed_results["cases"][0]["methods"];
  ASSERT_EQ(methods.size(), 1u);
  EXPECT_EQ(methods[0]["name"], "full");
  ASSERT_EQ(methods[0]["terms"].size(), 1u);
  EXPECT_EQ(methods[0]["terms"][0]["term"], "sky");
}

// A suite of two small cases, a and b (wind 5 and b_wind m/s), of the reference and full's sky
// with one flicker frame: the suite of the tests of --time-limit, --no-exr and --resume.
std::string two_case_suite(const std::string& name, const std::string& b_wind = "8") {
  return R"({"suite": ")" + name + R"(", "base": {"image.width": 16, "image.height": 8,
      "camera.pitch": -20}, "methods": ["reference", "full"], "terms": ["sky"],
      "flicker": {"frames": 1, "terms": ["sky"]}, "reference": {"pixel_samples": 4},
      "cases": [{"name": "a", "set": {"ocean.wind_speed": 5}},
                {"name": "b", "set": {"ocean.wind_speed": )" +
         b_wind + "}}]}";
}

// --time-limit begins no case that the longest case so far says would end past the limit: a
// limit already spent begins none (the report is written, with no case), and --resume goes on
// from there; a limit far off runs them all.
TEST_F(Cli, ValidateTimeLimitBeginsNoCaseItCannotEnd) {
  write("s.json", two_case_suite("limit"));
  const Result none = run("validate s.json -o out --time-limit 1e-6");
  ASSERT_EQ(none.status, 0) << none.err;
  EXPECT_NE(none.err.find("stopped before case a"), std::string::npos) << none.err;
  EXPECT_EQ(read_json("out/results.json")["cases"].size(), 0u);
  const Result all = run("validate s.json -o out --resume --time-limit 1e6");
  ASSERT_EQ(all.status, 0) << all.err;
  EXPECT_EQ(all.err.find("stopped before"), std::string::npos) << all.err;
  EXPECT_EQ(read_json("out/results.json")["cases"].size(), 2u);
  for (const std::string bad : {"0", "-5", "soon"}) {  // CLI11's usage error, status 2
    const Result refused = run("validate s.json -o out --time-limit " + bad);
    EXPECT_EQ(refused.status, 2) << refused.err;
    EXPECT_NE(refused.err.find("--time-limit: expected seconds greater than 0, got " + bad),
              std::string::npos)
        << refused.err;
  }
}

// --no-exr writes the images as PNG alone and the report names no EXR (a report that travels
// small: scripts/device/run); --resume keeps its cases, and a later run with EXRs keeps them
// too while writing EXRs for the cases it renders.
TEST_F(Cli, ValidateWithoutExrWritesPngsAlone) {
  write("s.json", two_case_suite("small"));
  const Result r = run("validate s.json -o out --case a --no-exr");
  ASSERT_EQ(r.status, 0) << r.err;
  int pngs = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "out" / "images")) {
    EXPECT_NE(entry.path().extension(), ".exr") << entry.path();
    pngs += entry.path().extension() == ".png";
  }
  EXPECT_EQ(pngs, 2);  // the reference's and full's sky
  const auto first = read_json("out/results.json");
  for (const auto& method : first["cases"][0]["methods"])
    for (const auto& term : method["terms"]) {
      EXPECT_EQ(term["exr"], "") << method["name"];
      EXPECT_TRUE(fs::exists(dir_ / "out" / term["png"].get<std::string>())) << method["name"];
    }
  std::ifstream html(dir_ / "out" / "index.html");
  const std::string page{std::istreambuf_iterator<char>(html), std::istreambuf_iterator<char>()};
  EXPECT_EQ(page.find(".exr"), std::string::npos);
  const Result resumed = run("validate s.json -o out --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("kept from the earlier run (--resume)"), std::string::npos)
      << resumed.err;
  const auto both = read_json("out/results.json");
  ASSERT_EQ(both["cases"].size(), 2u);
  EXPECT_EQ(both["cases"][0], first["cases"][0]);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "images" / "b_reference_sky.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "images" / "a_reference_sky.exr"));
}

// --resume keeps the cases of the report in the folder that were run with the same inputs and
// renders the rest, so that runs of different --case join into one report and a run cut short
// goes on; a case whose inputs changed is rendered again. A folder holding another suite's
// report, or a file that is no report, is refused before anything is rendered.
TEST_F(Cli, ValidateResumesTheReportInItsFolder) {
  write("s.json", two_case_suite("resume"));
  ASSERT_EQ(run("validate s.json -o out --case a").status, 0);
  const auto read_results = [&] { return read_json("out/results.json"); };
  const auto first = read_results();
  ASSERT_EQ(first["cases"].size(), 1u);
  const std::string fingerprint_a = first["cases"][0]["fingerprint"];
  EXPECT_EQ(fingerprint_a.size(), 16u);
  const auto a_image = dir_ / "out" / "images" / "a_reference_sky.exr";
  const auto a_time = fs::last_write_time(a_image);

  // Case b joins case a, which is kept (not rendered again: its image is untouched).
  const Result joined = run("validate s.json -o out --case b --resume");
  ASSERT_EQ(joined.status, 0) << joined.err;
  const auto both = read_results();
  ASSERT_EQ(both["cases"].size(), 2u);
  EXPECT_EQ(both["cases"][0]["name"], "a");
  EXPECT_EQ(both["cases"][0]["fingerprint"], fingerprint_a);
  EXPECT_EQ(both["cases"][0], first["cases"][0]);
  EXPECT_EQ(both["cases"][1]["name"], "b");
  EXPECT_EQ(fs::last_write_time(a_image), a_time);
  std::ifstream html(dir_ / "out" / "index.html");
  const std::string page{std::istreambuf_iterator<char>(html), std::istreambuf_iterator<char>()};
  EXPECT_EQ(page.find("A part of the suite"), std::string::npos);  // both cases are in it

  // Everything kept: nothing is rendered and the report stays whole.
  const Result again = run("validate s.json -o out --resume");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("kept from the earlier run"), std::string::npos) << again.err;
  EXPECT_EQ(read_results()["cases"], both["cases"]);
  EXPECT_EQ(fs::last_write_time(a_image), a_time);

  // A case that failed at run time (here its report says so) is rendered again, though its
  // inputs are the same: a shader that did not build must not stay in the report.
  {
    auto failed = both;
    failed["cases"][1]["exit_status"] = 1;
    failed["cases"][1]["message"] = "shader compile failed";
    failed["cases"][1]["passed"] = false;
    std::ofstream out(dir_ / "out" / "results.json");
    out << failed.dump();
  }
  const Result rerun = run("validate s.json -o out --resume");
  ASSERT_EQ(rerun.status, 0) << rerun.err;
  const auto mended = read_results();
  EXPECT_EQ(mended["cases"][0], first["cases"][0]);
  EXPECT_EQ(mended["cases"][1]["exit_status"], 0);
  EXPECT_EQ(mended["cases"][1]["passed"], true);
  EXPECT_EQ(fs::last_write_time(a_image), a_time);

  // Case b's sea changed: b is rendered again, a is kept.
  write("s.json", two_case_suite("resume", "12"));
  ASSERT_EQ(run("validate s.json -o out --resume").status, 0);
  const auto changed = read_results();
  EXPECT_EQ(changed["cases"][0], first["cases"][0]);
  EXPECT_NE(changed["cases"][1]["fingerprint"], both["cases"][1]["fingerprint"]);
  EXPECT_EQ(changed["cases"][1]["set"]["ocean.wind_speed"], 12);

  // Case a's EXR images gone (a GPU machine's report comes back without them where it would not
  // fit, scripts/device/run): a is kept from its PNGs and numbers, the report names no EXR of a.
  // Its PNG gone too: a is rendered again.
  {
    const auto a_png = dir_ / "out" / "images" / "a_reference_sky.png";
    const auto png_time = fs::last_write_time(a_png);
    for (const auto& entry : fs::directory_iterator(dir_ / "out" / "images"))
      if (entry.path().filename().string().starts_with("a_") && entry.path().extension() == ".exr")
        fs::remove(entry.path());
    const Result without = run("validate s.json -o out --resume");
    ASSERT_EQ(without.status, 0) << without.err;
    EXPECT_NE(without.err.find("without the 2 EXR images gone"), std::string::npos) << without.err;
    const auto kept = read_results();
    EXPECT_EQ(kept["cases"][0]["fingerprint"], fingerprint_a);
    EXPECT_EQ(fs::last_write_time(a_png), png_time);
    for (const auto& method : kept["cases"][0]["methods"])
      for (const auto& term : method["terms"]) {
        EXPECT_EQ(term["exr"], "") << method["name"];
        EXPECT_NE(term["png"], "") << method["name"];
      }
    EXPECT_EQ(kept["cases"][1], changed["cases"][1]);
    fs::remove(a_png);
    ASSERT_EQ(run("validate s.json -o out --resume").status, 0);
    EXPECT_TRUE(fs::exists(a_image));
    EXPECT_NE(read_results()["cases"][0]["methods"][0]["terms"][0]["exr"], "");
    EXPECT_EQ(read_results()["cases"][1], changed["cases"][1]);
  }

  // Without --resume the folder's report is replaced by this run's cases alone.
  ASSERT_EQ(run("validate s.json -o out --case b").status, 0);
  const auto b_alone = read_results();
  ASSERT_EQ(b_alone["cases"].size(), 1u);

  // A case earlier in the suite than the kept one joins it: the report written after a holds b
  // too (until stop 23 it held the cases up to the one just run, and b was lost).
  ASSERT_EQ(run("validate s.json -o out --case a --resume").status, 0);
  const auto a_then_b = read_results();
  ASSERT_EQ(a_then_b["cases"].size(), 2u);
  EXPECT_EQ(a_then_b["cases"][0]["name"], "a");
  EXPECT_EQ(a_then_b["cases"][1], b_alone["cases"][0]);

  // Another suite's report, and a file that is no report: refused, nothing rendered.
  write("other.json", R"({"suite": "other", "base": {"image.width": 16, "image.height": 8},
    "cases": [{"name": "a", "set": {}}]})");
  expect_invalid(run("validate other.json -o out --resume"),
                 {"--resume", "results.json", "\"resume\"", "another folder"});
  fs::create_directories(dir_ / "junk");
  write("junk/results.json", "{\"suite\": ");
  expect_invalid(run("validate s.json -o junk --resume"), {"--resume", "junk/results.json"});
  EXPECT_FALSE(fs::exists(dir_ / "junk" / "index.html"));
}

// A suite's timing: each method other than the references is timed apart at its size (the
// report's timing_ms; the error plot uses it), and a resumed run whose timing changed times the
// kept cases again without rendering their images.
TEST_F(Cli, ValidateTimesTheMethodsApartAndRetimesAResumedCase) {
  const auto suite = [](const std::string& timing) {
    return R"({"suite": "timed", "base": {"image.width": 16, "image.height": 8,
      "camera.pitch": -20}, "methods": ["reference", "full",
      {"name": "full_cell4", "method": "full", "set": {"ocean.grid_cell": 4}}],
      "terms": ["sky"], "flicker": {"frames": 1, "terms": ["sky"]},
      "reference": {"pixel_samples": 4}, "timing": )" +
           timing + R"(, "cases": [{"name": "a", "set": {"ocean.wind_speed": 5}}]})";
  };
  write("t.json", suite(R"({"width": 48, "height": 32, "frames": 2})"));
  const Result r = run("validate t.json -o out");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("full, timed at 48x32"), std::string::npos) << r.err;
  const auto read_results = [&] { return read_json("out/results.json"); };
  const auto first = read_results();
  EXPECT_EQ(first["timing"]["width"], 48);
  const auto& c = first["cases"][0];
  EXPECT_EQ(c["timing"]["height"], 32);
  EXPECT_FALSE(c["methods"][0].contains("timing_ms"));  // the reference
  for (int m : {1, 2}) {
    ASSERT_TRUE(c["methods"][m].contains("timing_ms")) << m;
    EXPECT_GT(c["methods"][m]["timing_ms"].get<double>(), 0.0) << m;
  }
  // The error plot's times are the timed frames.
  std::ifstream dat(dir_ / "out" / "plots" / "a_error_time.dat");
  const std::string data{std::istreambuf_iterator<char>(dat), std::istreambuf_iterator<char>()};
  char line[128];
  std::snprintf(line, sizeof line, "\nfull sky %.17g ", c["methods"][1]["timing_ms"].get<double>());
  EXPECT_NE(data.find(line), std::string::npos) << data;

  // Another timing: the case is kept, its images untouched, its methods timed again.
  const auto image = dir_ / "out" / "images" / "a_reference_sky.exr";
  const auto image_time = fs::last_write_time(image);
  write("t.json", suite(R"({"width": 40, "height": 24, "frames": 1})"));
  const Result again = run("validate t.json -o out --resume");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("kept from the earlier run"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("full_cell4, timed at 40x24"), std::string::npos) << again.err;
  EXPECT_EQ(fs::last_write_time(image), image_time);
  const auto retimed = read_results();
  EXPECT_EQ(retimed["cases"][0]["fingerprint"], c["fingerprint"]);
  EXPECT_EQ(retimed["cases"][0]["timing"]["width"], 40);
  EXPECT_EQ(retimed["cases"][0]["methods"][1]["terms"], c["methods"][1]["terms"]);
  // The same timing once more: nothing is timed.
  const Result kept = run("validate t.json -o out --resume");
  ASSERT_EQ(kept.status, 0) << kept.err;
  EXPECT_EQ(kept.err.find("timed at"), std::string::npos) << kept.err;
}

// ---- thalassa sky ----

// The centre of texel (i, j) of an n x n sky map in u units (column 0 west, row 0 north).
std::pair<double, double> sky_map_u(int i, int j, int n) {
  constexpr double kExtent = 1.25;
  return {-kExtent + 2.0 * kExtent * (i + 0.5) / n, kExtent - 2.0 * kExtent * (j + 0.5) / n};
}

// The texel of largest R + G + B: (column, row).
std::pair<int, int> brightest(const thalassa::Image& image) {
  std::pair<int, int> best{-1, -1};
  float best_sum = -1.0f;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      if (p[0] + p[1] + p[2] > best_sum) {
        best_sum = p[0] + p[1] + p[2];
        best = {x, y};
      }
    }
  return best;
}

TEST_F(Cli, SkyWritesTheStereographicMap) {
  const Result r = run("sky --size 64 -o sky.exr --stats s.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"s.json", "sky.exr", "sky.png"}));
  thalassa::Metadata metadata;
  const thalassa::Image map = thalassa::read_image((dir_ / "sky.exr").string(), &metadata);
  ASSERT_EQ(map.width, 64);
  ASSERT_EQ(map.height, 64);
  std::map<std::string, std::string> meta(metadata.begin(), metadata.end());
  EXPECT_NE(meta["thalassa:sky_map"].find("row 0 north, column 0 west"), std::string::npos);
  EXPECT_EQ(meta["thalassa:sun"], "zenith=60 azimuth=180 source=scene");
  EXPECT_EQ(nlohmann::json::parse(meta["thalassa:scene"])["sun"]["zenith"], 60.0);
  const thalassa::Image png = thalassa::read_image((dir_ / "sky.png").string());
  EXPECT_EQ(png.width, 64);

  // Inside the horizon circle: finite, positive sky. Outside it (texels wholly beyond it): the
  // one below-horizon radiance.
  const double half_diagonal = std::sqrt(2.0) * 1.25 / 64;
  const float* below = map.pixel(0, 0);
  int sky_texels = 0, below_texels = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const auto [ux, uy] = sky_map_u(i, j, 64);
      const double radius = std::hypot(ux, uy);
      const float* p = map.pixel(i, j);
      if (radius < 1.0 - half_diagonal) {
        ++sky_texels;
        for (int c = 0; c < 3; ++c)
          ASSERT_TRUE(std::isfinite(p[c]) && p[c] > 0.0f) << i << "," << j << " channel " << c;
      } else if (radius > 1.0 + half_diagonal) {
        ++below_texels;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(p[c], below[c]) << i << "," << j;
      }
    }
  // The circle covers pi (64 / 2.5)^2 = 2059 texels, the rest 2037; less a ring of ~160.
  EXPECT_GT(sky_texels, 1850);
  EXPECT_GT(below_texels, 1850);
  // A blue sky at the zenith (the four texels around u = 0), brighter than the dim
  // multiple-reflection radiance below the horizon.
  for (int j : {31, 32})
    for (int i : {31, 32}) {
      const float* p = map.pixel(i, j);
      EXPECT_GT(p[2], p[0]) << i << "," << j;
      EXPECT_GT(p[2], below[2]) << i << "," << j;
    }

  std::ifstream in(dir_ / "s.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  for (const char* key : {"backend", "renderer", "sky_provider", "map_size", "setup_ms", "built"})
    EXPECT_TRUE(stats.contains(key)) << key;
  EXPECT_EQ(stats["sky_provider"], "atmosphere");
  EXPECT_EQ(stats["map_size"], 64);
  EXPECT_EQ(stats["panorama_width"], 0);
  EXPECT_GT(stats["setup_ms"]["sky.map"].get<double>(), 0.0);
  const auto built = stats["built"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(built.begin(), built.end(), "atmosphere.sky_map"), built.end());
}

// The sun's glow marks its azimuth: north up (row 0), east right (the last column). The
// brightest texel lies on the horizon below the sun, in the sun's half of the map; the aureole
// is centred on the sun (at |u| = tan(zenith / 2)), brighter there than 30 deg of azimuth to
// either side at the same zenith angle.
TEST_F(Cli, SkyMapIsBrightestTowardTheSun) {
  const double half_turn = std::tan(30.0 * M_PI / 180.0);  // |u| of the default zenith, 60 deg
  // The texel of a 64-texel map that holds u: (column, row).
  auto texel_at = [](double azimuth_deg, double radius) {
    const double a = azimuth_deg * M_PI / 180.0;
    const double ux = radius * std::sin(a), uy = radius * std::cos(a);
    return std::make_pair(int((ux + 1.25) / 2.5 * 64), int((1.25 - uy) / 2.5 * 64));
  };
  for (int azimuth : {0, 90, 270}) {
    const std::string name = std::to_string(azimuth) + ".exr";
    ASSERT_EQ(
        run("sky --size 64 --no-png --set sun.azimuth=" + std::to_string(azimuth) + " -o " + name)
            .status,
        0)
        << azimuth;
    const thalassa::Image map = thalassa::read_image((dir_ / name).string());
    const auto [column, row] = brightest(map);
    // North: the top half; east: the right half; west: the left half.
    EXPECT_TRUE(azimuth == 0    ? row < 32
                : azimuth == 90 ? column >= 32
                                : column < 32)
        << azimuth << ": brightest at column " << column << ", row " << row;
    auto sum = [&](std::pair<int, int> t) {
      const float* p = map.pixel(t.first, t.second);
      return p[0] + p[1] + p[2];
    };
    const float at_sun = sum(texel_at(azimuth, half_turn));
    EXPECT_GT(at_sun, 1.2f * sum(texel_at(azimuth - 30, half_turn))) << azimuth;
    EXPECT_GT(at_sun, 1.2f * sum(texel_at(azimuth + 30, half_turn))) << azimuth;
  }
}

TEST_F(Cli, SkyPanoramaIsEquirectangular) {
  // Sun at azimuth 100, zenith 60: column 100 / 360 * 64 = 17.8, row 60 / 180 * 32 = 10.7.
  const Result r =
      run("sky --size 16 -o map.exr --panorama pano.exr --panorama-width 64 --set sun.azimuth=100 "
          "--stats s.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(files(),
            (std::vector<std::string>{"map.exr", "map.png", "pano.exr", "pano.png", "s.json"}));
  thalassa::Metadata metadata;
  const thalassa::Image pano = thalassa::read_image((dir_ / "pano.exr").string(), &metadata);
  ASSERT_EQ(pano.width, 64);
  ASSERT_EQ(pano.height, 32);
  std::map<std::string, std::string> meta(metadata.begin(), metadata.end());
  EXPECT_NE(meta["thalassa:panorama"].find("left edge north"), std::string::npos);
  for (float v : pano.rgba) ASSERT_TRUE(std::isfinite(v));
  // The sun's disc is the brightest texel, where its direction falls.
  EXPECT_EQ(brightest(pano), std::make_pair(17, 10));
  // Blue sky at the zenith row.
  EXPECT_GT(pano.pixel(40, 0)[2], pano.pixel(40, 0)[0]);
  std::ifstream in(dir_ / "s.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["panorama_width"], 64);
  EXPECT_EQ(stats["panorama_height"], 32);
  EXPECT_TRUE(stats["setup_ms"].contains("sky.panorama"));
}

// With an HDR photograph as the sky, its sun (not the scene's) lights the map and the panorama.
TEST_F(Cli, SkyFromAPhotographUsesItsSun) {
  thalassa::Image photo;
  photo.width = 64;
  photo.height = 32;
  photo.rgba.assign(64 * 32 * 4, 0.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      float* p = photo.pixel(x, y);
      p[0] = 0.05f, p[1] = 0.08f, p[2] = 0.12f, p[3] = 1.0f;
    }
  // The sun: one texel at azimuth [90, 95.6] deg, zenith angle [45, 50.6] deg.
  float* sun = photo.pixel(16, 8);
  sun[0] = sun[1] = sun[2] = 5000.0f;
  thalassa::write_exr((dir_ / "photo.exr").string(), photo, thalassa::ExrPixelType::Float);
  const Result r =
      run("sky --size 32 --no-png -o map.exr --panorama pano.exr --panorama-width 64 "
          "--set sky.exr=photo.exr --stats s.json");
  ASSERT_EQ(r.status, 0) << r.err;
  thalassa::Metadata metadata;
  const thalassa::Image pano = thalassa::read_image((dir_ / "pano.exr").string(), &metadata);
  std::map<std::string, std::string> meta(metadata.begin(), metadata.end());
  EXPECT_NE(meta["thalassa:sun"].find("source=sky.exr"), std::string::npos) << meta["thalassa:sun"];
  EXPECT_EQ(meta["thalassa:sky_provider"], "environment_map");
  EXPECT_EQ(brightest(pano), std::make_pair(16, 8));
  // The map holds the photograph's sky, sun removed: the zenith texel is the sky's value.
  const thalassa::Image map = thalassa::read_image((dir_ / "map.exr").string());
  EXPECT_NEAR(map.pixel(16, 16)[2], 0.12f, 1e-3f);
  std::ifstream in(dir_ / "s.json");
  EXPECT_EQ(nlohmann::json::parse(in)["sky_provider"], "environment_map");
}

TEST_F(Cli, SkyInvalidInputExitsWith2AndWritesNothing) {
  expect_invalid(run("sky -o s.exr --size 0"), {"--size 0", "[1, 8192]"});
  expect_invalid(run("sky -o s.exr --set nothing.here=1"), {"--set", "nothing.here"});
  expect_invalid(run("sky -o s.exr --panorama p.exr --panorama-width 3"),
                 {"--panorama-width 3", "even"});
  expect_invalid(run("sky -o s.exr --panorama-width 64"), {"--panorama-width", "--panorama"});
  expect_invalid(run("sky -o s.png"), {"-o", ".exr"});
  expect_invalid(run("sky -o s.exr --panorama p.png"), {"--panorama", ".exr"});
  expect_invalid(run("sky -o s.exr --panorama s.exr"), {"--panorama", "same file"});
  expect_invalid(run("sky -o s.exr --stats s.png"), {"--stats", "same file"});
  expect_invalid(run("sky -o nowhere/s.exr"), {"nowhere"});
  EXPECT_EQ(run("sky").status, 2);  // -o is required
  EXPECT_EQ(run("sky -o s.exr --backend glfw").status, 2);
  EXPECT_EQ(files(), std::vector<std::string>{});
}

// Wakes and calm areas (issue 9): bad geometry in the scene or in a GeoJSON file it names exits
// with 2 before anything is rendered, naming the file and the feature.
TEST_F(Cli, BadFeatureGeometryExitsWith2AndWritesNothing) {
  write("ring.geojson", R"({"type": "Feature", "properties": {"name": "slick"}, "geometry":
      {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 1]]]}})");
  write("areas.json", R"({"calm_areas": [{"geojson": "ring.geojson"}]})");
  expect_invalid(
      run("render areas.json -o r.exr"),
      {"ring.geojson: feature (\"slick\").geometry.coordinates[0]: expected a closed ring"});
  expect_invalid(
      run(R"(render -o r.exr --set 'wakes=[{"track": [{"lat": 0, "lon": 0, "time": 5}, {"lat": 0, "lon": 0.001, "time": 5}]}]')"),
      {"--set: wakes[0].track[1]: expected a time later than point 0's (5 s)"});
  for (const char* name : {"r.exr", "r.png"}) EXPECT_FALSE(fs::exists(dir_ / name));
}

TEST_F(Cli, InfoPrintsBackendAndCapabilities) {
  const std::string command = "'" THALASSA_EXE "' info > '" + (dir_ / "info.txt").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(dir_ / "info.txt");
  std::stringstream text;
  text << in.rdbuf();
  for (const char* fragment : {"backend:", "GL version:", "GL renderer:", "compute shaders",
                               "clip control", "context loss reported", "anisotropic filtering"})
    EXPECT_NE(text.str().find(fragment), std::string::npos) << fragment;
}

#ifdef THALASSA_TEST_BOTH_HEADLESS_BACKENDS  // a build with both EGL and OSMesa
// With no display and an EGL that finds no driver (GLVND pointed at no vendor library), the
// default backend falls back to OSMesa and the render still succeeds.
TEST_F(Cli, DefaultFallsBackToOsMesaWithoutEgl) {
  const Result r = run("render " + kSmall + " --no-png --stats s.json",
                       "env -u DISPLAY -u WAYLAND_DISPLAY "
                       "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json ");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(dir_ / "s.json");
  EXPECT_EQ(nlohmann::json::parse(in)["backend"], "osmesa");
}

TEST_F(Cli, BothHeadlessBackendsRenderTheSameImage) {
  ASSERT_EQ(run("render " + kSmall + " --backend egl -o egl.exr --no-png --float").status, 0);
  ASSERT_EQ(run("render " + kSmall + " --backend osmesa -o osmesa.exr --no-png --float").status, 0);
  thalassa::Metadata meta_a, meta_b;
  const auto a = thalassa::read_image((dir_ / "egl.exr").string(), &meta_a);
  const auto b = thalassa::read_image((dir_ / "osmesa.exr").string(), &meta_b);
  std::map<std::string, std::string> ma(meta_a.begin(), meta_a.end()),
      mb(meta_b.begin(), meta_b.end());
  if (ma["thalassa:renderer"] == mb["thalassa:renderer"]) {
    EXPECT_EQ(a.rgba, b.rgba);  // same rasteriser (llvmpipe): bit for bit
  } else {
    ASSERT_EQ(a.rgba.size(), b.rgba.size());  // a GPU under EGL: float-level differences only
    for (std::size_t i = 0; i < a.rgba.size(); ++i)
      EXPECT_NEAR(a.rgba[i], b.rgba[i], 1e-2 * std::abs(b.rgba[i]) + 1e-6) << i;
  }
}
#endif

// An HDR photograph lights the sea (issue 4, point 4): the environment-map provider replaces
// the atmosphere, its sun replaces sun.*, and a file that is not an equirectangular image is
// invalid input.
TEST_F(Cli, HdrPhotographLightsTheScene) {
  // A 64 x 32 sky: blue, brighter toward the horizon, with a 2 x 2-texel sun 1e5 times brighter
  // at azimuth 90 deg (east), 22.5 deg high.
  thalassa::Image sky;
  sky.width = 64;
  sky.height = 32;
  sky.rgba.assign(64 * 32 * 4, 1.0f);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      float* p = sky.pixel(x, y);
      const float horizon = float(y) / 16.0f;  // 0 at the zenith, 1 at the horizon
      p[0] = 0.02f + 0.05f * horizon, p[1] = 0.05f + 0.05f * horizon, p[2] = 0.12f;
    }
  for (int y = 11; y < 13; ++y)
    for (int x = 15; x < 17; ++x)
      for (int c = 0; c < 3; ++c) sky.pixel(x, y)[c] = 1e4f;
  thalassa::write_exr((dir_ / "photo.exr").string(), sky, thalassa::ExrPixelType::Float);
  const Result r = run("render " + kSmall + " --set sky.exr=photo.exr --no-png --stats s.json");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(dir_ / "s.json");
  const auto built = nlohmann::json::parse(in)["built"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(built.begin(), built.end(), "environment_map.panorama"), built.end());
  for (const auto& item : built) EXPECT_EQ(item.find("atmosphere.model"), std::string::npos);
  const auto image = thalassa::read_image((dir_ / "thalassa.exr").string());
  for (float v : image.rgba) EXPECT_TRUE(std::isfinite(v));

  thalassa::Image square;
  square.width = square.height = 16;
  square.rgba.assign(16 * 16 * 4, 1.0f);
  thalassa::write_exr((dir_ / "square.exr").string(), square, thalassa::ExrPixelType::Half);
  expect_invalid(run("render " + kSmall + " --set sky.exr=square.exr -o bad.exr"),
                 {"sky.exr", "square.exr"});
  EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
}

// --- thalassa fly ------------------------------------------------------------------------------

// A short descent: 5 frames at 4 frames per second, 200 m to 2 m, turning to the horizon.
const std::string kShortFlight = R"({
  "fps": 4, "duration": 1,
  "keyframes": [
    {"time": 0, "camera": {"height": 200, "pitch": -60, "heading": 350}},
    {"time": 1, "camera": {"height": 2, "pitch": -5, "heading": 10}}
  ]
})";

std::string frame_file(int frame, const std::string& extension) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d%s", frame, extension.c_str());
  return name;
}

std::map<std::string, std::string> metadata_of(const fs::path& exr) {
  thalassa::Metadata metadata;
  thalassa::read_image(exr.string(), &metadata);
  return {metadata.begin(), metadata.end()};
}

TEST_F(Cli, FlyWritesEveryFrameAsExrAndPng) {
  write("flight.json", kShortFlight);
  const Result r = run("fly flight.json -o out " + kSmall + " --stats stats.json");
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> expected;
  for (int i = 0; i < 5; ++i) {
    expected.push_back(frame_file(i, ".exr"));
    expected.push_back(frame_file(i, ".png"));
  }
  std::vector<std::string> written;
  for (const auto& entry : fs::directory_iterator(dir_ / "out"))
    written.push_back(entry.path().filename());
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written, expected);
  EXPECT_EQ(r.err.find("under the water"), std::string::npos) << r.err;  // 2 m and up
  // Not a terminal: one line per frame on stderr.
  for (int i = 0; i < 5; ++i)
    EXPECT_NE(r.err.find(frame_file(i, "") + " [" + std::to_string(i + 1) + "/5]"),
              std::string::npos)
        << r.err;
  // Each frame's metadata holds its own camera: the keyframes' at both ends.
  auto first = metadata_of(dir_ / "out" / frame_file(0, ".exr"));
  auto last = metadata_of(dir_ / "out" / frame_file(4, ".exr"));
  EXPECT_EQ(nlohmann::json::parse(first["thalassa:scene"])["camera"]["height"], 200.0);
  EXPECT_EQ(nlohmann::json::parse(last["thalassa:scene"])["camera"]["height"], 2.0);
  EXPECT_EQ(nlohmann::json::parse(last["thalassa:scene"])["camera"]["heading"], 10.0);
  EXPECT_EQ(nlohmann::json::parse(last["thalassa:scene"])["time"], 1.0);
  EXPECT_EQ(last["thalassa:flight"], "flight.json frame=4 t=1 fps=4");
  const thalassa::Image png = thalassa::read_image((dir_ / "out" / frame_file(2, ".png")).string());
  EXPECT_EQ(png.width, 32);
  EXPECT_EQ(png.height, 24);
  std::ifstream in(dir_ / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["frames_rendered"], 5);
  EXPECT_EQ(stats["frames_skipped"], 0);
  EXPECT_EQ(stats["mode"], "surface");
  EXPECT_EQ(stats["frames"].size(), 5u);
  EXPECT_GT(stats["frame_ms"].get<double>(), 0.0);
  // One sky provider for the flight: made by the first frame, kept by the others.
  EXPECT_EQ(stats["sky_provider_kept_frames"], 4);
  EXPECT_EQ(stats["frames"][0]["sky_provider_kept"], false);
  EXPECT_EQ(stats["frames"][4]["sky_provider_kept"], true);
}

TEST_F(Cli, FlyFramesRendersOnlyThatSlice) {
  write("flight.json", kShortFlight);
  ASSERT_EQ(run("fly flight.json -o out --frames 1:2 " + kSmall).status, 0);
  std::vector<std::string> written;
  for (const auto& entry : fs::directory_iterator(dir_ / "out"))
    written.push_back(entry.path().filename());
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written, (std::vector<std::string>{frame_file(1, ".exr"), frame_file(1, ".png"),
                                               frame_file(2, ".exr"), frame_file(2, ".png")}));
}

// --fps renders the flight at another rate, its length kept: the 4-fps, 1 s flight at 8 fps
// ends at frame 8, the last keyframe's camera; a bad rate exits with 2 before anything is written.
TEST_F(Cli, FlyFpsKeepsTheFlightsLength) {
  write("flight.json", kShortFlight);
  const Result r = run("fly flight.json -o out --fps 8 --frames 8:8 " + kSmall);
  ASSERT_EQ(r.status, 0) << r.err;
  auto meta = metadata_of(dir_ / "out" / frame_file(8, ".exr"));
  EXPECT_EQ(meta["thalassa:flight"], "flight.json frame=8 t=1 fps=8");
  EXPECT_EQ(nlohmann::json::parse(meta["thalassa:scene"])["camera"]["height"], 2.0);
  expect_invalid(run("fly flight.json -o bad --fps 0"),
                 {"--fps: expected a number in (0, 1000] (frames per second), got 0"});
  expect_invalid(run("fly flight.json -o bad --fps 8 --frames 9:9"),
                 {"--frames 9:9: expected A:B with 0 <= A <= B <= 8"});
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

TEST_F(Cli, FlyRerunSkipsFramesAlreadyWritten) {
  write("flight.json", kShortFlight);
  ASSERT_EQ(run("fly flight.json -o out --frames 0:1 " + kSmall).status, 0);
  const auto exr0 = dir_ / "out" / frame_file(0, ".exr");
  const auto time0 = fs::last_write_time(exr0);
  const Result r = run("fly flight.json -o out " + kSmall + " --stats stats.json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find(frame_file(0, "") + " [1/5]: skipped"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(frame_file(1, "") + " [2/5]: skipped"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(frame_file(2, "") + " [3/5]: skipped"), std::string::npos) << r.err;
  EXPECT_EQ(fs::last_write_time(exr0), time0);
  std::ifstream in(dir_ / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_EQ(stats["frames_rendered"], 3);
  EXPECT_EQ(stats["frames_skipped"], 2);
  // A frame whose PNG is missing or whose scene changed is rendered again.
  fs::remove(dir_ / "out" / frame_file(3, ".png"));
  const Result again = run("fly flight.json -o out --frames 2:3 " + kSmall);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find(frame_file(2, "") + " [1/2]: skipped"), std::string::npos);
  EXPECT_EQ(again.err.find(frame_file(3, "") + " [2/2]: skipped"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "out" / frame_file(3, ".png")));
  const Result changed =
      run("fly flight.json -o out --frames 0:0 " + kSmall + " --set ocean.wind_speed=3");
  ASSERT_EQ(changed.status, 0) << changed.err;
  EXPECT_EQ(changed.err.find("]: skipped"), std::string::npos) << changed.err;
  EXPECT_EQ(nlohmann::json::parse(metadata_of(exr0)["thalassa:scene"])["ocean"]["wind_speed"], 3.0);
}

TEST_F(Cli, FlyInvalidInputExitsWith2AndWritesNothing) {
  write("bad.json", R"({"keyframes": [{"time": 0}, {"time": 1, "camera": {"height": "x"}}]})");
  expect_invalid(
      run("fly bad.json -o out " + kSmall),
      {"bad.json: keyframes[1].camera.height: expected a number in [0, 1e9] (m", "got \"x\""});
  write("order.json", R"({"keyframes": [{"time": 2}, {"time": 1}]})");
  expect_invalid(run("fly order.json -o out"),
                 {"order.json: keyframes[1].time: expected a time after keyframes[0].time (2 s)"});
  write("flight.json", kShortFlight);
  expect_invalid(run("fly flight.json -o out --frames 3:9 " + kSmall),
                 {"--frames 3:9: expected A:B with 0 <= A <= B <= 4"});
  expect_invalid(run("fly flight.json -o out --frames 2:1"), {"--frames 2:1"});
  expect_invalid(run("fly flight.json -o out --set camera.height=5"),
                 {"--set: camera.height: expected a key the flight's keyframes do not animate"});
  expect_invalid(run("fly flight.json -o out --set image.width=0"), {"--set: image.width"});
  expect_invalid(run("fly missing.json -o out"), {"missing.json: expected a readable flight file"});
  expect_invalid(run("fly flight.json -o out --video out.avi"), {"--video out.avi", ".mp4"});
  write("file", "");
  expect_invalid(run("fly flight.json -o file"), {"-o file: expected a folder, got a file"});
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(Cli, FlyWithNoFileRendersTheDefaultFlight) {
  const Result r = run("fly -o out --frames 0:0 " + kSmall);
  ASSERT_EQ(r.status, 0) << r.err;
  auto meta = metadata_of(dir_ / "out" / frame_file(0, ".exr"));
  const auto scene = nlohmann::json::parse(meta["thalassa:scene"]);
  EXPECT_EQ(scene["camera"]["height"], 400000.0);
  EXPECT_EQ(scene["sun"]["zenith"], 88.0);
  EXPECT_EQ(meta["thalassa:flight"], "default flight frame=0 t=0 fps=24");
  EXPECT_EQ(meta["thalassa:mode"], "space");
}

TEST_F(Cli, FlyVideoEncodesTheFramesWithFfmpeg) {
  write("flight.json", kShortFlight);
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg is not installed (scripts/setup installs it): --video not tested";
  // An odd size is padded to even for 4:2:0.
  const Result r =
      run("fly flight.json -o out --video flight.mp4 --set image.width=33 "
          "--set image.height=24");
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir_ / "flight.mp4"));
  std::ifstream in(dir_ / "flight.mp4", std::ios::binary);
  char head[8] = {};
  in.read(head, sizeof head);
  EXPECT_EQ(std::string(head + 4, 4), "ftyp");  // an ISO base media (MP4) file
  EXPECT_GT(fs::file_size(dir_ / "flight.mp4"), 1000u);
  // Nothing left beside it: no pending file, no ffmpeg log.
  for (const std::string& name : files())
    EXPECT_TRUE(name == "flight.json" || name == "flight.mp4" || name == "out") << name;
}

TEST_F(Cli, FlyVideoWithoutFfmpegExitsWith1BeforeRendering) {
  write("flight.json", kShortFlight);
  const Result r = run("fly flight.json -o out --video flight.mp4 " + kSmall, "PATH=/nonexistent ");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("ffmpeg is not installed"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  EXPECT_FALSE(fs::exists(dir_ / "flight.mp4"));
}

// ---- thalassa sea ----

// The rows of a CSV file: the header's names, then each row's fields.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> names;
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    if (names.empty()) {
      names = fields;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < fields.size() && i < names.size(); ++i) row[names[i]] = fields[i];
    EXPECT_EQ(fields.size(), names.size()) << line;
    rows.push_back(row);
  }
  return rows;
}

TEST_F(Cli, SeaWritesTheSurfaceAtPointsAndTimesAsCsv) {
  Result r = run("sea --at 20,-150 --at 20.0001,-150 --times 0:2:0.5 -o series.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = read_csv(dir_ / "series.csv");
  ASSERT_EQ(rows.size(), 10u);  // 5 times, 2 points
  double lowest = 1e9, highest = -1e9;
  for (const auto& row : rows) {
    for (const char* key : {"height_m", "normal_up", "velocity_up_m_s", "height_rate_m_s"})
      EXPECT_TRUE(std::isfinite(std::stod(row.at(key)))) << key;
    EXPECT_EQ(row.at("converged"), "1");
    EXPECT_EQ(row.at("calm_scale"), "1");
    const double height = std::stod(row.at("height_m"));
    lowest = std::min(lowest, height);
    highest = std::max(highest, height);
    EXPECT_GT(std::stod(row.at("normal_up")), 0.5);
  }
  EXPECT_GT(highest - lowest, 0.05);  // the default sea (10 m/s) moves
  // One time on its own gives that time's row of the series.
  r = run("sea --at 20.0001,-150 --time 1.5 -o one.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto one = read_csv(dir_ / "one.csv");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0], rows[7]);
  // A calm area of scale 0 over the point stills it; a footprint longer than every wave too.
  r =
      run("sea --at 20,-150 -o calm.csv --set 'calm_areas=[{\"scale\": 0, \"fade\": 10, "
          "\"polygon\": [{\"lat\": 19.99, \"lon\": -150.01}, {\"lat\": 19.99, \"lon\": -149.99}, "
          "{\"lat\": 20.01, \"lon\": -150}]}]'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_csv(dir_ / "calm.csv")[0].at("height_m"), "0");
  ASSERT_EQ(run("sea --at 20,-150 --footprint 100 -o long.csv").status, 0);
  EXPECT_EQ(read_csv(dir_ / "long.csv")[0].at("height_m"), "0");
  // The sea needs no sky: a scene whose sky image is elsewhere (render refuses it) gives the
  // same rows.
  r = run("sea --at 20.0001,-150 --time 1.5 --set sky.exr=noon.exr -o skyless.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_csv(dir_ / "skyless.csv"), one);
  // `--footprint drawn`: each point's grid cell as `render` draws the scene (drawn_footprint),
  // here 20 m ahead of the default camera (4 m up, looking south): the same rows as that
  // footprint given in metres, not those of every wave.
  const double ahead = 19.99982;  // degrees: 20 m south, written exactly in the argument
  const std::optional<double> cell = thalassa::drawn_footprint(thalassa::Scene{}, ahead, -150.0);
  ASSERT_TRUE(cell.has_value());
  char place[64], metres[64];
  std::snprintf(place, sizeof place, "%.5f,-150", ahead);
  std::snprintf(metres, sizeof metres, "%.17g", *cell);
  r = run(std::string("sea --at ") + place + " --times 0:1:0.5 --footprint drawn -o drawn.csv");
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(run(std::string("sea --at ") + place + " --times 0:1:0.5 --footprint " + metres +
                " -o cell.csv")
                .status,
            0);
  ASSERT_EQ(run(std::string("sea --at ") + place + " --times 0:1:0.5 -o every.csv").status, 0);
  const auto drawn_rows = read_csv(dir_ / "drawn.csv");
  EXPECT_EQ(drawn_rows, read_csv(dir_ / "cell.csv"));
  EXPECT_NE(drawn_rows, read_csv(dir_ / "every.csv"));
}

// A camera under a crest (0.3 m, where the default sea stands 0.77 m high at 8 s) draws the wave
// from inside: `render` and `fly` say so, with how deep.
TEST_F(Cli, RenderAndFlyWarnOfACameraUnderTheWater) {
  Result r = run(
      "render --set camera.height=0.3 --set time=8 -o low.exr --no-png --stats low.json " + kSmall);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the camera (0.3 m) is 0.469 m under the water"), std::string::npos)
      << r.err;
  EXPECT_EQ(read_json("low.json")["warnings"].size(), 1u);
  r = run("render --set camera.height=1 --set time=8 -o high.exr --no-png " + kSmall);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("under the water"), std::string::npos) << r.err;
  write("low.json", R"({"scene": {"time": 8}, "fps": 4, "duration": 0.5,
      "keyframes": [{"time": 0, "camera": {"height": 0.3}}, {"time": 0.5, "camera": {"height": 0.3}}]})");
  r = run("fly low.json -o out --stats fly.json " + kSmall);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("have the camera under the water, up to"), std::string::npos) << r.err;
  const nlohmann::json stats = read_json("fly.json");
  EXPECT_NEAR(stats["frames"][0]["camera_depth"].get<double>(), 0.469, 1e-3);
}

TEST_F(Cli, SeaRefusesBadPlacesTimesAndOutputs) {
  expect_invalid(run("sea --at 91,0 -o a.csv"), {"--at 91,0", "LAT in [-90, 90]"});
  expect_invalid(run("sea --at 20 -o a.csv"), {"--at 20", "LAT,LON"});
  expect_invalid(run("sea --at 20,x -o a.csv"), {"--at 20,x"});
  expect_invalid(run("sea --at ' 20,-150' -o a.csv"), {"--at  20,-150", "LAT,LON"});
  expect_invalid(run("sea --at 0x14,-150 -o a.csv"), {"--at 0x14,-150"});
  // Another chart's sea: the default anchor is the camera's (20 N 150 W).
  expect_invalid(run("sea --at 0,0 -o a.csv"),
                 {"--at 0,0", "within 1000 km of the waves' anchor (20, -150)", "--anchor"});
  expect_invalid(run("sea --times 5:1:1 -o a.csv"), {"--times 5:1:1", "START <= STOP"});
  expect_invalid(run("sea --times 0:1:0 -o a.csv"), {"--times", "STEP > 0"});
  expect_invalid(run("sea --times 0:1e9:1e-3 -o a.csv"), {"--times", "at most 1e7"});
  expect_invalid(run("sea --time -1 -o a.csv"), {"--time -1", "[0, 1e12]"});
  expect_invalid(run("sea --time 1 --times 0:1:1 -o a.csv"), {"--time and --times"});
  expect_invalid(run("sea --footprint -2 -o a.csv"), {"--footprint -2"});
  expect_invalid(run("sea --footprint wide -o a.csv"), {"--footprint wide", "`drawn`"});
  // Behind the default camera (it looks south) its grid draws nothing.
  expect_invalid(run("sea --at 20.001,-150 --footprint drawn -o a.csv"),
                 {"--footprint drawn: --at 20.001,-150", "draws no waves there"});
  expect_invalid(run("sea --anchor 1,2,3 -o a.csv"), {"--anchor 1,2,3"});
  expect_invalid(run("sea -o a.txt"), {"-o", ".csv"});
  expect_invalid(run("sea --set ocean.wind_speed=99 -o a.csv"), {"ocean.wind_speed"});
  EXPECT_EQ(files(), std::vector<std::string>{});
}

}  // namespace
