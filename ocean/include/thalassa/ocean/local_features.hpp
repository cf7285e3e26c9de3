// thalassa — the wakes and calm areas of one frame, as the ocean's shaders need them (issue 9;
// docs/wakes.md, "On the GPU"): placed, culled and made camera-relative on the CPU in double by
// the planet module (planet/local_features.hpp), drawn by the ocean's nodes
// (ocean/gl/local_features_gpu.hpp, shaders/ocean/local_waves.glsl and calm_area.glsl).
//
// Frame and units: the nadir frame of planet/nadir_frame.hpp (x east, y north at the camera's
// nadir, metres, origin the nadir); only its horizontal (x, y) plane is used: a point of the sea
// at rest is located by the orthographic projection of its position on that plane, which is
// exactly the (x, y) the shaders hold in their rest positions.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "thalassa/ocean/kelvin_wake.hpp"

namespace thalassa::ocean {

// The calm areas' amplitude scale s (planet/calm_area.hpp; overlapping areas multiplied),
// sampled on a regular grid of the nadir frame's (x, y) plane. Outside the grid s = 1: the grid
// is laid so that its border samples are outside every area.
struct CalmScaleChart {
  glm::dvec2 origin{0.0};    // m, nadir frame: the point of sample (0, 0)
  double spacing = 1.0;      // m between neighbouring samples, along x and y
  int width = 0;             // samples along x
  int height = 0;            // samples along y
  std::vector<float> scale;  // s, dimensionless in [0, 1]; row y = j at scale[j * width + i]
  int areas = 0;             // calm areas sampled (after culling)
  bool operator==(const CalmScaleChart&) const = default;
};

// A wake in the frame: its past track (ShipWake::past_track: the ship, then the track's points
// it passed, out to the wake's length) laid in the nadir frame's plane as a polyline, its
// geodesics cut into pieces short enough to be straight there. At a point p the wake's ship
// frame (ocean/kelvin_wake.hpp) is ShipWake's track-following one: the foot is the polyline's
// point nearest to p, b the distance along the polyline from the ship to it, y the distance
// from it (> 0 to port), e the direction of travel of its piece (wake_frame_coordinates).
struct WakeInFrame {
  std::string name;
  std::vector<glm::dvec2> track;  // m, nadir frame; track[0] is the ship; >= 2 points
  KelvinWakeParams params;        // the speed is the ship's current one
  bool operator==(const WakeInFrame&) const = default;
};

// The wake's ship-frame coordinates at the frame point p (m), as the shaders compute them
// (shaders/ocean/local_waves.glsl, LocalWakeFrame), in double: the CPU reference of the GPU's
// foot search. `present` is false beyond the wake (farther than its half-width from the track,
// b outside (0, length), or past the polyline's last point: the track's start).
struct WakeFrameCoordinates {
  bool present = false;
  double behind = 0.0;          // b, m
  double lateral = 0.0;         // y, m, > 0 to port
  glm::dvec2 course{0.0, 1.0};  // e at the foot, unit, nadir frame
};
WakeFrameCoordinates wake_frame_coordinates(const WakeInFrame& wake, glm::dvec2 p);

struct LocalFeatures {
  std::optional<CalmScaleChart> calm;  // none when no calm area is in view
  std::vector<WakeInFrame> wakes;      // the wakes in view
  bool empty() const { return !calm && wakes.empty(); }
  bool operator==(const LocalFeatures&) const = default;
};

// The GPU's form of a wake's parameters (shaders/ocean/kelvin_wake.glsl, KelvinWake): k0
// (rad/m), the amplitude factor a_ref N (m; N of kelvin_wake.hpp, kelvin_reference_normalisation),
// the draft (m) and the length (m).
glm::dvec4 kelvin_wake_gpu_params(const KelvinWakeParams& params);

// The tail of the sea's unresolved slope variance inside a calm area of factor s
// (docs/wakes.md): the wave set's tails are summed on the CPU for s = 1, and the shaders scale
// them by s^2. For one trochoid of steepness x = k h this overestimates the exact variance
// 1 - sqrt(1 - (s x)^2) by the factor (1 + sqrt(1 - s^2 x^2)) / (1 + sqrt(1 - x^2)), at most
// 2 / (1 + sqrt(1 - x^2)): 1.072 for the steepness clamp x = 0.5, 1.034 for x = 0.36.
double calm_tail_variance_bound(double steepness);

}  // namespace thalassa::ocean
