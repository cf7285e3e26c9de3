#include "test_support.hpp"

#include <glad/gl.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>

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

}  // namespace thalassa::test
