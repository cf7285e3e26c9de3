#include "thalassa/engine/gl/state_guard.hpp"

#include "thalassa/engine/gl/scene_graph.hpp"

namespace thalassa::gl {

StateGuard::StateGuard() {
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_framebuffer_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
  depth_test_ = glIsEnabled(GL_DEPTH_TEST);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
  glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_mode_);
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, kFrameBinding, &uniform_buffer_);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
  glActiveTexture(GL_TEXTURE0);
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture_unit0_);
  glActiveTexture(static_cast<GLenum>(active_texture_));
}

StateGuard::~StateGuard() {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_framebuffer_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_framebuffer_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glUseProgram(static_cast<GLuint>(program_));
  glBindVertexArray(static_cast<GLuint>(vertex_array_));
  if (depth_test_) glEnable(GL_DEPTH_TEST); else glDisable(GL_DEPTH_TEST);
  glDepthMask(depth_mask_);
  glDepthFunc(static_cast<GLenum>(depth_func_));
  glClipControl(static_cast<GLenum>(clip_origin_), static_cast<GLenum>(clip_depth_mode_));
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBinding, static_cast<GLuint>(uniform_buffer_));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(texture_unit0_));
  glActiveTexture(static_cast<GLenum>(active_texture_));
}

}  // namespace thalassa::gl
