// thalassa — the scene keys `wakes` and `calm_areas` (issue 9, point 3): checking inline entries
// and GeoJSON files, and their typed form. Private to the engine (scene.cpp calls it); the
// formats are documented in docs/scene.md ("Wakes and calm areas") and docs/wakes.md.
//
// Every check throws SceneError with one line "<source>: <key path>: expected ..., got ...",
// where <source> is the scene (or the GeoJSON file, for an error inside it) and the key path
// names the entry ("wakes[1].track[3].time") or the GeoJSON feature ("features[2] (\"ferry\")
// .properties.times[3]").
#pragma once

#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "thalassa/engine/scene.hpp"

namespace thalassa::detail {

// Checks the value of `wakes` / `calm_areas` from `source` (a scene file's path, "--set" or
// "defaults"; relative GeoJSON paths are resolved from the scene file's folder, or the working
// directory for the others) and returns it in canonical form: an array of inline entries with
// every field written out, GeoJSON files read and expanded (one entry per feature, or per
// polygon of a MultiPolygon). The canonical form is itself a valid value of the key. `key` is
// the key's name as messages show it (with any prefix: "scene.wakes").
nlohmann::json check_wakes(const nlohmann::json& value, std::string_view source,
                           std::string_view key);
nlohmann::json check_calm_areas(const nlohmann::json& value, std::string_view source,
                                std::string_view key);

// The typed form of a canonical value.
std::vector<WakeSettings> wakes_from(const nlohmann::json& canonical);
std::vector<CalmAreaSettings> calm_areas_from(const nlohmann::json& canonical);

}  // namespace thalassa::detail
