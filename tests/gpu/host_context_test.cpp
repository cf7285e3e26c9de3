// Drawing into a context the host application owns: the "host" (this test) creates its own
// context and framebuffer with its own GL loader, hands thalassa its GetProcAddress, and asks it
// to render and present into the host's framebuffer. thalassa must draw the same frame as with
// its own context, leave the host's context current and give back every GL state it changed.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include "test_support.hpp"

namespace thalassa {
namespace {

TEST(HostContext, RendersIntoTheHostsFramebuffer) {
  // The host's own context, made by the backend under test; thalassa sees only the loader.
  auto host_owned = test::make_test_context();
  auto attached = attach_host_context(host_owned->proc_address(), "test host");
  EXPECT_EQ(attached->backend(), Backend::Host);

  const int width = 64, height = 48;
  GLuint color = 0, fbo = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &color);
  glTextureStorage2D(color, 1, GL_RGBA8, width, height);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
  ASSERT_EQ(glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER), GLenum(GL_FRAMEBUFFER_COMPLETE));
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  // Host state that thalassa's passes change internally and must give back.
  GLuint host_vao = 0;
  glCreateVertexArrays(1, &host_vao);
  glBindVertexArray(host_vao);
  glViewport(3, 4, 20, 10);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  // State that would spoil thalassa's frame if its passes relied on GL's defaults.
  glEnable(GL_BLEND);
  glBlendFunc(GL_ZERO, GL_ONE);  // would keep the target's old contents
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 1, 1);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT_AND_BACK);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  glEnable(GL_FRAMEBUFFER_SRGB);
  glPixelStorei(GL_PACK_ROW_LENGTH, 7);
  // The unpack state a host may leave set (the reference method uploads its average).
  GLuint host_unpack = 0;
  glCreateBuffers(1, &host_unpack);
  glNamedBufferStorage(host_unpack, 16, nullptr, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, host_unpack);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 5);
  auto expect_host_state = [&](const char* after) {
    GLint value = 0, viewport[4] = {0, 0, 0, 0};
    GLboolean mask = GL_TRUE;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &value);
    EXPECT_EQ(GLuint(value), fbo) << after;
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &value);
    EXPECT_EQ(GLuint(value), host_vao) << after;
    glGetIntegerv(GL_CURRENT_PROGRAM, &value);
    EXPECT_EQ(value, 0) << after;
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(viewport[0], 3) << after;
    EXPECT_EQ(viewport[3], 10) << after;
    EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST)) << after;
    glGetIntegerv(GL_DEPTH_FUNC, &value);
    EXPECT_EQ(value, GL_LEQUAL) << after;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
    EXPECT_EQ(mask, GL_FALSE) << after;
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &value);
    EXPECT_EQ(value, GL_NEGATIVE_ONE_TO_ONE) << after;
    EXPECT_TRUE(glIsEnabled(GL_BLEND)) << after;
    EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST)) << after;
    EXPECT_TRUE(glIsEnabled(GL_CULL_FACE)) << after;
    EXPECT_TRUE(glIsEnabled(GL_FRAMEBUFFER_SRGB)) << after;
    GLboolean color_mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    glGetBooleanv(GL_COLOR_WRITEMASK, color_mask);
    EXPECT_EQ(color_mask[1], GL_FALSE) << after;
    glGetIntegerv(GL_PACK_ROW_LENGTH, &value);
    EXPECT_EQ(value, 7) << after;
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &value);
    EXPECT_EQ(GLuint(value), host_unpack) << after;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &value);
    EXPECT_EQ(value, 1) << after;
    glGetIntegerv(GL_UNPACK_ROW_LENGTH, &value);
    EXPECT_EQ(value, 5) << after;
  };

  const Scene scene = test::scene_from(R"({"image": {"width": 64, "height": 48}})");
  Renderer renderer(*attached, scene);
  renderer.render();
  expect_host_state("after render()");
  renderer.present(fbo, width, height);
  expect_host_state("after present()");
  const Image hdr = renderer.image();
  expect_host_state("after image()");
  {
    RendererOptions options;
    options.method = ocean::OceanMethod::reference;
    options.reference.min_samples = options.reference.max_samples = 2;
    // A coarse lattice for its sun, unmeasured: the host's state is the point, not the sun (the
    // default lattice took this test 2-3 minutes on llvmpipe).
    options.reference.sun_cells = 16;
    options.reference.sun_cells_per_wavelength = 2.0;
    options.reference.measure_lattice = false;
    Renderer reference(*attached, scene, options);
    reference.render();
    expect_host_state("after a reference render()");
  }
  std::vector<unsigned char> pixels(width * height * 4);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);  // the host reads its own pixels with its own state
  glGetTextureImage(color, 0, GL_RGBA, GL_UNSIGNED_BYTE, int(pixels.size()), pixels.data());

  // The host's pixels are the PNG's tone mapping of thalassa's HDR frame (GL rows bottom-up).
  int mismatches = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double expected =
            255.0 * tone_map(hdr.pixel(x, height - 1 - y)[c], scene.image.exposure);
        if (std::abs(pixels[(y * width + x) * 4 + c] - expected) > 1.01) ++mismatches;
      }
  EXPECT_EQ(mismatches, 0);

  // And the HDR frame equals the one rendered with thalassa's own context.
  {
    auto own = create_context(test::backend_under_test());
    Renderer own_renderer(*own, scene);
    own_renderer.render();
    EXPECT_EQ(own_renderer.image().rgba, hdr.rgba);
  }

  host_owned->make_current();
  glDeleteVertexArrays(1, &host_vao);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  glDeleteBuffers(1, &host_unpack);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &color);
}

}  // namespace
}  // namespace thalassa
