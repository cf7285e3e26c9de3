// thalassa — RAII wrappers for GL object names (DSA, OpenGL 4.5). Move-only.
#pragma once

#include "thalassa/engine/gl/gl.hpp"

#include <utility>

namespace thalassa::gl {

// Owns one GL object name; Deleter is a function that deletes `n` names.
template <void (*Delete)(GLuint)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint name) : name_(name) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  GLuint get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }
  void reset() {
    if (name_ != 0) Delete(name_);
    name_ = 0;
  }

 private:
  GLuint name_ = 0;
};

void delete_buffer(GLuint name);
void delete_texture(GLuint name);
void delete_framebuffer(GLuint name);
void delete_vertex_array(GLuint name);
void delete_query(GLuint name);
void delete_program(GLuint name);
void delete_shader(GLuint name);

using Buffer = Handle<delete_buffer>;
using Texture = Handle<delete_texture>;
using Framebuffer = Handle<delete_framebuffer>;
using VertexArray = Handle<delete_vertex_array>;
using Query = Handle<delete_query>;
using ProgramName = Handle<delete_program>;
using ShaderName = Handle<delete_shader>;

Buffer make_buffer();
Texture make_texture(GLenum target);
Framebuffer make_framebuffer();
VertexArray make_vertex_array();
Query make_query(GLenum target);

// How a texture is sampled: its minification and magnification filters and its wrap modes along
// s, t and r (wrap_r 0 leaves r as it is, for a texture without that axis). The default, bilinear
// and clamped to the edge, is a table's: its samples interpolated, never blended with a border.
struct Sampling {
  GLenum min_filter = GL_LINEAR;
  GLenum mag_filter = GL_LINEAR;
  GLenum wrap_s = GL_CLAMP_TO_EDGE;
  GLenum wrap_t = GL_CLAMP_TO_EDGE;
  GLenum wrap_r = 0;
};
void set_sampling(GLuint texture, const Sampling& sampling);

}  // namespace thalassa::gl
