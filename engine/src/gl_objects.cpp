#include "thalassa/engine/gl/objects.hpp"

#include <string>

namespace thalassa::gl {

void check_error(const char* where) {
  std::string errors;
  for (GLenum error = glGetError(); error != GL_NO_ERROR; error = glGetError()) {
    switch (error) {
      case GL_INVALID_ENUM:
        errors += " GL_INVALID_ENUM";
        break;
      case GL_INVALID_VALUE:
        errors += " GL_INVALID_VALUE";
        break;
      case GL_INVALID_OPERATION:
        errors += " GL_INVALID_OPERATION";
        break;
      case GL_INVALID_FRAMEBUFFER_OPERATION:
        errors += " GL_INVALID_FRAMEBUFFER_OPERATION";
        break;
      case GL_OUT_OF_MEMORY:
        errors += " GL_OUT_OF_MEMORY";
        break;
      case GL_CONTEXT_LOST:
        errors += " GL_CONTEXT_LOST";
        break;
      default:
        errors += " GL error " + std::to_string(error);
    }
    if (errors.size() > 400) break;  // a lost context can report errors forever
  }
  const std::string reset = context_reset();
  if (!reset.empty()) errors += " (the context was reset, " + reset + ")";
  if (!errors.empty()) throw GlError(std::string(where) + ":" + errors);
}

std::string context_reset() {
  switch (const GLenum status = glGetGraphicsResetStatus()) {
    case GL_NO_ERROR:
      return "";
    case GL_GUILTY_CONTEXT_RESET:
      return "GL_GUILTY_CONTEXT_RESET: a command of this context made the GPU reset";
    case GL_INNOCENT_CONTEXT_RESET:
      return "GL_INNOCENT_CONTEXT_RESET: the GPU was reset by another context's work";
    case GL_UNKNOWN_CONTEXT_RESET:
      return "GL_UNKNOWN_CONTEXT_RESET: the GPU was reset, cause unknown";
    default:
      return "reset status " + std::to_string(status);
  }
}

bool context_told_of_resets() {
  GLint strategy = GL_NO_RESET_NOTIFICATION;
  glGetIntegerv(GL_RESET_NOTIFICATION_STRATEGY, &strategy);
  return strategy == GL_LOSE_CONTEXT_ON_RESET;
}

void delete_buffer(GLuint name) { glDeleteBuffers(1, &name); }
void delete_texture(GLuint name) { glDeleteTextures(1, &name); }
void delete_framebuffer(GLuint name) { glDeleteFramebuffers(1, &name); }
void delete_vertex_array(GLuint name) { glDeleteVertexArrays(1, &name); }
void delete_query(GLuint name) { glDeleteQueries(1, &name); }
void delete_program(GLuint name) { glDeleteProgram(name); }
void delete_shader(GLuint name) { glDeleteShader(name); }

Buffer make_buffer() {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  return Buffer(name);
}
Texture make_texture(GLenum target) {
  GLuint name = 0;
  glCreateTextures(target, 1, &name);
  return Texture(name);
}
Framebuffer make_framebuffer() {
  GLuint name = 0;
  glCreateFramebuffers(1, &name);
  return Framebuffer(name);
}
VertexArray make_vertex_array() {
  GLuint name = 0;
  glCreateVertexArrays(1, &name);
  return VertexArray(name);
}
Query make_query(GLenum target) {
  GLuint name = 0;
  glCreateQueries(target, 1, &name);
  return Query(name);
}

void set_sampling(GLuint texture, const Sampling& sampling) {
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(sampling.min_filter));
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(sampling.mag_filter));
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, static_cast<GLint>(sampling.wrap_s));
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, static_cast<GLint>(sampling.wrap_t));
  if (sampling.wrap_r != 0)
    glTextureParameteri(texture, GL_TEXTURE_WRAP_R, static_cast<GLint>(sampling.wrap_r));
}

}  // namespace thalassa::gl
