// thalassa — test suites: named variants of a scene that a program renders and checks, each
// with the exit status it must end with (docs/suites.md). `thalassa validate` runs them (issue 6);
// the tests run the same files in-process (tests/gpu/stress_test.cpp).
//
// A suite is a JSON file: a name, optional `base` overrides laid under every case, and a list of
// cases, each a set of scene-key overrides in the dotted `--set` form ("camera.height": 0.01)
// and the expected exit status, 0 (the scene renders; every pixel finite) or 2 (the scene is
// invalid input; the error message must contain `error`). Loading checks the file's own shape
// and that every override names a scene key; it does not check the values against the scene's
// ranges, since a case that expects 2 holds an out-of-range value on purpose.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "thalassa/engine/scene.hpp"

namespace thalassa {

// A suite file that cannot be used. what() is one line, like SceneError's:
//   "<source>: <path in the file>: expected <what>, got <what was found>", e.g.
//   "stress.json: cases[3].set.camera.hieght: expected a scene key (docs/scene.md),
//   got an unknown key".
class SuiteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One scene-key override: the dotted key path and its value as JSON text ("0.01", "\"omega-2\"").
using SuiteOverride = std::pair<std::string, std::string>;

struct SuiteCase {
  std::string name;                      // [a-z0-9_]+, unique within the suite
  std::string description;               // why the case is there ("" when not given)
  std::vector<SuiteOverride> overrides;  // in file order
  int expected_exit = 0;                 // 0 (renders, every pixel finite) or 2 (invalid input)
  std::string expected_error;            // with 2: a substring of the one-line error message
};

struct Suite {
  std::string name;  // [a-z0-9_]+
  std::string description;
  std::vector<SuiteOverride> base;  // laid under every case's overrides
  std::vector<SuiteCase> cases;     // in file order, at least one
};

// Parses a suite; `source` names it in messages. Throws SuiteError.
Suite load_suite_text(std::string_view json_text, std::string_view source);
// Reads and parses a suite file; a missing or unreadable file is a SuiteError.
Suite load_suite_file(const std::string& path);

// The `--set` assignments of a case ("key.path=value"): the suite's base, then the case's own
// overrides (a case's value wins over the base's for the same key).
std::vector<std::string> suite_case_assignments(const Suite& suite, const SuiteCase& c);
// The case's scene: the embedded defaults, then suite_case_assignments(). Throws SceneError where
// the case's scene is invalid input (as a case expecting exit status 2 requires).
Scene build_suite_case_scene(const Suite& suite, const SuiteCase& c);

}  // namespace thalassa
