// A scene's wakes and calm areas placed in the camera's frame for the GPU
// (planet/local_features.hpp; issue 9, points 1, 2, 5; docs/wakes.md "On the GPU"): the chart of
// calm-area scales equals CalmArea's own values, the plane's ship frame equals ShipWake's
// geodesic one near the camera, features out of view are culled, and the s^2 rule for the
// tails is within its stated bound.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "thalassa/ocean/local_features.hpp"
#include "thalassa/planet/calm_area.hpp"
#include "thalassa/planet/local_features.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/planet/ship_wake.hpp"

namespace thalassa {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Scene SceneAt(double lat, double lon, double height) {
  Scene scene;
  scene.camera.lat = lat;
  scene.camera.lon = lon;
  scene.camera.height = height;
  return scene;
}

// A square of side `side` degrees of latitude (and the same length in longitude) around a point.
CalmAreaSettings Square(double lat, double lon, double half_deg, double scale, double fade) {
  CalmAreaSettings s;
  const double dlon = half_deg / std::cos(lat * kDegree);
  s.exterior = {{lat - half_deg, lon - dlon},
                {lat - half_deg, lon + dlon},
                {lat + half_deg, lon + dlon},
                {lat + half_deg, lon - dlon}};
  for (GeoPoint& p : s.exterior)
    if (p.lon > 180.0)
      p.lon -= 360.0;
    else if (p.lon < -180.0)
      p.lon += 360.0;
  s.scale = scale;
  s.fade = fade;
  return s;
}

// The geodetic point of the sea at rest above the frame's plane point xy (m).
Geodetic PointAt(const Planet& planet, const NadirFrame& frame, glm::dvec2 xy) {
  const LocalFrame local(planet, frame.nadir.lat, frame.nadir.lon, 0.0);
  return planet.geodetic(
      local.to_ecef({xy.x, xy.y, ocean::sea_surface_sag(frame.sea_surface, xy)}));
}

// The chart's samples (block shortcut and distance estimates included) equal the product of the
// areas' own scales at the samples' points, to within what calm_chart_distance_tolerance allows:
// two overlapping areas, one across the antimeridian, from 2 km up (a chart of 20-70 m spacing,
// held to 1.1 cm or 1.1 % of it); a 200 km area seen over its edge from 2 km, where the estimate's
// bound exceeds its tolerance near the edge and the exact distance is taken; and wide areas seen
// whole from high up (a 200 km square from 100 km, a 1000 km one from 400 km: 1-5 km spacing),
// where the tolerance is a hundredth of a sample.
TEST(LocalFeatures, CalmChartEqualsTheAreasOwnScale) {
  const Planet planet;
  struct Case {
    const char* name;
    Scene scene;
    int samples;
    bool whole;  // the areas lie wholly inside the chart: its border is s = 1
    // A guard that the chart stays as close as it is in fact, well inside its stated bound:
    // 1.8 to 2.9 times the largest error measured in stop 47 (7.0e-5, 1.1e-4, 3.5e-3, 3.9e-2;
    // 2e-4 was the test's bound before the tolerance followed the spacing).
    double measured = 0.0;
  };
  std::vector<Case> cases;
  for (const double lon : {10.0, 179.99, -60.0}) {
    const bool wide = lon == -60.0;
    Scene scene = SceneAt(wide ? 42.1 : 43.0, lon, 2000.0);
    scene.camera.heading = 0.0;  // north, down on both areas, the whole of them in the image
    scene.camera.pitch = -60.0;
    scene.camera.fov_y = 90.0;
    scene.calm_areas = {Square(43.01, lon, wide ? 0.9 : 0.01, 0.2, 300.0),
                        Square(43.018, lon + 0.008, 0.006, 0.5, 100.0)};
    cases.push_back({wide                      ? "200 km area over its edge from 2 km"
                     : lon > 0.0 && lon < 90.0 ? "overlapping areas from 2 km at 10 E"
                                               : "overlapping areas from 2 km across 180",
                     scene, 128, !wide, 2e-4});
  }
  for (const auto& [half_deg, height] : {std::pair{0.9, 1e5}, {4.5, 4e5}}) {
    // Looking north 30 degrees down from over the southern edge, as planet_bench's squares.
    Scene scene = SceneAt(45.0 - half_deg, 10.0, height);
    scene.image.width = 1024;
    scene.image.height = 576;
    scene.camera.heading = 3.0;
    scene.camera.pitch = -30.0;
    scene.calm_areas = {Square(45.0, 10.0, half_deg, 0.2, 150.0)};
    cases.push_back({half_deg < 1.0 ? "200 km square from 100 km" : "1000 km square from 400 km",
                     scene, kCalmChartSamples, false, half_deg < 1.0 ? 1e-2 : 0.1});
  }
  for (const Case& c : cases) {
    const Scene& scene = c.scene;
    const NadirFrame frame = make_nadir_frame(planet, scene.camera);
    const auto start = std::chrono::steady_clock::now();
    const ocean::LocalFeatures features = place_local_features(planet, scene, frame, c.samples);
    std::printf("%s: chart built in %.0f ms (not asserted)\n", c.name,
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count());
    ASSERT_TRUE(features.calm.has_value()) << c.name;
    const ocean::CalmScaleChart& chart = *features.calm;
    EXPECT_EQ(chart.areas, int(scene.calm_areas.size()));
    EXPECT_LE(std::max(chart.width, chart.height), c.samples + 8);
    std::vector<CalmArea> areas;
    for (const CalmAreaSettings& s : scene.calm_areas) areas.emplace_back(planet, s);
    // The smoothstep's slope is at most 1.5 / fade: a distance off by the tolerance moves each
    // area's factor by 1.5 |1 - scale| tolerance / fade, and the product by their sum (each
    // factor <= 1); plus the float texture's rounding.
    const double tolerance = calm_chart_distance_tolerance(chart.spacing);
    double bound = 1e-6;
    for (const CalmAreaSettings& s : scene.calm_areas)
      bound += 1.5 * (1.0 - s.scale) * tolerance / s.fade;
    double worst = 0.0;
    int inside = 0, fading = 0;
    for (int j = 0; j < chart.height; j += 2)
      for (int i = 1; i < chart.width; i += 2) {
        const Geodetic g = PointAt(planet, frame, chart.origin + chart.spacing * glm::dvec2(i, j));
        const double expected = calm_amplitude_scale(areas, g.lat, g.lon);
        worst = std::max(worst, std::abs(chart.scale[std::size_t(j) * chart.width + i] - expected));
        inside += expected < 1.0;
        fading += expected < 1.0 && expected > 0.5;
      }
    std::printf("  spacing %.1f m, tolerance %.3f m: worst %.2e, bound %.2e, %d samples fading\n",
                chart.spacing, tolerance, worst, bound, fading);
    EXPECT_LE(worst, bound) << c.name;
    if (c.measured > 0.0) {
      EXPECT_LE(worst, c.measured) << c.name;
    }
    EXPECT_GT(inside, 100) << c.name;
    if (!c.whole) {
      // The area fills the image beyond its edge: the chart holds both sides of the edge.
      EXPECT_EQ(*std::min_element(chart.scale.begin(), chart.scale.end()), 0.2f) << c.name;
      EXPECT_EQ(*std::max_element(chart.scale.begin(), chart.scale.end()), 1.0f) << c.name;
      continue;
    }
    // The border is outside every area, so s = 1 beyond the chart.
    for (int i = 0; i < chart.width; ++i) {
      EXPECT_EQ(chart.scale[i], 1.0f);
      EXPECT_EQ(chart.scale[std::size_t(chart.height - 1) * chart.width + i], 1.0f);
    }
  }
}

// The tolerance: 1.1 cm up to a 1 m spacing, then 1.1 % of the spacing.
TEST(LocalFeatures, CalmChartToleranceFollowsTheSpacingBeyondAMetre) {
  EXPECT_DOUBLE_EQ(calm_chart_distance_tolerance(0.01), 0.011);
  EXPECT_DOUBLE_EQ(calm_chart_distance_tolerance(1.0), 0.011);
  EXPECT_DOUBLE_EQ(calm_chart_distance_tolerance(1000.0), 11.0);
}

// The wake's past track laid in the camera's plane gives the same ship frame as ShipWake's
// geodesic track-following coordinates near the camera, and so the same waves: a straight wake
// (position form) and a track with a 30-degree turn 1 km astern, at 43 N across the
// antimeridian and at 89.9 N. Over the points whose foot is not within kTie of a tie between two
// pieces (where both searches may pick either side of the nearest-point jump of docs/wakes.md).
TEST(LocalFeatures, WakeInThePlaneMatchesTheGeodesicShipFrame) {
  const Planet planet;
  constexpr double kTie = 1.0;  // m
  for (const double lat : {43.0, 89.9})
    for (const bool turn : {false, true}) {
      Scene scene = SceneAt(lat, 179.995, 50.0);
      WakeSettings wake;
      wake.speed = 8.0;
      wake.length = 4000.0;
      if (turn) {
        // South-west, then due south: the ship 1.33 km south of the camera at t = 280 s.
        const double dlon = 0.009 / std::cos(lat * kDegree);
        auto wrap = [](double lon) { return lon > 180.0 ? lon - 360.0 : lon; };
        wake.track = {{lat + 0.0, wrap(179.995 + 2.0 * dlon), 0.0},
                      {lat - 0.003, wrap(179.995 + dlon - 1e-4), 150.0},
                      {lat - 0.015, wrap(179.995 - 1e-4), 300.0}};
        scene.time = 280.0;
      } else {
        wake.lat = lat - 0.012;
        wake.lon = 179.995;
        wake.heading = 200.0;
        wake.speed = 8.0;
      }
      scene.wakes = {wake};
      const NadirFrame frame = make_nadir_frame(planet, scene.camera);
      const ocean::LocalFeatures features = place_local_features(planet, scene, frame);
      ASSERT_EQ(features.wakes.size(), 1u);
      const ocean::WakeInFrame& placed = features.wakes[0];
      const ShipWake reference(planet, wake);
      double worst_b = 0.0, worst_y = 0.0, worst_height = 0.0;
      int compared = 0, disagree = 0;
      for (double x = -1500.0; x <= 1500.0; x += 50.0)
        for (double y = -1500.0; y <= 1500.0; y += 50.0) {
          const Geodetic g = PointAt(planet, frame, {x, y});
          const auto c = reference.coordinates(g.lat, g.lon, scene.time);
          const ocean::WakeFrameCoordinates f = ocean::wake_frame_coordinates(placed, {x, y});
          if (c.has_value() != f.present) {
            ++disagree;
            continue;
          }
          if (!c) continue;
          if (std::abs(c->behind - f.behind) > kTie && turn) continue;  // across the jump
          worst_b = std::max(worst_b, std::abs(f.behind - c->behind));
          worst_y = std::max(worst_y, std::abs(f.lateral - c->lateral));
          const double plane =
              ocean::kelvin_wake_at(placed.params, f.behind, f.lateral).linear_height();
          worst_height = std::max(
              worst_height,
              std::abs(plane - reference.sample(g.lat, g.lon, scene.time).linear_height()));
          ++compared;
        }
      std::printf(
          "lat %.1f%s: %d points, %d disagree on presence, |b - b_geodesic| %.2g m, "
          "|y - y_geodesic| %.2g m, height %.2g m\n",
          lat, turn ? " (turn)" : "", compared, disagree, worst_b, worst_y, worst_height);
      EXPECT_GT(compared, 200);
      EXPECT_LE(disagree, compared / 200);  // only at the wake's edges, to the tolerance
      EXPECT_LE(worst_b, 0.01);
      EXPECT_LE(worst_y, 0.01);
      EXPECT_LE(worst_height, 0.003 * wake.amplitude);
    }
}

// Culling (issue 9, point 5): a wake and a calm area 1000 km away are not placed from 2 km, nor
// from 400 km where the image does not see them; a scene with none places nothing; the
// footprint of a camera under the sea is empty.
TEST(LocalFeatures, FeaturesOutOfViewAreCulled) {
  const Planet planet;
  Scene scene = SceneAt(10.0, 20.0, 2000.0);
  WakeSettings wake;
  wake.lat = 19.0;
  wake.lon = 20.0;
  wake.speed = 10.0;
  scene.wakes = {wake};
  scene.calm_areas = {Square(10.0, 30.0, 0.1, 0.0, 100.0)};
  scene.camera.pitch = -90.0;
  const NadirFrame frame = make_nadir_frame(planet, scene.camera);
  EXPECT_TRUE(place_local_features(planet, scene, frame).empty());
  EXPECT_TRUE(place_local_features(planet, SceneAt(10.0, 20.0, 2000.0), frame).empty());
  // From 400 km the horizon is 2300 km away: both are in view of a camera looking down with a
  // wide lens, and neither of one looking south along the horizon.
  Scene high = scene;
  high.camera.height = 400000.0;
  high.camera.pitch = -5.0;
  high.camera.heading = 180.0;
  EXPECT_TRUE(place_local_features(planet, high, make_nadir_frame(planet, high.camera)).empty());
  high.camera.pitch = -90.0;
  high.camera.fov_y = 170.0;
  const ocean::LocalFeatures seen =
      place_local_features(planet, high, make_nadir_frame(planet, high.camera));
  EXPECT_EQ(seen.wakes.size(), 1u);
  EXPECT_TRUE(seen.calm.has_value());
  Scene under = scene;
  under.camera.height = -5.0;
  EXPECT_TRUE(view_footprint(planet, make_nadir_frame(planet, under.camera)).empty());
}

// The tails' s^2 rule (docs/wakes.md): for one trochoid of steepness x, s^2 (1 - sqrt(1 - x^2))
// over the exact 1 - sqrt(1 - (s x)^2) is in [1, calm_tail_variance_bound(x)], and the bound is
// 1.072 at the steepness clamp.
TEST(LocalFeatures, TailVarianceScaledBySquareIsWithinItsBound) {
  auto v = [](double x) { return x * x / (1.0 + std::sqrt(1.0 - x * x)); };
  for (double x : {0.01, 0.1, 0.36, 0.5})
    for (double s : {0.0001, 0.1, 0.5, 0.9, 1.0}) {
      const double ratio = s * s * v(x) / v(s * x);
      EXPECT_GE(ratio, 1.0 - 1e-12);
      EXPECT_LE(ratio, ocean::calm_tail_variance_bound(x) * (1.0 + 1e-12));
    }
  EXPECT_NEAR(ocean::calm_tail_variance_bound(0.5), 1.0718, 1e-4);
  EXPECT_NEAR(ocean::calm_tail_variance_bound(0.36), 1.0347, 1e-4);
}

}  // namespace
}  // namespace thalassa
