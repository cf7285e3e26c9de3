// thalassa — OpenGL 4.5 core contexts: headless EGL (default), OSMesa (fallback), a GLFW window,
// or a context that the host application owns.
//
// Every backend loads the GL functions with glad through its own API's GetProcAddress
// (DESIGN section 7: libepoxy and GL_GLEXT_PROTOTYPES fail under OSMesa). This header exposes
// no GL types, so that a host application can include it next to its own GL loader.
#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace thalassa {

enum class Backend {
  Egl,     // EGL without a window: device platform, else surfaceless, else the default display
  OsMesa,  // Mesa's off-screen renderer (software)
  Glfw,    // a window through GLFW; needs a display
  Host,    // a context created and made current by the host application
};

std::string_view backend_name(Backend backend);  // "egl", "osmesa", "glfw", "host"
// Parses "egl", "osmesa", "glfw"; std::nullopt for anything else.
std::optional<Backend> parse_backend(std::string_view name);
// The backends compiled into this build, in the order the default tries them.
std::vector<Backend> available_backends();

// Same type as eglGetProcAddress, glfwGetProcAddress and OSMesaGetProcAddress.
using GlProc = void (*)();
using GlProcAddressFn = GlProc (*)(const char* name);

// A context cannot be created (no driver, no display, version too low). The message says which
// backend failed and why.
class ContextError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ContextOptions {
  int width = 640;   // pixels; the window's size (GLFW only: headless contexts draw only
  int height = 480;  // pixels   into thalassa's own framebuffers)
  std::string title = "thalassa";
  bool visible = true;  // GLFW only
  bool debug = false;   // request a debug context and log KHR_debug messages to stderr (also
                        // with the environment's THALASSA_GL_DEBUG=1)
};

// An OpenGL 4.5 core context, current on the thread that created it, with GL functions loaded.
// Rendering happens into thalassa's own HDR framebuffer objects; the context's default
// framebuffer is only used to show a window.
class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  virtual Backend backend() const = 0;
  // Human-readable detail of how the context was made, e.g. "EGL 1.5 device platform (Mesa)".
  virtual std::string description() const = 0;
  virtual void make_current() = 0;
  // The context API's GetProcAddress, for a host that wants to load its own GL functions for
  // this context (thalassa's own table is private to the library).
  virtual GlProcAddressFn proc_address() const = 0;
  // Windowed backends: show the default framebuffer, poll events. Headless: no-op.
  virtual void present() {}
  // Windowed backends: whether the user asked to close the window.
  virtual bool should_close() const { return false; }
  // Size of the context's default framebuffer in pixels (window backends); 0x0 for headless.
  virtual void default_framebuffer_size(int& width, int& height) const {
    width = 0;
    height = 0;
  }

 protected:
  GlContext() = default;
};

// Creates a context with the given backend; throws ContextError on failure.
std::unique_ptr<GlContext> create_context(Backend backend, const ContextOptions& options = {});

// The default headless context: EGL, and OSMesa if EGL cannot give an OpenGL 4.5 core context.
// `log`, when given, receives one line per backend that was tried and failed.
std::unique_ptr<GlContext> create_headless_context(const ContextOptions& options = {},
                                                   std::string* log = nullptr);

// Drawing into a context the host application owns: the host creates the context (OpenGL 4.5
// core), makes it current and passes its loader's GetProcAddress. thalassa loads its own GL
// function table through it and never changes which context is current.
std::unique_ptr<GlContext> attach_host_context(GlProcAddressFn get_proc_address,
                                               std::string description = "host context");

}  // namespace thalassa
