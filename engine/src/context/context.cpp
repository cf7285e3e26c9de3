#include "thalassa/engine/context.hpp"

#include "context/backends.hpp"
#include "context/gl_loader.hpp"

#include <cstdlib>
#include <string>

namespace thalassa {
namespace {

class HostContext final : public GlContext {
 public:
  HostContext(GlProcAddressFn get_proc_address, std::string description)
      : get_proc_address_(get_proc_address), description_(std::move(description)) {}
  GlProcAddressFn proc_address() const override { return get_proc_address_; }
  Backend backend() const override { return Backend::Host; }
  std::string description() const override { return description_; }
  // The host decides which context is current; thalassa never changes it, but makes sure its
  // function table is the one loaded through the host's GetProcAddress.
  void make_current() override { detail::use_gl_functions(get_proc_address_, "host"); }

 private:
  GlProcAddressFn get_proc_address_;
  std::string description_;
};

}  // namespace

std::string_view backend_name(Backend backend) {
  switch (backend) {
    case Backend::Egl:
      return "egl";
    case Backend::OsMesa:
      return "osmesa";
    case Backend::Glfw:
      return "glfw";
    case Backend::Host:
      return "host";
  }
  return "unknown";
}

std::optional<Backend> parse_backend(std::string_view name) {
  if (name == "egl") return Backend::Egl;
  if (name == "osmesa") return Backend::OsMesa;
  if (name == "glfw") return Backend::Glfw;
  return std::nullopt;
}

std::vector<Backend> available_backends() {
  std::vector<Backend> backends;
#ifdef THALASSA_HAVE_EGL
  backends.push_back(Backend::Egl);
#endif
#ifdef THALASSA_HAVE_OSMESA
  backends.push_back(Backend::OsMesa);
#endif
#ifdef THALASSA_HAVE_GLFW
  backends.push_back(Backend::Glfw);
#endif
  return backends;
}

std::unique_ptr<GlContext> create_context(Backend backend, const ContextOptions& requested) {
  // THALASSA_GL_DEBUG=1: a debug context whatever the caller asked, its driver's messages on
  // stderr, for diagnosing a driver without rebuilding (the H200's lost scatter, stop 26).
  ContextOptions options = requested;
  if (const char* env = std::getenv("THALASSA_GL_DEBUG"); env && std::string(env) == "1")
    options.debug = true;
  switch (backend) {
    case Backend::Egl:
#ifdef THALASSA_HAVE_EGL
      return detail::create_egl_context(options);
#else
      throw ContextError("egl: this build of thalassa has no EGL backend");
#endif
    case Backend::OsMesa:
#ifdef THALASSA_HAVE_OSMESA
      return detail::create_osmesa_context(options);
#else
      throw ContextError("osmesa: this build of thalassa has no OSMesa backend");
#endif
    case Backend::Glfw:
#ifdef THALASSA_HAVE_GLFW
      return detail::create_glfw_context(options);
#else
      throw ContextError("glfw: this build of thalassa has no GLFW backend");
#endif
    case Backend::Host:
      throw ContextError("host: use attach_host_context() with the host's GetProcAddress");
  }
  throw ContextError("unknown backend");
}

std::unique_ptr<GlContext> create_headless_context(const ContextOptions& options,
                                                   std::string* log) {
  std::string why;
  for (Backend backend : available_backends()) {
    if (backend == Backend::Glfw) continue;
    try {
      auto context = create_context(backend, options);
      if (log) *log += why;
      return context;
    } catch (const ContextError& error) {
      why += std::string(error.what()) + "\n";
    }
  }
  if (log) *log += why;
  throw ContextError("no headless OpenGL 4.5 core context could be created:\n" + why);
}

std::unique_ptr<GlContext> attach_host_context(GlProcAddressFn get_proc_address,
                                               std::string description) {
  detail::load_gl_functions(get_proc_address, "host", false);
  return std::make_unique<HostContext>(get_proc_address, std::move(description));
}

}  // namespace thalassa
