// thalassa — a frame's wakes and calm areas on the GPU (GL layer, not installed): the calm
// areas' amplitude-scale chart as a float texture and the wakes as a storage buffer, the
// shader defines that switch their code on (CALM_AREAS, KELVIN_WAKES: a scene without them
// compiles none of it) and the uniforms of shaders/ocean/calm_area.glsl and local_waves.glsl.
#pragma once

#include <string>
#include <vector>

#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/ocean/local_features.hpp"

namespace thalassa::ocean {

// Texture unit of the calm-area chart (shaders/ocean/calm_area.glsl's binding) and storage
// buffer bindings of the wakes and their tracks (local_waves.glsl's), clear of the sky provider's
// units (4 to 11) and the ocean's buffers (1, 2).
inline constexpr unsigned kCalmScaleUnit = 12;
inline constexpr unsigned kWakeBufferBinding = 3;
inline constexpr unsigned kWakeTrackBufferBinding = 4;

class LocalFeatureBuffers {
 public:
  // Uploads `features` (nothing for an empty set).
  explicit LocalFeatureBuffers(const LocalFeatures& features);

  bool calm_areas() const { return calm_areas_ > 0; }
  int wake_count() const { return wake_count_; }
  // CALM_AREAS and KELVIN_WAKES where there is something to draw.
  void add_defines(gl::Defines& defines) const;
  // The uniforms of a program compiled with add_defines's defines.
  void set_uniforms(unsigned program) const;
  // Binds the chart and the buffer to their units.
  void bind() const;
  // "ocean.calm_areas.N" (N areas in view, chart WxH), "ocean.kelvin_wakes.N".
  std::vector<std::string> built() const;
  // An upper estimate of the loop iterations local_waves.glsl runs at one point of the sea with
  // these features (its loops over the wakes and over each wake's track pieces, for the
  // displacement and the normals): what a shader's loop budget must allow per point.
  int loop_iterations_per_point() const;

 private:
  gl::Texture calm_texture_;
  gl::Buffer wake_buffer_;
  gl::Buffer track_buffer_;
  int calm_areas_ = 0;
  int calm_width_ = 0, calm_height_ = 0;
  glm::dvec2 calm_origin_{0.0};
  double calm_spacing_ = 1.0;
  int wake_count_ = 0;
  int track_points_ = 0;  // of every wake's track together
};

}  // namespace thalassa::ocean
