// thalassa — the reference method's running per-pixel sums, kept on the GPU.
//
// The reference (Renderer, issue 6 point 1) averages thousands of frames per image. Until stop
// 32 each frame was read back and added up on the host: a wait for the GPU and a read-back per
// sample, 0.76 ms of the host's per sample on an NVIDIA H200 (docs/validation.md, stop 30),
// more than the sample's own GPU time for the sky and the refracted light. Now a compute pass
// adds each sample to sums in a GPU buffer (shaders/planet/reference_accumulate.comp, in double
// precision, the same operations as add_reference_sample below) and the host reads them once per
// doubling of the samples.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/shader_library.hpp"

namespace thalassa {

// The sea's samples carry |alpha| >= this (shaders/ocean/ocean_lighting.frag,
// REFERENCE_SEA_ALPHA: 2 + the sample's visible-area weight), every other pass 1.
inline constexpr double kReferenceSeaAlpha = 2.0;

// One pixel's sums over the reference's samples; the layout of reference_accumulate.comp's
// PixelSums (std430, 96 bytes).
struct ReferencePixelSums {
  glm::dvec3 sky{0.0};         // sum of the sky's samples' radiance (W m^-2 sr^-1)
  glm::dvec3 weighted{0.0};    // sum of w L over the sea's samples
  glm::dvec3 plain{0.0};       // sum of L over the sea's samples (where every w is 0)
  double weight = 0.0;         // sum of w
  std::int32_t sea = 0;        // the sea's samples
  std::int32_t resolved = 0;   // samples whose sun resolved every wave (each of the sky's)
  std::int32_t nonfinite = 0;  // samples whose radiance was not finite (counted as given)
  std::int32_t unused = 0;

  // The sea's samples averaged with their weights (0 without any).
  glm::dvec3 sea_mean() const {
    return weight > 0.0 ? weighted / weight : sea > 0 ? plain / double(sea) : glm::dvec3(0.0);
  }
  // The pixel: (sum of sky samples + n_sea x sum(w L) / sum(w)) / count.
  glm::dvec3 mean(int count) const { return (sky + double(sea) * sea_mean()) / double(count); }
};

// Adds one sample's pixel (RGBA as the reference's frame holds it: radiance, and in alpha 1 for
// the sky or +-(2 + w) for the sea, negative where the sun was not resolved) to `sums`: the
// host's twin of reference_accumulate.comp. A sample whose alpha is NaN counts as the sky's;
// one whose alpha is infinite as the sea's with weight 0.
void add_reference_sample(ReferencePixelSums& sums, const float rgba[4]);

// The sums of a width x height image's samples in a GPU buffer (the context must be current
// for every call, and the one the accumulator was made in).
class ReferenceAccumulator {
 public:
  // Makes the buffer and compiles the pass (so that no sample's time includes compiling it);
  // `shaders` must outlive the accumulator.
  ReferenceAccumulator(int width, int height, gl::ShaderLibrary& shaders);

  // Sets every sum to 0.
  void clear();
  // Adds the sample in `texture` (RGBA32F, width x height, GL's rows from the bottom; complete
  // for texelFetch). Queued on the GPU: nothing waits.
  void add(GLuint texture);
  // The sums so far, rows from the top (waits for the GPU).
  std::vector<ReferencePixelSums> read() const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  gl::Buffer buffer_;
  GLuint program_;  // the shader library's
  GLint size_location_, image_location_;  // its uniforms image_size and sample_image
};

}  // namespace thalassa
