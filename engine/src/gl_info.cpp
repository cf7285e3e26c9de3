#include "thalassa/engine/gl_info.hpp"

#include "thalassa/engine/gl/gl.hpp"

namespace thalassa {
namespace {

std::string gl_string(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text ? text : "";
}

// Whether an RGBA32F colour + DEPTH32F depth framebuffer is complete on this context.
bool float_target_works() {
  GLuint color = 0, depth = 0, fbo = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &color);
  glTextureStorage2D(color, 1, GL_RGBA32F, 4, 4);
  glCreateTextures(GL_TEXTURE_2D, 1, &depth);
  glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, 4, 4);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
  glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
  const bool ok = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &depth);
  glDeleteTextures(1, &color);
  return ok;
}

}  // namespace

GlInfo query_gl_info() {
  GlInfo info;
  info.version = gl_string(GL_VERSION);
  info.glsl_version = gl_string(GL_SHADING_LANGUAGE_VERSION);
  info.vendor = gl_string(GL_VENDOR);
  info.renderer = gl_string(GL_RENDERER);
  GLint profile = 0, major = 0, minor = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  auto add = [&](const std::string& name, bool present, bool required) {
    info.capabilities.emplace_back(name, present ? "yes" : "no");
    if (required && !present) info.missing.push_back(name);
  };
  add("OpenGL 4.5 core profile",
      (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0 && major * 10 + minor >= 45, true);
  add("float render targets (RGBA32F + DEPTH32F)", float_target_works(), true);
  add("compute shaders", GLAD_GL_VERSION_4_3 != 0, true);
  add("clip control (reversed-Z)", GLAD_GL_VERSION_4_5 || GLAD_GL_ARB_clip_control, true);
  add("fp64 in shaders", GLAD_GL_VERSION_4_0 || GLAD_GL_ARB_gpu_shader_fp64, false);
  add("timer queries", GLAD_GL_VERSION_3_3 || GLAD_GL_ARB_timer_query, true);
  add("float atomics (GL_NV_shader_atomic_float)", GLAD_GL_NV_shader_atomic_float != 0, false);
  add("context loss reported (GPU resets)", gl::context_told_of_resets(), false);
  const bool aniso =
      GLAD_GL_ARB_texture_filter_anisotropic || GLAD_GL_EXT_texture_filter_anisotropic;
  GLfloat max_aniso = 1.0f;
  if (aniso) glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &max_aniso);
  info.capabilities.emplace_back("anisotropic filtering",
                                 aniso ? std::to_string(static_cast<int>(max_aniso)) + "x" : "no");
  GLint max_texture = 0, max_layers = 0, viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  info.capabilities.emplace_back("max texture size", std::to_string(max_texture));
  info.capabilities.emplace_back("max array texture layers", std::to_string(max_layers));
  info.capabilities.emplace_back("max viewport",
                                 std::to_string(viewport[0]) + "x" + std::to_string(viewport[1]));
  glGetError();  // the probes above must not leave an error behind
  return info;
}

}  // namespace thalassa
