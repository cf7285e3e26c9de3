// Shared by the GPU tests: the backend under test (THALASSA_TEST_BACKEND, "egl" by default),
// a context with this program's own GL function table loaded (as a host application would),
// and where failing tests write their diagnostics.
#pragma once

#include <memory>
#include <string>

#include "thalassa/thalassa.hpp"

namespace thalassa::test {

Backend backend_under_test();
// A context of the backend under test, current, with the test program's glad table loaded.
std::unique_ptr<GlContext> make_test_context();
// THALASSA_TEST_OUTPUT_DIR/<backend>/, created on demand.
std::string output_dir();
// The scene of `json` laid over the defaults.
Scene scene_from(const std::string& json);

}  // namespace thalassa::test
