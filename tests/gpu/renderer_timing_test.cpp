// The renderer's frame times (RenderStats::frames, frame_ms, passes): a median over the frames
// rendered since the Renderer was made or its timings were last reset (Renderer::reset_timings,
// which validate calls after its warm-up frames, so that a GPU's rising clocks stay out of the
// methods' times).
#include <gtest/gtest.h>

#include "test_support.hpp"
#include "thalassa/planet/renderer.hpp"

namespace thalassa {
namespace {

TEST(RendererTiming, ResetForgetsTheFramesBefore) {
  auto context = test::make_test_context();
  Scene scene = test::scene_from(R"({"camera": {"height": 10, "pitch": -10}})");
  scene.image.width = 32;
  scene.image.height = 24;
  Renderer renderer(*context, scene);
  // The constructor's frame (which compiles the shaders) is not counted.
  EXPECT_EQ(renderer.stats().frames, 0);
  for (int k = 0; k < 3; ++k) renderer.render();
  const RenderStats warm = renderer.stats();
  EXPECT_EQ(warm.frames, 3);
  EXPECT_GT(warm.frame_ms, 0.0);
  EXPECT_FALSE(warm.passes.empty());
  renderer.reset_timings();
  const RenderStats reset = renderer.stats();
  EXPECT_EQ(reset.frames, 0);
  EXPECT_EQ(reset.frame_ms, 0.0);
  EXPECT_EQ(reset.timing_fallback_frames, 0);
  renderer.render();
  renderer.render();
  const RenderStats timed = renderer.stats();
  EXPECT_EQ(timed.frames, 2);
  EXPECT_GT(timed.frame_ms, 0.0);
  // The same passes are timed again, each a median of the two frames since the reset.
  ASSERT_EQ(timed.passes.size(), warm.passes.size());
  for (std::size_t i = 0; i < timed.passes.size(); ++i) {
    EXPECT_EQ(timed.passes[i].first, warm.passes[i].first);
    EXPECT_GE(timed.passes[i].second, 0.0);
  }
}

}  // namespace
}  // namespace thalassa
