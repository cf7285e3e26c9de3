// thalassa — the CPU side of a frame's wakes and calm areas (ocean/local_features.hpp) and
// their upload (ocean/gl/local_features_gpu.hpp).
#include "thalassa/ocean/local_features.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/ocean/gl/local_features_gpu.hpp"

namespace thalassa::ocean {

glm::dvec4 kelvin_wake_gpu_params(const KelvinWakeParams& params) {
  return {kelvin_transverse_wavenumber(params.speed),
          params.amplitude * kelvin_reference_normalisation(), params.draft, params.length};
}

WakeFrameCoordinates wake_frame_coordinates(const WakeInFrame& wake, glm::dvec2 p) {
  WakeFrameCoordinates c;
  double best = INFINITY, along = 0.0;
  for (std::size_t j = 0; j + 1 < wake.track.size(); ++j) {
    const glm::dvec2 newer = wake.track[j], older = wake.track[j + 1];
    const double len = glm::length(newer - older);
    if (!(len > 0.0)) continue;
    const glm::dvec2 e = (newer - older) / len;  // the direction of travel
    const double t = std::clamp(glm::dot(p - older, e), 0.0, len);
    const glm::dvec2 foot = older + t * e;
    const double d = glm::length(p - foot);
    if (d < best) {
      best = d;
      c.behind = along + (len - t);
      c.lateral = glm::dot(p - foot, glm::dvec2(-e.y, e.x)) < 0.0 ? -d : d;
      c.course = e;
    }
    along += len;
  }
  c.present = best <= kelvin_wake_half_width(wake.params) && c.behind > 0.0 &&
              c.behind < std::min(wake.params.length, along);
  return c;
}

double calm_tail_variance_bound(double steepness) {
  const double x = std::min(std::abs(steepness), 1.0);
  return 2.0 / (1.0 + std::sqrt((1.0 - x) * (1.0 + x)));
}

LocalFeatureBuffers::LocalFeatureBuffers(const LocalFeatures& features) {
  if (features.calm && features.calm->width > 0 && features.calm->height > 0) {
    const CalmScaleChart& chart = *features.calm;
    calm_texture_ = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(calm_texture_.get(), 1, GL_R32F, chart.width, chart.height);
    glTextureSubImage2D(calm_texture_.get(), 0, 0, 0, chart.width, chart.height, GL_RED, GL_FLOAT,
                        chart.scale.data());
    // Bilinear between samples; beyond the chart its border samples (s = 1) go on.
    gl::set_sampling(calm_texture_.get(), {});
    calm_areas_ = std::max(chart.areas, 1);
    calm_width_ = chart.width;
    calm_height_ = chart.height;
    calm_origin_ = chart.origin;
    calm_spacing_ = chart.spacing;
  }
  if (!features.wakes.empty()) {
    // Per wake three vec4 (shaders/ocean/local_waves.glsl): the parameters, (half-width, first
    // point, point count, 0) and the box (m) its polyline grown by the half-width covers; the
    // polylines' points in a second buffer.
    std::vector<float> packed, points;
    for (const WakeInFrame& wake : features.wakes) {
      const glm::dvec4 p = kelvin_wake_gpu_params(wake.params);
      // Slightly widened (1e-4 relative) so that float rounding never cuts the Airy tail.
      const double half_width = 1.0001 * kelvin_wake_half_width(wake.params);
      glm::dvec2 lo(INFINITY), hi(-INFINITY);
      for (const glm::dvec2& q : wake.track) {
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
      }
      lo -= half_width;
      hi += half_width;
      for (double value : {p.x, p.y, p.z, p.w, half_width, double(points.size() / 2),
                           double(wake.track.size()), 0.0, lo.x, lo.y, hi.x, hi.y})
        packed.push_back(static_cast<float>(value));
      for (const glm::dvec2& q : wake.track) {
        points.push_back(static_cast<float>(q.x));
        points.push_back(static_cast<float>(q.y));
      }
    }
    wake_buffer_ = gl::make_buffer();
    glNamedBufferStorage(wake_buffer_.get(), static_cast<GLsizeiptr>(packed.size() * sizeof(float)),
                         packed.data(), 0);
    track_buffer_ = gl::make_buffer();
    glNamedBufferStorage(track_buffer_.get(),
                         static_cast<GLsizeiptr>(points.size() * sizeof(float)), points.data(), 0);
    wake_count_ = static_cast<int>(features.wakes.size());
    track_points_ = static_cast<int>(points.size() / 2);
  }
}

int LocalFeatureBuffers::loop_iterations_per_point() const {
  // Three loops over the wakes (local_waves.glsl), and in two of them each wake's track (the
  // frame of its nearest piece), plus each loop's exit.
  return 3 * (wake_count_ + 1) + 2 * (track_points_ + wake_count_);
}

void LocalFeatureBuffers::add_defines(gl::Defines& defines) const {
  if (calm_areas()) defines["CALM_AREAS"] = "1";
  if (wake_count_ > 0) defines["KELVIN_WAKES"] = "1";
}

void LocalFeatureBuffers::set_uniforms(unsigned program) const {
  if (calm_areas())
    glProgramUniform3f(program, glGetUniformLocation(program, "calm_chart"), float(calm_origin_.x),
                       float(calm_origin_.y), float(1.0 / calm_spacing_));
  if (wake_count_ > 0)
    glProgramUniform1i(program, glGetUniformLocation(program, "wake_count"), wake_count_);
}

void LocalFeatureBuffers::bind() const {
  if (calm_areas()) glBindTextureUnit(kCalmScaleUnit, calm_texture_.get());
  if (wake_count_ > 0) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWakeBufferBinding, wake_buffer_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWakeTrackBufferBinding, track_buffer_.get());
  }
}

std::vector<std::string> LocalFeatureBuffers::built() const {
  std::vector<std::string> list;
  if (calm_areas())
    list.push_back("ocean.calm_areas." + std::to_string(calm_areas_) + ".chart." +
                   std::to_string(calm_width_) + "x" + std::to_string(calm_height_));
  if (wake_count_ > 0) list.push_back("ocean.kelvin_wakes." + std::to_string(wake_count_));
  return list;
}

}  // namespace thalassa::ocean
