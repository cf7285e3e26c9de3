#include "thalassa/engine/gl/hdr_target.hpp"

#include "thalassa/engine/gl/state_guard.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace thalassa::gl {

HdrTarget::HdrTarget(int width, int height)
    : width_(width),
      height_(height),
      color_(make_texture(GL_TEXTURE_2D)),
      depth_(make_texture(GL_TEXTURE_2D)),
      framebuffer_(make_framebuffer()) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    throw GlError("HDR target: " + std::to_string(width) + "x" + std::to_string(height) +
                  " is outside 1.." + std::to_string(max_size) + " pixels on this GL");
  glTextureStorage2D(color_.get(), 1, GL_RGBA32F, width, height);
  glTextureParameteri(color_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(color_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureStorage2D(depth_.get(), 1, GL_DEPTH_COMPONENT32F, width, height);
  glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, color_.get(), 0);
  glNamedFramebufferTexture(framebuffer_.get(), GL_DEPTH_ATTACHMENT, depth_.get(), 0);
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.get(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("HDR target: framebuffer incomplete (status " + std::to_string(status) + ")");
  check_error("HDR target creation");
}

void HdrTarget::begin() {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, width_, height_);
  set_pass_state();
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  const GLfloat zero_color[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  const GLfloat far_depth = 0.0f;
  glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, 0, zero_color);
  glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, &far_depth);
}

std::vector<float> read_texture_rgba_top_down(GLuint texture, int width, int height,
                                              const char* what) {
  const StateGuard guard;  // the pack state below is a host's to keep
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glPixelStorei(GL_PACK_SKIP_ROWS, 0);
  glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  std::vector<float> pixels(row * static_cast<std::size_t>(height));
  const std::size_t bytes = pixels.size() * sizeof(float);
  // The scene caps images at 8192 x 8192 (1 GiB of RGBA floats), below GLsizei's 2 GiB.
  if (bytes > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max()))
    throw GlError(std::string(what) + ": " + std::to_string(width) + "x" + std::to_string(height) +
                  " is larger than one GL read can return");
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(bytes), pixels.data());
  check_error(what);
  // GL's rows run bottom-up: flip in place (no second copy of a possibly large image).
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(pixels.begin() + static_cast<std::ptrdiff_t>(y * row),
                     pixels.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     pixels.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
  return pixels;
}

std::vector<float> HdrTarget::read_rgba_top_down() const {
  return read_texture_rgba_top_down(color_.get(), width_, height_, "HDR target read-back");
}

void HdrTarget::write_rgba_top_down(const std::vector<float>& rgba) {
  const std::size_t row = std::size_t(width_) * 4;
  if (rgba.size() != row * std::size_t(height_))
    throw GlError("HDR target write: expected " + std::to_string(row * height_) + " floats, got " +
                  std::to_string(rgba.size()));
  std::vector<float> bottom_up(rgba.size());
  for (int y = 0; y < height_; ++y)
    std::copy_n(rgba.begin() + std::ptrdiff_t(y * row), row,
                bottom_up.begin() + std::ptrdiff_t((height_ - 1 - y) * row));
  const StateGuard guard;  // the unpack state below is a host's to keep
  set_pass_state();        // client memory, tightly packed
  glTextureSubImage2D(color_.get(), 0, 0, 0, width_, height_, GL_RGBA, GL_FLOAT, bottom_up.data());
  check_error("HDR target write");
}

}  // namespace thalassa::gl
