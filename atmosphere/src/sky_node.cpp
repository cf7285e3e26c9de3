#include "thalassa/atmosphere/gl/sky_node.hpp"

#include <cmath>

namespace thalassa::atmosphere {
namespace {

class SkyNode final : public gl::Node {
 public:
  SkyNode(const SkyNodeOptions& options, std::shared_ptr<SkyProvider> provider)
      : options_(options), provider_(std::move(provider)) {}
  std::string name() const override { return "sky"; }
  std::vector<std::string> built() const override {
    std::vector<std::string> list = {"sky.background"};
    if (options_.sun_disc) list.push_back("sky.sun_disc");
    return list;
  }
  void draw(const gl::FrameInputs& inputs, Context& context) override {
    gl::Defines defines = provider_->defines();
    if (options_.sun_disc) defines["SUN_DISC"] = "1";
    const GLuint program =
        context.shaders.program({"engine/fullscreen.vert", "atmosphere/sky.frag", "", defines});
    const glm::dvec3 disc = provider_->sun_disc_radiance();
    glProgramUniform3f(program, glGetUniformLocation(program, "camera_position"), 0.0f, 0.0f,
                       float(provider_->planet_radius() + inputs.camera_height));
    glProgramUniform3f(program, glGetUniformLocation(program, "sun_disc_radiance"), float(disc.x),
                       float(disc.y), float(disc.z));
    glProgramUniform1f(program, glGetUniformLocation(program, "sun_cos_angular_radius"),
                       float(std::cos(provider_->sun_angular_radius())));
    glProgramUniform1f(program, glGetUniformLocation(program, "sun_angular_radius"),
                       float(provider_->sun_angular_radius()));
    glUseProgram(program);
    provider_->bind();
    // The sky lies at infinity: nothing drawn later can be hidden by it.
    gl::draw_fullscreen_pass();
    context.timer.end_pass("sky");
  }

 private:
  SkyNodeOptions options_;
  std::shared_ptr<SkyProvider> provider_;
};

}  // namespace

std::unique_ptr<gl::Node> make_sky_node(const SkyNodeOptions& options,
                                        std::shared_ptr<SkyProvider> provider) {
  return std::make_unique<SkyNode>(options, std::move(provider));
}

}  // namespace thalassa::atmosphere
