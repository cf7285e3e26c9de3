// The sky provider of an HDR photograph (issue 4, point 4): the EnvironmentMap's stereographic
// map and panorama uploaded as textures, its extracted sun as the sun, no atmosphere between the
// camera and the scene (a photograph carries none: aerial perspective is the identity).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "sky_map_texture.hpp"
#include "thalassa/atmosphere/environment_map.hpp"
#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/gpu_timer.hpp"
#include "thalassa/engine/gl/objects.hpp"

namespace thalassa::atmosphere {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The sun's angular radius when the photograph has none to measure (IAU 2015 nominal solar
// radius over 1 au, as the atmosphere's default).
constexpr double kDefaultSunAngularRadius = 695700.0 / 149597870.7;

// Panorama width for the sky behind the scene: 2048 x 1024 texels (0.18 deg per texel), enough
// for a background at the fields of view the renderer is used with, 8 MB in float.
constexpr int kPanoramaWidth = 2048;

glm::dvec3 to_glm(const Rgb& v) { return {v[0], v[1], v[2]}; }
Vec3 to_array(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// Uploads an Image (rows top first) with its top row at t = 1, as sky_provider.glsl reads.
void upload_flipped(GLuint texture, const Image& image, int layer) {
  std::vector<float> rows(image.rgba.size());
  const std::size_t row = static_cast<std::size_t>(image.width) * 4;
  for (int y = 0; y < image.height; ++y) {
    std::copy_n(&image.rgba[y * row], row, &rows[(image.height - 1 - y) * row]);
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (layer < 0) {
    glTextureSubImage2D(texture, 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT,
                        rows.data());
  } else {
    glTextureSubImage3D(texture, 0, 0, 0, layer, image.width, image.height, 1, GL_RGBA, GL_FLOAT,
                        rows.data());
  }
}

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

class EnvironmentProvider final : public SkyProvider {
 public:
  EnvironmentProvider(std::shared_ptr<const EnvironmentMap> map, double planet_radius,
                      const SkyMapSettings& settings)
      : map_(std::move(map)), planet_radius_(planet_radius), settings_(settings) {
    check_sky_map_settings(settings_);
    const Image panorama = map_->panorama(kPanoramaWidth);
    panorama_ = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(panorama_.get(), 1, GL_RGBA32F, panorama.width, panorama.height);
    upload_flipped(panorama_.get(), panorama, -1);
    gl::set_sampling(panorama_.get(), {.wrap_s = GL_REPEAT});  // s: the azimuth
  }

  std::string kind() const override { return "environment_map"; }
  std::vector<std::string> built() const override {
    std::vector<std::string> list = {"environment_map.panorama"};
    if (sky_map_) list.push_back("environment_map.sky_map");
    if (sky_map_array_) list.push_back("environment_map.sky_map_array");
    return list;
  }
  gl::Defines defines() const override {
    gl::Defines defines = sky_map_array_defines(settings_);
    defines["SKY_PROVIDER_ENVIRONMENT"] = "1";
    defines["SKY_MAP_EXTENT"] = glsl_float_literal(kSkyMapExtent);
    return defines;
  }
  void bind() const override {
    glBindTextureUnit(kSkyMapUnit, sky_map_.get());
    glBindTextureUnit(kSkyPanoramaUnit, panorama_.get());
    if (sky_map_array_) glBindTextureUnit(kSkyMapArrayUnit, sky_map_array_.get());
  }

  // The photograph is one sky for every height and sun: built once.
  GLuint sky_map(double, const glm::dvec3&, gl::ShaderLibrary&, gl::GpuTimer* timer) override {
    if (sky_map_) return sky_map_.get();
    const auto start = std::chrono::steady_clock::now();
    map_image_ = map_->stereographic_map(settings_.size, kSkyMapExtent);
    sky_map_ = gl::make_texture(GL_TEXTURE_2D);
    glTextureStorage2D(sky_map_.get(), sky_map_mip_levels(settings_.size), GL_RGBA32F,
                       settings_.size, settings_.size);
    upload_flipped(sky_map_.get(), map_image_, -1);
    glGenerateTextureMipmap(sky_map_.get());
    set_sky_map_sampling(sky_map_.get());
    if (timer) timer->end_pass("sky.map");
    sky_map_ms_ = elapsed_ms(start);
    ++sky_map_builds_;
    return sky_map_.get();
  }

  // Every layer holds the same map: a photograph is one sky for one sun. The array's contract is
  // the sun at azimuth 0 (north, +t), so the map is turned about the zenith to put the
  // photograph's sun there; with no sun found, it is left as photographed (north is north).
  GLuint sky_map_array(gl::ShaderLibrary&, gl::GpuTimer* timer) override {
    if (sky_map_array_) return sky_map_array_.get();
    const auto start = std::chrono::steady_clock::now();
    const double north_azimuth = array_north_azimuth();
    Image turned;
    if (north_azimuth != 0.0) {
      turned = map_->stereographic_map(settings_.size, kSkyMapExtent, north_azimuth);
    } else if (map_image_.width == 0) {
      map_image_ = map_->stereographic_map(settings_.size, kSkyMapExtent);
    }
    const Image& layer_image = north_azimuth != 0.0 ? turned : map_image_;
    sky_map_array_ = gl::make_texture(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(sky_map_array_.get(), sky_map_mip_levels(settings_.size), GL_RGBA32F,
                       settings_.size, settings_.size, settings_.array_layers);
    for (int layer = 0; layer < settings_.array_layers; ++layer)
      upload_flipped(sky_map_array_.get(), layer_image, layer);
    glGenerateTextureMipmap(sky_map_array_.get());
    set_sky_map_sampling(sky_map_array_.get());
    if (timer) timer->end_pass("sky.map_array");
    sky_map_array_ms_ = elapsed_ms(start);
    return sky_map_array_.get();
  }

  const SkyMapSettings& sky_map_settings() const override { return settings_; }
  double sky_map_ms() const override { return sky_map_ms_; }
  int sky_map_builds() const override { return sky_map_builds_; }
  double sky_map_array_ms() const override { return sky_map_array_ms_; }
  std::vector<std::pair<std::string, double>> setup_ms() const override { return {}; }

  glm::dvec3 sun_radiance(double, const glm::dvec3&) const override {
    if (!map_->sun()) return glm::dvec3(0.0);
    const double solid_angle = 2.0 * kPi * (1.0 - std::cos(sun_angular_radius()));
    return to_glm(map_->sun_irradiance()) / solid_angle;
  }
  double sun_angular_radius() const override {
    return map_->sun() ? map_->sun()->angular_radius : kDefaultSunAngularRadius;
  }
  glm::dvec3 sun_disc_radiance() const override { return sun_radiance(0.0, glm::dvec3(0.0)); }
  glm::dvec3 sun_irradiance(double, const glm::dvec3&) const override {
    const std::optional<Vec3> d = map_->sun_direction();
    if (!d) return glm::dvec3(0.0);
    return to_glm(map_->sun_irradiance()) * std::max((*d)[2], 0.0);
  }
  glm::dvec3 sky_irradiance(double, const glm::dvec3&) const override {
    return to_glm(map_->sky_irradiance());
  }
  glm::dvec3 below_horizon_radiance(double, const glm::dvec3&) const override {
    return to_glm(map_->below_horizon_radiance());
  }
  glm::dvec3 sky_radiance(double, const glm::dvec3& view, const glm::dvec3&) const override {
    return to_glm(map_->sky_radiance(to_array(view)));
  }
  glm::dvec3 aerial_perspective(double, const glm::dvec3&, const glm::dvec3&,
                                glm::dvec3* transmittance) const override {
    if (transmittance) *transmittance = glm::dvec3(1.0);
    return glm::dvec3(0.0);
  }
  std::optional<glm::dvec3> sun_direction() const override {
    const std::optional<Vec3> d = map_->sun_direction();
    if (!d) return std::nullopt;
    return glm::dvec3((*d)[0], (*d)[1], (*d)[2]);
  }
  double planet_radius() const override { return planet_radius_; }

 private:
  // The photograph's azimuth (rad, clockwise from north) that the array's north shows: its sun's
  // azimuth, or 0 without a sun (or with the sun at the zenith, where any azimuth is north).
  double array_north_azimuth() const {
    const std::optional<Vec3> sun = map_->sun_direction();
    if (!sun || ((*sun)[0] == 0.0 && (*sun)[1] == 0.0)) return 0.0;
    return std::atan2((*sun)[0], (*sun)[1]);
  }

  std::shared_ptr<const EnvironmentMap> map_;
  double planet_radius_;
  SkyMapSettings settings_;
  Image map_image_;
  gl::Texture panorama_, sky_map_, sky_map_array_;
  double sky_map_ms_ = 0.0, sky_map_array_ms_ = 0.0;
  int sky_map_builds_ = 0;
};

}  // namespace

std::shared_ptr<SkyProvider> make_environment_provider(std::shared_ptr<const EnvironmentMap> map,
                                                       double planet_radius,
                                                       const SkyMapSettings& settings) {
  if (!map) throw std::invalid_argument("make_environment_provider: no map");
  return std::make_shared<EnvironmentProvider>(std::move(map), planet_radius, settings);
}

}  // namespace thalassa::atmosphere
