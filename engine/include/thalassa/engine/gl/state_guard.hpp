// thalassa — saves the GL state thalassa's passes change and restores it on destruction, so that
// drawing into a host application's context leaves the host's state as it was: framebuffer
// bindings, viewport, program, vertex array, depth test/function/mask, clip control (thalassa
// uses reversed-Z, zero-to-one), the uniform buffer binding 0 and texture unit 0.
#pragma once

#include "thalassa/engine/gl/gl.hpp"

namespace thalassa::gl {

class StateGuard {
 public:
  StateGuard();
  ~StateGuard();
  StateGuard(const StateGuard&) = delete;
  StateGuard& operator=(const StateGuard&) = delete;

 private:
  GLint draw_framebuffer_ = 0, read_framebuffer_ = 0;
  GLint viewport_[4] = {0, 0, 0, 0};
  GLint program_ = 0, vertex_array_ = 0;
  GLboolean depth_test_ = GL_FALSE, depth_mask_ = GL_TRUE;
  GLint depth_func_ = GL_LESS;
  GLint clip_origin_ = GL_LOWER_LEFT, clip_depth_mode_ = GL_NEGATIVE_ONE_TO_ONE;
  GLint uniform_buffer_ = 0;
  GLint active_texture_ = GL_TEXTURE0, texture_unit0_ = 0;
};

}  // namespace thalassa::gl
