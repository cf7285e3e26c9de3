// Wakes and calm areas on the GPU (issue 9; docs/wakes.md "On the GPU"):
// - shaders/ocean/kelvin_wake.glsl in float against ocean::kelvin_wake_at in double over a grid
//   of points of the ship frame (amplitudes, arguments, wave vectors, the linear height);
// - a scene with calm areas and a wake renders them, lists them in `built`, and a scene without
//   them compiles none of their code.
//   THALASSA_TEST_BACKEND=egl build/tests/gpu_tests --gtest_filter='LocalWaves*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "thalassa/engine/gl/hdr_target.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/ocean/kelvin_wake.hpp"
#include "thalassa/ocean/local_features.hpp"

namespace thalassa {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double RoundToFloat(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}

// |a - b| of two angles, modulo 2 pi, rad.
double AngleDifference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), kTwoPi);
  return std::min(d, kTwoPi - d);
}

class LocalWavesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = test::make_test_context();
    library_ = std::make_unique<gl::ShaderLibrary>(
        std::vector<std::filesystem::path>{THALASSA_SOURCE_DIR "/tests/gpu/shaders"});
    vao_ = gl::make_vertex_array();
  }

  // KelvinWake at each (b, y) (width x height texels), OUTPUT 1 or 2; rows bottom first.
  std::vector<glm::vec4> evaluate(int output, const std::vector<glm::vec4>& inputs, int width,
                                  int height, const glm::dvec4& params) {
    gl::Texture input = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(input.get(), 1, GL_RGBA32F, width, height);
    glTextureSubImage2D(input.get(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, inputs.data());
    gl::HdrTarget target(width, height);
    const GLuint program = library_->program({.vertex = "engine/fullscreen.vert",
                                              .fragment = "kelvin_wake_eval.frag",
                                              .defines = {{"OUTPUT", std::to_string(output)}}});
    glProgramUniform4f(program, glGetUniformLocation(program, "params"), float(params.x),
                       float(params.y), float(params.z), float(params.w));
    target.begin();
    glDisable(GL_DEPTH_TEST);
    glUseProgram(program);
    glBindTextureUnit(0, input.get());
    glBindVertexArray(vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
    const std::vector<float> top_down = target.read_rgba_top_down();
    std::vector<glm::vec4> out(inputs.size());
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const float* t = &top_down[(std::size_t(height - 1 - y) * width + x) * 4];
        out[std::size_t(y) * width + x] = glm::vec4(t[0], t[1], t[2], t[3]);
      }
    return out;
  }

  std::unique_ptr<GlContext> context_;
  std::unique_ptr<gl::ShaderLibrary> library_;
  gl::VertexArray vao_;
};

// The float shader against the double reference on a 96 x 64 grid: b from 0 to 1.05 length
// (the ship, the fade in, the far field, the tail, beyond), y / b from -0.45 to 0.45 (both
// sides, the cusp lines at +-0.354 and Airy's tail beyond), for a slow and a fast ship.
TEST_F(LocalWavesTest, KelvinWakeMatchesTheDoubleReference) {
  constexpr int kWidth = 96, kHeight = 64;
  for (const ocean::KelvinWakeParams params :
       {ocean::KelvinWakeParams{.speed = 5.0, .amplitude = 0.3, .draft = 2.0, .length = 2000.0},
        ocean::KelvinWakeParams{.speed = 12.0, .amplitude = 0.5, .draft = 4.0, .length = 5000.0}}) {
    std::vector<glm::vec4> inputs;
    for (int j = 0; j < kHeight; ++j)
      for (int i = 0; i < kWidth; ++i) {
        const double b = RoundToFloat(1.05 * params.length * (i + 0.5) / kWidth);
        const double y = RoundToFloat(b * (-0.45 + 0.9 * (j + 0.5) / kHeight));
        inputs.emplace_back(float(b), float(y), 0.0f, 0.0f);
      }
    const glm::dvec4 gpu_params = ocean::kelvin_wake_gpu_params(params);
    const std::vector<glm::vec4> waves = evaluate(1, inputs, kWidth, kHeight, gpu_params);
    const std::vector<glm::vec4> vectors = evaluate(2, inputs, kWidth, kHeight, gpu_params);
    double worst_amplitude = 0.0, worst_argument = 0.0, worst_vector = 0.0, worst_height = 0.0;
    int compared = 0;
    for (std::size_t n = 0; n < inputs.size(); ++n) {
      const ocean::KelvinWakeSample cpu = ocean::kelvin_wake_at(params, inputs[n].x, inputs[n].y);
      const glm::vec4 w = waves[n], k = vectors[n];
      for (float value : {w.x, w.y, w.z, w.w, k.x, k.y, k.z, k.w})
        ASSERT_TRUE(std::isfinite(value)) << "b " << inputs[n].x << ", y " << inputs[n].y;
      const ocean::WakeWave* branch[2] = {&cpu.transverse, &cpu.divergent};
      const double gpu_h[2] = {w.x, w.z}, gpu_theta[2] = {w.y, w.w};
      const glm::dvec2 gpu_k[2] = {{k.x, k.y}, {k.z, k.w}};
      double gpu_height = 0.0;
      for (int b = 0; b < 2; ++b) {
        const ocean::WakeWave& c = *branch[b];
        // Amplitudes relative to a_ref; arguments and wave vectors where the wave is visible
        // (above 1e-4 a_ref: the fades' ends and Airy's tail are continuous, so their arguments
        // matter only through their amplitude).
        worst_amplitude =
            std::max(worst_amplitude, std::abs(gpu_h[b] - c.amplitude) / params.amplitude);
        gpu_height += gpu_h[b] * std::cos(gpu_theta[b]);
        if (c.amplitude > 1e-4 * params.amplitude) {
          ++compared;
          worst_argument = std::max(worst_argument, AngleDifference(gpu_theta[b], c.argument));
          worst_vector =
              std::max(worst_vector, glm::length(gpu_k[b] - c.wave_vector) / c.wavenumber);
        }
      }
      worst_height =
          std::max(worst_height, std::abs(gpu_height - cpu.linear_height()) / params.amplitude);
    }
    std::printf(
        "KelvinWake float vs double, U = %.0f m/s, %d branches: amplitude %.2g a_ref, "
        "argument %.2g rad, wave vector %.2g relative, linear height %.2g a_ref\n",
        params.speed, compared, worst_amplitude, worst_argument, worst_vector, worst_height);
    EXPECT_GT(compared, kWidth * kHeight / 2);
    EXPECT_LE(worst_amplitude, 2e-6);
    EXPECT_LE(worst_argument, 1e-3);
    EXPECT_LE(worst_vector, 2e-6);
    EXPECT_LE(worst_height, 1e-4);
  }
}

}  // namespace
}  // namespace thalassa
