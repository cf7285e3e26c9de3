// thalassa — the engine's public surface for applications: GL contexts, scenes, images.
// (The GL-level surface shared by thalassa's own modules is under thalassa/engine/gl/ and is
// not installed.)
#pragma once

#include "thalassa/engine/context.hpp"
#include "thalassa/engine/file_io.hpp"
#include "thalassa/engine/gl_info.hpp"
#include "thalassa/engine/image.hpp"
#include "thalassa/engine/program.hpp"
#include "thalassa/engine/scene.hpp"
