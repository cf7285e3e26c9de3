// thalassa — HDR images and their files: EXR (linear radiance, half or float, with metadata)
// and PNG (tone-mapped), both through OpenImageIO, both written atomically.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "thalassa/engine/scene.hpp"

namespace thalassa {

// An RGBA float image, rows top first. Colour is linear spectral radiance
// (W m^-2 sr^-1 nm^-1 at 680, 550, 440 nm); alpha is 1 where something was drawn.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // width * height * 4

  float* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const float* pixel(int x, int y) const {
    return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
  }
};

// Reading or writing an image failed. The message names the file.
class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The PNG's tone mapping, per channel: v = 1 - exp(-exposure * L) (an exponential shoulder that
// never clips: Bruneton's 2017 demo uses the same), then the sRGB transfer function (IEC
// 61966-2-1), then quantize_8bit(). Non-finite or negative radiance maps to 0.
double tone_map(double radiance, double exposure);
double srgb_encode(double linear);  // [0, 1] -> [0, 1]
// Rounds an encoded value in [0, 1] to 8 bits with an 8x8 ordered (Bayer) dither of the pixel
// (x, y), y counted from the top: floor(255 v + 0.5 + d(x, y)), d in (-0.5, 0.5) with mean 0.
// Sky and sea gradients change by less than one 8-bit step over tens of pixels; plain rounding
// shows those steps as bands, the dither does not. Deterministic, so PNGs stay reproducible.
unsigned char quantize_8bit(double encoded, int x, int y);
// The radiance (W m^-2 sr^-1 nm^-1) below which write_png shows 0 wherever the pixel lies in the
// dither: quantize_8bit gives 0 below an encoded value of 1/255 times the largest dither
// threshold's distance from the next step, 0.5 / 64. Radiance below it is black in every PNG of
// that exposure (2.4e-7 at the default exposure 10); the validation calls a reference term black
// when none of its pixels reaches it (docs/validation.md). 0 for an exposure that is not > 0.
double png_black_level(double exposure);

// "" when every channel of every pixel is finite; otherwise what is not, for an error message
// (DESIGN section 4: finite results or a clear error, never NaN): how many pixels, and the first
// in reading order, x from the left and y from the top row, as an image viewer counts them. The
// command line refuses to write a rendered image that is not finite.
std::string nonfinite_pixels(const Image& image);

using Metadata = std::vector<std::pair<std::string, std::string>>;

// Writes an OpenEXR file of RGBA (half or float) with each metadata entry as a string
// attribute ("thalassa:scene", "thalassa:camera", ...). The file appears complete or not at
// all: it is written to a temporary name in the same folder, then renamed.
void write_exr(const std::string& path, const Image& image, ExrPixelType type,
               const Metadata& metadata = {});
// Writes an 8-bit sRGB PNG tone-mapped with tone_map(), atomically.
void write_png(const std::string& path, const Image& image, double exposure,
               const Metadata& metadata = {});
// Reads any image OpenImageIO can read as RGBA float, rows top first (for tests and tools).
Image read_image(const std::string& path, Metadata* metadata = nullptr);

}  // namespace thalassa
