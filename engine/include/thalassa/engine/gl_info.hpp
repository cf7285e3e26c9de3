// thalassa — what the current OpenGL context is and can do (`thalassa info`).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace thalassa {

struct GlInfo {
  std::string version;       // GL_VERSION
  std::string glsl_version;  // GL_SHADING_LANGUAGE_VERSION
  std::string vendor;        // GL_VENDOR
  std::string renderer;      // GL_RENDERER
  // The capabilities the engine relies on, each with "yes"/"no" or a number, in a fixed order:
  // core profile 4.5, float render targets, compute shaders, clip control (reversed-Z), fp64,
  // timer queries, float atomics (optional: the reference's sun scatter uses them where present),
  // context loss reported (optional: a GPU reset reads as a lost context, gl::context_reset),
  // anisotropic filtering (max), max texture size, max array texture layers, max viewport.
  std::vector<std::pair<std::string, std::string>> capabilities;
  // Names of required capabilities that are missing (empty when the engine can run).
  std::vector<std::string> missing;
};

// Queries the current context (GL functions must be loaded: any GlContext does it).
GlInfo query_gl_info();

}  // namespace thalassa
