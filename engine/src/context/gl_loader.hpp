// Loads the GL 4.5 core function table with glad through a context API's GetProcAddress and
// checks that the context really is 4.5 core. Shared by every backend.
#pragma once

#include <string>

#include "thalassa/engine/context.hpp"

namespace thalassa::detail {

// Loads GL through `get_proc_address` for the current context. Throws ContextError naming
// `who` when loading fails or the version is below 4.5.
void load_gl_functions(GlProcAddressFn get_proc_address, const std::string& who, bool debug);

// thalassa has one GL function table for the process. Contexts of one driver share it; a
// context of another driver (a vendor's EGL beside Mesa's OSMesa) needs its own functions, so
// making a context current reloads the table when its GetProcAddress differs from the one that
// filled it last. Cheap when nothing changes.
void use_gl_functions(GlProcAddressFn get_proc_address, const std::string& who);

}  // namespace thalassa::detail
