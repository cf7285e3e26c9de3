// A window through GLFW 3.3 (X11 on Debian). Needs a display; under CI it runs under Xvfb.
#include "context/backends.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <mutex>
#include <string>

#include "context/gl_loader.hpp"

namespace thalassa::detail {
namespace {

std::string& last_glfw_error() {
  static std::string error;
  return error;
}

void record_glfw_error(int /*code*/, const char* description) {
  last_glfw_error() = description ? description : "unknown GLFW error";
}

// glfwInit/glfwTerminate are process-wide: count the windows that need GLFW.
int glfw_users = 0;

class GlfwContext final : public GlContext {
 public:
  explicit GlfwContext(GLFWwindow* window) : window_(window) {}
  ~GlfwContext() override {
    glfwDestroyWindow(window_);
    if (--glfw_users == 0) glfwTerminate();
  }
  Backend backend() const override { return Backend::Glfw; }
  std::string description() const override {
    return std::string("GLFW ") + glfwGetVersionString() + " window" +
           (glfwGetWindowAttrib(window_, GLFW_CONTEXT_ROBUSTNESS) == GLFW_LOSE_CONTEXT_ON_RESET
                ? ", told of GPU resets"
                : "");
  }
  GlProcAddressFn proc_address() const override {
    return reinterpret_cast<GlProcAddressFn>(&glfwGetProcAddress);
  }
  void make_current() override {
    glfwMakeContextCurrent(window_);
    use_gl_functions(proc_address(), "glfw");
  }
  void present() override {
    glfwSwapBuffers(window_);
    glfwPollEvents();
  }
  bool should_close() const override { return glfwWindowShouldClose(window_) != 0; }
  void default_framebuffer_size(int& width, int& height) const override {
    glfwGetFramebufferSize(window_, &width, &height);
  }

 private:
  GLFWwindow* window_;
};

}  // namespace

std::unique_ptr<GlContext> create_glfw_context(const ContextOptions& options) {
  glfwSetErrorCallback(record_glfw_error);
  if (glfw_users == 0) {
    if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
      throw ContextError("glfw: no display (DISPLAY is not set); use --backend egl or osmesa");
    if (!glfwInit()) throw ContextError("glfw: glfwInit failed: " + last_glfw_error());
  }
  ++glfw_users;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  // First a context told of GPU resets, as EGL's (egl_context.cpp: a GPU fault then reads as a
  // lost context, gl::context_reset), then, where the driver refuses it, one without.
  GLFWwindow* window = nullptr;
  for (const int robustness : {GLFW_LOSE_CONTEXT_ON_RESET, GLFW_NO_ROBUSTNESS}) {
    glfwWindowHint(GLFW_CONTEXT_ROBUSTNESS, robustness);
    window =
        glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (window != nullptr) break;
  }
  glfwWindowHint(GLFW_CONTEXT_ROBUSTNESS, GLFW_NO_ROBUSTNESS);
  if (window == nullptr) {
    if (--glfw_users == 0) glfwTerminate();
    throw ContextError("glfw: no OpenGL 4.5 core window: " + last_glfw_error());
  }
  auto result = std::make_unique<GlfwContext>(window);
  result->make_current();
  glfwSwapInterval(0);
  load_gl_functions(reinterpret_cast<GlProcAddressFn>(&glfwGetProcAddress), "glfw", options.debug);
  return result;
}

}  // namespace thalassa::detail
