#include "thalassa/engine/gl/shader_library.hpp"

#include <dlfcn.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

namespace thalassa::gl {
namespace {

namespace fs = std::filesystem;

// Deeper nesting than this is taken for an include cycle.
constexpr int kMaxIncludeDepth = 32;

std::vector<fs::path> default_roots(std::vector<fs::path> extra) {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("THALASSA_SHADER_PATH")) {
    std::stringstream list(env);
    for (std::string item; std::getline(list, item, ':');)
      if (!item.empty()) candidates.emplace_back(item);
  }
  for (auto& path : extra) candidates.push_back(std::move(path));
  // share/thalassa/shaders relative to the library file itself, so that a relocated install
  // finds its own shaders before anything compiled in.
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&default_roots), &info) != 0 && info.dli_fname != nullptr) {
    std::error_code ec;
    fs::path library = fs::canonical(info.dli_fname, ec);
    if (!ec) candidates.push_back(library.parent_path() / THALASSA_SHADER_RELATIVE_DIR);
  }
  // THALASSA_SHADER_BUILTIN_PATHS=0 leaves out the folders compiled into the library, so that
  // a relocated install (and the package test) can prove it uses its own shaders.
  const char* builtin = std::getenv("THALASSA_SHADER_BUILTIN_PATHS");
  if (builtin == nullptr || std::string(builtin) != "0") {
    candidates.emplace_back(THALASSA_SHADER_INSTALL_DIR);
    candidates.emplace_back(THALASSA_SHADER_SOURCE_DIR);
  }
  std::vector<fs::path> roots;
  for (const auto& candidate : candidates) {
    std::error_code ec;
    if (fs::is_directory(candidate, ec)) roots.push_back(fs::weakly_canonical(candidate, ec));
  }
  return roots;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ShaderError(path.string() + ": cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Parses `#include "x"` (leading white space allowed); returns the path or "" if not one.
std::string include_target(const std::string& line, const std::string& file, int line_number) {
  std::size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || line[i] != '#') return "";
  i = line.find_first_not_of(" \t", i + 1);
  if (i == std::string::npos || line.compare(i, 7, "include") != 0) return "";
  const std::size_t open = line.find('"', i + 7);
  const std::size_t close = open == std::string::npos ? open : line.find('"', open + 1);
  if (close == std::string::npos)
    throw ShaderError(file + ":" + std::to_string(line_number) +
                      ": #include expects a quoted path: " + line);
  return line.substr(open + 1, close - open - 1);
}

struct Expander {
  const ShaderLibrary& library;
  ExpandedSource out;

  int file_index(const std::string& path) {
    for (std::size_t i = 0; i < out.files.size(); ++i)
      if (out.files[i] == path) return static_cast<int>(i);
    out.files.push_back(path);
    return static_cast<int>(out.files.size() - 1);
  }

  void expand(const std::string& path, int depth, const std::string& included_from) {
    if (depth > kMaxIncludeDepth)
      throw ShaderError(included_from + ": #include nested deeper than " +
                        std::to_string(kMaxIncludeDepth) + " (a cycle?) at " + path);
    fs::path absolute;
    try {
      absolute = library.resolve(path);
    } catch (const ShaderError& error) {
      throw ShaderError((included_from.empty() ? "" : included_from + ": ") + error.what());
    }
    const int index = file_index(path);
    std::istringstream in(read_file(absolute));
    int line_number = 0;
    for (std::string line; std::getline(in, line);) {
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const std::string target = include_target(line, path, line_number);
      if (target.empty()) {
        // A #version in a library file would land in the middle of the shader.
        const std::size_t i = line.find_first_not_of(" \t");
        if (i != std::string::npos && line.compare(i, 8, "#version") == 0)
          throw ShaderError(path + ":" + std::to_string(line_number) +
                            ": #version is added by the shader library; remove it");
        out.text += line;
        out.text += '\n';
        continue;
      }
      out.text += "#line 1 " + std::to_string(file_index(target)) + "\n";
      expand(target, depth + 1, path + ":" + std::to_string(line_number));
      out.text += "#line " + std::to_string(line_number + 1) + " " + std::to_string(index) + "\n";
    }
  }
};

std::string describe(const ProgramDesc& desc) {
  std::string key = desc.compute.empty() ? desc.vertex + "+" + desc.fragment : desc.compute;
  if (!desc.defines.empty()) {
    key += "[";
    bool first = true;
    for (const auto& [name, value] : desc.defines) {
      key += (first ? "" : ",") + name + (value.empty() ? "" : "=" + value);
      first = false;
    }
    key += "]";
  }
  return key;
}

}  // namespace

ShaderLibrary::ShaderLibrary(std::vector<fs::path> extra_roots)
    : roots_(default_roots(std::move(extra_roots))) {}

fs::path ShaderLibrary::resolve(const std::string& relative) const {
  if (relative.empty() || fs::path(relative).is_absolute())
    throw ShaderError("shader path must be relative to the shader root: '" + relative + "'");
  for (const auto& root : roots_) {
    std::error_code ec;
    fs::path candidate = root / relative;
    if (fs::is_regular_file(candidate, ec)) return candidate;
  }
  std::string searched;
  for (const auto& root : roots_) searched += " " + root.string();
  throw ShaderError("shader '" + relative + "' not found in:" +
                    (searched.empty() ? std::string(" (no shader folder exists)") : searched) +
                    " (set THALASSA_SHADER_PATH to the shaders/ folder)");
}

ExpandedSource ShaderLibrary::expand(const std::string& path, const Defines& defines) const {
  Expander expander{*this, {}};
  expander.out.text = "#version 450 core\n";
  for (const auto& [name, value] : defines) {
    if (name.empty() || name.find_first_of(" \t\n") != std::string::npos)
      throw ShaderError(path + ": invalid feature macro name '" + name + "'");
    expander.out.text += "#define " + name + (value.empty() ? "" : " " + value) + "\n";
  }
  expander.out.text += "#line 1 0\n";
  expander.expand(path, 0, "");
  return std::move(expander.out);
}

std::string ShaderLibrary::map_log(const std::string& log, const std::vector<std::string>& files) {
  // Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error C0000: ...".
  static const std::regex mesa(R"(^\s*(\d+):(\d+)\((\d+)\):\s*(.*)$)");
  static const std::regex nvidia(R"(^\s*(\d+)\((\d+)\)\s*:\s*(.*)$)");
  std::istringstream in(log);
  std::string mapped;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    std::smatch m;
    std::string file, line_no, text;
    if (std::regex_match(line, m, mesa)) {
      file = m[1];
      line_no = m[2];
      text = m[4];
    } else if (std::regex_match(line, m, nvidia)) {
      file = m[1];
      line_no = m[2];
      text = m[3];
    }
    if (!file.empty()) {
      const std::size_t index = std::stoul(file);
      const std::string name = index < files.size() ? files[index] : "source " + file;
      mapped += name + ":" + line_no + ": " + text + "\n";
    } else {
      mapped += line + "\n";
    }
  }
  return mapped;
}

GLuint ShaderLibrary::compile(GLenum stage, const std::string& path, const Defines& defines) const {
  const ExpandedSource source = expand(path, defines);
  GLuint shader = glCreateShader(stage);
  const char* text = source.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    std::string defines_text;
    for (const auto& [name, value] : defines) defines_text += " " + name + "=" + value;
    throw ShaderError("shader compile failed: " + path +
                      (defines_text.empty() ? "" : " (defines:" + defines_text + ")") + "\n" +
                      map_log(log.c_str(), source.files));
  }
  return shader;
}

GLuint ShaderLibrary::program(const ProgramDesc& desc) {
  const std::string key = describe(desc);
  if (auto it = programs_.find(key); it != programs_.end()) {
    it->second.last_use = use_record_;
    return it->second.name.get();
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<ShaderName> shaders;
  if (!desc.compute.empty()) {
    shaders.emplace_back(compile(GL_COMPUTE_SHADER, desc.compute, desc.defines));
  } else {
    if (desc.vertex.empty() || desc.fragment.empty())
      throw ShaderError(key + ": a program needs a vertex and a fragment shader, or a compute one");
    shaders.emplace_back(compile(GL_VERTEX_SHADER, desc.vertex, desc.defines));
    shaders.emplace_back(compile(GL_FRAGMENT_SHADER, desc.fragment, desc.defines));
  }
  ProgramName program(glCreateProgram());
  for (const auto& shader : shaders) glAttachShader(program.get(), shader.get());
  glLinkProgram(program.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program.get(), length, nullptr, log.data());
    throw ShaderError("shader link failed: " + key + "\n" + log.c_str());
  }
  for (const auto& shader : shaders) glDetachShader(program.get(), shader.get());
  const GLuint name = program.get();
  programs_.emplace(key, Program{std::move(program), use_record_});
  compile_ms_ +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return name;
}

std::vector<std::string> ShaderLibrary::built_programs() const {
  std::vector<std::string> keys;
  for (const auto& entry : programs_) keys.push_back(entry.first);
  return keys;
}

std::vector<std::string> ShaderLibrary::used_programs() const {
  std::vector<std::string> keys;
  for (const auto& [key, program] : programs_)
    if (program.last_use == use_record_) keys.push_back(key);
  return keys;
}

}  // namespace thalassa::gl
