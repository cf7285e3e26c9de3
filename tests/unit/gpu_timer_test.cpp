// The check on GL timestamps (thalassa/engine/gl/gpu_timer.hpp): a span is used only where it
// can be one of the frame's.
#include "thalassa/engine/gl/gpu_timer.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace thalassa::gl {
namespace {

// NVIDIA's stamps are nanoseconds since 1970: the first GPU run's was 1.7957e18.
constexpr std::uint64_t kStamp = 1'795'687'305'217'000'000ull;

TEST(GpuTimer, TimestampSpanIsTheDifferenceInMilliseconds) {
  const auto span = timestamp_span_ms(kStamp, kStamp + 2'500'000, 10.0);
  ASSERT_TRUE(span.has_value());
  EXPECT_DOUBLE_EQ(*span, 2.5);
  EXPECT_EQ(timestamp_span_ms(kStamp, kStamp, 0.0), 0.0);  // an empty pass, an instant frame
}

TEST(GpuTimer, AZeroStampIsNoTime) {
  // The first GPU run's garbage: 0 for the frame's first mark read as 1.8e12 ms.
  EXPECT_FALSE(timestamp_span_ms(0, kStamp, 1e300).has_value());
  EXPECT_FALSE(timestamp_span_ms(kStamp, 0, 1e300).has_value());
}

TEST(GpuTimer, ABackwardSpanIsNoTime) {
  EXPECT_FALSE(timestamp_span_ms(kStamp + 1, kStamp, 1e300).has_value());
}

TEST(GpuTimer, ASpanLongerThanTheHostWaitedIsNoTime) {
  // 20 ms on the GPU cannot fit in 10 ms of the host's time; 10.05 is within the slack.
  EXPECT_FALSE(timestamp_span_ms(kStamp, kStamp + 20'000'000, 10.0).has_value());
  EXPECT_TRUE(timestamp_span_ms(kStamp, kStamp + 10'050'000, 10.0).has_value());
  EXPECT_FALSE(timestamp_span_ms(kStamp, kStamp + 10'300'000, 10.0).has_value());
}

}  // namespace
}  // namespace thalassa::gl
