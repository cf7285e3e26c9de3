// The disk cache of the atmosphere's tables (internal; atmosphere/src/model.cpp), exposed for
// the tests of the loader (tests/unit/atmosphere_model_test.cpp).
//
// File layout: 8 magic bytes, the key's length (uint64) and text, then for each table of
// ModelTables in order its float count (uint64) and floats (RGB, the texture's layout), in the
// machine's byte order, and nothing after.
#pragma once

#include <string>

#include "model_tables.hpp"

namespace thalassa::atmosphere {

// The cache key of `parameters`: every field and the model's table layout and sample counts.
std::string cache_key(const AtmosphereParameters& parameters);
// The file name (no folder) of that key: "atmosphere-<64-bit FNV-1a of the key>.bin".
std::string cache_file_name(const std::string& key);

// Reads the tables of `key` from `path`: false (tables unspecified) for a missing file, another
// key, a wrong size, a truncated file, trailing bytes, or a value that is not finite and >= 0.
bool load_cache(const std::string& path, const std::string& key, ModelTables& tables);
// Writes them through a unique temporary file renamed into place (concurrent writers never leave
// a half-written file). Returns an empty string, or why it failed.
std::string store_cache(const std::string& path, const std::string& key, const ModelTables& tables);

}  // namespace thalassa::atmosphere
