// The renderer's frame times (RenderStats::frames, frame_ms, passes): a median over the frames
// rendered since the Renderer was made or its timings were last reset (Renderer::reset_timings,
// which validate calls after its warm-up frames, so that a GPU's rising clocks stay out of the
// methods' times).
#include <gtest/gtest.h>

#include <string>

#include "test_support.hpp"
#include "thalassa/engine/gl/gl.hpp"
#include "thalassa/engine/gl/gpu_timer.hpp"
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

// Frames left in flight (gl::GpuTimer::defer_frame, the reference's samples) resolve later as
// each would have resolved at once: in order, each with its own passes, the frame's span the
// sum of its passes', and a frame resolved in between keeps its own marks.
TEST(GpuTimer, DeferredFramesResolveInOrderAsResolveWould) {
  auto context = test::make_test_context();
  for (const gl::TimingSource source :
       {gl::TimingSource::TimestampQuery, gl::TimingSource::FinishWallClock}) {
    SCOPED_TRACE(source == gl::TimingSource::TimestampQuery ? "queries" : "wall clock");
    gl::GpuTimer timer(source);
    constexpr int kFrames = 3;
    for (int f = 0; f < kFrames; ++f) {
      timer.begin_frame();
      for (int p = 0; p <= f; ++p) {
        glFlush();
        timer.end_pass("frame " + std::to_string(f) + " pass " + std::to_string(p));
      }
      timer.defer_frame();
    }
    EXPECT_EQ(timer.deferred_frames(), std::size_t(kFrames));
    timer.begin_frame();
    timer.end_pass("at once");
    gl::PassTime now;
    const std::vector<gl::PassTime> passes = timer.resolve(now);
    ASSERT_EQ(passes.size(), 1u);
    EXPECT_EQ(passes[0].name, "at once");

    const std::vector<gl::GpuTimer::FrameTimes> frames = timer.resolve_deferred();
    EXPECT_EQ(timer.deferred_frames(), 0u);
    ASSERT_EQ(frames.size(), std::size_t(kFrames));
    const bool wall = source == gl::TimingSource::FinishWallClock;
    for (int f = 0; f < kFrames; ++f) {
      ASSERT_EQ(frames[f].passes.size(), std::size_t(f + 1));
      double sum = 0.0;
      for (int p = 0; p <= f; ++p) {
        const gl::PassTime& pass = frames[f].passes[p];
        EXPECT_EQ(pass.name, "frame " + std::to_string(f) + " pass " + std::to_string(p));
        sum += wall ? pass.wall_ms : pass.query_ms;
      }
      const double frame_ms = wall ? frames[f].frame.wall_ms : frames[f].frame.query_ms;
      EXPECT_GE(frame_ms, 0.0);
      EXPECT_NEAR(sum, frame_ms, 1e-9 * frame_ms + 1e-9);
    }
    EXPECT_EQ(timer.fallback_frames(), 0);
    EXPECT_TRUE(timer.resolve_deferred().empty());
  }
}

}  // namespace
}  // namespace thalassa
