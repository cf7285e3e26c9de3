// Earth's atmosphere: default parameters and their sources, validation, and the cache key.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "thalassa/atmosphere/model.hpp"

namespace thalassa::atmosphere {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Height of the top of the atmosphere above the sea, m: 60 km as in Bruneton 2017, where the
// Rayleigh density is exp(-7.5) = 5.5e-4 of its sea-level value.
constexpr double kAtmosphereThickness = 60000.0;

// Rayleigh scale height, m (Bruneton 2017; the US Standard Atmosphere's density scale height
// near the surface is 8.4 km, and 8 km is the usual fit over the lower 30 km).
constexpr double kRayleighScaleHeight = 8000.0;

// Rayleigh vertical optical depth of the whole atmosphere at 1013.25 hPa at 680, 550, 440 nm:
// Bodhaine et al. (1999), "On Rayleigh optical depth calculations", J. Atmos. Oceanic Technol.
// 16, eq. 30 (the same values as the foundation's analytic sky; the tests recompute them from
// the formula and check the model's vertical optical depth against them).
constexpr double kRayleighOpticalDepth[3] = {0.0409592, 0.0970652, 0.2426054};

// Aerosols, as in Bruneton's 2017 demo (after Bruneton 2016, "A qualitative and quantitative
// evaluation of 8 clear sky models"): Angstrom beta 5.328e-3 and alpha 0 (an optical depth of
// 0.0053 at every wavelength: a very clear sky), scale height 1.2 km, single-scattering albedo
// 0.9, Cornette-Shanks g = 0.8.
constexpr double kMieAngstromBeta = 5.328e-3;
constexpr double kMieScaleHeight = 1200.0;  // m
constexpr double kMieSingleScatteringAlbedo = 0.9;
constexpr double kMiePhaseG = 0.8;

// Ozone: a 300 Dobson-unit column in a tent profile from 10 to 40 km peaking at 25 km (Bruneton
// 2017), absorption cross sections at 680, 550 and 440 nm from Serdyuchenko et al. (2014) as
// tabulated in Bruneton's demo, times the peak number density 300 DU x 2.687e20 m^-2 / 15 km.
constexpr double kOzoneAbsorption[3] = {6.5e-7, 1.881e-6, 8.5e-8};  // m^-1 at the peak
constexpr double kOzoneBottom = 10000.0;                            // m
constexpr double kOzonePeak = 25000.0;                              // m
constexpr double kOzoneHalfWidth = 15000.0;                         // m

// Top-of-atmosphere spectral solar irradiance, W m^-2 nm^-1, ASTM G-173 extraterrestrial
// spectrum in 10 nm bins at 680, 550, 440 nm (Bruneton's 2017 demo, kSolarIrradiance).
constexpr double kSolarIrradiance[3] = {1.474, 1.8504, 1.91198};

// Angular radius of the sun, rad: the IAU 2015 nominal solar radius 695,700 km over 1 au
// (149,597,870.7 km).
constexpr double kSunAngularRadius = 695700.0 / 149597870.7;

// Albedo of the sea surface for diffuse light, Payne (1972), "Albedo of the sea surface",
// J. Atmos. Sci. 29, 959-970 (about 0.06 under overcast and high suns).
constexpr double kSeaAlbedo = 0.06;

// The tables hold suns down to 12 degrees below the horizon (nautical twilight), as issue 4
// asks (102 degrees zenith).
constexpr double kMaxSunZenith = 102.0 * kPi / 180.0;

void require(bool ok, const char* field, const char* expected) {
  if (!ok) {
    throw std::invalid_argument(std::string("atmosphere parameter ") + field + ": expected " +
                                expected);
  }
}

bool finite3(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool non_negative3(const glm::dvec3& v) {
  return finite3(v) && v.x >= 0.0 && v.y >= 0.0 && v.z >= 0.0;
}

void print(std::ostringstream& out, const char* name, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  out << name << '=' << buffer << ';';
}
void print(std::ostringstream& out, const char* name, const glm::dvec3& v) {
  print(out, name, v.x);
  print(out, name, v.y);
  print(out, name, v.z);
}
void print(std::ostringstream& out, const char* name, const DensityProfile& p) {
  for (const DensityLayer* l : {&p.lower, &p.upper}) {
    print(out, name, l->width);
    print(out, name, l->exp_term);
    print(out, name, l->exp_scale);
    print(out, name, l->linear_term);
    print(out, name, l->constant_term);
  }
}

DensityProfile exponential(double scale_height) {
  DensityProfile p;
  p.upper.exp_term = 1.0;
  p.upper.exp_scale = -1.0 / scale_height;
  return p;
}

}  // namespace

AtmosphereParameters AtmosphereParameters::earth(double bottom_radius) {
  AtmosphereParameters a;
  a.solar_irradiance = {kSolarIrradiance[0], kSolarIrradiance[1], kSolarIrradiance[2]};
  a.sun_angular_radius = kSunAngularRadius;
  a.bottom_radius = bottom_radius;
  a.top_radius = bottom_radius + kAtmosphereThickness;
  a.rayleigh_density = exponential(kRayleighScaleHeight);
  // Sea-level coefficient such that the column up to the top equals Bodhaine's optical depth:
  // tau = beta H (1 - exp(-thickness / H)).
  const double column =
      kRayleighScaleHeight * (1.0 - std::exp(-kAtmosphereThickness / kRayleighScaleHeight));
  a.rayleigh_scattering = {kRayleighOpticalDepth[0] / column, kRayleighOpticalDepth[1] / column,
                           kRayleighOpticalDepth[2] / column};
  a.mie_density = exponential(kMieScaleHeight);
  const double mie_extinction = kMieAngstromBeta / kMieScaleHeight;
  a.mie_extinction = glm::dvec3(mie_extinction);
  a.mie_scattering = glm::dvec3(mie_extinction * kMieSingleScatteringAlbedo);
  a.mie_phase_g = kMiePhaseG;
  a.absorption_density.lower = {kOzonePeak, 0.0, 0.0, 1.0 / kOzoneHalfWidth,
                                -kOzoneBottom / kOzoneHalfWidth};
  a.absorption_density.upper = {0.0, 0.0, 0.0, -1.0 / kOzoneHalfWidth,
                                (kOzonePeak + kOzoneHalfWidth) / kOzoneHalfWidth};
  a.absorption_extinction = {kOzoneAbsorption[0], kOzoneAbsorption[1], kOzoneAbsorption[2]};
  a.ground_albedo = glm::dvec3(kSeaAlbedo);
  a.max_sun_zenith = kMaxSunZenith;
  a.scattering_orders = 4;
  return a;
}

void AtmosphereParameters::validate() const {
  require(non_negative3(solar_irradiance), "solar_irradiance", "finite values >= 0");
  require(std::isfinite(sun_angular_radius) && sun_angular_radius > 0.0 && sun_angular_radius < 0.1,
          "sun_angular_radius", "a value in (0, 0.1) rad");
  require(std::isfinite(bottom_radius) && bottom_radius >= 1e3 && bottom_radius <= 1e8,
          "bottom_radius", "a value in [1e3, 1e8] m");
  require(
      std::isfinite(top_radius) && top_radius > bottom_radius && top_radius <= 2.0 * bottom_radius,
      "top_radius", "a value in (bottom_radius, 2 bottom_radius]");
  require(non_negative3(rayleigh_scattering), "rayleigh_scattering", "finite values >= 0");
  require(non_negative3(mie_scattering), "mie_scattering", "finite values >= 0");
  require(non_negative3(mie_extinction) && mie_extinction.x >= mie_scattering.x &&
              mie_extinction.y >= mie_scattering.y && mie_extinction.z >= mie_scattering.z,
          "mie_extinction", "finite values >= mie_scattering");
  require(std::isfinite(mie_phase_g) && mie_phase_g > -1.0 && mie_phase_g < 1.0, "mie_phase_g",
          "a value in (-1, 1)");
  require(non_negative3(absorption_extinction), "absorption_extinction", "finite values >= 0");
  require(non_negative3(ground_albedo) && ground_albedo.x <= 1.0 && ground_albedo.y <= 1.0 &&
              ground_albedo.z <= 1.0,
          "ground_albedo", "values in [0, 1]");
  require(
      std::isfinite(max_sun_zenith) && max_sun_zenith >= kPi / 2.0 && max_sun_zenith <= kPi * 0.75,
      "max_sun_zenith", "a value in [90, 135] degrees (as radians)");
  require(scattering_orders >= 1 && scattering_orders <= 16, "scattering_orders",
          "an integer in [1, 16]");
  for (const DensityProfile* p : {&rayleigh_density, &mie_density, &absorption_density}) {
    for (const DensityLayer* l : {&p->lower, &p->upper}) {
      require(std::isfinite(l->width) && std::isfinite(l->exp_term) &&
                  std::isfinite(l->exp_scale) && std::isfinite(l->linear_term) &&
                  std::isfinite(l->constant_term),
              "density profile", "finite coefficients");
    }
  }
}

std::string AtmosphereParameters::key() const {
  std::ostringstream out;
  print(out, "solar_irradiance", solar_irradiance);
  print(out, "sun_angular_radius", sun_angular_radius);
  print(out, "bottom_radius", bottom_radius);
  print(out, "top_radius", top_radius);
  print(out, "rayleigh_density", rayleigh_density);
  print(out, "rayleigh_scattering", rayleigh_scattering);
  print(out, "mie_density", mie_density);
  print(out, "mie_scattering", mie_scattering);
  print(out, "mie_extinction", mie_extinction);
  print(out, "mie_phase_g", mie_phase_g);
  print(out, "absorption_density", absorption_density);
  print(out, "absorption_extinction", absorption_extinction);
  print(out, "ground_albedo", ground_albedo);
  print(out, "max_sun_zenith", max_sun_zenith);
  out << "scattering_orders=" << scattering_orders << ';';
  return out.str();
}

}  // namespace thalassa::atmosphere
