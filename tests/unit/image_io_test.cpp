// Image files: EXR round trips (half and float) with metadata, the PNG's documented tone
// mapping, atomic writes (no file left on failure), and upright rows (row 0 is the top).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "thalassa/engine/file_io.hpp"
#include "thalassa/engine/image.hpp"

namespace thalassa {
namespace {

namespace fs = std::filesystem;

class ImageIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("thalassa_image_io_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::size_t file_count() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }
  fs::path dir_;
};

// A 5x3 image whose pixel (x, y) has radiance (x, y, x + 10 y) / 16, y counted from the top.
Image gradient() {
  Image image{5, 3, std::vector<float>(5 * 3 * 4)};
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      float* p = image.pixel(x, y);
      p[0] = x / 16.0f;
      p[1] = y / 16.0f;
      p[2] = (x + 10 * y) / 16.0f;
      p[3] = 1.0f;
    }
  return image;
}

TEST(NonFinitePixels, CountsThemAndNamesTheFirstInReadingOrder) {
  Image image = gradient();
  EXPECT_EQ(nonfinite_pixels(image), "");
  // Any channel, alpha included; NaN and both infinities; the first from the top left.
  image.pixel(4, 2)[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(nonfinite_pixels(image),
            "1 pixel is not finite, the first at x 4, y 2 (from the top left)");
  image.pixel(1, 1)[3] = std::numeric_limits<float>::infinity();
  image.pixel(3, 1)[0] = -std::numeric_limits<float>::infinity();
  image.pixel(3, 1)[2] = std::numeric_limits<float>::quiet_NaN();  // one pixel, two channels
  EXPECT_EQ(nonfinite_pixels(image),
            "3 pixels are not finite, the first at x 1, y 1 (from the top left)");
  // The largest finite float is finite.
  Image big = gradient();
  big.pixel(0, 0)[0] = std::numeric_limits<float>::max();
  EXPECT_EQ(nonfinite_pixels(big), "");
  EXPECT_EQ(nonfinite_pixels(Image{}), "");
}

TEST_F(ImageIo, FloatExrRoundTripIsExactAndKeepsRowsAndMetadata) {
  const Image image = gradient();
  write_exr(path("a.exr"), image, ExrPixelType::Float, {{"thalassa:scene", "{\"x\":1}"}});
  Metadata metadata;
  const Image back = read_image(path("a.exr"), &metadata);
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  EXPECT_EQ(back.rgba, image.rgba);  // bit for bit, row 0 still the top
  bool found = false;
  for (const auto& [key, value] : metadata)
    if (key == "thalassa:scene") found = value == "{\"x\":1}";
  EXPECT_TRUE(found);
}

TEST_F(ImageIo, HalfExrRoundTripWithinHalfPrecision) {
  Image image = gradient();
  image.pixel(0, 0)[0] = 1234.5f;  // radiance of a sun disc: large but within half's range
  write_exr(path("h.exr"), image, ExrPixelType::Half);
  const Image back = read_image(path("h.exr"));
  for (std::size_t i = 0; i < image.rgba.size(); ++i)
    EXPECT_NEAR(back.rgba[i], image.rgba[i], std::abs(image.rgba[i]) * 1e-3 + 1e-6) << i;
  // Half pixels really are 16-bit: the same image as float is larger on disc.
  write_exr(path("f.exr"), image, ExrPixelType::Float);
  EXPECT_LT(fs::file_size(path("h.exr")), fs::file_size(path("f.exr")));
}

TEST(ToneMap, DocumentedOperator) {
  EXPECT_EQ(tone_map(0.0, 10.0), 0.0);
  EXPECT_EQ(tone_map(-1.0, 10.0), 0.0);
  EXPECT_EQ(tone_map(std::nan(""), 10.0), 0.0);
  EXPECT_EQ(tone_map(INFINITY, 10.0), 0.0);
  // 1 - exp(-exposure L), then sRGB.
  const double v = 1.0 - std::exp(-10.0 * 0.05);
  EXPECT_NEAR(tone_map(0.05, 10.0), 1.055 * std::pow(v, 1 / 2.4) - 0.055, 1e-12);
  EXPECT_NEAR(tone_map(1e6, 10.0), 1.0, 1e-12);  // never clips abruptly, saturates at 1
  // sRGB's two pieces meet, up to the 3e-8 step that the standard's rounded constants leave.
  EXPECT_NEAR(srgb_encode(0.0031308 - 1e-12), srgb_encode(0.0031308 + 1e-12), 5e-8);
  EXPECT_NEAR(srgb_encode(1.0), 1.0, 1e-12);
  // Monotone.
  for (double l = 0.001; l < 1; l *= 1.5) EXPECT_LT(tone_map(l, 10), tone_map(l * 1.5, 10));
}

TEST(ToneMap, BlackLevelIsTheLargestRadianceEveryDitherPositionShowsAsZero) {
  for (double exposure : {1e-3, 1.0, 10.0, 1e6}) {
    const double black = png_black_level(exposure);
    ASSERT_GT(black, 0.0);
    int below = 0, above = 0;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        below += quantize_8bit(tone_map(black * (1.0 - 1e-6), exposure), x, y);
        above += quantize_8bit(tone_map(black * (1.0 + 1e-6), exposure), x, y);
      }
    EXPECT_EQ(below, 0) << exposure;  // black at every one of the 64 dither positions
    EXPECT_EQ(above, 1) << exposure;  // the largest threshold lets one of them show a step
  }
  EXPECT_EQ(png_black_level(0.0), 0.0);
  EXPECT_EQ(png_black_level(std::nan("")), 0.0);
}

TEST_F(ImageIo, PngIsToneMappedAndUpright) {
  Image image{2, 2, std::vector<float>(16, 0.0f)};
  image.pixel(0, 0)[0] = 0.05f;  // top-left red
  image.pixel(1, 1)[2] = 1.0f;   // bottom-right blue
  write_png(path("p.png"), image, 10.0);
  const Image back = read_image(path("p.png"));
  ASSERT_EQ(back.width, 2);
  EXPECT_NEAR(back.pixel(0, 0)[0], quantize_8bit(tone_map(0.05, 10), 0, 0) / 255.0, 1e-6);
  EXPECT_EQ(back.pixel(1, 0)[0], 0.0f);
  EXPECT_NEAR(back.pixel(1, 1)[2], quantize_8bit(tone_map(1.0, 10), 1, 1) / 255.0, 1e-6);
}

TEST(Quantize, DitherIsUnbiasedWithinOneStepAndExactAtTheEnds) {
  for (double v : {0.0, 1.0}) {
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) EXPECT_EQ(quantize_8bit(v, x, y), v * 255);
  }
  for (double v = 0.001; v < 1.0; v += 0.0137) {
    double sum = 0;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const int q = quantize_8bit(v, x, y);
        EXPECT_LE(std::abs(q - 255 * v), 1.0);  // never more than one step off
        sum += q;
      }
    // Over the 8x8 tile the mean is the exact value to within 1/64 step: no bias, no bands.
    EXPECT_NEAR(sum / 64, 255 * v, 1.0 / 64 + 1e-9) << v;
  }
  EXPECT_EQ(quantize_8bit(-1, 0, 0), 0);
  EXPECT_EQ(quantize_8bit(2, 0, 0), 255);
}

TEST_F(ImageIo, FailedWriteLeavesNothingBehind) {
  const Image image = gradient();
  EXPECT_THROW(write_exr(path("missing/a.exr"), image, ExrPixelType::Half), ImageError);
  EXPECT_THROW(write_exr(path("a.unknownformat"), image, ExrPixelType::Half), ImageError);
  Image broken = image;
  broken.rgba.resize(3);
  EXPECT_THROW(write_png(path("b.png"), broken, 1.0), ImageError);
  EXPECT_EQ(file_count(), 0u);
  // A failure after the temporary is complete: renaming it over a non-empty folder fails, and
  // the temporary must go.
  fs::create_directories(dir_ / "taken.exr" / "inside");
  EXPECT_THROW(write_exr(path("taken.exr"), image, ExrPixelType::Half), ImageError);
  EXPECT_THROW(write_text_atomically(path("taken.exr"), "{}"), FileError);
  EXPECT_EQ(file_count(), 1u);  // only the folder
}

TEST_F(ImageIo, OverwriteIsAtomic) {
  write_exr(path("a.exr"), gradient(), ExrPixelType::Half);
  Image other = gradient();
  other.pixel(0, 0)[0] = 7.0f;
  write_exr(path("a.exr"), other, ExrPixelType::Half);
  EXPECT_EQ(read_image(path("a.exr")).pixel(0, 0)[0], 7.0f);
  EXPECT_EQ(file_count(), 1u);  // no temporary left beside it
}

TEST_F(ImageIo, TextFilesAreWrittenAtomically) {
  write_text_atomically(path("s.json"), "{}\n");
  EXPECT_EQ(fs::file_size(path("s.json")), 3u);
  EXPECT_THROW(write_text_atomically(path("no/s.json"), "{}"), FileError);
  EXPECT_EQ(file_count(), 1u);
}

}  // namespace
}  // namespace thalassa
