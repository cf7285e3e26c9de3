// thalassa — the planet module's public surface: camera frames and the scene renderer.
#pragma once

#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/renderer.hpp"
