// OSMesa: Mesa's off-screen software renderer, the fallback when EGL gives no context.
#include "context/backends.hpp"

#include <GL/osmesa.h>

#include <vector>

#include "context/gl_loader.hpp"

namespace thalassa::detail {
namespace {

class OsMesaContext final : public GlContext {
 public:
  explicit OsMesaContext(OSMesaContext context) : context_(context), buffer_(kSize * kSize * 4) {}
  ~OsMesaContext() override { OSMesaDestroyContext(context_); }
  Backend backend() const override { return Backend::OsMesa; }
  std::string description() const override { return "OSMesa (Mesa off-screen)"; }
  GlProcAddressFn proc_address() const override {
    return reinterpret_cast<GlProcAddressFn>(&OSMesaGetProcAddress);
  }
  void make_current() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, kSize, kSize))
      throw ContextError("osmesa: OSMesaMakeCurrent failed");
    use_gl_functions(proc_address(), "osmesa");
  }

 private:
  // thalassa renders into its own framebuffer objects; OSMesa only needs some colour buffer
  // to make the context current, so it gets a tiny one.
  static constexpr int kSize = 16;
  OSMesaContext context_;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> create_osmesa_context(const ContextOptions& options) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         4,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         5,
                         0};
  OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (context == nullptr) throw ContextError("osmesa: no OpenGL 4.5 core context");
  auto result = std::make_unique<OsMesaContext>(context);
  result->make_current();
  load_gl_functions(reinterpret_cast<GlProcAddressFn>(&OSMesaGetProcAddress), "osmesa",
                    options.debug);
  return result;
}

}  // namespace thalassa::detail
