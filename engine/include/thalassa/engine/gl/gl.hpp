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

// Throws GlError naming `where` if glGetError reports an error (draining all pending errors) or
// the context was reset (context_reset).
void check_error(const char* where);

// Empty while the context has not been reset; else what glGetGraphicsResetStatus says, e.g.
// "GL_GUILTY_CONTEXT_RESET: a command of this context made the GPU reset". Only a context made
// with a reset notification strategy (LOSE_CONTEXT_ON_RESET: thalassa's EGL contexts, where the
// driver offers it; `thalassa info`'s "context loss reported") is told: in any other, a GPU
// fault leaves the context running on, its reads undefined. After a reset every GL call of the
// context is void: it must be made again.
std::string context_reset();

// Whether the current context was made to be told of GPU resets (its reset notification
// strategy is LOSE_CONTEXT_ON_RESET), so that context_reset can report one.
bool context_told_of_resets();

}  // namespace thalassa::gl
