// thalassa — the GL layer shared by thalassa's modules (atmosphere, ocean, planet).
//
// Everything under thalassa/engine/gl/ uses glad's OpenGL 4.5 core header. It is the engine's
// surface for the other modules of thalassa and is NOT installed: applications use the GL-free
// headers (context, scene, image, renderer), so thalassa's loader can never clash with theirs.
#pragma once

#include <glad/gl.h>

#include <stdexcept>
#include <string>

namespace thalassa::gl {

// A GL call failed at run time (framebuffer incomplete, out of memory, ...).
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws GlError naming `where` if glGetError reports an error (draining all pending errors).
void check_error(const char* where);

}  // namespace thalassa::gl
