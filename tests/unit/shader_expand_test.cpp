// The shader library's CPU side: #include expansion with #line mapping, defines after
// #version, errors for missing files, cycles and stray #version, and the mapping of Mesa and
// NVIDIA compiler logs back to file:line. (Compiling on a GL context: tests/gpu.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "thalassa/engine/gl/shader_library.hpp"

namespace thalassa::gl {
namespace {

namespace fs = std::filesystem;

class ShaderExpand : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("thalassa_shaders_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "lib");
    write("lib/a.glsl", "float A() { return 1.0; }\n");
    write("lib/b.glsl", "#include \"lib/a.glsl\"\nfloat B() { return A(); }\n");
    write("main.frag", "// main\n#include \"lib/b.glsl\"\nvoid main() {}\n");
    write("cycle.glsl", "#include \"cycle.glsl\"\n");
    write("versioned.glsl", "#version 330\n");
    write("bad_include.glsl", "#include <lib/a.glsl>\n");
  }
  void TearDown() override { fs::remove_all(root_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(root_ / name) << text;
  }
  fs::path root_;
};

TEST_F(ShaderExpand, IncludesAreExpandedWithLineDirectives) {
  ShaderLibrary library({root_});
  const ExpandedSource source = library.expand("main.frag", {{"FEATURE", "1"}, {"FLAG", ""}});
  EXPECT_EQ(source.files, (std::vector<std::string>{"main.frag", "lib/b.glsl", "lib/a.glsl"}));
  const std::string expected =
      "#version 450 core\n#define FEATURE 1\n#define FLAG\n#line 1 0\n"
      "// main\n"
      "#line 1 1\n"
      "#line 1 2\nfloat A() { return 1.0; }\n#line 2 1\n"
      "float B() { return A(); }\n"
      "#line 3 0\n"
      "void main() {}\n";
  EXPECT_EQ(source.text, expected);
}

TEST_F(ShaderExpand, ErrorsNameTheFile) {
  ShaderLibrary library({root_});
  try {
    library.expand("cycle.glsl", {});
    FAIL() << "a cycle must be an error";
  } catch (const ShaderError& error) {
    EXPECT_NE(std::string(error.what()).find("cycle"), std::string::npos);
  }
  EXPECT_THROW(library.expand("missing.frag", {}), ShaderError);
  EXPECT_THROW(library.expand("versioned.glsl", {}), ShaderError);
  EXPECT_THROW(library.expand("bad_include.glsl", {}), ShaderError);
  EXPECT_THROW(library.expand("/abs/path.frag", {}), ShaderError);
  EXPECT_THROW(library.expand("main.frag", {{"BAD NAME", "1"}}), ShaderError);
}

TEST_F(ShaderExpand, FirstRootWins) {
  const fs::path other = root_ / "other";
  fs::create_directories(other / "lib");
  std::ofstream(other / "lib/a.glsl") << "float A() { return 2.0; }\n";
  ShaderLibrary library({other, root_});
  EXPECT_EQ(library.resolve("lib/a.glsl"), other / "lib/a.glsl");
  EXPECT_EQ(library.resolve("lib/b.glsl"), root_ / "lib/b.glsl");
}

TEST(ShaderLog, MesaAndNvidiaFormatsMapToFileAndLine) {
  const std::vector<std::string> files = {"ocean/sea.frag", "common/definitions.glsl"};
  EXPECT_EQ(ShaderLibrary::map_log("1:12(5): error: `x' undeclared\n", files),
            "common/definitions.glsl:12: error: `x' undeclared\n");
  EXPECT_EQ(ShaderLibrary::map_log("0(7) : error C1008: undefined variable \"y\"\n", files),
            "ocean/sea.frag:7: error C1008: undefined variable \"y\"\n");
  EXPECT_EQ(ShaderLibrary::map_log("9:3(1): warning: w\n", files), "source 9:3: warning: w\n");
  EXPECT_EQ(ShaderLibrary::map_log("plain text\n", files), "plain text\n");
}

TEST(ShaderRoots, TheRepositoryShadersAreFound) {
  ShaderLibrary library;
  EXPECT_TRUE(fs::is_regular_file(library.resolve("engine/fullscreen.vert")));
}

}  // namespace
}  // namespace thalassa::gl
