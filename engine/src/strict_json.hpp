// thalassa — strict JSON input, shared by the readers of scene files (engine/src/scene.cpp),
// flight files (planet/src/flight.cpp) and suite files (validation/src/suite.cpp). Private to the
// library. Every reader refuses bad input with one line of the form
//   "<source>: <key path>: expected <what>, got <what was found>"
// (SceneError's, engine/scene.hpp) and throws its own exception type: the functions here build
// the message, and call the reader's `fail` to throw it.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace thalassa::detail {

// The one-line message: an empty `key` is for errors about the whole input (syntax, an
// unreadable file); line breaks in a path or value become spaces.
std::string input_message(std::string_view source, std::string_view key, std::string_view expected,
                          std::string_view got);

// Throws the reader's exception with input_message(source, key, expected, got). It must throw.
using FailFunction = void (*)(std::string_view source, std::string_view key,
                              std::string_view expected, std::string_view got);

// Parses `text` as JSON in which each object gives each key once: JSON allows a repeat and
// nlohmann keeps the last, which would drop a value silently. Refused through `fail`:
//   "<source>:<line>:<column>: expected valid JSON, got <the parser's reason>"  (syntax)
//   "<source>: expected valid JSON, got number overflow ..."                  (no position)
//   "<source>: <prefix><a.b.c>: expected each key once, got \"c\" a second time"
// `key_prefix` goes in front of key paths ("scene." for a scene nested in a flight file).
// Json is nlohmann::json or nlohmann::ordered_json (which keeps the file's key order).
template <class Json>
Json parse_strict_json(std::string_view text, std::string_view source, std::string_view key_prefix,
                       FailFunction fail);

// The whole content of the file at `path`, or a refusal through `fail` saying it is missing, a
// directory or unreadable, "expected a readable <what>". With an empty `source` the message names
// the path itself ("x.json: expected a readable flight file, got no such file"); otherwise it
// names the file that referred to it and its key ("f.json: steps[0].scene: expected a readable
// scene file ..., got \"x.json\", no such file").
std::string read_text_file(const std::string& path, std::string_view what, std::string_view source,
                           std::string_view key, FailFunction fail);

}  // namespace thalassa::detail
