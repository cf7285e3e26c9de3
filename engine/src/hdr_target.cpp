#include "thalassa/engine/gl/hdr_target.hpp"

#include <cstring>
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
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  const GLfloat zero_color[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  const GLfloat far_depth = 0.0f;
  glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, 0, zero_color);
  glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, &far_depth);
}

std::vector<float> HdrTarget::read_rgba_top_down() const {
  const std::size_t row = static_cast<std::size_t>(width_) * 4;
  std::vector<float> bottom_up(row * static_cast<std::size_t>(height_));
  // RGBA float rows are 16-byte multiples: aligned for any GL_PACK_ALIGNMENT a host has set.
  glGetTextureImage(color_.get(), 0, GL_RGBA, GL_FLOAT,
                    static_cast<GLsizei>(bottom_up.size() * sizeof(float)), bottom_up.data());
  check_error("HDR target read-back");
  std::vector<float> top_down(bottom_up.size());
  for (int y = 0; y < height_; ++y)
    std::memcpy(&top_down[static_cast<std::size_t>(y) * row],
                &bottom_up[static_cast<std::size_t>(height_ - 1 - y) * row], row * sizeof(float));
  return top_down;
}

}  // namespace thalassa::gl
