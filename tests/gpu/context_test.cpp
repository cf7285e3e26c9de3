// Contexts: the backend asked for is the one made, it is OpenGL 4.5 core with every capability
// the engine relies on, and unknown or absent backends fail with a clear error.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <cstdlib>

#include "test_support.hpp"
#include "thalassa/engine/gl/objects.hpp"

namespace thalassa {
namespace {

TEST(Context, BackendIsOpenGl45CoreWithEverythingTheEngineNeeds) {
  auto context = test::make_test_context();
  EXPECT_EQ(context->backend(), test::backend_under_test());
  EXPECT_FALSE(context->description().empty());
  const GlInfo info = query_gl_info();
  EXPECT_TRUE(info.missing.empty()) << "missing: " << (info.missing.empty() ? "" : info.missing[0]);
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 45);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_FALSE(info.renderer.empty());
}

TEST(Context, TwoContextsInOneProcess) {
  auto first = test::make_test_context();
  auto second = test::make_test_context();
  second->make_current();
  EXPECT_TRUE(query_gl_info().missing.empty());
  first->make_current();
  EXPECT_TRUE(query_gl_info().missing.empty());
}

TEST(Context, HeadlessDefaultWorksWithoutDisplay) {
  std::string log;
  auto context = create_headless_context({}, &log);
  EXPECT_NE(context->backend(), Backend::Glfw);
  EXPECT_NE(context->backend(), Backend::Host);
}

// THALASSA_GL_DEBUG=1 logs the driver's messages on stderr (GL_DEBUG_OUTPUT) whatever the
// program asked for, from a debug context where the backend makes one (EGL; OSMesa makes none).
TEST(Context, DebugFromTheEnvironment) {
  GLint flags = 0;
  {
    auto context = test::make_test_context();
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    EXPECT_FALSE(flags & GL_CONTEXT_FLAG_DEBUG_BIT);
    EXPECT_FALSE(glIsEnabled(GL_DEBUG_OUTPUT));
  }
  setenv("THALASSA_GL_DEBUG", "1", 1);
  auto context = test::make_test_context();
  unsetenv("THALASSA_GL_DEBUG");
  EXPECT_TRUE(glIsEnabled(GL_DEBUG_OUTPUT));
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  if (test::backend_under_test() == Backend::Egl) {
    EXPECT_TRUE(flags & GL_CONTEXT_FLAG_DEBUG_BIT);
  }
}

// gl::set_sampling sets what it is given on the texture and leaves an axis it is not given alone.
TEST(Context, TextureSamplingIsWhatWasAsked) {
  auto context = test::make_test_context();
  const auto parameter = [](GLuint texture, GLenum name) {
    GLint value = 0;
    glGetTextureParameteriv(texture, name, &value);
    return static_cast<GLenum>(value);
  };
  const gl::Texture table = gl::make_texture(GL_TEXTURE_3D);
  gl::set_sampling(table.get(), {.wrap_r = GL_CLAMP_TO_EDGE});
  EXPECT_EQ(parameter(table.get(), GL_TEXTURE_MIN_FILTER), GLenum(GL_LINEAR));
  EXPECT_EQ(parameter(table.get(), GL_TEXTURE_MAG_FILTER), GLenum(GL_LINEAR));
  EXPECT_EQ(parameter(table.get(), GL_TEXTURE_WRAP_S), GLenum(GL_CLAMP_TO_EDGE));
  EXPECT_EQ(parameter(table.get(), GL_TEXTURE_WRAP_T), GLenum(GL_CLAMP_TO_EDGE));
  EXPECT_EQ(parameter(table.get(), GL_TEXTURE_WRAP_R), GLenum(GL_CLAMP_TO_EDGE));
  const gl::Texture map = gl::make_texture(GL_TEXTURE_2D);
  gl::set_sampling(map.get(), {.min_filter = GL_LINEAR_MIPMAP_LINEAR, .wrap_s = GL_REPEAT});
  EXPECT_EQ(parameter(map.get(), GL_TEXTURE_MIN_FILTER), GLenum(GL_LINEAR_MIPMAP_LINEAR));
  EXPECT_EQ(parameter(map.get(), GL_TEXTURE_WRAP_S), GLenum(GL_REPEAT));
  EXPECT_EQ(parameter(map.get(), GL_TEXTURE_WRAP_T), GLenum(GL_CLAMP_TO_EDGE));
  EXPECT_EQ(parameter(map.get(), GL_TEXTURE_WRAP_R), GLenum(GL_REPEAT));  // GL's default, left
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST(Context, NamesAndErrors) {
  EXPECT_EQ(parse_backend("egl"), Backend::Egl);
  EXPECT_EQ(parse_backend("osmesa"), Backend::OsMesa);
  EXPECT_EQ(parse_backend("glfw"), Backend::Glfw);
  EXPECT_FALSE(parse_backend("vulkan").has_value());
  EXPECT_THROW(create_context(Backend::Host), ContextError);
  EXPECT_THROW(attach_host_context(nullptr), ContextError);
}

}  // namespace
}  // namespace thalassa
