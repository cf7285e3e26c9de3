// Headless EGL: the device platform (EGL_EXT_platform_device: a GPU, or Mesa's software device),
// then Mesa's surfaceless platform, then the default display. No window system is touched.
#include "context/backends.hpp"

#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>
#include <vector>

#include "context/gl_loader.hpp"

namespace thalassa::detail {
namespace {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

std::string egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "EGL error " + std::to_string(error);
  }
}

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, EGLContext context, EGLSurface surface, std::string description)
      : display_(display),
        context_(context),
        surface_(surface),
        description_(std::move(description)) {}
  ~EglContext() override {
    // Release only our own context: another one (a host's) may be current on this thread.
    if (eglGetCurrentContext() == context_)
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    eglDestroyContext(display_, context_);
    // No eglTerminate: a platform display is one per device and process, shared by every
    // context on it (a host's included), and terminating it would invalidate them all.
  }
  Backend backend() const override { return Backend::Egl; }
  std::string description() const override { return description_; }
  GlProcAddressFn proc_address() const override {
    return reinterpret_cast<GlProcAddressFn>(&eglGetProcAddress);
  }
  void make_current() override {
    if (!eglMakeCurrent(display_, surface_, surface_, context_))
      throw ContextError("egl: eglMakeCurrent failed: " + egl_error_name(eglGetError()));
    use_gl_functions(proc_address(), "egl");
  }

 private:
  EGLDisplay display_;
  EGLContext context_;
  EGLSurface surface_;
  std::string description_;
};

// Creates a 4.5 core context on a display; returns nullptr and appends to `why` on failure.
std::unique_ptr<GlContext> try_display(EGLDisplay display, const std::string& platform,
                                       const ContextOptions& options, std::string& why) {
  auto fail = [&](const std::string& what) -> std::unique_ptr<GlContext> {
    why += platform + ": " + what + " (" + egl_error_name(eglGetError()) + "); ";
    return nullptr;
  };
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY) {
    why += platform + ": no display; ";
    return nullptr;
  }
  if (!eglInitialize(display, &major, &minor)) {
    why += platform + ": eglInitialize failed (" + egl_error_name(eglGetError()) + "); ";
    return nullptr;
  }
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!eglBindAPI(EGL_OPENGL_API)) return fail("no desktop OpenGL API");

  // DESIGN section 7: with Mesa's surfaceless platform eglChooseConfig must set
  // EGL_SURFACE_TYPE, or it finds no config. A pbuffer-capable config also serves the fallback
  // below where surfaceless contexts are not supported.
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
                                   EGL_PBUFFER_BIT,
                                   EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT,
                                   EGL_RED_SIZE,
                                   8,
                                   EGL_GREEN_SIZE,
                                   8,
                                   EGL_BLUE_SIZE,
                                   8,
                                   EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  const bool no_config = has_extension(extensions, "EGL_KHR_no_config_context");
  if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count == 0) {
    if (!no_config) return fail("no OpenGL config");
    config = nullptr;  // EGL_NO_CONFIG_KHR
  }
  // With EGL 1.5, first a context told of GPU resets (LOSE_CONTEXT_ON_RESET, without robust
  // buffer access and its bounds checks): a GPU fault then reads back as a lost context
  // (gl::context_reset) instead of leaving it running on with its reads undefined, as the H200's
  // scattered sun may have been (docs/validation.md, stop 40). Where the driver does not offer
  // it, the same context without (Mesa 22.3's llvmpipe offers it).
  const bool egl15 = major > 1 || (major == 1 && minor >= 5);
  EGLContext context = EGL_NO_CONTEXT;
  bool reset_notification = false;
  for (const bool notify : {true, false}) {
    if (notify && !egl15) continue;
    std::vector<EGLint> context_attribs = {
        EGL_CONTEXT_MAJOR_VERSION,       4,
        EGL_CONTEXT_MINOR_VERSION,       5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
    if (options.debug) {
      context_attribs.push_back(EGL_CONTEXT_OPENGL_DEBUG);
      context_attribs.push_back(EGL_TRUE);
    }
    if (notify) {
      context_attribs.push_back(EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY);
      context_attribs.push_back(EGL_LOSE_CONTEXT_ON_RESET);
    }
    context_attribs.push_back(EGL_NONE);
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs.data());
    if (context != EGL_NO_CONTEXT) {
      reset_notification = notify;
      break;
    }
  }
  if (context == EGL_NO_CONTEXT) return fail("no OpenGL 4.5 core context");

  EGLSurface surface = EGL_NO_SURFACE;
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
    if (config == nullptr) {
      eglDestroyContext(display, context);
      return fail("neither surfaceless contexts nor a pbuffer config");
    }
    const EGLint pbuffer_attribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface = eglCreatePbufferSurface(display, config, pbuffer_attribs);
    if (surface == EGL_NO_SURFACE) {
      eglDestroyContext(display, context);
      return fail("no pbuffer surface");
    }
  }
  if (!eglMakeCurrent(display, surface, surface, context)) {
    if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
    eglDestroyContext(display, context);
    return fail("eglMakeCurrent failed");
  }
  const char* vendor = eglQueryString(display, EGL_VENDOR);
  std::string description = "EGL " + std::to_string(major) + "." + std::to_string(minor) + " " +
                            platform + " (" + (vendor ? vendor : "unknown vendor") + ")" +
                            (reset_notification ? ", told of GPU resets" : "");
  auto result = std::make_unique<EglContext>(display, context, surface, description);
  load_gl_functions(reinterpret_cast<GlProcAddressFn>(&eglGetProcAddress), "egl", options.debug);
  return result;
}

}  // namespace

std::unique_ptr<GlContext> create_egl_context(const ContextOptions& options) {
  std::string why;
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));

  // 1. Device platform: prefer a hardware device to Mesa's software one.
  auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (get_platform_display && query_devices &&
      has_extension(client_extensions, "EGL_EXT_platform_device")) {
    EGLint device_count = 0;
    EGLDeviceEXT devices[16];
    if (query_devices(16, devices, &device_count) && device_count > 0) {
      std::vector<EGLDeviceEXT> ordered;
      for (int i = 0; i < device_count; ++i) {
        const char* ext =
            query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : nullptr;
        if (has_extension(ext, "EGL_MESA_device_software"))
          ordered.push_back(devices[i]);
        else
          ordered.insert(ordered.begin(), devices[i]);
      }
      for (EGLDeviceEXT device : ordered) {
        EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
        if (auto context = try_display(display, "device platform", options, why)) return context;
      }
    } else {
      why += "device platform: no devices; ";
    }
  }
  // 2. Mesa's surfaceless platform.
  if (get_platform_display && has_extension(client_extensions, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display =
        get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (auto context = try_display(display, "surfaceless platform", options, why)) return context;
  }
  // 3. Whatever the default display is.
  if (auto context =
          try_display(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default display", options, why))
    return context;
  throw ContextError("egl: no OpenGL 4.5 core context: " + why);
}

}  // namespace thalassa::detail
