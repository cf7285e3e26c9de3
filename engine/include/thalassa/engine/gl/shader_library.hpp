// thalassa — the shader library: GLSL sources under shaders/, `#include "path"`, feature
// permutations through `#define`, and compile or link errors reported with the original file
// and line.
//
// Sources are looked up, in order, in: the folders of the THALASSA_SHADER_PATH environment
// variable (colon-separated), the folders given to the constructor, share/thalassa/shaders next
// to the installed library, the install prefix's share/thalassa/shaders, and the source tree's
// shaders/ (for the build tree); THALASSA_SHADER_BUILTIN_PATHS=0 leaves out the last two. `#include
// "path"` paths are relative to that root and are expanded textually, as in C (library files carry
// include guards; a cycle is an error). A
// `#line L F` directive before and after each inclusion makes the driver's messages point at
// source string F, which the library maps back to the file's name.
#pragma once

#include "thalassa/engine/gl/objects.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace thalassa::gl {

// A shader failed to load, compile or link. what() lists each message as "file:line: text".
class ShaderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One feature permutation: macro names and values, inserted after `#version` as `#define N V`.
using Defines = std::map<std::string, std::string>;

struct ProgramDesc {
  std::string vertex;    // path under the shader root, e.g. "engine/fullscreen.vert"
  std::string fragment;  // e.g. "atmosphere/sky.frag"; empty for compute programs
  std::string compute;   // e.g. "atmosphere/transmittance.comp"
  Defines defines;
};

// The source after #include expansion, with the table that maps GLSL source-string numbers
// (the second argument of #line) to file paths.
struct ExpandedSource {
  std::string text;
  std::vector<std::string> files;  // index = source-string number
};

class ShaderLibrary {
 public:
  explicit ShaderLibrary(std::vector<std::filesystem::path> extra_roots = {});

  // The folders searched, in order (only those that exist).
  const std::vector<std::filesystem::path>& roots() const { return roots_; }
  // The absolute path of `relative`, or ShaderError if no root has it.
  std::filesystem::path resolve(const std::string& relative) const;

  // Reads `path`, expands includes and inserts `#version 450 core` and the defines.
  ExpandedSource expand(const std::string& path, const Defines& defines) const;

  // Compiles and links (cached by description): the returned GL program name stays owned by
  // the library. Throws ShaderError with file:line messages.
  GLuint program(const ProgramDesc& desc);
  // Every program built so far, as "vertex+fragment[DEFINE=V,...]", for statistics.
  std::vector<std::string> built_programs() const;
  // The programs built so far, and the wall-clock ms spent compiling and linking them (the
  // driver's work included: the link status waits for it).
  std::size_t program_count() const { return programs_.size(); }
  double compile_ms() const { return compile_ms_; }
  // The programs asked for (built, or found built) since the last start_use_record(), or since
  // the library was made, in the form of built_programs(): what a renderer's current scene uses
  // of a library that its earlier scenes filled (planet/renderer.hpp, Renderer::set_scene).
  void start_use_record() { ++use_record_; }
  std::vector<std::string> used_programs() const;

  // Maps a driver info log (Mesa "0:12(5): error: ..." or NVIDIA "0(12) : error C0000: ...")
  // to "file:line: ..." lines using the source-string table.
  static std::string map_log(const std::string& log, const std::vector<std::string>& files);

 private:
  GLuint compile(GLenum stage, const std::string& path, const Defines& defines) const;
  std::vector<std::filesystem::path> roots_;
  struct Program {
    ProgramName name;
    unsigned long long last_use = 0;  // the use record it was last asked for in
  };
  std::map<std::string, Program> programs_;
  unsigned long long use_record_ = 0;
  double compile_ms_ = 0.0;
};

}  // namespace thalassa::gl
