#include "thalassa/engine/image.hpp"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace thalassa {
namespace {

namespace fs = std::filesystem;
namespace oiio = OIIO;

// sRGB (IEC 61966-2-1): linear segment below this value, power 1/2.4 above.
constexpr double kSrgbLinearThreshold = 0.0031308;
constexpr double kSrgbLinearSlope = 12.92;

void check_image(const std::string& path, const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4)
    throw ImageError(path + ": image has inconsistent size " + std::to_string(image.width) + "x" +
                     std::to_string(image.height));
}

// A temporary path beside `path`, with the same extension (OpenImageIO picks the format by it).
fs::path temporary_path(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  fs::path folder = path.parent_path();
  const std::string name = "." + path.stem().string() + ".tmp-" + std::to_string(getpid()) + "-" +
                           std::to_string(counter++) + path.extension().string();
  return folder / name;
}

// Writes with `spec` and `pixels` (of `format`) to a temporary file, then renames it to `path`.
void write_atomically(const std::string& path, const oiio::ImageSpec& spec, oiio::TypeDesc format,
                      const void* pixels) {
  const fs::path target(path);
  std::error_code ec;
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(folder, ec)) throw ImageError(path + ": folder does not exist");
  const fs::path temporary = temporary_path(target);
  auto output = oiio::ImageOutput::create(temporary.string());
  if (!output) throw ImageError(path + ": no image writer for this extension: " + oiio::geterror());
  bool ok = output->open(temporary.string(), spec) && output->write_image(format, pixels);
  std::string error = ok ? "" : output->geterror();
  ok = output->close() && ok;
  if (ok) {
    fs::rename(temporary, target, ec);
    if (ec) {
      ok = false;
      error = ec.message();
    }
  }
  if (!ok) {
    fs::remove(temporary, ec);
    throw ImageError(path + ": cannot write: " + (error.empty() ? "unknown error" : error));
  }
}

}  // namespace

unsigned char quantize_8bit(double encoded, int x, int y) {
  // Bayer's 8x8 threshold matrix: each of 0..63 once, neighbours far apart.
  static constexpr unsigned char kBayer[8][8] = {
      {0, 32, 8, 40, 2, 34, 10, 42},  {48, 16, 56, 24, 50, 18, 58, 26},
      {12, 44, 4, 36, 14, 46, 6, 38}, {60, 28, 52, 20, 62, 30, 54, 22},
      {3, 35, 11, 43, 1, 33, 9, 41},  {51, 19, 59, 27, 49, 17, 57, 25},
      {15, 47, 7, 39, 13, 45, 5, 37}, {63, 31, 55, 23, 61, 29, 53, 21}};
  const double dither = (kBayer[y & 7][x & 7] + 0.5) / 64.0 - 0.5;
  const double level = std::floor(255.0 * std::clamp(encoded, 0.0, 1.0) + 0.5 + dither);
  return static_cast<unsigned char>(std::clamp(level, 0.0, 255.0));
}

double srgb_encode(double linear) {
  const double x = std::clamp(linear, 0.0, 1.0);
  return x <= kSrgbLinearThreshold ? kSrgbLinearSlope * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

double png_black_level(double exposure) {
  if (!(exposure > 0.0)) return 0.0;
  // Inverts tone_map: the encoded value, then the sRGB curve's linear segment (the value lies
  // far below kSrgbLinearThreshold), then 1 - exp(-exposure L).
  constexpr double kSmallestVisibleEncoded = 0.5 / 64.0 / 255.0;
  return -std::log1p(-kSmallestVisibleEncoded / kSrgbLinearSlope) / exposure;
}

std::string nonfinite_pixels(const Image& image) {
  std::size_t count = 0;
  std::size_t first = 0;
  for (std::size_t p = 0; 4 * p + 3 < image.rgba.size(); ++p) {
    const float* v = &image.rgba[4 * p];
    if (std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]))
      continue;
    if (count++ == 0) first = p;
  }
  if (count == 0) return "";
  const std::size_t width = static_cast<std::size_t>(std::max(image.width, 1));
  return std::to_string(count) + (count == 1 ? " pixel is" : " pixels are") +
         " not finite, the first at x " + std::to_string(first % width) + ", y " +
         std::to_string(first / width) + " (from the top left)";
}

double tone_map(double radiance, double exposure) {
  if (!std::isfinite(radiance) || radiance <= 0.0 || !(exposure > 0.0)) return 0.0;
  return srgb_encode(-std::expm1(-exposure * radiance));
}

void write_exr(const std::string& path, const Image& image, ExrPixelType type,
               const Metadata& metadata) {
  check_image(path, image);
  const oiio::TypeDesc format =
      type == ExrPixelType::Half ? oiio::TypeDesc::HALF : oiio::TypeDesc::FLOAT;
  oiio::ImageSpec spec(image.width, image.height, 4, format);
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  for (const auto& [key, value] : metadata) spec.attribute(key, value);
  write_atomically(path, spec, oiio::TypeDesc::FLOAT, image.rgba.data());
}

void write_png(const std::string& path, const Image& image, double exposure,
               const Metadata& metadata) {
  check_image(path, image);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(image.width) * image.height * 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * image.width + x;
      for (int c = 0; c < 3; ++c)
        bytes[i * 3 + c] = quantize_8bit(tone_map(image.rgba[i * 4 + c], exposure), x, y);
    }
  oiio::ImageSpec spec(image.width, image.height, 3, oiio::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  for (const auto& [key, value] : metadata) spec.attribute(key, value);
  write_atomically(path, spec, oiio::TypeDesc::UINT8, bytes.data());
}

Image read_image(const std::string& path, Metadata* metadata) {
  auto input = oiio::ImageInput::open(path);
  if (!input) throw ImageError(path + ": cannot read: " + oiio::geterror());
  const oiio::ImageSpec& spec = input->spec();
  Image image;
  image.width = spec.width;
  image.height = spec.height;
  const int channels = spec.nchannels;
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * channels);
  if (!input->read_image(0, 0, 0, channels, oiio::TypeDesc::FLOAT, pixels.data()))
    throw ImageError(path + ": cannot read pixels: " + input->geterror());
  image.rgba.assign(static_cast<std::size_t>(spec.width) * spec.height * 4, 1.0f);
  for (std::size_t i = 0, n = static_cast<std::size_t>(spec.width) * spec.height; i < n; ++i)
    for (int c = 0; c < std::min(channels, 4); ++c)
      image.rgba[i * 4 + c] = pixels[i * channels + c];
  if (channels < 3)  // grey: copy to G and B
    for (std::size_t i = 0, n = static_cast<std::size_t>(spec.width) * spec.height; i < n; ++i)
      image.rgba[i * 4 + 1] = image.rgba[i * 4 + 2] = image.rgba[i * 4];
  if (metadata) {
    for (const auto& attribute : spec.extra_attribs)
      if (attribute.type() == oiio::TypeDesc::STRING)
        metadata->emplace_back(attribute.name().string(), attribute.get_string());
  }
  input->close();
  return image;
}

}  // namespace thalassa
