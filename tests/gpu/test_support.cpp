#include "test_support.hpp"

#include <glad/gl.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "thalassa/engine/gl/hdr_target.hpp"
#include "thalassa/engine/gl/objects.hpp"

namespace thalassa::test {

Backend backend_under_test() {
  const char* name = std::getenv("THALASSA_TEST_BACKEND");
  if (name == nullptr) return Backend::Egl;
  if (auto backend = parse_backend(name)) return *backend;
  throw std::runtime_error(std::string("THALASSA_TEST_BACKEND: unknown backend ") + name);
}

std::unique_ptr<GlContext> make_test_context() {
  auto context = create_context(backend_under_test());
  if (gladLoadGL(reinterpret_cast<GLADloadfunc>(context->proc_address())) == 0)
    throw std::runtime_error("the test's glad could not load GL");
  return context;
}

std::string output_dir() {
  const std::filesystem::path dir = std::filesystem::path(THALASSA_TEST_OUTPUT_DIR) /
                                    std::string(backend_name(backend_under_test()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

Scene scene_from(const std::string& json) {
  SceneBuilder builder;
  builder.load_text(json, "test scene");
  return builder.build();
}

std::vector<glm::vec4> evaluate_fragment(unsigned program, const std::vector<glm::vec4>& texels,
                                         int width, int height) {
  if (texels.size() != std::size_t(width) * height)
    throw std::invalid_argument("evaluate_fragment: texels do not fill the target");
  gl::Texture input = gl::make_texture(GL_TEXTURE_2D);
  glTextureStorage2D(input.get(), 1, GL_RGBA32F, width, height);
  glTextureSubImage2D(input.get(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, texels.data());
  gl::HdrTarget target(width, height);
  const gl::VertexArray vao = gl::make_vertex_array();
  target.begin();
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program);
  glBindTextureUnit(0, input.get());
  glBindVertexArray(vao.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glEnable(GL_DEPTH_TEST);
  // The target reads top row first; texel row 0 is the bottom one.
  const std::vector<float> top_down = target.read_rgba_top_down();
  std::vector<glm::vec4> out(texels.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float* t = &top_down[(std::size_t(height - 1 - y) * width + x) * 4];
      out[std::size_t(y) * width + x] = glm::vec4(t[0], t[1], t[2], t[3]);
    }
  return out;
}

std::vector<float> read_depth(const Renderer& renderer, int width, int height) {
  std::vector<float> depth(static_cast<std::size_t>(width) * height);
  GLint previous = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, renderer.hdr_framebuffer());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
  return depth;
}

}  // namespace thalassa::test
