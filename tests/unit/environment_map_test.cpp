// Tests of the environment-map sky provider (atmosphere/include/thalassa/atmosphere/
// environment_map.hpp): the stereographic coordinates against their definition and the ocean
// shader, exact texel solid angles, the sky irradiance of skies whose integral is known, sun
// extraction on synthetic photographs, the paper's below-horizon radiance, the GPU maps, and
// the errors for bad input. Frame: east-north-up (x east, y north, z up); angles in radians
// unless a name says degrees.
#include "thalassa/atmosphere/environment_map.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <numbers>
#include <string>
#include <vector>

#include "ross_brdf_reference.hpp"
#include "thalassa/engine/image.hpp"

namespace thalassa::atmosphere {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// The test's own direction formula: zenith angle theta, azimuth alpha clockwise from north.
Vec3 Direction(double theta, double alpha) {
  return {std::sin(alpha) * std::sin(theta), std::cos(alpha) * std::sin(theta), std::cos(theta)};
}
double Dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double Angle(const Vec3& a, const Vec3& b) {
  const Vec3 c = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::hypot(c[0], c[1], c[2]), Dot(a, b));
}
// (2 pi / W) (cos theta_top - cos theta_bottom), written directly (the library uses a product
// of sines).
double TexelSolidAngle(int width, int height, int y) {
  return 2.0 * kPi / width * (std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height));
}

// An RGBA image whose texel (x, y) is value(x, y).
Image MakeImage(int width, int height, const std::function<Rgb(int, int)>& value) {
  Image image{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 4)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Rgb v = value(x, y);
      float* p = image.pixel(x, y);
      for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(v[c]);
      p[3] = 1.0f;
    }
  return image;
}

// Radiance `sky` in every row whose top edge is above the horizon, `ground` below.
Image SkyAndGround(int width, int height, Rgb sky, Rgb ground) {
  return MakeImage(width, height, [&](int, int y) { return 2 * y < height ? sky : ground; });
}

void ExpectRelativeNear(double actual, double expected, double tolerance, const std::string& what) {
  EXPECT_LE(std::abs(actual - expected), tolerance * std::abs(expected))
      << what << ": " << actual << " vs " << expected;
}

// ---- Stereographic coordinates -------------------------------------------------------------

TEST(EnvironmentMapStereographic, ZenithHorizonAndRoundTrip) {
  const Vec2 zenith = stereographic_coordinates({0.0, 0.0, 1.0});
  EXPECT_EQ(zenith[0], 0.0);
  EXPECT_EQ(zenith[1], 0.0);
  const Vec3 up = stereographic_direction({0.0, 0.0});
  EXPECT_EQ(up[2], 1.0);
  // East is +u_x, north +u_y, both on the unit circle.
  const Vec2 east = stereographic_coordinates({1.0, 0.0, 0.0});
  EXPECT_NEAR(east[0], 1.0, 1e-15);
  EXPECT_NEAR(east[1], 0.0, 1e-15);
  const Vec2 north = stereographic_coordinates({0.0, 1.0, 0.0});
  EXPECT_NEAR(north[1], 1.0, 1e-15);
  for (double alpha_deg = 0.0; alpha_deg < 360.0; alpha_deg += 17.0) {
    const Vec2 u = stereographic_coordinates(Direction(kPi / 2, alpha_deg * kDeg));
    EXPECT_NEAR(std::hypot(u[0], u[1]), 1.0, 1e-14) << alpha_deg;
    const Vec3 r =
        stereographic_direction({std::cos(alpha_deg * kDeg), std::sin(alpha_deg * kDeg)});
    EXPECT_NEAR(r[2], 0.0, 1e-15) << alpha_deg;
  }
  for (double theta_deg : {0.5, 10.0, 45.0, 89.0, 90.0, 91.0, 135.0, 170.0, 179.0})
    for (double alpha_deg : {0.0, 33.0, 90.0, 181.0, 300.0}) {
      const Vec3 d = Direction(theta_deg * kDeg, alpha_deg * kDeg);
      const Vec2 u = stereographic_coordinates(d);
      // The definition u = (r_x, r_y) / (1 + r_z).
      EXPECT_NEAR(u[0], d[0] / (1.0 + d[2]), 1e-12 * (1.0 + std::abs(u[0])));
      EXPECT_NEAR(u[1], d[1] / (1.0 + d[2]), 1e-12 * (1.0 + std::abs(u[1])));
      const Vec3 back = stereographic_direction(u);
      EXPECT_NEAR(std::hypot(back[0], back[1], back[2]), 1.0, 1e-15);
      EXPECT_LT(Angle(back, d), 1e-13) << theta_deg << " " << alpha_deg;
    }
  // Far outside the unit circle: finite, unit, towards the nadir.
  for (double radius : {10.0, 1e6, 1e200}) {
    const Vec3 r = stereographic_direction({radius, -radius});
    EXPECT_NEAR(std::hypot(r[0], r[1], r[2]), 1.0, 1e-15) << radius;
    if (radius < 1e100)
      EXPECT_NEAR(r[2], (1.0 - 2.0 * radius * radius) / (1.0 + 2.0 * radius * radius), 1e-15);
    else
      EXPECT_EQ(r[2], -1.0);
  }
  EXPECT_THROW(stereographic_direction({std::nan(""), 0.0}), std::invalid_argument);
  EXPECT_THROW(stereographic_coordinates({0.0, 0.0, 0.0}), std::invalid_argument);
}

TEST(EnvironmentMapStereographic, AgreesWithTheOceanShader) {
  EXPECT_EQ(kSkyMapMaxRadius, glsl::OCEAN_SKY_MAP_MAX_RADIUS);
  for (double theta_deg : {0.0, 30.0, 90.0, 150.0, 179.0, 179.99, 179.9999, 180.0})
    for (double alpha_deg : {0.0, 70.0, 200.0}) {
      const Vec3 d = Direction(theta_deg * kDeg, alpha_deg * kDeg);
      const Vec2 u = stereographic_coordinates(d);
      const glm::dvec2 expected = glsl::OceanStereographic(glm::dvec3(d[0], d[1], d[2]));
      EXPECT_NEAR(u[0], expected.x, 1e-12 * (1.0 + std::abs(expected.x))) << theta_deg;
      EXPECT_NEAR(u[1], expected.y, 1e-12 * (1.0 + std::abs(expected.y))) << theta_deg;
      EXPECT_LE(std::hypot(u[0], u[1]), kSkyMapMaxRadius * (1.0 + 1e-15));
    }
}

// ---- Texels and irradiance -------------------------------------------------------------------

TEST(EnvironmentMapTexels, SolidAnglesAreExactAndSumTo4Pi) {
  for (int height : {4, 5, 7, 64, 1000, 1024}) {
    const int width = 2 * height;
    double sum = 0.0;
    for (int y = 0; y < height; ++y) {
      const double omega = equirect_texel_solid_angle(width, height, y);
      ExpectRelativeNear(omega, TexelSolidAngle(width, height, y), 1e-9, "texel");
      sum += omega * width;
    }
    EXPECT_NEAR(sum, 4.0 * kPi, 1e-12) << height;
  }
}

// A uniform sky L above the horizon (and a different ground, which must not count) gives
// E = pi L; the odd height has a row straddling the horizon, split by the integration.
TEST(EnvironmentMapIrradiance, UniformSkyGivesPiL) {
  const Rgb sky = {0.5, 1.0, 2.0};
  for (int height : {64, 63, 5}) {
    const EnvironmentMap map(SkyAndGround(2 * height, height, sky, {0.3, 0.3, 0.3}));
    for (int c = 0; c < 3; ++c)
      ExpectRelativeNear(map.sky_irradiance()[c], kPi * sky[c], 1e-9,
                         "height " + std::to_string(height));
    EXPECT_FALSE(map.sun().has_value());
  }
}

// L(theta) = cos theta above the horizon: E = ∫ cos^2 theta dω = 2 pi / 3. Texels hold the
// exact texel average of cos theta, (c_t + c_b) / 2 with c = cos theta at the row's edges, and
// are integrated as constants over their rows: row by row that is (c_t + c_b) (c_t^2 - c_b^2) / 4
// = (c_t^3 - c_b^3) / 3 - (c_t - c_b)^3 / 12, so the sum is exactly 2 pi / 3 minus
// 2 pi sum (c_t - c_b)^3 / 12 (2.5e-5 relative at H = 256, falling as 1 / H^2). The pixels
// are floats (each rounded by up to 6e-8 relative), hence 1e-8 rather than rounding.
TEST(EnvironmentMapIrradiance, CosineSkyGivesTwoPiOverThree) {
  for (int height : {256, 257}) {
    const auto edge = [&](int y) { return std::max(0.0, std::cos(kPi * y / height)); };
    const Image image = MakeImage(2 * height, height, [&](int, int y) {
      const double c = 0.5 * (edge(y) + edge(y + 1));
      return Rgb{c, c, c};
    });
    double defect = 0.0;
    for (int y = 0; 2 * y < height; ++y) defect += std::pow(edge(y) - edge(y + 1), 3) / 12.0;
    EnvironmentMapOptions options;
    options.scale = 3.0;
    const EnvironmentMap map(image, options);
    const std::string what = "cosine sky, height " + std::to_string(height);
    ExpectRelativeNear(map.sky_irradiance()[1], 3.0 * (2.0 * kPi / 3.0 - 2.0 * kPi * defect), 1e-8,
                       what);
    ExpectRelativeNear(map.sky_irradiance()[1], 3.0 * 2.0 * kPi / 3.0, 3e-5, what);
  }
}

// ---- Sun extraction ------------------------------------------------------------------------

struct SunCase {
  double azimuth_deg;    // clockwise from north
  double elevation_deg;  // above the horizon
  double north_offset;   // radians
  const char* what;
};

constexpr double kSky = 1.0;
constexpr double kSunRadiance = 1e5;       // times the sky
constexpr double kSunRadius = 1.0 * kDeg;  // the synthetic disc's angular radius
constexpr int kSunHeight = 512;            // texels of 0.35 deg
constexpr int kCoverageSamples = 16;       // per axis, equal-area in each texel

// A uniform sky of radiance kSky with a disc of radiance kSunRadiance * kSky, each texel the
// exact area average (coverage from 16 x 16 equal-area samples: uniform in cos theta and alpha).
Image SunImage(const SunCase& sun_case) {
  const int height = kSunHeight, width = 2 * height;
  const Vec3 centre =
      Direction((90.0 - sun_case.elevation_deg) * kDeg, sun_case.azimuth_deg * kDeg);
  const double cos_radius = std::cos(kSunRadius);
  return MakeImage(width, height, [&](int x, int y) {
    const double alpha0 = sun_case.north_offset + 2.0 * kPi * x / width;
    const double theta_c = kPi * (y + 0.5) / height;
    const Vec3 texel_centre = Direction(theta_c, alpha0 + kPi / width);
    // Every point of a texel is within 0.5 deg of its centre at this size.
    if (Angle(texel_centre, centre) > kSunRadius + 1.0 * kDeg) return Rgb{kSky, kSky, kSky};
    const double z_top = std::cos(kPi * y / height), z_bottom = std::cos(kPi * (y + 1) / height);
    int inside = 0;
    for (int sy = 0; sy < kCoverageSamples; ++sy)
      for (int sx = 0; sx < kCoverageSamples; ++sx) {
        const double z = z_top + (z_bottom - z_top) * (sy + 0.5) / kCoverageSamples;
        const double alpha = alpha0 + 2.0 * kPi / width * (sx + 0.5) / kCoverageSamples;
        const double s = std::sqrt(1.0 - z * z);
        inside += Dot({s * std::sin(alpha), s * std::cos(alpha), z}, centre) >= cos_radius;
      }
    const double coverage = static_cast<double>(inside) / (kCoverageSamples * kCoverageSamples);
    const double v = kSky * (1.0 + (kSunRadiance - 1.0) * coverage);
    return Rgb{v, v, v};
  });
}

class EnvironmentMapSun : public ::testing::TestWithParam<SunCase> {};

TEST_P(EnvironmentMapSun, RecoversDirectionIrradianceAndLeavesASmoothSky) {
  const SunCase& sun_case = GetParam();
  const Image image = SunImage(sun_case);
  const int width = image.width, height = image.height;
  // The irradiance the disc adds, from the image itself: sum (L - sky) Ω.
  double added = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      added += (image.pixel(x, y)[1] - kSky) * TexelSolidAngle(width, height, y);
  const double disc = (kSunRadiance - 1.0) * kSky * 2.0 * kPi * (1.0 - std::cos(kSunRadius));

  EnvironmentMapOptions options;
  options.north_offset = sun_case.north_offset;
  const EnvironmentMap map(image, options);
  ASSERT_TRUE(map.sun().has_value()) << map.sun_search();
  const ExtractedSun& sun = *map.sun();
  const Vec3 expected =
      Direction((90.0 - sun_case.elevation_deg) * kDeg, sun_case.azimuth_deg * kDeg);
  EXPECT_LT(Angle(sun.direction, expected), 0.25 * kPi / height) << map.sun_search();
  for (int c = 0; c < 3; ++c) {
    ExpectRelativeNear(sun.irradiance[c], added, 1e-6, "irradiance vs the image");
    ExpectRelativeNear(sun.irradiance[c], disc, 0.01, "irradiance vs the disc");
  }
  EXPECT_EQ(map.sun_irradiance(), sun.irradiance);
  ExpectRelativeNear(sun.angular_radius, kSunRadius, 0.05, "angular radius");
  ASSERT_TRUE(map.sun_direction().has_value());

  // What is left is the uniform sky: every texel (read back at its centre through a panorama of
  // the photograph's own size and offset) and the irradiance.
  const Image left = map.panorama(width, sun_case.north_offset);
  double worst = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(left.pixel(x, y)[c] - kSky));
  EXPECT_LT(worst, 1e-6);
  ExpectRelativeNear(map.sky_irradiance()[0], kPi * kSky, 1e-9, "sky irradiance after");
}

INSTANTIATE_TEST_SUITE_P(
    EnvironmentMapDiscs, EnvironmentMapSun,
    ::testing::Values(
        SunCase{100.0, 30.0, 0.0, "east_south_east"}, SunCase{0.0, 20.0, 0.0, "on_the_seam"},
        SunCase{359.6, 10.0, 0.0, "just_left_of_the_seam"},
        SunCase{0.7 / kDeg, 45.0, 0.7, "on_the_seam_with_an_offset"},
        SunCase{250.0, 40.0, -2.0, "offset_negative"}, SunCase{45.0, 89.5, 0.0, "over_the_zenith"},
        SunCase{200.0, 90.0, 0.0, "at_the_zenith"}, SunCase{300.0, 0.4, 0.0, "on_the_horizon"}),
    [](const ::testing::TestParamInfo<SunCase>& info) { return std::string(info.param.what); });

TEST(EnvironmentMapSunSearch, FindsNoSunInUniformOvercastOrBroadlyBrightSkies) {
  const int height = 128, width = 2 * height;
  // Uniform.
  const EnvironmentMap uniform(SkyAndGround(width, height, {1, 1, 1}, {1, 1, 1}));
  EXPECT_FALSE(uniform.sun().has_value());
  EXPECT_FALSE(uniform.sun_direction().has_value());
  EXPECT_EQ(uniform.sun_irradiance(), (Rgb{0, 0, 0}));
  EXPECT_EQ(uniform.sun_search().rfind("no sun found", 0), 0u) << uniform.sun_search();
  // Overcast: the CIE overcast sky's (1 + 2 cos theta) / 3 over a darker ground.
  const Image overcast_image = MakeImage(width, height, [&](int, int y) {
    const double theta = kPi * (y + 0.5) / height;
    const double v = theta < kPi / 2 ? (1.0 + 2.0 * std::cos(theta)) / 3.0 : 0.2;
    return Rgb{v, v, v};
  });
  const EnvironmentMap overcast(overcast_image);
  EXPECT_FALSE(overcast.sun().has_value()) << overcast.sun_search();
  // A bright region 100 times the sky, 7 deg in radius (0.37% of the sphere, so P99 stays the
  // sky's): too large to be the sun; left as is.
  const Vec3 centre = Direction(40.0 * kDeg, 120.0 * kDeg);
  const Image patch_image = MakeImage(width, height, [&](int x, int y) {
    const Vec3 d = Direction(kPi * (y + 0.5) / height, 2.0 * kPi * (x + 0.5) / width);
    const double v = Angle(d, centre) < 7.0 * kDeg ? 100.0 : 1.0;
    return Rgb{v, v, v};
  });
  const EnvironmentMap patch(patch_image);
  EXPECT_FALSE(patch.sun().has_value());
  EXPECT_NE(patch.sun_search().find("sr, more than"), std::string::npos) << patch.sun_search();
  EXPECT_NEAR(patch.sky_radiance(centre)[0], 100.0, 1e-9);
  // A small glint wholly below the horizon is not the sun.
  const Vec3 glint = Direction(120.0 * kDeg, 10.0 * kDeg);
  const Image glint_image = MakeImage(width, height, [&](int x, int y) {
    const Vec3 d = Direction(kPi * (y + 0.5) / height, 2.0 * kPi * (x + 0.5) / width);
    const double v = Angle(d, glint) < 2.0 * kDeg ? 1e4 : 1.0;
    return Rgb{v, v, v};
  });
  EXPECT_FALSE(EnvironmentMap(glint_image).sun().has_value());
  // With the search off, a real sun stays in the map.
  EnvironmentMapOptions off;
  off.extract_sun = false;
  const EnvironmentMap kept(SunImage({100.0, 30.0, 0.0, "kept"}), off);
  EXPECT_FALSE(kept.sun().has_value());
  EXPECT_GT(kept.sky_radiance(Direction(60.0 * kDeg, 100.0 * kDeg))[0], 1e3);
}

// ---- Below the horizon -----------------------------------------------------------------------

TEST(EnvironmentMapBelowHorizon, IsMeanFresnelTimesSkyIrradianceOverPi) {
  const int height = 32, width = 2 * height;
  const Image image = MakeImage(width, height, [&](int x, int y) {
    return Rgb{1.0 + 0.1 * x, 2.0 + 0.05 * y, 0.5 + 0.01 * x * y};
  });
  const EnvironmentMap map(image);
  const Rgb e = map.sky_irradiance();
  for (int c = 0; c < 3; ++c) {
    ExpectRelativeNear(map.below_horizon_radiance()[c], mean_water_fresnel() * e[c] / kPi, 1e-14,
                       "below horizon");
    EXPECT_EQ(map.radiance({0.3, 0.2, -0.01})[c], map.below_horizon_radiance()[c]);
    EXPECT_NE(map.radiance({0.3, 0.2, -0.01})[c], map.sky_radiance({0.3, 0.2, -0.01})[c]);
  }
  const Vec3 up = {0.3, -0.2, 0.5};
  EXPECT_EQ(map.radiance(up), map.sky_radiance(up));
  // At the horizon the sky side holds the last sky row (bilinear in azimuth only), while
  // sky_radiance() blends in the photograph's first row below the horizon.
  const Rgb horizon = map.radiance({1.0, 0.0, 0.0});
  const Rgb last_sky_row = map.sky_radiance(Direction(kPi * (height / 2 - 0.5) / height, kPi / 2));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(horizon[c], last_sky_row[c], 1e-12);
  EXPECT_NE(horizon[1], map.sky_radiance({1.0, 0.0, 0.0})[1]);  // G changes with the row
  EXPECT_THROW(map.radiance({0.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(map.sky_radiance({std::nan(""), 0.0, 1.0}), std::invalid_argument);
}

// F̄ = 2 ∫ F cos θ sin θ dθ by composite Simpson in the angle, with Fresnel's equations in their
// sine / tangent form (r_s = -sin(θi - θt) / sin(θi + θt), r_p = tan(θi - θt) / tan(θi + θt)),
// not the library's cosine form and Gauss-Legendre rule in cos θ.
TEST(EnvironmentMapFresnel, MeanWaterFresnelMatchesAnIndependentQuadrature) {
  const double n = kWaterRefractiveIndex;
  const auto fresnel = [&](double theta_i) {
    if (theta_i == 0.0) return std::pow((n - 1.0) / (n + 1.0), 2);
    const double theta_t = std::asin(std::sin(theta_i) / n);
    const double rs = -std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
    const double rp = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
    return 0.5 * (rs * rs + rp * rp);
  };
  const int intervals = 20000;  // even
  const double h = (kPi / 2) / intervals;
  double sum = 0.0;
  for (int k = 0; k <= intervals; ++k) {
    const double theta = k * h;
    const double f = 2.0 * fresnel(theta) * std::cos(theta) * std::sin(theta);
    sum += f * (k == 0 || k == intervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0));
  }
  const double reference = sum * h / 3.0;
  EXPECT_NEAR(mean_water_fresnel(), reference, 1e-10);
  // The diffuse reflectance of a flat water surface, ~0.066 (e.g. Mobley, "Light and Water",
  // 1994, sec. 4.3).
  EXPECT_NEAR(mean_water_fresnel(), 0.066, 0.001);
  EXPECT_NEAR(fresnel_reflectance(1.0, n), std::pow((n - 1.0) / (n + 1.0), 2), 1e-15);
  EXPECT_EQ(fresnel_reflectance(0.0, n), 1.0);
  EXPECT_NEAR(fresnel_reflectance(std::cos(60.0 * kDeg), n), fresnel(60.0 * kDeg), 1e-14);
  EXPECT_THROW(mean_fresnel_reflectance(1.0), std::invalid_argument);
}

// ---- Maps for the GPU -------------------------------------------------------------------------

TEST(EnvironmentMapStereographicMap, UniformSkyInsideBelowHorizonRadianceOutside) {
  const Rgb sky = {0.5, 1.0, 2.0};
  const EnvironmentMap map(SkyAndGround(128, 64, sky, {7.0, 7.0, 7.0}));
  const int size = 64;
  const Image image = map.stereographic_map(size);
  ASSERT_EQ(image.width, size);
  ASSERT_EQ(image.height, size);
  const double texel = 2.0 * kSkyMapExtent / size;
  int inside = 0, outside = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      double near = 1e300, far = 0.0;  // the texel corners' smallest and largest |u|
      for (int cj = 0; cj <= 1; ++cj)
        for (int ci = 0; ci <= 1; ++ci) {
          const double r =
              std::hypot(-kSkyMapExtent + texel * (i + ci), kSkyMapExtent - texel * (j + cj));
          near = std::min(near, r);
          far = std::max(far, r);
        }
      const float* p = image.pixel(i, j);
      EXPECT_EQ(p[3], 1.0f);
      for (int c = 0; c < 3; ++c) {
        if (far < 1.0) {
          ExpectRelativeNear(p[c], sky[c], 1e-6, "inside");
        } else if (near > 1.0) {
          ExpectRelativeNear(p[c], map.below_horizon_radiance()[c], 1e-6, "outside");
        } else {
          EXPECT_GE(p[c], map.below_horizon_radiance()[c] * (1.0 - 1e-6));
          EXPECT_LE(p[c], sky[c] * (1.0 + 1e-6));
        }
      }
      inside += far < 1.0;
      outside += near > 1.0;
    }
  EXPECT_GT(inside, 0);
  EXPECT_GT(outside, 0);
  EXPECT_THROW(map.stereographic_map(0), std::invalid_argument);
  EXPECT_THROW(map.stereographic_map(8, -1.0), std::invalid_argument);
}

// Row 0 is north (u_y = +extent) and column 0 west: a sky L = 2 + r_x + 0.5 r_y read at the
// texel centres, to the map's smoothing (bilinear in angle, area average).
TEST(EnvironmentMapStereographicMap, RowsAndColumnsFaceNorthAndEast) {
  const int height = 256, width = 2 * height;
  const Image image = MakeImage(width, height, [&](int x, int y) {
    const Vec3 d = Direction(kPi * (y + 0.5) / height, 2.0 * kPi * (x + 0.5) / width);
    return Rgb{2.0 + d[0] + 0.5 * d[1], 1.0, 1.0};
  });
  const EnvironmentMap map(image);
  const int size = 32;
  const double extent = 1.0;
  const Image sky_map = map.stereographic_map(size, extent);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double ux = -extent + 2.0 * extent * (i + 0.5) / size;
      const double uy = extent - 2.0 * extent * (j + 0.5) / size;
      if (std::hypot(ux, uy) > 0.95) continue;
      const Vec3 r = stereographic_direction({ux, uy});
      EXPECT_NEAR(sky_map.pixel(i, j)[0], 2.0 + r[0] + 0.5 * r[1], 0.01) << i << " " << j;
    }
}

// north_azimuth turns the sky about the zenith: with pi / 2 the map's north shows the
// photograph's east, so the turned map at u = (u_x, u_y) is the map at (u_y, -u_x), which for a
// square map is texel (i, j) of the turned map = texel (size - 1 - j, i) (the sample grid within a
// texel is symmetric under the quarter turn). A turn by a full circle changes nothing.
TEST(EnvironmentMapStereographicMap, NorthAzimuthTurnsTheSkyAboutTheZenith) {
  const int height = 64, width = 2 * height;
  const Image image = MakeImage(width, height, [&](int x, int y) {
    const Vec3 d = Direction(kPi * (y + 0.5) / height, 2.0 * kPi * (x + 0.5) / width);
    return Rgb{2.0 + d[0] + 0.5 * d[1], 1.0 + 0.3 * d[0] * d[1], 1.5 - 0.2 * d[1]};
  });
  const EnvironmentMap map(image);
  const int size = 16;
  const Image north = map.stereographic_map(size);
  const Image east = map.stereographic_map(size, kSkyMapExtent, kPi / 2.0);
  const Image around = map.stereographic_map(size, kSkyMapExtent, 2.0 * kPi);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
      for (int c = 0; c < 3; ++c) {
        ExpectRelativeNear(east.pixel(i, j)[c], north.pixel(size - 1 - j, i)[c], 1e-6, "east");
        ExpectRelativeNear(around.pixel(i, j)[c], north.pixel(i, j)[c], 1e-6, "full turn");
      }
  // The sky L_R = 2 + r_x + 0.5 r_y turned by pi / 2 reads 2 + r_y - 0.5 r_x at the map's r:
  // the map's north (+u_y) is as bright as the photograph's east. At the texel centres, to the
  // map's smoothing (as RowsAndColumnsFaceNorthAndEast).
  const Image probe = map.stereographic_map(size, 1.0, kPi / 2.0);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double ux = -1.0 + 2.0 * (i + 0.5) / size, uy = 1.0 - 2.0 * (j + 0.5) / size;
      if (std::hypot(ux, uy) > 0.95) continue;
      const Vec3 r = stereographic_direction({ux, uy});
      EXPECT_NEAR(probe.pixel(i, j)[0], 2.0 + r[1] - 0.5 * r[0], 0.01) << i << " " << j;
    }
  EXPECT_THROW(map.stereographic_map(size, kSkyMapExtent, NAN), std::invalid_argument);
}

TEST(EnvironmentMapPanorama, ReproducesThePhotographAndTurnsWithTheOffset) {
  const int height = 16, width = 2 * height;
  const Image image = MakeImage(width, height, [&](int x, int y) {
    return Rgb{1.0 + x, 1.0 + 0.5 * y, 1.0 + (x * 7 + y * 3) % 5};
  });
  EnvironmentMapOptions options;
  options.north_offset = 0.4;
  options.scale = 2.0;
  const EnvironmentMap map(image, options);
  ASSERT_FALSE(map.sun().has_value()) << map.sun_search();
  const Image same = map.panorama(width, 0.4);
  const Image turned = map.panorama(width, 0.4 + kPi / 2);  // a quarter turn: W / 4 columns
  ASSERT_EQ(same.height, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        ExpectRelativeNear(same.pixel(x, y)[c], 2.0 * image.pixel(x, y)[c], 1e-6, "same");
        ExpectRelativeNear(turned.pixel(x, y)[c], 2.0 * image.pixel((x + width / 4) % width, y)[c],
                           1e-6, "turned");
      }
  const Image half = map.panorama(width / 2, 0.4);
  EXPECT_EQ(half.width, width / 2);
  EXPECT_EQ(half.height, height / 2);
  EXPECT_THROW(map.panorama(7), std::invalid_argument);
}

// ---- Files and bad input ---------------------------------------------------------------------

class EnvironmentMapFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("thalassa_environment_map_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(EnvironmentMapFile, LoadsAnExrWithItsOffsetAndScale) {
  const int height = 8, width = 16;
  const Image image = MakeImage(width, height, [&](int x, int y) {
    return Rgb{0.25 * x, 0.5 * y, 1.0};
  });
  write_exr(path("sky.exr"), image, ExrPixelType::Float);
  EnvironmentMapOptions options;
  options.north_offset = -kPi / 2;  // the left edge looks west
  options.scale = 4.0;
  const EnvironmentMap map(path("sky.exr"), options);
  EXPECT_EQ(map.width(), width);
  EXPECT_EQ(map.height(), height);
  for (int y : {1, 3, 6})
    for (int x : {0, 5, 15}) {
      const Vec3 d = Direction(kPi * (y + 0.5) / height, -kPi / 2 + 2.0 * kPi * (x + 0.5) / width);
      const Rgb l = map.sky_radiance(d);
      EXPECT_NEAR(l[0], 4.0 * 0.25 * x, 1e-9) << x << " " << y;
      EXPECT_NEAR(l[1], 4.0 * 0.5 * y, 1e-9) << x << " " << y;
    }
  // East is a quarter of the way right of the left edge (west): column W / 2.
  EXPECT_NEAR(map.sky_radiance({1.0, 0.0, 1e-9})[0], 4.0 * 0.25 * (width / 2 - 0.5), 1e-6);
}

// Runs `make` and expects an EnvironmentMapError whose message holds every one of `parts`.
void ExpectErrorNaming(const std::function<void()>& make,
                       std::initializer_list<std::string> parts) {
  try {
    make();
    ADD_FAILURE() << "no error";
  } catch (const EnvironmentMapError& error) {
    const std::string message = error.what();
    for (const std::string& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
}

TEST_F(EnvironmentMapFile, BadInputThrowsNamingTheFileAndTheProblem) {
  const std::string missing = path("missing.exr");
  ExpectErrorNaming([&] { EnvironmentMap map(missing); }, {missing});

  const Image wide = MakeImage(16, 9, [](int, int) { return Rgb{1, 1, 1}; });
  write_exr(path("wide.exr"), wide, ExrPixelType::Float);
  ExpectErrorNaming([&] { EnvironmentMap map(path("wide.exr")); },
                    {path("wide.exr"), "16x9", "2:1"});

  ExpectErrorNaming(
      [] {
        EnvironmentMap map(MakeImage(6, 3, [](int, int) { return Rgb{1, 1, 1}; }));
      },
      {"in-memory image", "6x3", "at least 8x4"});

  Image nan_image = MakeImage(16, 8, [](int, int) { return Rgb{1, 1, 1}; });
  nan_image.pixel(3, 2)[1] = std::nanf("");
  nan_image.pixel(9, 5)[0] = INFINITY;
  ExpectErrorNaming([&] { EnvironmentMap map(nan_image, {}, "nan.exr"); },
                    {"nan.exr", "2 pixel values are not finite", "(x 3, y 2) channel G"});

  Image negative = MakeImage(16, 8, [](int, int) { return Rgb{1, 1, 1}; });
  negative.pixel(15, 7)[2] = -0.5f;
  write_exr(path("negative.exr"), negative, ExrPixelType::Float);
  ExpectErrorNaming(
      [&] { EnvironmentMap map(path("negative.exr")); },
      {path("negative.exr"), "1 pixel value is negative", "(x 15, y 7) channel B", "-0.5"});

  EnvironmentMapOptions zero_scale;
  zero_scale.scale = 0.0;
  ExpectErrorNaming(
      [&] {
        EnvironmentMap map(SkyAndGround(16, 8, {1, 1, 1}, {1, 1, 1}), zero_scale);
      },
      {"scale"});
  EnvironmentMapOptions huge_scale;  // 1 x 1e300 is a double but not a float
  huge_scale.scale = 1e300;
  ExpectErrorNaming(
      [&] {
        EnvironmentMap map(SkyAndGround(16, 8, {1, 1, 1}, {1, 1, 1}), huge_scale);
      },
      {"384 pixel values are not finite (or beyond float range once scaled)", "times scale"});
}

}  // namespace
}  // namespace thalassa::atmosphere
