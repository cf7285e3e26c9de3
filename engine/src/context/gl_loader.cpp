#include "context/gl_loader.hpp"

#include <glad/gl.h>

#include <cstdio>

namespace thalassa::detail {
namespace {

void GLAD_API_PTR log_debug_message(GLenum /*source*/, GLenum /*type*/, GLuint /*id*/,
                                    GLenum severity, GLsizei /*length*/, const GLchar* message,
                                    const void* /*user*/) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  std::fprintf(stderr, "thalassa: GL: %s\n", message);
}

// The GetProcAddress that filled glad's table last.
GlProcAddressFn loaded_from = nullptr;

}  // namespace

void use_gl_functions(GlProcAddressFn get_proc_address, const std::string& who) {
  if (get_proc_address == loaded_from) return;
  if (gladLoadGL(reinterpret_cast<GLADloadfunc>(get_proc_address)) == 0)
    throw ContextError(who + ": glad could not load the OpenGL functions");
  loaded_from = get_proc_address;
}

void load_gl_functions(GlProcAddressFn get_proc_address, const std::string& who, bool debug) {
  if (get_proc_address == nullptr) throw ContextError(who + ": no GetProcAddress function");
  // GLADloadfunc and GlProcAddressFn are the same function type: GlProc(*)(const char*).
  const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(get_proc_address));
  if (version == 0) throw ContextError(who + ": glad could not load the OpenGL functions");
  loaded_from = get_proc_address;
  const int major = GLAD_VERSION_MAJOR(version);
  const int minor = GLAD_VERSION_MINOR(version);
  if (major * 10 + minor < 45) {
    throw ContextError(who + ": OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                       " found; thalassa needs OpenGL 4.5 core");
  }
  if (debug && GLAD_GL_KHR_debug) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(log_debug_message, nullptr);
  }
}

}  // namespace thalassa::detail
