// Energy checks of the ocean's lighting (issue 7, point 3), through the renderer itself.
//
// (a) White furnace. Under a uniform sky of radiance 1 (an HDR photograph of 1 everywhere, read
// by the environment-map provider like any sky.exr: no atmosphere, no sun found in it), with the
// sun's glint and the refracted light off (LightTerms), the sea reflects the sky only: its
// radiance is F-bar(v) L-bar (eq. 21, 26), with the effective Fresnel F-bar in [R, 1] (eq. 26:
// R + (1 - R) (1 - cos theta_v)^e / (1 + 22.7 sigma_v^1.5) with e > 0; eq. 24's table,
// ocean.effective_fresnel = "table": R + (1 - R) I with I held to [0, 1]) and L-bar the filtered
// sky map, an average of texels that hold 1 above the horizon and, below it, the paper's
// multiple-reflection radiance F_mean E_sky / pi = 0.0664 (sec. 6; E_sky = pi). So no pixel may
// exceed 1 (beyond float rounding), and no pixel may fall below R, the minimum over view angles
// of the sea's reflectance (R = F-bar at normal incidence), wherever the filtered reflection
// reads the sky above the horizon: where it dips below, L-bar < 1 can pull F-bar L-bar under R
// only where F-bar is near R, i.e. near normal incidence, where the reflected ray points up. The
// measured minimum over every view below is the proof that this holds (docs/numerics.md).
//
// (b) The sun's glint energy over distance. The irradiance that the glint sends to the camera,
// E_cam = sum over pixels of L_sun-term x pixel solid angle, is independent of the camera's
// height over a flat sea (the glint's angular pattern depends on the view directions only). Over
// a sphere of radius a the sea is a convex mirror of focal length a / 2: to first order in the
// glint's angular size its pattern shrinks by m = (a / 2) / (h + a / 2), so E_cam shrinks by m^2.
// G(h) = E_cam / (E_sun m^2) is then the same at every height, from the projected grid (waves as
// geometry, normals and BRDF) to the view from space (every wave in the BRDF), if the hierarchy
// conserves the glint's energy. The test renders the sun term alone (sun at the zenith, camera
// looking straight down, the field of view scaled by m so the glint fills the same share of the
// image), and compares G(h) with the same sum evaluated on the CPU from the double-precision
// Ross BRDF with the wave set's total slope variance on the sphere (ross_brdf_reference.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "ross_brdf_reference.hpp"
#include "test_support.hpp"
#include "thalassa/atmosphere/environment_map.hpp"
#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/ocean/wave_set.hpp"
#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/nadir_frame.hpp"

namespace thalassa {
namespace {

constexpr double kDegree = M_PI / 180.0;

// Float rounding allowed above 1 in the furnace: the sky map's mip levels and the filter's
// weights are sums in float (a few ulp of 1, 6e-8 each).
constexpr double kFurnaceRoundoff = 1e-5;

std::string write_sky(const std::string& name, int width, int height, float sky, float cap,
                      int cap_rows) {
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(std::size_t(width) * height * 4, 1.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = y < cap_rows ? cap : sky;
  const std::string path = test::output_dir() + "/" + name + ".exr";
  write_exr(path, image, ExrPixelType::Float);
  return path;
}

// Which pixels see the sea at rest (the planet's quadric), `margin` pixels from the horizon.
std::vector<bool> sea_mask(const Scene& scene, double margin) {
  const CameraBasis basis =
      camera_basis(scene.camera.heading, scene.camera.pitch, scene.camera.roll);
  const ocean::SeaSurface surface =
      make_nadir_frame(Planet(scene.planet), scene.camera).sea_surface;
  const double tan_half = std::tan(0.5 * scene.camera.fov_y * kDegree);
  const double aspect = double(scene.image.width) / scene.image.height;
  std::vector<bool> mask(std::size_t(scene.image.width) * scene.image.height);
  for (int y = 0; y < scene.image.height; ++y)
    for (int x = 0; x < scene.image.width; ++x) {
      bool sea = true;
      for (double d : {-margin, 0.0, margin}) {
        const double u = 2.0 * (x + 0.5) / scene.image.width - 1.0;
        const double v = 1.0 - 2.0 * (y + 0.5 + d) / scene.image.height;
        const glm::dvec3 ray = glm::normalize(view_ray(basis, tan_half, aspect, u, v));
        sea = sea && ocean::sea_surface_distance(surface, scene.camera.height, ray).has_value();
      }
      mask[std::size_t(y) * scene.image.width + x] = sea;
    }
  return mask;
}

struct FurnaceView {
  const char* name;
  const char* scene;  // JSON over the defaults
};

const FurnaceView kFurnaceViews[] = {
    {"surface_straight_down_calm",
     R"({"camera": {"pitch": -90, "height": 10}, "ocean": {"wind_speed": 0}})"},
    {"surface_straight_down", R"({"camera": {"pitch": -90, "height": 10}})"},
    {"surface_oblique", R"({"camera": {"pitch": -30, "height": 10}})"},
    {"surface_horizon", R"({"camera": {"pitch": -5, "height": 4}})"},
    {"surface_horizon_across_wind", R"({"camera": {"pitch": 0, "height": 2, "heading": 90}})"},
    {"surface_horizon_wind_40",
     R"({"camera": {"pitch": -3, "height": 4}, "ocean": {"wind_speed": 40, "lambda_max": 1000}})"},
    {"surface_wide_wind_40",
     R"({"camera": {"pitch": -45, "height": 30, "fov_y": 150}, "ocean": {"wind_speed": 40, "lambda_max": 1000}})"},
    {"surface_nine_samples",
     R"({"camera": {"pitch": -10, "height": 4}, "ocean": {"sky_filter": "nine_samples", "wind_speed": 20, "lambda_max": 300}})"},
    {"surface_shrm",
     R"({"camera": {"pitch": -10, "height": 4}, "ocean": {"sky_filter": "shrm", "wind_speed": 20, "lambda_max": 300}})"},
    {"surface_shrm_sky_lobe",
     R"({"camera": {"pitch": -3, "height": 4}, "ocean": {"sky_filter": "shrm", "sky_lobe_centre": "fresnel_weighted", "wind_speed": 40, "lambda_max": 1000}})"},
    {"surface_horizon_table",
     R"({"camera": {"pitch": -3, "height": 4}, "ocean": {"effective_fresnel": "table", "wind_speed": 40, "lambda_max": 1000}})"},
    {"surface_horizon_sky_lobe",
     R"({"camera": {"pitch": -3, "height": 4}, "ocean": {"sky_lobe_centre": "fresnel_weighted", "effective_fresnel": "table", "wind_speed": 40, "lambda_max": 1000}})"},
    {"surface_horizon_parallax",
     R"({"camera": {"pitch": -3, "height": 4}, "ocean": {"parallax_iterations": 8, "wind_speed": 40, "lambda_max": 1000}})"},
    {"surface_19_km_sky_lobe",
     R"({"camera": {"pitch": -20, "height": 19000}, "ocean": {"sky_lobe_centre": "fresnel_weighted"}})"},
    {"surface_19_km", R"({"camera": {"pitch": -20, "height": 19000}})"},
    {"space_20_km", R"({"camera": {"pitch": -20, "height": 20000}})"},
    {"space_straight_down", R"({"camera": {"pitch": -90, "height": 400000}})"},
    {"space_limb_wind_40",
     R"({"camera": {"pitch": -15, "height": 400000}, "ocean": {"wind_speed": 40, "lambda_max": 1000}})"},
    {"space_limb_table",
     R"({"camera": {"pitch": -15, "height": 400000}, "ocean": {"effective_fresnel": "table", "wind_speed": 40, "lambda_max": 1000}})"},
    {"space_limb_sky_lobe",
     R"({"camera": {"pitch": -15, "height": 400000}, "ocean": {"sky_lobe_centre": "fresnel_weighted", "wind_speed": 40, "lambda_max": 1000}})"},
    {"space_geostationary",
     R"({"camera": {"pitch": -90, "height": 36000000, "fov_y": 20, "lat": 0}})"},
};

void PrintTo(const FurnaceView& view, std::ostream* out) { *out << view.name; }

class WhiteFurnace : public ::testing::TestWithParam<FurnaceView> {};

TEST_P(WhiteFurnace, SeaRadianceIsBetweenRAndOne) {
  const FurnaceView& view = GetParam();
  const std::string sky = write_sky("uniform_sky", 64, 32, 1.0f, 1.0f, 0);
  SceneBuilder builder;
  builder.load_text(R"({"image": {"width": 96, "height": 64}})", "furnace");
  builder.load_text(view.scene, view.name);
  builder.set("sky.exr=\"" + sky + "\"");
  const Scene scene = builder.build();
  RendererOptions options;
  options.terms = {.sun = false, .sky = true, .sea = false, .air = true};
  auto context = test::make_test_context();
  Renderer renderer(*context, scene, options);
  const Image image = renderer.image();
  const std::vector<bool> sea = sea_mask(scene, 1.5);

  const double r = scene.ocean.fresnel_r;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  double sea_low = low, sea_high = -low;
  int sea_pixels = 0, low_x = -1, low_y = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double value = image.pixel(x, y)[c];
        ASSERT_TRUE(std::isfinite(value)) << x << ", " << y;
        low = std::min(low, value);
        high = std::max(high, value);
        if (!sea[std::size_t(y) * image.width + x]) continue;
        sea_pixels += c == 0;
        sea_high = std::max(sea_high, value);
        if (value < sea_low) {
          sea_low = value;
          low_x = x;
          low_y = y;
        }
      }
  std::printf(
      "furnace %-28s %-7s sea pixels %4d: sea min %.5f (R x %.4f, at %d,%d) max %.7f; "
      "image min %.5f max %.7f\n",
      view.name, renderer.stats().mode.c_str(), sea_pixels, sea_low, sea_low / r, low_x, low_y,
      sea_high, low, high);
  EXPECT_GT(sea_pixels, 0);
  // Every pixel, the sky's (exactly 1) and the sea's.
  EXPECT_LE(high, 1.0 + kFurnaceRoundoff);
  EXPECT_GE(low, r * (1.0 - kFurnaceRoundoff));
}

INSTANTIATE_TEST_SUITE_P(Views, WhiteFurnace, ::testing::ValuesIn(kFurnaceViews),
                         [](const ::testing::TestParamInfo<FurnaceView>& info) {
                           return std::string(info.param.name);
                         });

// ---- (b) the glint's energy over distance ----------------------------------------------------

// The photograph of the glint test: a black-ish sky (1e-3) and a sun filling the top kSunRows
// rows of a 256 x 128 map, a cap of 1.4 deg radius about the zenith (the environment map finds
// it, takes it out and reports its centroid, the zenith, and its irradiance).
constexpr int kSunRows = 1;
constexpr float kSunCap = 1.0e4f;  // W m^-2 sr^-1 nm^-1
constexpr float kDarkSky = 1.0e-3f;

constexpr double kPlanetRadius = 6371000.0;  // m, planet.shape = sphere
constexpr double kNearTanHalfFov = 1.0;      // tan(fov_y / 2) of the flat limit: 90 deg
constexpr int kGlintImage = 128;             // pixels, square

// The camera's irradiance from the glint per unit sun irradiance, from an image of the sun term
// alone: sum of L x pixel solid angle (green channel), over E_sun.
double glint_irradiance(const Image& image, double tan_half, double sun_irradiance) {
  double sum = 0.0;
  const double step = 2.0 * tan_half / image.width;  // square pixels, square image
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double u = (2.0 * (x + 0.5) / image.width - 1.0) * tan_half;
      const double v = (1.0 - 2.0 * (y + 0.5) / image.height) * tan_half;
      const double solid_angle = step * step / std::pow(1.0 + u * u + v * v, 1.5);
      sum += image.pixel(x, y)[1] * solid_angle;
    }
  return sum / sun_irradiance;
}

// The same sum on the CPU: each pixel's ray met with the sphere, the sun term of the Ross BRDF
// (eq. 15, double precision) with the wave set's total slope variance in the point's tangent
// frame, wind along t_x. Sun at the nadir's zenith, camera straight down.
double reference_glint_irradiance(const Scene& scene, double tan_half) {
  const ocean::WaveSet waves = ocean::make_wave_set(scene.ocean);
  const ocean::SlopeVariance total = ocean::total_slope_variance(waves);
  const glm::dvec2 variance(total.along, total.across);
  const glm::dvec3 wind(waves.downwind, 0.0);
  const glm::dvec3 sun(0.0, 0.0, 1.0);
  const glm::dvec3 camera(0.0, 0.0, scene.camera.height);
  const glm::dvec3 centre(0.0, 0.0, -kPlanetRadius);
  const CameraBasis basis = camera_basis(scene.camera.heading, -90.0, 0.0);
  const int n = scene.image.width;
  const double step = 2.0 * tan_half / n;
  double sum = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double u = (2.0 * (x + 0.5) / n - 1.0);
      const double v = (1.0 - 2.0 * (y + 0.5) / n);
      const glm::dvec3 ray = glm::normalize(view_ray(basis, tan_half, 1.0, u, v));
      // |camera + t ray - centre| = a, the nearer root.
      const glm::dvec3 oc = camera - centre;
      const double b = glm::dot(oc, ray);
      const double c = (scene.camera.height) * (scene.camera.height + 2.0 * kPlanetRadius);
      const double disc = b * b - c;
      if (disc < 0.0) continue;
      const double t = c / (-b + std::sqrt(disc));  // cancellation-free nearer root
      const glm::dvec3 normal = glm::normalize(camera + t * ray - centre);
      const glm::dvec3 t_x = glm::normalize(wind - glm::dot(wind, normal) * normal);
      const glm::dvec3 t_y = glm::cross(normal, t_x);
      auto tangent = [&](const glm::dvec3& w) {
        return glm::dvec3(glm::dot(w, t_x), glm::dot(w, t_y), glm::dot(w, normal));
      };
      const double radiance =
          glsl::OceanReflectedSun(tangent(-ray), tangent(sun), variance, scene.ocean.fresnel_r);
      const double pu = u * tan_half, pv = v * tan_half;
      sum += radiance * step * step / std::pow(1.0 + pu * pu + pv * pv, 1.5);
    }
  return sum;
}

// One height of the sweep: the heights where waves are geometry or normals (below ~300 m here)
// show one realisation of the sea, whose few long waves in view move the glint's energy by a
// few percent from one seed to the next (the sun's image is a sum of sparkles there, as on a
// real sea): they are averaged over kNearSeeds seeds.
struct GlintHeight {
  double height;  // m
  int seeds;      // realisations averaged
};
constexpr int kNearSeeds = 4;
const GlintHeight kGlintHeights[] = {{10.0, kNearSeeds}, {30.0, kNearSeeds}, {100.0, kNearSeeds},
                                     {300.0, 1},         {1000.0, 1},        {10000.0, 1},
                                     {19999.0, 1},       {20001.0, 1},       {1.0e5, 1},
                                     {1.0e6, 1},         {3.6e7, 1}};
// Tolerances on G(h) / G_ref(h), G_ref the CPU sum of the BRDF with every wave's slope variance,
// taken from the measured values (docs/numerics.md, "Energy checks") with margin:
// - where every wave is in the BRDF (a pixel's footprint, 2 h / 128, wider than lambda_max /
//   N_min = 4 m: from 256 m up, and the whole view from space): measured |G / G_ref - 1| <=
//   4.4e-6;
constexpr double kBrdfTolerance = 2e-3;
// - where the long waves are geometry and normals (10 to 100 m): the seed-averaged G is below
//   G_ref by 0.35 % at 100 m, 2.6 % at 30 m, 4.4 % at 10 m (the hierarchy's approximation: a
//   tilted facet's BRDF with the short waves' variance is not exactly the convolution of the
//   two slope distributions), so G may be up to 8 % below and 2 % above G_ref.
constexpr double kNearDeficit = 0.08;
constexpr double kNearExcess = 0.02;
constexpr double kNearHeightLimit = 300.0;  // m: below, kNearDeficit / kNearExcess apply

TEST(GlintEnergy, StaysStableAsTheViewDistanceGrows) {
  const std::string sky = write_sky("glint_sky", 256, 128, kDarkSky, kSunCap, kSunRows);
  const atmosphere::EnvironmentMap map(sky);
  ASSERT_TRUE(map.sun().has_value()) << map.sun_search();
  const auto direction = *map.sun_direction();
  ASSERT_GT(direction[2], 1.0 - 1e-9);  // the zenith
  const double sun_irradiance = map.sun_irradiance()[1];

  RendererOptions options;
  options.terms = {.sun = true, .sky = false, .sea = false, .air = false};
  auto context = test::make_test_context();
  double lowest = std::numeric_limits<double>::infinity(), highest = 0.0;
  for (const GlintHeight& level : kGlintHeights) {
    const double h = level.height;
    // The convex mirror's magnification, and the field of view that keeps the glint's share.
    const double m = 0.5 * kPlanetRadius / (h + 0.5 * kPlanetRadius);
    const double tan_half = kNearTanHalfFov * m;
    double gpu = 0.0, cpu = 0.0, border_share = 0.0;
    std::string mode;
    for (int seed = 1; seed <= level.seeds; ++seed) {
      // A 5 m/s sea of 60 waves from 2 cm to 4 m: lambda_max small against the 20 m of sea
      // seen from 10 m, so that a realisation holds several of its longest waves.
      SceneBuilder builder;
      builder.load_text(R"({"image": {"width": 128, "height": 128},
                           "camera": {"pitch": -90, "heading": 0, "lat": 0, "lon": 0},
                           "planet": {"shape": "sphere", "radius": 6371000},
                           "ocean": {"wind_speed": 5, "lambda_max": 4}})",
                        "glint");
      builder.set("camera.height=" + std::to_string(h));
      builder.set("ocean.seed=" + std::to_string(seed));
      builder.set("sky.exr=\"" + sky + "\"");
      Scene scene = builder.build();
      scene.camera.fov_y = 2.0 * std::atan(tan_half) / kDegree;
      ASSERT_EQ(scene.image.width, kGlintImage);
      Renderer renderer(*context, scene, options);
      mode = renderer.stats().mode;
      const Image image = renderer.image();
      // The glint's share at the image's border: it must fit in the view.
      double border = 0.0, all = 0.0;
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
          const double g = image.pixel(x, y)[1];
          ASSERT_TRUE(std::isfinite(g));
          all += g;
          if (x == 0 || y == 0 || x == image.width - 1 || y == image.height - 1) border += g;
        }
      border_share = std::max(border_share, border / all);
      gpu += glint_irradiance(image, tan_half, sun_irradiance) / (m * m) / level.seeds;
      cpu += reference_glint_irradiance(scene, tan_half) / (m * m) / level.seeds;
    }
    const double ratio = gpu / cpu;
    std::printf(
        "glint h %10.0f m %-7s seeds %d  m %.5f  G %.6f  G_ref %.6f  G/G_ref - 1 %+.2e  "
        "border share %.1e\n",
        h, mode.c_str(), level.seeds, m, gpu, cpu, ratio - 1.0, border_share);
    EXPECT_LT(border_share, 0.01) << "the glint does not fit in the view at " << h << " m";
    if (h < kNearHeightLimit) {
      EXPECT_GT(ratio, 1.0 - kNearDeficit) << h << " m";
      EXPECT_LT(ratio, 1.0 + kNearExcess) << h << " m";
    } else {
      EXPECT_NEAR(ratio, 1.0, kBrdfTolerance) << h << " m";
    }
    lowest = std::min(lowest, gpu);
    highest = std::max(highest, gpu);
  }
  std::printf("glint G over the heights: %.6f to %.6f (max / min - 1 = %.4f)\n", lowest, highest,
              highest / lowest - 1.0);
}

}  // namespace
}  // namespace thalassa
