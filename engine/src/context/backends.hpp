// The backend constructors behind create_context(). Each lives in its own file so that the
// window-system and OSMesa headers (which include <GL/gl.h>) never meet glad's header.
#pragma once

#include <memory>

#include "thalassa/engine/context.hpp"

namespace thalassa::detail {

std::unique_ptr<GlContext> create_egl_context(const ContextOptions& options);
std::unique_ptr<GlContext> create_osmesa_context(const ContextOptions& options);
std::unique_ptr<GlContext> create_glfw_context(const ContextOptions& options);

}  // namespace thalassa::detail
