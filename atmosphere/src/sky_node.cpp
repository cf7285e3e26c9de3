#include "thalassa/atmosphere/gl/sky_node.hpp"

namespace thalassa::atmosphere {
namespace {

class SkyNode final : public gl::Node {
 public:
  explicit SkyNode(const SkyNodeOptions& options) : options_(options) {}
  std::string name() const override { return "sky"; }
  std::vector<std::string> built() const override {
    std::vector<std::string> list = {"atmosphere.analytic_sky"};
    if (options_.sun_disc) list.push_back("atmosphere.sun_disc");
    return list;
  }
  void draw(const gl::FrameInputs& /*inputs*/, Context& context) override {
    gl::ShaderLibrary& shaders = context.shaders;
    gl::Defines defines;
    if (options_.sun_disc) defines["SUN_DISC"] = "1";
    const GLuint program =
        shaders.program({"engine/fullscreen.vert", "atmosphere/sky.frag", "", defines});
    glUseProgram(program);
    // The sky lies at infinity: nothing drawn later can be hidden by it.
    gl::draw_fullscreen_pass();
    context.timer.end_pass("sky");
  }

 private:
  SkyNodeOptions options_;
};

}  // namespace

std::unique_ptr<gl::Node> make_sky_node(const SkyNodeOptions& options) {
  return std::make_unique<SkyNode>(options);
}

}  // namespace thalassa::atmosphere
