// thalassa — the planet module's public surface: camera frames, geodesy, scripted flights, the
// scene renderer, the sky export, wakes and calm areas (issue 9).
#pragma once

#include "thalassa/planet/calm_area.hpp"
#include "thalassa/planet/camera_controls.hpp"
#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/flight.hpp"
#include "thalassa/planet/geo_bounds.hpp"
#include "thalassa/planet/geodesy.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/planet/renderer.hpp"
#include "thalassa/planet/sea_state.hpp"
#include "thalassa/planet/ship_wake.hpp"
#include "thalassa/planet/sky_export.hpp"
