#include "space_ocean_node.hpp"

#include <cmath>
#include <stdexcept>

#include "thalassa/ocean/gl/effective_fresnel_texture.hpp"
#include "thalassa/ocean/gl/local_features_gpu.hpp"
#include "thalassa/ocean/wave_set.hpp"

namespace thalassa {
namespace {

constexpr double kPi = 3.14159265358979323846;

class SpaceOceanNode final : public gl::Node {
 public:
  explicit SpaceOceanNode(const SpaceOceanNodeOptions& options)
      : options_(options), waves_(ocean::make_wave_set(options.settings)) {
    if (options_.features && !options_.features->empty())
      local_features_ = std::make_unique<ocean::LocalFeatureBuffers>(*options_.features);
    // Eq. 24's table where the scene asks for it and a term reads it (as the surface's).
    effective_fresnel_ = ocean::EffectiveFresnelTexture::make_if_used(
        options_.settings, options_.sky || options_.sea, options_.sky);
  }

  std::string name() const override { return "ocean"; }
  std::vector<std::string> built() const override {
    std::vector<std::string> list = {"planet.space_ocean", "ocean.ross_brdf"};
    if (options_.sun_glint) list.push_back("ocean.sun_glint");
    if (options_.sky) list.push_back("ocean.sky_reflection.sky_map_array");
    if (options_.sea) list.push_back("ocean.refracted_light");
    if (effective_fresnel_)
      for (const std::string& item : effective_fresnel_->built()) list.push_back(item);
    if (options_.air) list.push_back("ocean.aerial_perspective");
    if (local_features_)
      for (const std::string& item : local_features_->built()) list.push_back(item);
    return list;
  }

  void draw(const gl::FrameInputs& inputs, Context& context) override {
    atmosphere::SkyProvider& provider = *options_.provider;
    gl::Defines defines = provider.defines();
    if (options_.sun_glint) defines["SUN_GLINT"] = "1";
    if (options_.sky) defines["SKY_TERM"] = "1";
    if (options_.sea) defines["SEA_TERM"] = "1";
    if (options_.air) defines["AIR_TERM"] = "1";
    if (effective_fresnel_) effective_fresnel_->add_defines(defines);
    if (options_.sky) {
      defines["SKY_MAP_ARRAY"] = "1";
      provider.sky_map_array(context.shaders, &context.timer);
    }
    if (local_features_) local_features_->add_defines(defines);
    const GLuint program = context.shaders.program({.vertex = "engine/fullscreen.vert",
                                                    .fragment = "planet/ocean_space.frag",
                                                    .defines = defines});
    auto location = [&](const char* name) { return glGetUniformLocation(program, name); };
    // The wind's direction and the slope variance of every wave (eq. 4, w_r = 1), in the nadir
    // frame (the waves' chart turned by wave_axes, planet/nadir_frame.hpp).
    const glm::dvec2 downwind = ocean::chart_direction_in_frame(inputs.wave_axes, waves_.downwind);
    const ocean::SlopeVariance total = waves_.tail_variance.front();
    const double sun_solid_angle = 2.0 * kPi * (1.0 - std::cos(provider.sun_angular_radius()));
    const glm::dvec3 sun_disc = provider.sun_disc_radiance() * sun_solid_angle;
    glProgramUniform2f(program, location("downwind"), float(downwind.x), float(downwind.y));
    glProgramUniform2f(program, location("slope_variance"), float(total.along),
                       float(total.across));
    glProgramUniform1f(program, location("fresnel_r"), float(options_.settings.fresnel_r));
    glProgramUniform3f(
        program, location("deep_reflectance"), float(options_.settings.deep_reflectance_r),
        float(options_.settings.deep_reflectance_g), float(options_.settings.deep_reflectance_b));
    glProgramUniform3f(program, location("sun_disc_irradiance"), float(sun_disc.x),
                       float(sun_disc.y), float(sun_disc.z));
    glProgramUniform1f(program, location("atmosphere_radius"), float(provider.planet_radius()));
    if (provider.kind() == "environment_map") {
      const glm::dvec3 sky = provider.sky_irradiance(0.0, inputs.sun_direction);
      glProgramUniform3f(program, location("environment_sky_irradiance"), float(sky.x),
                         float(sky.y), float(sky.z));
    }
    provider.bind();
    if (effective_fresnel_) effective_fresnel_->bind();
    if (local_features_) {
      local_features_->set_uniforms(program);
      local_features_->bind();
    }
    glUseProgram(program);
    // Depth written per pixel (gl_FragDepth), so later features can be tested against the sea.
    glDepthFunc(GL_ALWAYS);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_GREATER);
    context.timer.end_pass("ocean.space");
  }

 private:
  SpaceOceanNodeOptions options_;
  ocean::WaveSet waves_;
  std::unique_ptr<ocean::LocalFeatureBuffers> local_features_;  // only with wakes or calm areas
  // Only with eq. 24's table or the Fresnel-weighted sky lobe.
  std::unique_ptr<ocean::EffectiveFresnelTexture> effective_fresnel_;
};

}  // namespace

std::unique_ptr<gl::Node> make_space_ocean_node(const SpaceOceanNodeOptions& options) {
  if (!options.provider) throw std::invalid_argument("make_space_ocean_node: no sky provider");
  return std::make_unique<SpaceOceanNode>(options);
}

}  // namespace thalassa
