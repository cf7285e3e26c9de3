// thalassa — the planet module's public surface: camera frames, geodesy, scripted flights, the
// scene renderer and the sky export.
#pragma once

#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/flight.hpp"
#include "thalassa/planet/geodesy.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/planet/renderer.hpp"
#include "thalassa/planet/sky_export.hpp"
