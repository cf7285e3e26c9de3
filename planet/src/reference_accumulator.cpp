#include "reference_accumulator.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "thalassa/engine/gl/gl.hpp"

namespace thalassa {

// reference_accumulate.comp's std430 struct, member for member.
static_assert(sizeof(glm::dvec3) == 24);
static_assert(offsetof(ReferencePixelSums, weighted) == 24);
static_assert(offsetof(ReferencePixelSums, plain) == 48);
static_assert(offsetof(ReferencePixelSums, weight) == 72);
static_assert(offsetof(ReferencePixelSums, sea) == 80);
static_assert(offsetof(ReferencePixelSums, nonfinite) == 88);
static_assert(sizeof(ReferencePixelSums) == 96);

namespace {
// The compute pass's work group: 8 x 8 pixels (reference_accumulate.comp).
constexpr int kGroupSide = 8;
// Buffer binding and texture unit of the pass (both among those gl::StateGuard restores).
constexpr GLuint kSumsBinding = 1;
constexpr GLuint kSampleUnit = 0;
}  // namespace

void add_reference_sample(ReferencePixelSums& sums, const float rgba[4]) {
  const glm::dvec3 radiance(rgba[0], rgba[1], rgba[2]);
  if (!(std::isfinite(rgba[0]) && std::isfinite(rgba[1]) && std::isfinite(rgba[2])))
    ++sums.nonfinite;
  const double code = std::abs(double(rgba[3]));
  if (!std::isnan(rgba[3]) && code >= kReferenceSeaAlpha) {
    const double w = std::isfinite(rgba[3]) ? code - kReferenceSeaAlpha : 0.0;
    sums.weighted += w * radiance;
    sums.plain += radiance;
    sums.weight += w;
    ++sums.sea;
    if (rgba[3] > 0.0f) ++sums.resolved;
  } else {
    sums.sky += radiance;
    ++sums.resolved;
  }
}

ReferenceAccumulator::ReferenceAccumulator(int width, int height, gl::ShaderLibrary& shaders)
    : width_(width),
      height_(height),
      buffer_(gl::make_buffer()),
      program_(shaders.program({.compute = "planet/reference_accumulate.comp"})),
      size_location_(glGetUniformLocation(program_, "image_size")),
      image_location_(glGetUniformLocation(program_, "sample_image")) {
  const std::size_t bytes = std::size_t(width) * std::size_t(height) * sizeof(ReferencePixelSums);
  if (width < 1 || height < 1 || bytes > std::size_t(std::numeric_limits<GLsizeiptr>::max()))
    throw gl::GlError("reference sums: " + std::to_string(width) + "x" + std::to_string(height) +
                      " pixels do not fit one GL buffer");
  glNamedBufferStorage(buffer_.get(), static_cast<GLsizeiptr>(bytes), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  gl::check_error("reference sums: buffer");
  clear();
}

void ReferenceAccumulator::clear() {
  const std::uint32_t zero = 0;  // every member's zero is all bits 0
  glClearNamedBufferData(buffer_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

void ReferenceAccumulator::add(GLuint texture) {
  // Set at each pass: another accumulator of the same shader library shares the program.
  glUseProgram(program_);
  glProgramUniform2i(program_, size_location_, width_, height_);
  glProgramUniform1i(program_, image_location_, GLint(kSampleUnit));
  glBindTextureUnit(kSampleUnit, texture);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSumsBinding, buffer_.get());
  // The previous sample's sums written before this pass reads them.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glDispatchCompute(GLuint((width_ + kGroupSide - 1) / kGroupSide),
                    GLuint((height_ + kGroupSide - 1) / kGroupSide), 1);
  // The next frame renders into the texture: not bound to a unit while it does.
  glBindTextureUnit(kSampleUnit, 0);
  gl::check_error("reference sums: add");
}

std::vector<ReferencePixelSums> ReferenceAccumulator::read() const {
  std::vector<ReferencePixelSums> sums(std::size_t(width_) * std::size_t(height_));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffer_.get(), 0,
                          static_cast<GLsizeiptr>(sums.size() * sizeof(ReferencePixelSums)),
                          sums.data());
  gl::check_error("reference sums: read");
  return sums;
}

}  // namespace thalassa
