#include "thalassa/engine/gl/scene_graph.hpp"

namespace thalassa::gl {
namespace {

void store(float out[4], const glm::dvec3& v, double w) {
  out[0] = static_cast<float>(v.x);
  out[1] = static_cast<float>(v.y);
  out[2] = static_cast<float>(v.z);
  out[3] = static_cast<float>(w);
}

}  // namespace

FrameUniforms make_frame_uniforms(const FrameInputs& inputs) {
  FrameUniforms u{};
  const double aspect = double(inputs.width) / double(inputs.height);
  store(u.camera_right, inputs.camera_right, inputs.tan_half_fov_y * aspect);
  store(u.camera_up, inputs.camera_up, inputs.tan_half_fov_y);
  store(u.camera_forward, inputs.camera_forward, inputs.camera_height);
  store(u.sun_direction, inputs.sun_direction, 0.0);
  u.viewport[0] = static_cast<float>(inputs.width);
  u.viewport[1] = static_cast<float>(inputs.height);
  u.viewport[2] = static_cast<float>(1.0 / inputs.width);
  u.viewport[3] = static_cast<float>(1.0 / inputs.height);
  for (int column = 0; column < 3; ++column)
    store(u.sea_curvature[column], inputs.sea_curvature[column], 0.0);
  u.pixel_offset[0] = static_cast<float>(inputs.pixel_offset.x);
  u.pixel_offset[1] = static_cast<float>(inputs.pixel_offset.y);
  u.pixel_offset[2] = static_cast<float>(inputs.pixel_stratum);
  return u;
}

void draw_fullscreen_pass() {
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_ALWAYS);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
}

SceneGraph::SceneGraph() : frame_uniforms_(make_buffer()), empty_vao_(make_vertex_array()) {
  glNamedBufferStorage(frame_uniforms_.get(), sizeof(FrameUniforms), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
}

void SceneGraph::add(std::unique_ptr<Node> node) { nodes_.push_back(std::move(node)); }

std::vector<std::unique_ptr<Node>> SceneGraph::set_nodes(std::vector<std::unique_ptr<Node>> nodes) {
  nodes_.swap(nodes);
  return nodes;
}

void SceneGraph::render(const FrameInputs& inputs, HdrTarget& target, ShaderLibrary& shaders,
                        GpuTimer& timer) {
  const FrameUniforms uniforms = make_frame_uniforms(inputs);
  glNamedBufferSubData(frame_uniforms_.get(), 0, sizeof(uniforms), &uniforms);
  timer.begin_frame();
  target.begin();
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBinding, frame_uniforms_.get());
  glBindVertexArray(empty_vao_.get());
  timer.end_pass("clear");
  Node::Context context{shaders, target, timer};
  for (const auto& node : nodes_) node->draw(inputs, context);
  glBindVertexArray(0);
  check_error("scene graph render");
}

}  // namespace thalassa::gl
