#include "thalassa/engine/gl/state_guard.hpp"

#include "thalassa/engine/gl/scene_graph.hpp"

namespace thalassa::gl {
namespace {

// The on/off capabilities set_pass_state() turns off, in the order StateGuard saves them.
constexpr GLenum kCapabilities[] = {GL_BLEND,
                                    GL_SCISSOR_TEST,
                                    GL_STENCIL_TEST,
                                    GL_CULL_FACE,
                                    GL_POLYGON_OFFSET_FILL,
                                    GL_SAMPLE_ALPHA_TO_COVERAGE,
                                    GL_RASTERIZER_DISCARD,
                                    GL_FRAMEBUFFER_SRGB};

}  // namespace

void set_pass_state() {
  for (GLenum capability : kCapabilities) glDisable(capability);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glBindSampler(0, 0);
  glBindSampler(1, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
  glPixelStorei(GL_UNPACK_SKIP_IMAGES, 0);
}

StateGuard::StateGuard() {
  static_assert(sizeof(kCapabilities) / sizeof(kCapabilities[0]) == kCapabilityCount);
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
  for (int i = 0; i < kCapabilityCount; ++i) capabilities_[i] = glIsEnabled(kCapabilities[i]);
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask_);
  glGetIntegerv(GL_POLYGON_MODE, polygon_mode_);
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, kFrameBinding, &uniform_buffer_);
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 1, &storage_buffers_[0]);
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 2, &storage_buffers_[1]);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
  for (int unit = 0; unit < kTextureUnits; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &textures_[unit]);
    glGetIntegerv(GL_SAMPLER_BINDING, &samplers_[unit]);
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glGetIntegerv(GL_PACK_ALIGNMENT, &pack_alignment_);
  glGetIntegerv(GL_PACK_ROW_LENGTH, &pack_row_length_);
  glGetIntegerv(GL_PACK_SKIP_ROWS, &pack_skip_rows_);
  glGetIntegerv(GL_PACK_SKIP_PIXELS, &pack_skip_pixels_);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer_);
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpack_alignment_);
  glGetIntegerv(GL_UNPACK_ROW_LENGTH, &unpack_row_length_);
  glGetIntegerv(GL_UNPACK_SKIP_ROWS, &unpack_skip_rows_);
  glGetIntegerv(GL_UNPACK_SKIP_PIXELS, &unpack_skip_pixels_);
  glGetIntegerv(GL_UNPACK_IMAGE_HEIGHT, &unpack_image_height_);
  glGetIntegerv(GL_UNPACK_SKIP_IMAGES, &unpack_skip_images_);
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer_);
}

StateGuard::~StateGuard() {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_framebuffer_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read_framebuffer_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glUseProgram(static_cast<GLuint>(program_));
  glBindVertexArray(static_cast<GLuint>(vertex_array_));
  if (depth_test_)
    glEnable(GL_DEPTH_TEST);
  else
    glDisable(GL_DEPTH_TEST);
  glDepthMask(depth_mask_);
  glDepthFunc(static_cast<GLenum>(depth_func_));
  glClipControl(static_cast<GLenum>(clip_origin_), static_cast<GLenum>(clip_depth_mode_));
  for (int i = 0; i < kCapabilityCount; ++i)
    if (capabilities_[i])
      glEnable(kCapabilities[i]);
    else
      glDisable(kCapabilities[i]);
  glColorMask(color_mask_[0], color_mask_[1], color_mask_[2], color_mask_[3]);
  // Core profile: one mode for both faces, so the front face's value stands for both.
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygon_mode_[0]));
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBinding, static_cast<GLuint>(uniform_buffer_));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, static_cast<GLuint>(storage_buffers_[0]));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, static_cast<GLuint>(storage_buffers_[1]));
  for (int unit = 0; unit < kTextureUnits; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(textures_[unit]));
    glBindSampler(unit, static_cast<GLuint>(samplers_[unit]));
  }
  glActiveTexture(static_cast<GLenum>(active_texture_));
  glPixelStorei(GL_PACK_ALIGNMENT, pack_alignment_);
  glPixelStorei(GL_PACK_ROW_LENGTH, pack_row_length_);
  glPixelStorei(GL_PACK_SKIP_ROWS, pack_skip_rows_);
  glPixelStorei(GL_PACK_SKIP_PIXELS, pack_skip_pixels_);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(pack_buffer_));
  glPixelStorei(GL_UNPACK_ALIGNMENT, unpack_alignment_);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, unpack_row_length_);
  glPixelStorei(GL_UNPACK_SKIP_ROWS, unpack_skip_rows_);
  glPixelStorei(GL_UNPACK_SKIP_PIXELS, unpack_skip_pixels_);
  glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, unpack_image_height_);
  glPixelStorei(GL_UNPACK_SKIP_IMAGES, unpack_skip_images_);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(unpack_buffer_));
}

}  // namespace thalassa::gl
