// Shared by the GPU tests: the backend under test (THALASSA_TEST_BACKEND, "egl" by default),
// a context with this program's own GL function table loaded (as a host application would),
// and where failing tests write their diagnostics.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "thalassa/thalassa.hpp"

namespace thalassa::test {

Backend backend_under_test();
// A context of the backend under test, current, with the test program's glad table loaded.
std::unique_ptr<GlContext> make_test_context();
// THALASSA_TEST_OUTPUT_DIR/<backend>/, created on demand.
std::string output_dir();
// The scene of `json` laid over the defaults.
Scene scene_from(const std::string& json);

// Runs a full-screen fragment `program` (vertex shader engine/fullscreen.vert, its uniforms
// already set) over a width x height float target, its input texels bound as an RGBA32F texture
// on unit 0, and returns the target's texels in the same order as `texels` (row 0 first, as
// texelFetch sees them). For the shader-function tests that compare GPU and CPU over a grid.
std::vector<glm::vec4> evaluate_fragment(unsigned program, const std::vector<glm::vec4>& texels,
                                         int width, int height);

// The HDR target's depth after `renderer`'s render() (reversed-Z: 0 where no triangle was drawn,
// the sky's and the holes the backstop shades), width x height, rows bottom first (as
// gl_FragCoord counts them). Restores the read framebuffer binding.
std::vector<float> read_depth(const Renderer& renderer, int width, int height);

}  // namespace thalassa::test
