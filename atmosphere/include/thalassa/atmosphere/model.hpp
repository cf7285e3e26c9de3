// thalassa — the physical atmosphere: parameters (Earth defaults with their sources), the
// precomputed tables (transmittance, single and multiple scattering, ground irradiance) after
// Bruneton 2008/2017, cached on disk under a key of the parameters, and double-precision CPU
// queries that read the same tables with the same code as the GPU (shaders/atmosphere/model.glsl).
// CPU only; the GL side (sky maps, the sky pass, aerial perspective) is the sky provider's
// (thalassa/atmosphere/sky_provider.hpp).
//
// Frames and units: positions in metres relative to the planet's centre; directions unit vectors
// in the same frame; radiance in W m^-2 sr^-1 nm^-1 and irradiance in W m^-2 nm^-1 per RGB
// channel at 680, 550 and 440 nm (DESIGN section 4); coefficients in m^-1.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include <glm/vec3.hpp>

namespace thalassa::atmosphere {

// density(h) = exp_term exp(exp_scale h) + linear_term h + constant_term, clamped to [0, 1], for
// altitudes h (m) below `width`; exp_scale and linear_term in m^-1.
struct DensityLayer {
  double width = 0.0;
  double exp_term = 0.0;
  double exp_scale = 0.0;
  double linear_term = 0.0;
  double constant_term = 0.0;
};

// `lower` below lower.width, `upper` above.
struct DensityProfile {
  DensityLayer lower;
  DensityLayer upper;
};

// Mean radius of the Earth (IUGG, Moritz 2000, "Geodetic Reference System 1980", R1), m. The
// atmosphere is a spherical shell; on the WGS84 ellipsoid heights above the ellipsoid are taken as
// heights above this sphere.
inline constexpr double kEarthMeanRadius = 6371008.8;

struct AtmosphereParameters {
  glm::dvec3 solar_irradiance{0.0};  // top of the atmosphere, W m^-2 nm^-1
  double sun_angular_radius = 0.0;   // rad
  double bottom_radius = 0.0;        // m
  double top_radius = 0.0;           // m
  DensityProfile rayleigh_density;
  glm::dvec3 rayleigh_scattering{0.0};  // m^-1 at density 1
  DensityProfile mie_density;
  glm::dvec3 mie_scattering{0.0};  // m^-1 at density 1
  glm::dvec3 mie_extinction{0.0};  // m^-1 at density 1
  double mie_phase_g = 0.0;        // Cornette-Shanks asymmetry
  DensityProfile absorption_density;
  glm::dvec3 absorption_extinction{0.0};  // m^-1 at density 1
  glm::dvec3 ground_albedo{0.0};          // Lambertian
  double max_sun_zenith = 0.0;            // rad: the tables hold suns up to this zenith angle
  int scattering_orders = 4;              // single scattering is order 1

  // Earth's atmosphere over the sea, with a planet of the given radius (m); the sources of each
  // value are in the definition (atmosphere/src/parameters.cpp) and docs/atmosphere.md.
  static AtmosphereParameters earth(double bottom_radius = kEarthMeanRadius);

  // Throws std::invalid_argument naming the first field out of its physical range.
  void validate() const;
  // A canonical text of every field (and of the model's table layout), the key of the cache.
  std::string key() const;
};

struct PrecomputeOptions {
  // Folder of the table cache. Empty: $THALASSA_CACHE_DIR, else $XDG_CACHE_HOME/thalassa, else
  // $HOME/.cache/thalassa. A cache that cannot be read or written is not an error: the tables
  // are recomputed (and `cache_status` says why).
  std::string cache_dir;
  bool use_cache = true;
  // With the cache: reuse the tables of a model of the same parameters still alive in this
  // process (no file read; cache_status "shared", load and precompute times 0). Off: read the
  // file (or precompute) even so, e.g. to time the cache.
  bool share_in_process = true;
  int threads = 0;  // 0: std::thread::hardware_concurrency()
};

struct ModelTables;  // the tables themselves (internal)

// The precomputed atmosphere: immutable once built, shared by providers.
class AtmosphereModel {
 public:
  // Loads the tables for `parameters` from the cache, or precomputes (and caches) them.
  static std::shared_ptr<const AtmosphereModel> create(const AtmosphereParameters& parameters,
                                                       const PrecomputeOptions& options = {});
  ~AtmosphereModel();
  AtmosphereModel(const AtmosphereModel&) = delete;
  AtmosphereModel& operator=(const AtmosphereModel&) = delete;

  const AtmosphereParameters& parameters() const;
  // Seconds spent precomputing (0 when loaded from the cache) and loading (both 0 when shared).
  double precompute_seconds() const;
  double load_seconds() const;
  // "computed", "loaded", "shared" (the tables of a live model of the same parameters, see
  // PrecomputeOptions::share_in_process), "computed (cache not written: why)",
  // "computed (cache disabled)".
  const std::string& cache_status() const;
  const std::string& cache_path() const;

  // The sky's radiance along `view` (unit) from `camera` (planet-centred, m), without the sun's
  // disc; `transmittance` (optional) to the end of the ray (0 where it hits the ground).
  glm::dvec3 sky_radiance(const glm::dvec3& camera, const glm::dvec3& view,
                          const glm::dvec3& sun_direction,
                          glm::dvec3* transmittance = nullptr) const;
  // Aerial perspective: in-scattered radiance between `camera` and `point`, and transmittance.
  glm::dvec3 sky_radiance_to_point(const glm::dvec3& camera, const glm::dvec3& point,
                                   const glm::dvec3& sun_direction,
                                   glm::dvec3* transmittance = nullptr) const;
  // Transmittance from the top of the atmosphere to `point` toward the sun, times the visible
  // fraction of the sun's disc.
  glm::dvec3 sun_transmittance(const glm::dvec3& point, const glm::dvec3& sun_direction) const;
  // The sun's radiance at `point` (the disc's mean, W m^-2 sr^-1 nm^-1): solar irradiance /
  // disc solid angle x sun_transmittance.
  glm::dvec3 sun_radiance(const glm::dvec3& point, const glm::dvec3& sun_direction) const;
  // Irradiance on a surface at `point` with unit `normal`: the sun's (returned) and the sky's.
  glm::dvec3 sun_and_sky_irradiance(const glm::dvec3& point, const glm::dvec3& normal,
                                    const glm::dvec3& sun_direction,
                                    glm::dvec3* sky_irradiance) const;

  const ModelTables& tables() const;  // for the GPU upload (internal type)

 private:
  AtmosphereModel();
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace thalassa::atmosphere
