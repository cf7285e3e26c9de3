// thalassa — the scene graph: nodes created from the scene file, drawn in order into the HDR
// target, each pass timed on the GPU (DESIGN section 3).
#pragma once

#include <glm/glm.hpp>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "thalassa/engine/gl/gpu_timer.hpp"
#include "thalassa/engine/gl/hdr_target.hpp"
#include "thalassa/engine/gl/objects.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/engine/image.hpp"

namespace thalassa::gl {

// What every pass of one frame sees, computed on the CPU in double. Directions are unit vectors
// in the local east-north-up frame tangent at the camera's nadir (x east, y north, z up).
struct FrameInputs {
  int width = 1;   // pixels
  int height = 1;  // pixels
  glm::dvec3 camera_right{1, 0, 0};
  glm::dvec3 camera_up{0, 0, 1};
  glm::dvec3 camera_forward{0, 1, 0};
  double tan_half_fov_y = 0.41421356237309503;  // tan(fov_y / 2), fov_y = 45 degrees
  double camera_height = 4.0;                   // m above the sea surface (z = 0)
  glm::dvec3 sun_direction{0, 0, 1};            // toward the sun
  double time = 0.0;                            // s
  // The sea at rest in this frame (origin the nadir on the sea; the camera at (0, 0,
  // camera_height)): the points x with z + 1/2 x^T C x = 0, C = sea_curvature in 1/m (0: the flat
  // sea; I / R: a sphere; the ellipsoid's own C: planet/nadir_frame.hpp, ocean/sea_surface.hpp).
  glm::dmat3 sea_curvature{0.0};
  // The waves' chart (planet/nadir_frame.hpp): a point x of this frame has the chart coordinates
  // wave_origin + wave_axes * (x.x, x.y), metres.
  glm::dvec2 wave_origin{0.0};
  glm::dmat2 wave_axes{1.0};
  // Where in its pixel each pixel is sampled, relative to the centre (pixels, x right, y up;
  // each in [-0.5, 0.5]): 0 for one sample per pixel; a supersampled render (the reference
  // method) averages frames drawn with different offsets.
  glm::dvec2 pixel_offset{0.0};
  // The side of the square stratum of the pixel that this frame's sample stands for (pixels,
  // (0, 1]; the offset lies in it): the reference method cuts each pixel into s x s strata and
  // integrates its sun over the sample's stratum only (shaders/ocean/reference_sun.glsl). 1: the
  // whole pixel.
  double pixel_stratum = 1.0;
};

// The per-frame uniform block shared by all passes: shaders/common/frame.glsl declares the
// same std140 layout at binding point kFrameBinding.
struct FrameUniforms {
  float camera_right[4];      // xyz; w = tan(fov_y / 2) * aspect
  float camera_up[4];         // xyz; w = tan(fov_y / 2)
  float camera_forward[4];    // xyz; w = camera height above the sea, m
  float sun_direction[4];     // xyz; w unused
  float viewport[4];          // width, height, 1 / width, 1 / height (pixels)
  float sea_curvature[3][4];  // the columns of FrameInputs::sea_curvature (std140 mat3), 1/m
  float pixel_offset[4];      // xy: FrameInputs::pixel_offset; z: pixel_stratum (pixels)
};
static_assert(sizeof(FrameUniforms) == 9 * 16, "std140 layout of shaders/common/frame.glsl");
constexpr GLuint kFrameBinding = 0;

FrameUniforms make_frame_uniforms(const FrameInputs& inputs);

// Draws the full-screen triangle of shaders/engine/fullscreen.vert with the bound program. The
// triangle lies on reversed-Z's far plane (0, the cleared depth), so the depth test is set to
// pass and depth writes are off during the draw; both are restored after it.
void draw_fullscreen_pass();

class Node {
 public:
  virtual ~Node() = default;
  // The node's name ("sky", "ocean"); its passes are named in the statistics by end_pass.
  virtual std::string name() const = 0;
  // What this node caused to be created ("atmosphere.sky_map", ...), for `built`.
  virtual std::vector<std::string> built() const = 0;
  // What a node draws with: the shader library, the HDR target (bound when draw() is called;
  // a node that draws elsewhere first must bind it back) and the timer, on which the node
  // marks the end of each of its passes (at least one) with end_pass("name").
  struct Context {
    ShaderLibrary& shaders;
    HdrTarget& target;
    GpuTimer& timer;
  };
  // Draws into the HDR target; the frame uniform block is bound at kFrameBinding.
  virtual void draw(const FrameInputs& inputs, Context& context) = 0;
  // For the statistics: the waves this node summed as geometry or normals in its last frame,
  // at the pixel where it summed the most (0 for nodes without waves).
  virtual int resolved_waves() const { return 0; }
  // For the statistics: named numbers of the node's last computation that the frame times do not
  // show (the ocean's reference sun: its time and convergence), name without the node's prefix.
  virtual std::vector<std::pair<std::string, double>> measurements() const { return {}; }
  // The same, one number per image row (top row first; NaN where a row has none).
  virtual std::vector<std::pair<std::string, std::vector<double>>> row_measurements() const {
    return {};
  }
  // The same, four numbers per pixel of the image (rows top first), read back from the GPU: the
  // node's GL context must be current. Each name says what its channels hold.
  virtual std::vector<std::pair<std::string, Image>> pixel_measurements() const { return {}; }
  // What the node had to work around in its last computation, in words, for the statistics and
  // the user (the ocean's reference sun: a lattice scattered again, and why); empty as a rule.
  virtual std::vector<std::string> warnings() const { return {}; }
};

class SceneGraph {
 public:
  SceneGraph();
  void add(std::unique_ptr<Node> node);
  // Replaces every node with `nodes` (drawn in that order) and hands back the ones it held.
  std::vector<std::unique_ptr<Node>> set_nodes(std::vector<std::unique_ptr<Node>> nodes);
  const std::vector<std::unique_ptr<Node>>& nodes() const { return nodes_; }

  // Draws every node in order into `target`, timing each as a pass of `timer`.
  void render(const FrameInputs& inputs, HdrTarget& target, ShaderLibrary& shaders,
              GpuTimer& timer);

 private:
  std::vector<std::unique_ptr<Node>> nodes_;
  Buffer frame_uniforms_;
  VertexArray empty_vao_;  // full-screen passes draw a triangle from gl_VertexID
};

}  // namespace thalassa::gl
