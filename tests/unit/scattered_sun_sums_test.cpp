// The check of the reference's scattered sun (ocean/src/scattered_sun_sums.hpp): sums a scatter
// can write pass; the H200's fault of stop 40, the buffer read back as GLSL source text, is
// caught, as are the other things no scatter writes (not finite, negative, a solid angle past
// the sphere's, more unresolved solid angle than solid angle).

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scattered_sun_sums.hpp"

namespace thalassa::ocean {
namespace {

constexpr int kWidth = 16, kHeight = 9;

// Sums a scatter could write: each pixel's solid angle about a 128 x 72 image's pixel's (1.2e-4
// sr), part of it unresolved or hidden, and a sun factor up to 1e6 per sr (a bright glint's).
std::vector<float> plausible_sums(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> sums(4 * kWidth * kHeight);
  for (int i = 0; i < kWidth * kHeight; ++i) {
    const float omega = 1.2e-4f * unit(random);
    sums[4 * i + 0] = omega * 1e6f * unit(random) * unit(random);
    sums[4 * i + 1] = omega;
    sums[4 * i + 2] = i % 3 == 0 ? omega : 0.0f;  // a footprint past the cap: all of it
    sums[4 * i + 3] = 0.3f * omega * unit(random);
  }
  sums[0] = 2e-6f;  // a glint in a pixel no cell's centre fell in (sum omega 0)
  sums[1] = sums[2] = sums[3] = 0.0f;
  return sums;
}

TEST(ScatteredSunSums, WhatAScatterWritesPasses) {
  for (unsigned seed = 0; seed < 20; ++seed)
    EXPECT_EQ(scattered_sun_sums_fault(plausible_sums(seed), kWidth, kHeight), "") << seed;
  EXPECT_EQ(
      scattered_sun_sums_fault(std::vector<float>(4 * kWidth * kHeight, 0.0f), kWidth, kHeight),
      "");
}

// The bytes the H200 read back (stop 40: "Tail(IN(Number) " and "tion w (tangent " in the two
// references' first bad pixels), and other stretches of the shaders' source, laid over the buffer
// from every offset: each is caught.
TEST(ScatteredSunSums, SourceTextIsCaught) {
  const std::vector<std::string> texts = {
      "Tail(IN(Number) ", "tion w (tangent ",
      "// The reference method's reflected sun (issue 6, point 1; Bruneton, Neyret & ",
      "  const vec3 centre = 0.25 * (c00.position + c10.position + c01.position + c11.position);"};
  for (const std::string& text : texts)
    for (std::size_t offset = 0; offset < text.size(); ++offset) {
      std::vector<float> sums(4 * kWidth * kHeight);
      for (std::size_t i = 0; i < sums.size(); ++i) {
        char word[4];
        for (std::size_t b = 0; b < 4; ++b) word[b] = text[(offset + 4 * i + b) % text.size()];
        std::memcpy(&sums[i], word, sizeof(float));
      }
      const std::string fault = scattered_sun_sums_fault(sums, kWidth, kHeight);
      EXPECT_NE(fault, "") << '"' << text << "\" from " << offset;
    }
}

TEST(ScatteredSunSums, WhatNoScatterWritesIsCaughtAndPlaced) {
  struct Bad {
    int component;
    float value;
    const char* why;
  };
  const float inf = std::numeric_limits<float>::infinity();
  for (const Bad& bad :
       {Bad{0, std::nanf(""), "not finite"}, Bad{1, inf, "not finite"}, Bad{3, -1e-9f, "negative"},
        Bad{1, 13.0f, "larger than the sphere"}, Bad{3, 13.0f, "larger than the sphere"}}) {
    std::vector<float> sums = plausible_sums(1);
    const int x = 5, y = 7;
    sums[4 * (y * kWidth + x) + bad.component] = bad.value;
    const std::string fault = scattered_sun_sums_fault(sums, kWidth, kHeight);
    EXPECT_NE(fault.find(bad.why), std::string::npos) << fault;
    EXPECT_NE(fault.find("(5, 7)"), std::string::npos) << fault;
  }
  // More unresolved than solid angle, past the float additions' slack; within it, none.
  std::vector<float> sums = plausible_sums(2);
  const int i = 4 * (3 * kWidth + 2);
  sums[i + 1] = 1e-4f;
  sums[i + 2] = 1e-4f * (1.0f + 0.5f * float(kScatteredSunUnresolvedSlack));
  EXPECT_EQ(scattered_sun_sums_fault(sums, kWidth, kHeight), "");
  sums[i + 2] = 1e-4f * (1.0f + 2.0f * float(kScatteredSunUnresolvedSlack));
  EXPECT_NE(scattered_sun_sums_fault(sums, kWidth, kHeight).find("more unresolved"),
            std::string::npos);
  // A sun factor past a float's range (the lighting divides in float).
  sums = plausible_sums(3);
  sums[i + 0] = 1e30f;
  sums[i + 1] = 1e-10f;
  sums[i + 2] = 0.0f;
  EXPECT_NE(scattered_sun_sums_fault(sums, kWidth, kHeight).find("sun factor"), std::string::npos);
  // The wrong size.
  EXPECT_NE(scattered_sun_sums_fault(plausible_sums(4), kWidth, kHeight + 1), "");
}

// The cells' solid angle against the sea's in the image: at least half passes (the facets facing
// away from the eye are in neither sum), zeros, a few pixels' worth or NaN do not; no sea in view
// checks nothing.
TEST(ScatteredSunSums, CoverageBelowHalfTheSeaIsCaught) {
  const std::vector<float> sums = plausible_sums(5);
  double covered = 0.0;
  for (std::size_t i = 0; i < sums.size(); i += 4) covered += double(sums[i + 1]) + sums[i + 3];
  EXPECT_EQ(scattered_sun_coverage_fault(sums, covered), "");
  EXPECT_EQ(scattered_sun_coverage_fault(sums, 1.9 * covered), "");
  const std::string fault = scattered_sun_coverage_fault(sums, 2.1 * covered);
  EXPECT_NE(fault.find("under 0.5 of the sea's"), std::string::npos) << fault;
  EXPECT_NE(scattered_sun_coverage_fault(std::vector<float>(sums.size(), 0.0f), 1e-3), "");
  std::vector<float> unwritten = sums;
  unwritten[5] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(scattered_sun_coverage_fault(unwritten, covered), "");
  EXPECT_EQ(scattered_sun_coverage_fault(std::vector<float>(sums.size(), 0.0f), 0.0), "");
}

}  // namespace
}  // namespace thalassa::ocean
