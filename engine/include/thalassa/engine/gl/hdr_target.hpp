// thalassa — the linear HDR framebuffer every frame is drawn into (DESIGN section 3, step 3):
// RGBA32F colour (radiance in W m^-2 sr^-1 nm^-1 per channel, alpha unused = 1) and a 32-bit
// float depth buffer set up for reversed-Z (clip control zero-to-one, cleared to 0, GL_GREATER),
// which keeps depth precision from 1 m to 36,000 km.
#pragma once

#include "thalassa/engine/gl/objects.hpp"

#include <vector>

namespace thalassa::gl {

// Reads level 0 of a 2D texture of width x height texels as RGBA floats, top row first (GL's
// rows are bottom-up, so row 0 of the result is t = 1). Leaves the pack state as it found it;
// throws GlError naming `what` if the read fails or is larger than one GL read can return.
std::vector<float> read_texture_rgba_top_down(GLuint texture, int width, int height,
                                              const char* what);

class HdrTarget {
 public:
  HdrTarget(int width, int height);  // throws GlError if the framebuffer is incomplete

  int width() const { return width_; }
  int height() const { return height_; }
  GLuint framebuffer() const { return framebuffer_.get(); }
  GLuint color_texture() const { return color_.get(); }
  GLuint depth_texture() const { return depth_.get(); }

  // Binds the framebuffer, sets the viewport, reversed-Z state, and clears colour to 0 and
  // depth to 0 (the far plane under reversed-Z).
  void begin();
  // Reads the colour back as RGBA floats, top row first (GL's rows are bottom-up).
  std::vector<float> read_rgba_top_down() const;
  // Replaces the colour with RGBA floats given top row first (width * height * 4 of them), as a
  // supersampled image's average.
  void write_rgba_top_down(const std::vector<float>& rgba);

 private:
  int width_;
  int height_;
  Texture color_;
  Texture depth_;
  Framebuffer framebuffer_;
};

}  // namespace thalassa::gl
