// RendererOptions::sky_cache (planet/renderer.hpp): Renderers drawing one after another keep one
// sky provider, and draw what each would draw with its own: the same images to the bit, the
// sky map built again only when the sun moves, the sun-zenith array of the views from 10 km up
// once, and a new provider for another sky.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace thalassa {
namespace {

struct Drawn {
  Image image;
  RenderStats stats;
};

Drawn draw(GlContext& context, const Scene& scene, const std::shared_ptr<SkyProviderCache>& cache) {
  RendererOptions options;
  options.sky_cache = cache;
  Renderer renderer(context, scene, options);
  renderer.render();
  return {renderer.image(), renderer.stats()};
}

bool paid(const RenderStats& stats, const std::string& name) {
  return std::any_of(stats.setup_ms.begin(), stats.setup_ms.end(),
                     [&](const auto& item) { return item.first == name; });
}

Scene small(const std::string& json) {
  Scene scene = test::scene_from(json);
  scene.image.width = 64;
  scene.image.height = 36;
  return scene;
}

TEST(SkyProviderCache, KeepsTheProviderAndDrawsWhatEachRendererWouldDrawAlone) {
  auto context = test::make_test_context();
  const auto cache = make_sky_provider_cache();
  const Scene near = small(R"({"camera": {"height": 100, "pitch": -8}})");
  Scene sun_moved = near;
  sun_moved.sun.zenith = 75.0;
  // Another sky: a photograph (a uniform one, written here) instead of the atmosphere.
  Scene other_sky = near;
  other_sky.sky.exr = test::output_dir() + "/sky_provider_cache_test_sky.exr";
  {
    Image sky{64, 32, std::vector<float>(64 * 32 * 4, 0.05f)};
    for (std::size_t i = 3; i < sky.rgba.size(); i += 4) sky.rgba[i] = 1.0f;
    write_exr(other_sky.sky.exr, sky, ExrPixelType::Float);
  }

  // The first makes the provider and pays for it and its sky map.
  const Drawn first = draw(*context, near, cache);
  EXPECT_FALSE(first.stats.sky_provider_kept);
  EXPECT_TRUE(paid(first.stats, "sky.provider"));
  EXPECT_TRUE(paid(first.stats, "sky.map"));
  // The same sky again: kept, nothing built, the same image as one drawn alone.
  const Drawn again = draw(*context, near, cache);
  EXPECT_TRUE(again.stats.sky_provider_kept);
  EXPECT_FALSE(paid(again.stats, "sky.provider"));
  EXPECT_FALSE(paid(again.stats, "sky.map"));
  EXPECT_EQ(again.image.rgba, draw(*context, near, nullptr).image.rgba);
  EXPECT_EQ(again.image.rgba, first.image.rgba);
  // The sun moved: the provider kept, its sky map built again for the new sun.
  const Drawn moved = draw(*context, sun_moved, cache);
  EXPECT_TRUE(moved.stats.sky_provider_kept);
  EXPECT_TRUE(paid(moved.stats, "sky.map"));
  const Drawn moved_alone = draw(*context, sun_moved, nullptr);
  EXPECT_EQ(moved.image.rgba, moved_alone.image.rgba);
  EXPECT_NE(moved.image.rgba, first.image.rgba);
  // Another sky: a new provider.
  const Drawn other = draw(*context, other_sky, cache);
  EXPECT_FALSE(other.stats.sky_provider_kept);
  EXPECT_TRUE(paid(other.stats, "sky.provider"));
  EXPECT_EQ(other.image.rgba, draw(*context, other_sky, nullptr).image.rgba);
  // Back to the first sky: made anew (the cache holds one provider), the first image again.
  const Drawn back = draw(*context, near, cache);
  EXPECT_FALSE(back.stats.sky_provider_kept);
  EXPECT_EQ(back.image.rgba, first.image.rgba);
}

// From 10 km up the sky's reflection hands over to the sun-zenith-indexed array of the view from
// space (32 maps): built by the first Renderer, kept by the next.
TEST(SkyProviderCache, BuildsTheSunZenithArrayOnce) {
  auto context = test::make_test_context();
  const auto cache = make_sky_provider_cache();
  const Scene high = small(R"({"camera": {"height": 15000, "pitch": -20}})");
  Scene higher = high;
  higher.camera.height = 16000.0;
  const Drawn first = draw(*context, high, cache);
  EXPECT_TRUE(paid(first.stats, "sky.map_array"));
  const Drawn next = draw(*context, higher, cache);
  EXPECT_TRUE(next.stats.sky_provider_kept);
  EXPECT_FALSE(paid(next.stats, "sky.map_array"));
  EXPECT_FALSE(paid(next.stats, "sky.map"));  // the sea's map: the same sun at the same nadir
  EXPECT_EQ(next.image.rgba, draw(*context, higher, nullptr).image.rgba);
}

}  // namespace
}  // namespace thalassa
