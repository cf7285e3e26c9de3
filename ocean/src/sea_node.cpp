#include "thalassa/ocean/gl/sea_node.hpp"

#include <string>

#include "flat_sea_reference.hpp"

namespace thalassa::ocean {
namespace {

class SeaNode final : public gl::Node {
 public:
  explicit SeaNode(const SeaNodeOptions& options) : options_(options) {}
  std::string name() const override { return "ocean"; }
  std::vector<std::string> built() const override {
    std::vector<std::string> list = {"ocean.flat_sea"};
    if (options_.sun_glint) list.push_back("ocean.sun_glint");
    return list;
  }
  void draw(const gl::FrameInputs& inputs, gl::ShaderLibrary& shaders) override {
    gl::Defines defines;
    if (options_.sun_glint) defines["SUN_GLINT"] = "1";
    const GLuint program = shaders.program(
        {.vertex = "engine/fullscreen.vert", .fragment = "ocean/flat_sea.frag", .defines = defines});
    // The downwelling irradiance is the same for every pixel of the flat sea: computed once per
    // frame on the CPU, in double, by the reference of the very functions the shader uses.
    const glm::dvec3 irradiance = glsl::AnalyticSunHorizontalIrradiance(inputs.sun_direction) +
                                  glsl::AnalyticSkyIrradiance(inputs.sun_direction);
    const glm::dvec3 reflectance = glsl::FLAT_SEA_DEFAULT_DEEP_REFLECTANCE;
    glUseProgram(program);
    glProgramUniform1f(program, glGetUniformLocation(program, "wind_speed"),
                       static_cast<float>(options_.wind_speed));
    glProgramUniform3f(program, glGetUniformLocation(program, "deep_reflectance"),
                       float(reflectance.x), float(reflectance.y), float(reflectance.z));
    glProgramUniform3f(program, glGetUniformLocation(program, "horizontal_irradiance"),
                       float(irradiance.x), float(irradiance.y), float(irradiance.z));
    // The flat placeholder writes no depth; the planet's sea (issue 5) writes its true depth.
    gl::draw_fullscreen_pass();
  }

 private:
  SeaNodeOptions options_;
};

}  // namespace

std::unique_ptr<gl::Node> make_sea_node(const SeaNodeOptions& options) {
  return std::make_unique<SeaNode>(options);
}

}  // namespace thalassa::ocean
