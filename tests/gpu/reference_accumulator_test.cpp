// The reference method's running sums on the GPU (planet/src/reference_accumulator.hpp,
// shaders/planet/reference_accumulate.comp) against their host twin, add_reference_sample:
// every sum the same to the last bit after several samples, on the sky, the sea resolved and
// not, and on the inputs a driver may treat loosely (NaN and infinite radiance or alpha, alpha
// at the sea's threshold), on an image whose sides are not multiples of the pass's work group.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

#include "reference_accumulator.hpp"
#include "test_support.hpp"
#include "thalassa/engine/gl/gl.hpp"
#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/shader_library.hpp"

namespace thalassa {
namespace {

// The same double, bit for bit (two NaNs of any payload count as the same: the host and the
// GPU need not agree on a NaN's bits, only on its being one).
bool SameBits(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool SameBits(const glm::dvec3& a, const glm::dvec3& b) {
  return SameBits(a.x, b.x) && SameBits(a.y, b.y) && SameBits(a.z, b.z);
}

TEST(ReferenceAccumulator, GpuSumsAreTheHostsSums) {
  auto context = test::make_test_context();
  gl::ShaderLibrary shaders;
  constexpr int kWidth = 13, kHeight = 7;  // neither a multiple of the work group's 8
  constexpr int kSamples = 6;
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  ReferenceAccumulator accumulator(kWidth, kHeight, shaders);
  gl::Texture texture = gl::make_texture(GL_TEXTURE_2D);
  glTextureStorage2D(texture.get(), 1, GL_RGBA32F, kWidth, kHeight);
  glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  // The kinds of sample: alpha = `alpha` + `spread` x a weight in [0, 5); radiance channel
  // `bad_channel` (none if -1) set to `bad`.
  struct SampleKind {
    float alpha, spread;
    int bad_channel;
    float bad;
  };
  const SampleKind kKinds[] = {
      {1.0f, 0.0f, -1, 0.0f},                        // the sky
      {2.0f, 1.0f, -1, 0.0f},                        // the sea, resolved
      {-2.0f, -1.0f, -1, 0.0f},                      // the sea, unresolved
      {2.0f, 0.0f, -1, 0.0f},                        // the sea, weight 0
      {2.0f, 1e-7f, -1, 0.0f},                       // weights near 0
      {std::nextafter(2.0f, 0.0f), 0.0f, -1, 0.0f},  // just below the sea's threshold: the sky
      {2.5f, 0.0f, 0, kNaN},                         // radiance not finite, on the sea
      {1.0f, 0.0f, 1, kInf},                         // and on the sky
      {-3.0f, 0.0f, 2, -kInf},                       // and on the unresolved sea
      {kNaN, 0.0f, -1, 0.0f},                        // alpha NaN: the sky's
      {kInf, 0.0f, -1, 0.0f},                        // alpha +inf: the sea, weight 0
      {-kInf, 0.0f, -1, 0.0f},                       // alpha -inf: the sea, unresolved
  };
  std::vector<ReferencePixelSums> expected(kWidth * kHeight);  // rows from the top
  std::mt19937 random(20261127);
  std::uniform_real_distribution<float> radiance(0.0f, 3.0f), weight(0.0f, 5.0f);
  for (int k = 0; k < kSamples; ++k) {
    std::vector<float> gl_rows(4 * kWidth * kHeight);  // GL's rows, from the bottom
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        // Each pixel its own kind, a different one on each sample.
        const SampleKind& kind = kKinds[std::size_t(x + 3 * y + k) % std::size(kKinds)];
        float p[4] = {radiance(random), radiance(random), radiance(random),
                      kind.alpha + kind.spread * weight(random)};
        if (kind.bad_channel >= 0) p[kind.bad_channel] = kind.bad;
        std::memcpy(&gl_rows[4 * std::size_t((kHeight - 1 - y) * kWidth + x)], p, sizeof p);
        add_reference_sample(expected[std::size_t(y * kWidth + x)], p);
      }
    glTextureSubImage2D(texture.get(), 0, 0, 0, kWidth, kHeight, GL_RGBA, GL_FLOAT, gl_rows.data());
    accumulator.add(texture.get());
  }
  const std::vector<ReferencePixelSums> sums = accumulator.read();
  ASSERT_EQ(sums.size(), expected.size());
  int nonfinite_pixels = 0, sea_pixels = 0;
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const ReferencePixelSums &got = sums[i], &want = expected[i];
    SCOPED_TRACE("pixel " + std::to_string(i % kWidth) + ", " + std::to_string(i / kWidth));
    EXPECT_TRUE(SameBits(got.sky, want.sky));
    EXPECT_TRUE(SameBits(got.weighted, want.weighted));
    EXPECT_TRUE(SameBits(got.plain, want.plain));
    EXPECT_TRUE(SameBits(got.weight, want.weight));
    EXPECT_EQ(got.sea, want.sea);
    EXPECT_EQ(got.resolved, want.resolved);
    EXPECT_EQ(got.nonfinite, want.nonfinite);
    nonfinite_pixels += want.nonfinite > 0;
    sea_pixels += want.sea > 0;
  }
  // The inputs reached every branch.
  EXPECT_GT(nonfinite_pixels, 0);
  EXPECT_GT(sea_pixels, 0);

  // clear() starts again from 0.
  accumulator.clear();
  for (const ReferencePixelSums& p : accumulator.read()) {
    EXPECT_EQ(p.sky, glm::dvec3(0.0));
    EXPECT_EQ(p.weight, 0.0);
    EXPECT_EQ(p.sea + p.resolved + p.nonfinite, 0);
  }
}

// The host twin's rules, which the reference's image relies on.
TEST(ReferenceAccumulator, HostTwinCountsEachKindOfSample) {
  ReferencePixelSums sums;
  const float sky[4] = {1.0f, 2.0f, 3.0f, 1.0f};
  const float sea[4] = {2.0f, 2.0f, 2.0f, 2.5f};          // weight 0.5, resolved
  const float unresolved[4] = {4.0f, 4.0f, 4.0f, -3.0f};  // weight 1, not resolved
  add_reference_sample(sums, sky);
  add_reference_sample(sums, sea);
  add_reference_sample(sums, unresolved);
  EXPECT_EQ(sums.sky, glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(sums.sea, 2);
  EXPECT_EQ(sums.resolved, 2);
  EXPECT_DOUBLE_EQ(sums.weight, 1.5);
  // The sea's mean weighted by w: (0.5 x 2 + 1 x 4) / 1.5.
  EXPECT_DOUBLE_EQ(sums.sea_mean().x, 5.0 / 1.5);
  // The pixel over 3 samples: (sky + 2 x sea mean) / 3.
  EXPECT_DOUBLE_EQ(sums.mean(3).x, (1.0 + 2.0 * 5.0 / 1.5) / 3.0);
  EXPECT_EQ(sums.nonfinite, 0);
  const float bad[4] = {std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f, 1.0f};
  add_reference_sample(sums, bad);
  EXPECT_EQ(sums.nonfinite, 1);
}

}  // namespace
}  // namespace thalassa
