// thalassa — drawing correctly in a context whose state someone else set, and giving that state
// back. A host application's context may come with blending, scissor, culling, colour masks,
// sRGB conversion or pixel-pack and unpack settings of its own: thalassa's passes set what they
// rely on (set_pass_state) and a StateGuard restores the host's values afterwards.
#pragma once

#include "thalassa/engine/gl/gl.hpp"

namespace thalassa::gl {

// Puts the fixed-function state a full-screen HDR pass relies on into a known form: no blending,
// scissor, stencil, culling, polygon offset, alpha-to-coverage, rasterizer discard or sRGB
// conversion; colour writes on; filled polygons; no sampler object on texture units 0 and 1;
// pixel uploads from client memory, tightly packed (no unpack buffer, alignment 4, no row length
// or skips), as texture and buffer uploads between passes assume.
void set_pass_state();

// Saves, then restores on destruction: framebuffer bindings, viewport, program, vertex array,
// depth test/function/mask, clip control (thalassa uses reversed-Z, zero-to-one), everything
// set_pass_state() changes, the uniform buffer binding 0, the shader storage buffer bindings 1
// and 2, texture units 0 and 1 and the pixel-pack and pixel-unpack state (alignment, row length,
// skips, pack and unpack buffers).
class StateGuard {
 public:
  StateGuard();
  ~StateGuard();
  StateGuard(const StateGuard&) = delete;
  StateGuard& operator=(const StateGuard&) = delete;

 private:
  static constexpr int kCapabilityCount = 8;
  GLint draw_framebuffer_ = 0, read_framebuffer_ = 0;
  GLint viewport_[4] = {0, 0, 0, 0};
  GLint program_ = 0, vertex_array_ = 0;
  GLboolean depth_test_ = GL_FALSE, depth_mask_ = GL_TRUE;
  GLint depth_func_ = GL_LESS;
  GLint clip_origin_ = GL_LOWER_LEFT, clip_depth_mode_ = GL_NEGATIVE_ONE_TO_ONE;
  GLboolean capabilities_[kCapabilityCount] = {};
  GLboolean color_mask_[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
  GLint polygon_mode_[2] = {GL_FILL, GL_FILL};
  GLint uniform_buffer_ = 0;
  GLint storage_buffers_[2] = {0, 0};  // bindings 1 and 2
  // Texture units thalassa's passes bind (0 and 1): their 2D texture and sampler object.
  static constexpr int kTextureUnits = 2;
  GLint active_texture_ = GL_TEXTURE0;
  GLint textures_[kTextureUnits] = {};
  GLint samplers_[kTextureUnits] = {};
  GLint pack_alignment_ = 4, pack_row_length_ = 0, pack_skip_rows_ = 0, pack_skip_pixels_ = 0;
  GLint pack_buffer_ = 0;
  GLint unpack_alignment_ = 4, unpack_row_length_ = 0, unpack_skip_rows_ = 0,
        unpack_skip_pixels_ = 0, unpack_image_height_ = 0, unpack_skip_images_ = 0;
  GLint unpack_buffer_ = 0;
};

}  // namespace thalassa::gl
