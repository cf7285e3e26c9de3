// thalassa — the sky provider: the one interface through which the ocean, the planet and the sky
// pass get sky light (issue 4, point 3; DESIGN sections 2 and 3). Two implementations: the
// physical atmosphere (AtmosphereModel's tables) and an HDR photograph (EnvironmentMap). Nothing
// else computes sky light. GL layer: the methods that build textures need a current context.
//
// On the GPU the provider is shaders/atmosphere/sky_provider.glsl, compiled with defines() and
// fed by bind(). On the CPU it answers the per-frame constants (sun radiance, irradiance) in
// double.
//
// Frames and units: heights in metres above the sea; sun and view directions unit vectors in the
// east-north-up frame of the point concerned (x east, y north, z up); spectral radiance in
// W m^-2 sr^-1 nm^-1 and irradiance in W m^-2 nm^-1, RGB at 680, 550, 440 nm.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "thalassa/engine/gl/gl.hpp"
#include "thalassa/engine/gl/shader_library.hpp"

namespace thalassa::gl {
class GpuTimer;
}

namespace thalassa::atmosphere {

class AtmosphereModel;
class EnvironmentMap;

// Texture units of the provider's textures (shaders/atmosphere/sky_provider.glsl).
inline constexpr GLuint kSkyMapUnit = 4;
inline constexpr GLuint kSkyTransmittanceUnit = 5;
inline constexpr GLuint kSkyScatteringUnit = 6;
inline constexpr GLuint kSkySingleMieUnit = 7;
inline constexpr GLuint kSkyIrradianceUnit = 8;
inline constexpr GLuint kSkyPanoramaUnit = 9;
// Unit 10 is the glossy sky maps' (kSkyShrmUnit, sky_shrm.hpp).
inline constexpr GLuint kSkyMapArrayUnit = 11;  // SKY_MAP_ARRAY_BINDING

struct SkyMapSettings {
  int size = 512;         // texels per side (issue 4: 512 x 512 by default)
  int array_layers = 32;  // sun zeniths of the array, from 0 to array_max_sun_zenith
  double array_max_sun_zenith = 102.0 * 3.14159265358979323846 / 180.0;  // rad
  // The array's layers are spaced evenly in sun zenith on each side of a knee: layers 0 to
  // array_knee_layer cover [0, array_knee_zenith], the rest [array_knee_zenith, max]. The sky
  // changes slowly with a high sun and by orders of magnitude per degree at twilight, so the
  // default puts 11 intervals (7.3 deg) on the day and 20 (1.1 deg) on the last 22 degrees,
  // where a uniform spacing (3.3 deg) left interpolation errors of 20-30% on average (measured,
  // tests/gpu/sky_provider_test.cpp; docs/atmosphere.md).
  double array_knee_zenith = 80.0 * 3.14159265358979323846 / 180.0;  // rad
  int array_knee_layer = 11;
  bool operator==(const SkyMapSettings&) const = default;
};

// The sun zenith angle (rad) of a (fractional) layer of the array, and its inverse (clamped to
// the array): the piecewise-linear spacing of SkyMapSettings. Between two layers, interpolate
// geometrically, texel by texel and channel by channel (sqrt(L_k L_k+1) halfway): the twilight
// sky falls exponentially with the sun's depression, which a linear mix overestimates by up to
// 5x at a 3.3-degree spacing. The error this leaves is measured in
// tests/gpu/sky_provider_test.cpp (ArrayLayersInterpolateWithinAStatedError).
double sky_map_array_zenith(const SkyMapSettings& settings, double layer);
double sky_map_array_layer(const SkyMapSettings& settings, double zenith);

class SkyProvider {
 public:
  virtual ~SkyProvider() = default;

  // "atmosphere" or "environment_map".
  virtual std::string kind() const = 0;
  // What this provider created so far (for `built` in the statistics).
  virtual std::vector<std::string> built() const = 0;
  // The shader defines of sky_provider.glsl for this provider, the constants of the array's
  // lookup (SKY_MAP_ARRAY_LAYERS, _KNEE_LAYER, _KNEE_ZENITH, _MAX_ZENITH) included whether or
  // not the array is built; a shader that reads the array adds SKY_MAP_ARRAY itself.
  virtual gl::Defines defines() const = 0;
  // Binds the textures the shaders read (the sky map of the last sky_map() call included, and
  // the array to kSkyMapArrayUnit once sky_map_array() has built it; unit 11 is left alone
  // before).
  virtual void bind() const = 0;

  // (a) The stereographic sky map seen from `height` with the sun at `sun` (ENU), as a mipmapped
  // float 2D texture laid out as sky_provider.glsl says; built on the first call and whenever the
  // arguments change (then timed into `timer` as the pass "sky.map", if given).
  virtual GLuint sky_map(double height, const glm::dvec3& sun, gl::ShaderLibrary& shaders,
                         gl::GpuTimer* timer) = 0;
  // (b) The sun-zenith-indexed array of such maps seen from the sea surface, the sun at azimuth
  // 0 (north, +t) and the zenith angle sky_map_array_zenith(layer): a mipmapped 2D array
  // texture, read by SkyMapArrayRadianceGrad at the layer SkyMapArrayLayer gives for a point's
  // local sun zenith (Bruneton, Neyret & Holzschuch 2010, sec. 6, planet-scale rendering). An
  // HDR photograph is one sky for one sun: its provider fills every layer with the same map,
  // turned about the zenith so that the photograph's sun is at azimuth 0 (as photographed when
  // no sun was found in it).
  virtual GLuint sky_map_array(gl::ShaderLibrary& shaders, gl::GpuTimer* timer) = 0;
  virtual const SkyMapSettings& sky_map_settings() const = 0;
  // Milliseconds spent building the last sky map and the array (0 until built), and how many
  // times the sky map has been built (a provider kept between Renderers builds it again only
  // when the sun moves: planet/renderer.hpp, SkyProviderCache).
  virtual double sky_map_ms() const = 0;
  virtual double sky_map_array_ms() const = 0;
  virtual int sky_map_builds() const = 0;
  // One-off costs of creating the provider, wall-clock ms by name ("atmosphere.precompute" or
  // "atmosphere.load").
  virtual std::vector<std::pair<std::string, double>> setup_ms() const = 0;

  // (c) The sun's mean radiance over its disc at `height`, transmittance applied, and the disc's
  // angular radius (rad).
  virtual glm::dvec3 sun_radiance(double height, const glm::dvec3& sun) const = 0;
  virtual double sun_angular_radius() const = 0;
  // The radiance of the sun's disc before the shaders' transmittance along the view ray
  // (SkyBackgroundRadiance's): the top-of-atmosphere radiance for the atmosphere, the
  // photograph's sun for an environment map (whose transmittance is 1).
  virtual glm::dvec3 sun_disc_radiance() const = 0;
  // (d) Irradiance on a horizontal surface at `height`: the sun's and the sky's.
  virtual glm::dvec3 sun_irradiance(double height, const glm::dvec3& sun) const = 0;
  virtual glm::dvec3 sky_irradiance(double height, const glm::dvec3& sun) const = 0;
  // The radiance the sky map holds below the horizon (the ocean paper's sec. 6: mean Fresnel
  // reflectance of water x sky irradiance / pi).
  virtual glm::dvec3 below_horizon_radiance(double height, const glm::dvec3& sun) const = 0;
  // (e, f) on the CPU: the sky's radiance along `view` from `height` (no sun disc) and the
  // aerial perspective to a point `offset` metres away (ENU at the camera's nadir).
  virtual glm::dvec3 sky_radiance(double height, const glm::dvec3& view,
                                  const glm::dvec3& sun) const = 0;
  virtual glm::dvec3 aerial_perspective(double height, const glm::dvec3& offset,
                                        const glm::dvec3& sun, glm::dvec3* transmittance) const = 0;

  // The sun direction the provider imposes (an HDR photograph's sun), if any.
  virtual std::optional<glm::dvec3> sun_direction() const = 0;
  // Radius of the sphere the provider's positions are relative to (m): planet-centred positions
  // in sky_provider.glsl are (0, 0, planet_radius() + height) for the camera.
  virtual double planet_radius() const = 0;
};

std::shared_ptr<SkyProvider> make_atmosphere_provider(std::shared_ptr<const AtmosphereModel> model,
                                                      const SkyMapSettings& settings = {});
std::shared_ptr<SkyProvider> make_environment_provider(std::shared_ptr<const EnvironmentMap> map,
                                                       double planet_radius,
                                                       const SkyMapSettings& settings = {});

}  // namespace thalassa::atmosphere
