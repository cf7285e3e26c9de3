// The shader library on a real GL context: a compile error inside an included file is reported
// with that file's name and line; feature permutations are distinct, cached programs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "test_support.hpp"
#include "thalassa/engine/gl/hdr_target.hpp"
#include "thalassa/engine/gl/shader_library.hpp"

namespace thalassa {
namespace {

namespace fs = std::filesystem;

class ShaderLibraryGpu : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = test::make_test_context();
    root_ = fs::temp_directory_path() / ("thalassa_gpu_shaders_" + std::to_string(getpid()));
    fs::create_directories(root_ / "lib");
    std::ofstream(root_ / "lib/good.glsl") << "float Good() { return 1.0; }\n";
    // Line 3 of lib/bad.glsl uses an undeclared name.
    std::ofstream(root_ / "lib/bad.glsl") << "// a library file\n"
                                             "float Bad() {\n"
                                             "  return undeclared_name;\n"
                                             "}\n";
    std::ofstream(root_ / "good.frag") << "#include \"lib/good.glsl\"\n"
                                          "out vec4 color;\n"
                                          "void main() {\n"
                                          "#ifdef RED\n"
                                          "  color = vec4(Good(), 0.0, 0.0, 1.0);\n"
                                          "#else\n"
                                          "  color = vec4(0.0, Good(), 0.0, 1.0);\n"
                                          "#endif\n"
                                          "}\n";
    std::ofstream(root_ / "bad.frag") << "#include \"lib/good.glsl\"\n"
                                         "#include \"lib/bad.glsl\"\n"
                                         "out vec4 color;\n"
                                         "void main() { color = vec4(Bad()); }\n";
    std::ofstream(root_ / "bad_main.frag") << "out vec4 color;\n"
                                              "void main() {\n"
                                              "  color = vec4(1.0)\n"  // missing ';'
                                              "}\n";
  }
  void TearDown() override { fs::remove_all(root_); }
  std::unique_ptr<GlContext> context_;
  fs::path root_;
};

TEST_F(ShaderLibraryGpu, ErrorInIncludedFileNamesFileAndLine) {
  gl::ShaderLibrary library({root_});
  try {
    library.program({.vertex = "engine/fullscreen.vert", .fragment = "bad.frag"});
    FAIL() << "the program must not compile";
  } catch (const gl::ShaderError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("lib/bad.glsl:3:"), std::string::npos) << message;
  }
}

TEST_F(ShaderLibraryGpu, ErrorInMainFileNamesItsLine) {
  gl::ShaderLibrary library({root_});
  try {
    library.program({.vertex = "engine/fullscreen.vert", .fragment = "bad_main.frag"});
    FAIL() << "the program must not compile";
  } catch (const gl::ShaderError& error) {
    const std::string message = error.what();
    // The missing ';' is seen at line 3 or at the '}' of line 4, depending on the compiler.
    EXPECT_TRUE(message.find("bad_main.frag:3:") != std::string::npos ||
                message.find("bad_main.frag:4:") != std::string::npos)
        << message;
  }
}

TEST_F(ShaderLibraryGpu, PermutationsAreDistinctAndCached) {
  gl::ShaderLibrary library({root_});
  const GLuint green =
      library.program({.vertex = "engine/fullscreen.vert", .fragment = "good.frag"});
  const GLuint red = library.program(
      {.vertex = "engine/fullscreen.vert", .fragment = "good.frag", .defines = {{"RED", "1"}}});
  EXPECT_NE(green, 0u);
  EXPECT_NE(red, green);
  EXPECT_EQ(library.program({.vertex = "engine/fullscreen.vert", .fragment = "good.frag"}), green);
  EXPECT_EQ(library.built_programs().size(), 2u);

  // The permutation really changes the code: draw each into a 1x1 float target.
  gl::HdrTarget target(1, 1);
  gl::VertexArray vao = gl::make_vertex_array();
  for (GLuint program : {green, red}) {
    target.begin();
    glDisable(GL_DEPTH_TEST);  // the triangle lies on the far plane
    glUseProgram(program);
    glBindVertexArray(vao.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    const std::vector<float> pixel = target.read_rgba_top_down();
    EXPECT_EQ(pixel[0], program == red ? 1.0f : 0.0f);
    EXPECT_EQ(pixel[1], program == red ? 0.0f : 1.0f);
  }
}

}  // namespace
}  // namespace thalassa
