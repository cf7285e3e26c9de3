// Contexts: the backend asked for is the one made, it is OpenGL 4.5 core with every capability
// the engine relies on, and unknown or absent backends fail with a clear error.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <algorithm>
#include <cstdlib>
#include <string>

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

// An EGL context asks to be told of GPU resets (LOSE_CONTEXT_ON_RESET), so that a GPU fault reads
// as a lost context (gl::context_reset, gl::check_error) rather than leaving it running on with
// undefined reads (the H200's scattered sun, docs/validation.md stop 40); it falls back to a
// context without where the driver does not offer it. Mesa's llvmpipe offers it (22.3, measured);
// OSMesa makes no such context. Its description and `thalassa info` say which it got, with or
// without a debug context. A healthy context reports no reset.
TEST(Context, EglIsToldOfGpuResetsWhereTheDriverOffersIt) {
  for (const bool debug : {false, true}) {
    if (debug) setenv("THALASSA_GL_DEBUG", "1", 1);
    auto context = test::make_test_context();
    if (debug) unsetenv("THALASSA_GL_DEBUG");
    GLint strategy = 0;
    glGetIntegerv(GL_RESET_NOTIFICATION_STRATEGY, &strategy);
    const bool told = strategy == GL_LOSE_CONTEXT_ON_RESET;
    if (!told) {
      EXPECT_EQ(strategy, GL_NO_RESET_NOTIFICATION);
    }
    EXPECT_EQ(context->description().find("told of GPU resets") != std::string::npos, told)
        << context->description();
    const GlInfo info = query_gl_info();
    const auto reported =
        std::find_if(info.capabilities.begin(), info.capabilities.end(),
                     [](const auto& c) { return c.first == "context loss reported (GPU resets)"; });
    ASSERT_NE(reported, info.capabilities.end());
    EXPECT_EQ(reported->second, told ? "yes" : "no");
    if (context->backend() == Backend::Egl && info.renderer.find("llvmpipe") != std::string::npos) {
      EXPECT_TRUE(told) << "debug " << debug;
    }
    if (context->backend() == Backend::OsMesa) {
      EXPECT_FALSE(told);
    }
    EXPECT_EQ(gl::context_reset(), "");
    EXPECT_NO_THROW(gl::check_error("a healthy context"));
  }
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
