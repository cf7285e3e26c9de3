// Renderer::set_scene (planet/renderer.hpp): one Renderer given scene after scene draws what a
// new Renderer of each scene draws (with the waves' anchor it kept), to the bit, while it keeps
// its programs, its sky provider and the nodes whose options did not change; a scene that
// cannot be drawn leaves it drawing the last one.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "thalassa/planet/nadir_frame.hpp"

namespace thalassa {
namespace {

bool paid(const RenderStats& stats, const std::string& name) {
  return std::any_of(stats.setup_ms.begin(), stats.setup_ms.end(),
                     [&](const auto& item) { return item.first == name; });
}

bool kept(const RenderStats& stats, const std::string& node) {
  return std::find(stats.kept_nodes.begin(), stats.kept_nodes.end(), node) !=
         stats.kept_nodes.end();
}

// The image a new Renderer draws of `scene`, with the waves' chart at `anchor` where given.
Image drawn_alone(GlContext& context, const Scene& scene,
                  const std::optional<Geodetic>& anchor = std::nullopt,
                  RendererOptions options = {}) {
  options.wave_anchor = anchor;
  Renderer renderer(context, scene, options);
  renderer.render();
  return renderer.image();
}

Image drawn(Renderer& renderer) {
  renderer.render();
  return renderer.image();
}

// 4 m over the default sea at 20 N 150 W, the sun ahead: waves a pixel wide and more, so that a
// chart moved by a metre shows.
Scene near_sea() {
  Scene scene = test::scene_from(
      R"({"image": {"width": 64, "height": 36}, "camera": {"height": 4, "pitch": -12}})");
  return scene;
}

TEST(RendererSetScene, DrawsWhatANewRendererDrawsAndKeepsWhatTheScenesShare) {
  auto context = test::make_test_context();
  const Scene first = near_sea();
  Renderer renderer(*context, first);
  const Image first_image = drawn(renderer);
  const RenderStats first_stats = renderer.stats();
  const unsigned texture = renderer.hdr_texture();
  EXPECT_TRUE(first_stats.kept_nodes.empty());
  EXPECT_TRUE(paid(first_stats, "shaders.compile"));
  EXPECT_FALSE(paid(first_stats, "renderer.set_scene"));

  // The next frame: the camera 300 m east and turned, the sun lower, 5 s later.
  Scene next = first;
  next.camera.lon += 300.0 / 104600.0;  // degrees: 300 m at 20 degrees of latitude
  next.camera.heading += 10.0;
  next.sun.zenith += 5.0;
  next.time += 5.0;
  renderer.set_scene(next);
  const Image next_image = drawn(renderer);
  const RenderStats stats = renderer.stats();
  EXPECT_EQ(stats.frames, 1);
  EXPECT_TRUE(kept(stats, "sky"));
  EXPECT_TRUE(kept(stats, "ocean"));
  EXPECT_TRUE(stats.sky_provider_kept);
  EXPECT_FALSE(paid(stats, "sky.provider"));
  EXPECT_FALSE(paid(stats, "shaders.compile"));  // nothing new to compile
  EXPECT_TRUE(paid(stats, "sky.map"));           // the sun moved
  EXPECT_TRUE(paid(stats, "renderer.set_scene"));
  EXPECT_EQ(stats.wave_anchor.lat, first_stats.wave_anchor.lat);
  EXPECT_EQ(stats.wave_anchor.lon, first_stats.wave_anchor.lon);
  EXPECT_NE(next_image.rgba, first_image.rgba);
  EXPECT_EQ(next_image.rgba, drawn_alone(*context, next, stats.wave_anchor).rgba);
  EXPECT_EQ(renderer.scene().camera.lon, next.camera.lon);
  EXPECT_EQ(renderer.hdr_texture(), texture);  // a host's texture stays while the size does

  // The image resized (a window's): the nodes are kept and draw the new size as a new Renderer
  // would.
  Scene resized = next;
  resized.image.width = 80;
  resized.image.height = 45;
  renderer.set_scene(resized);
  const Image resized_image = drawn(renderer);
  EXPECT_TRUE(kept(renderer.stats(), "ocean"));
  EXPECT_EQ(resized_image.width, 80);
  EXPECT_EQ(resized_image.height, 45);
  EXPECT_EQ(resized_image.rgba, drawn_alone(*context, resized, stats.wave_anchor).rgba);

  // Only the sea's settings change: the sky node stays, the sea is made again.
  Scene windier = next;
  windier.ocean.wind_speed = 15.0;
  renderer.set_scene(windier);
  const Image windier_image = drawn(renderer);
  EXPECT_TRUE(kept(renderer.stats(), "sky"));
  EXPECT_FALSE(kept(renderer.stats(), "ocean"));
  EXPECT_EQ(windier_image.rgba, drawn_alone(*context, windier, stats.wave_anchor).rgba);

  // The same scene again draws the same image.
  renderer.set_scene(first);
  EXPECT_EQ(drawn(renderer).rgba, first_image.rgba);
}

// From the sea to space and back, with the image's size changed on the way: each frame is a new
// Renderer's, the frame that compiles the other mode's programs is drawn twice (its time holds
// no compiling) and says what it compiled.
TEST(RendererSetScene, CrossesToSpaceAndBackAndResizes) {
  auto context = test::make_test_context();
  Renderer renderer(*context, near_sea());
  renderer.render();

  // From 400 km over a point 50 km north of the first camera: no wave shows, and the anchor is
  // the lattice point nearest the camera's.
  Scene space = test::scene_from(R"({"image": {"width": 48, "height": 32},
      "camera": {"lat": 20.45, "height": 400000, "pitch": -60}})");
  renderer.set_scene(space);
  const Image space_image = drawn(renderer);
  RenderStats stats = renderer.stats();
  EXPECT_EQ(stats.mode, "space");
  EXPECT_EQ(stats.width, 48);
  EXPECT_EQ(space_image.width, 48);
  EXPECT_EQ(space_image.height, 32);
  EXPECT_EQ(stats.frames, 1);
  EXPECT_TRUE(paid(stats, "shaders.compile"));
  EXPECT_FALSE(kept(stats, "ocean"));
  EXPECT_EQ(space_image.rgba, drawn_alone(*context, space).rgba);
  EXPECT_EQ(stats.wave_anchor.lat, 20.5);
  // Only the programs this scene drew with are listed: none of the projected grid's.
  for (const std::string& item : stats.built)
    EXPECT_EQ(item.find("ocean/ocean.vert"), std::string::npos) << item;

  // Down to the sea there, 50 km from the first anchor: the anchor is the one taken in space,
  // the camera's nearest, not the first (which is within kWaveAnchorKeepDistance); the programs
  // are the library's already.
  Scene back = near_sea();
  back.camera.height = 50.0;
  back.camera.lat = 20.45;
  renderer.set_scene(back);
  const Image back_image = drawn(renderer);
  stats = renderer.stats();
  EXPECT_EQ(stats.mode, "surface");
  EXPECT_FALSE(paid(stats, "shaders.compile"));
  const Geodetic nearest = nearest_wave_anchor(back.camera.lat, back.camera.lon);
  EXPECT_EQ(stats.wave_anchor.lat, nearest.lat);
  EXPECT_EQ(stats.wave_anchor.lon, nearest.lon);
  EXPECT_EQ(back_image.rgba, drawn_alone(*context, back).rgba);
}

// The waves stay on the planet as the camera moves: the anchor is kept within
// kWaveAnchorKeepDistance, and beyond it the camera takes the lattice point nearest it.
TEST(RendererSetScene, KeepsTheWavesAnchorWithinItsDistance) {
  auto context = test::make_test_context();
  const Scene first = near_sea();  // 20 N 150 W: a lattice point, its own anchor
  Renderer renderer(*context, first);
  renderer.render();
  const Geodetic anchor = renderer.stats().wave_anchor;
  EXPECT_EQ(anchor.lat, 20.0);
  EXPECT_EQ(anchor.lon, -150.0);

  // 21 km east: the nearest lattice point is another (150.25 W would be 26 km), the anchor kept.
  Scene moved = first;
  moved.camera.lon += 0.2;
  ASSERT_NE(nearest_wave_anchor(moved.camera.lat, moved.camera.lon).lon, anchor.lon);
  renderer.set_scene(moved);
  const Image moved_image = drawn(renderer);
  EXPECT_EQ(renderer.stats().wave_anchor.lon, anchor.lon);
  EXPECT_EQ(moved_image.rgba, drawn_alone(*context, moved, anchor).rgba);
  // A new Renderer there charts the waves from its own nearest point: other waves.
  EXPECT_NE(moved_image.rgba, drawn_alone(*context, moved).rgba);
  // The sea the renderer answers for on the CPU is the one it draws: its kept anchor's, at its
  // scene's time, not a new SeaState's of the moved scene (planet/sea_state.hpp).
  {
    const SeaState sea = renderer.sea_state();
    EXPECT_EQ(sea.wave_anchor().lat, anchor.lat);
    EXPECT_EQ(sea.wave_anchor().lon, anchor.lon);
    const double lat = moved.camera.lat, lon = moved.camera.lon;
    EXPECT_EQ(sea.at(lat, lon).height, SeaState(moved, anchor).at(lat, lon, moved.time).height);
    EXPECT_NE(sea.at(lat, lon).height, SeaState(moved).at(lat, lon).height);
  }

  // 167 km north: past the distance, the nearest lattice point.
  Scene far = first;
  far.camera.lat += 1.5;
  renderer.set_scene(far);
  const Image far_image = drawn(renderer);
  EXPECT_EQ(renderer.stats().wave_anchor.lat, 21.5);
  EXPECT_EQ(far_image.rgba, drawn_alone(*context, far).rgba);

  // The options' anchor holds for good.
  RendererOptions fixed;
  fixed.wave_anchor = anchor;
  Renderer pinned(*context, first, fixed);
  pinned.set_scene(far);
  pinned.render();
  EXPECT_EQ(pinned.stats().wave_anchor.lat, anchor.lat);
}

// A scene that cannot be drawn is refused and the Renderer draws the last one as before.
TEST(RendererSetScene, RefusedSceneLeavesTheLastOne) {
  auto context = test::make_test_context();
  const Scene first = near_sea();
  Renderer renderer(*context, first);
  const Image before = drawn(renderer);
  Scene missing_sky = first;
  missing_sky.camera.height = 100.0;
  missing_sky.sky.exr = test::output_dir() + "/set_scene_test_no_such_sky.exr";
  EXPECT_THROW(renderer.set_scene(missing_sky), SceneError);
  EXPECT_EQ(renderer.scene().camera.height, first.camera.height);
  EXPECT_EQ(drawn(renderer).rgba, before.rgba);

  // A method that draws the projected grid only, given a camera in space.
  RendererOptions normals;
  normals.method = ocean::OceanMethod::normals;
  Renderer grid_only(*context, first, normals);
  const Image grid_before = drawn(grid_only);
  Scene space = first;
  space.camera.height = 400000.0;
  EXPECT_THROW(grid_only.set_scene(space), SceneError);
  EXPECT_EQ(drawn(grid_only).rgba, grid_before.rgba);
}

// Wakes and calm areas are placed anew for each scene: the same ones in view keep the sea's node,
// the clock alone keeps the calm areas' chart, a moved camera (the features move in its frame)
// makes both again, and each image is a new Renderer's.
TEST(RendererSetScene, PlacesWakesAndCalmAreasAnew) {
  auto context = test::make_test_context();
  const Scene first = test::scene_from(R"({"image": {"width": 48, "height": 32},
      "camera": {"lat": 10, "lon": 20, "height": 50, "pitch": -20, "heading": 0},
      "wakes": [{"lat": 10.003, "lon": 20, "heading": 0, "speed": 8, "length": 500}],
      "calm_areas": [{"polygon": [{"lat": 10.001, "lon": 19.999}, {"lat": 10.001, "lon": 20.001},
                                  {"lat": 10.002, "lon": 20.0}]}]})");
  Renderer renderer(*context, first);
  const Image first_image = drawn(renderer);
  const std::vector<std::string> built = renderer.stats().built;
  const auto has = [&](const std::string& prefix) {
    return std::any_of(built.begin(), built.end(),
                       [&](const std::string& item) { return item.rfind(prefix, 0) == 0; });
  };
  ASSERT_TRUE(has("ocean.kelvin_wakes.1"));
  ASSERT_TRUE(has("ocean.calm_areas.1"));
  renderer.set_scene(first);
  EXPECT_TRUE(kept(renderer.stats(), "ocean"));
  EXPECT_EQ(drawn(renderer).rgba, first_image.rgba);

  // The clock alone: the ship moves on, the calm areas' chart is the last one, and the image a
  // new Renderer's all the same.
  Scene later = first;
  later.time += 3.0;
  renderer.set_scene(later);
  const Image later_image = drawn(renderer);
  EXPECT_TRUE(renderer.stats().calm_chart_kept);
  EXPECT_NE(later_image.rgba, first_image.rgba);
  EXPECT_EQ(later_image.rgba, drawn_alone(*context, later, renderer.stats().wave_anchor).rgba);

  Scene moved = first;
  moved.camera.lat -= 0.0005;  // 55 m south
  moved.time += 2.0;           // and the ship 16 m on
  renderer.set_scene(moved);
  const Image moved_image = drawn(renderer);
  EXPECT_FALSE(kept(renderer.stats(), "ocean"));
  EXPECT_TRUE(kept(renderer.stats(), "sky"));
  EXPECT_FALSE(renderer.stats().calm_chart_kept);
  EXPECT_NE(moved_image.rgba, first_image.rgba);
  EXPECT_EQ(moved_image.rgba, drawn_alone(*context, moved, renderer.stats().wave_anchor).rgba);
}

// The reference method: its samples after set_scene are a new reference Renderer's.
TEST(RendererSetScene, ReferenceDrawsWhatANewReferenceDraws) {
  auto context = test::make_test_context();
  RendererOptions options;
  options.method = ocean::OceanMethod::reference;
  options.terms.sun = false;  // the sky and the refracted light: no lattice to scatter
  options.reference.min_samples = 4;
  options.reference.max_samples = 4;
  options.reference.fixed_samples = true;
  Scene first = near_sea();
  first.image.width = 32;
  first.image.height = 18;
  Renderer renderer(*context, first, options);
  renderer.render();
  Scene next = first;
  next.camera.heading += 5.0;
  next.time += 1.0;
  renderer.set_scene(next);
  const Image image = drawn(renderer);
  const RenderStats stats = renderer.stats();
  EXPECT_EQ(stats.samples, 4);
  EXPECT_EQ(image.rgba, drawn_alone(*context, next, stats.wave_anchor, options).rgba);
}

}  // namespace
}  // namespace thalassa
