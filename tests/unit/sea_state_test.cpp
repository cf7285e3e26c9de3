// SeaState (planet/sea_state.hpp): the sea's surface at a latitude and longitude on the CPU. The
// identities: a trochoid's Eulerian mean and mean square over its wavelength (-k h^2 / 2 and
// h^2 / 2, which only the inverted map gives: the particles' own heights average 0), the normal
// and the rates against finite differences of the heights, the particle carried by its velocity
// keeping its rest point, the sea's height variance against the wave set's, the calm areas' and
// the wakes' trochoids at the rest point, and the refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "thalassa/engine/scene.hpp"
#include "thalassa/ocean/kelvin_wake.hpp"
#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/ocean/wave_set.hpp"
#include "thalassa/planet/geodesy.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/planet/sea_state.hpp"
#include "thalassa/planet/ship_wake.hpp"

namespace thalassa {
namespace {

constexpr double kPi = std::numbers::pi;

Scene MakeScene(const std::vector<std::string>& sets) {
  SceneBuilder builder;
  for (const std::string& s : sets) builder.set(s);
  return builder.build();
}

// The point of the sea at rest at `xy` (m, east and north) from (lat, lon) in its tangent plane.
Geodetic Offset(const Planet& planet, double lat, double lon, glm::dvec2 xy) {
  const LocalFrame frame(planet, lat, lon, 0.0);
  const ocean::SeaSurface surface = planet_sea_surface(planet, lat, lon);
  return planet.geodetic(frame.to_ecef({xy.x, xy.y, ocean::sea_surface_sag(surface, xy)}));
}

// One trochoid: 1 wave of 20 m from the omega^-2 spectrum at 15 m/s (steepness k h = 0.08).
Scene OneWave() {
  return MakeScene({"ocean.waves=1", "ocean.lambda_min=20", "ocean.lambda_max=20",
                    "ocean.wind_speed=15", "ocean.spectrum=omega-2"});
}

TEST(SeaState, OneTrochoidsEulerianMeanAndMeanSquareOverItsWavelength) {
  const Scene scene = OneWave();
  const SeaState sea(scene);
  const ocean::WaveSet waves = ocean::make_wave_set(scene.ocean);
  ASSERT_EQ(waves.waves.size(), 1u);
  const ocean::Wave& w = waves.waves[0];
  const double kh = w.wavenumber * w.amplitude;
  ASSERT_GT(kh, 0.02);
  // Along the wave's direction in the frame of the scene's camera's nadir, one wavelength in 64
  // steps: the trapezoid rule of a smooth periodic function, exact to rounding.
  const Planet planet(scene.planet);
  const NadirFrame nadir = make_nadir_frame(planet, scene.camera, sea.wave_anchor());
  const glm::dvec2 d = ocean::chart_direction_in_frame(nadir.wave_axes, w.direction);
  constexpr int kSteps = 64;
  double mean = 0.0, square = 0.0, highest = -1e9, lowest = 1e9;
  for (int j = 0; j < kSteps; ++j) {
    const Geodetic p =
        Offset(planet, scene.camera.lat, scene.camera.lon, (w.wavelength * j / kSteps + 3.0) * d);
    const SeaPoint s = sea.at(p.lat, p.lon, 7.0);
    ASSERT_TRUE(s.converged);
    mean += s.height / kSteps;
    square += s.height * s.height / kSteps;
    highest = std::max(highest, s.height);
    lowest = std::min(lowest, s.height);
  }
  // Mean: integral of h cos(theta) (1 - k h cos(theta)) over the rest points: -k h^2 / 2; the
  // square's: h^2 / 2 (the odd power integrates to 0).
  const double h = w.amplitude;
  EXPECT_NEAR(mean, -0.5 * kh * h, 1e-9 * h) << "h " << h << " k h " << kh;
  EXPECT_NEAR(square, 0.5 * h * h, 1e-9 * h * h);
  EXPECT_LE(highest, h * (1.0 + 1e-12));
  EXPECT_GE(lowest, -h * (1.0 + 1e-12));
  EXPECT_GT(highest, 0.95 * h);
}

// The finite differences of the heights over `step` (m) east and north of (lat, lon), and of
// time over `dt` (s).
struct Differences {
  glm::dvec2 slope;
  double rate;
};
Differences Difference(const SeaState& sea, const Planet& planet, double lat, double lon,
                       double time, double step, double dt) {
  auto height = [&](glm::dvec2 xy, double t) {
    const Geodetic p = Offset(planet, lat, lon, xy);
    return sea.at(p.lat, p.lon, t).height;
  };
  Differences out;
  out.slope.x = (height({step, 0.0}, time) - height({-step, 0.0}, time)) / (2.0 * step);
  out.slope.y = (height({0.0, step}, time) - height({0.0, -step}, time)) / (2.0 * step);
  // The times as doubles hold them (at 1e9 s their step is 1.2e-7 s).
  const double later = time + dt, earlier = time - dt;
  out.rate =
      (sea.at(lat, lon, later).height - sea.at(lat, lon, earlier).height) / (later - earlier);
  return out;
}

// The most the normal's slopes and the height rate of `s` differ from the heights' differences.
double DifferencesOff(const Differences& d, const SeaPoint& s) {
  return std::max({std::abs(d.slope.x + s.normal.x / s.normal.z),
                   std::abs(d.slope.y + s.normal.y / s.normal.z),
                   std::abs(d.rate - s.height_rate)});
}

TEST(SeaState, NormalAndHeightRateAreTheHeightsDerivatives) {
  // The default sea (60 waves, 2 cm to 30 m, 10 m/s), and at 20 m/s at a long time across the
  // antimeridian, and 11 m from the north pole (the points around it cross it).
  struct Case {
    std::vector<std::string> sets;
    double time;
  };
  const std::vector<Case> cases = {
      {{}, 12.5},
      {{"ocean.wind_speed=20", "camera.lat=-62.3", "camera.lon=180"}, 1e9},
      {{"camera.lat=89.9999", "camera.lon=-40"}, 3600.0},
  };
  for (const Case& c : cases) {
    const Scene scene = MakeScene(c.sets);
    const SeaState sea(scene);
    const Planet planet(scene.planet);
    int checked = 0;
    for (double x : {-7.0, 0.0, 11.3}) {
      for (double y : {-2.1, 5.0}) {
        const Geodetic p = Offset(planet, scene.camera.lat, scene.camera.lon, {x, y});
        const SeaPoint s = sea.at(p.lat, p.lon, c.time);
        ASSERT_TRUE(s.converged) << x << " " << y;
        EXPECT_LE(s.iterations, 12);
        if (s.normal.z < 0.2) continue;  // near a fold the differences are not a slope
        // The shortest wave is 2 cm: a 10 um step's central difference is within (k step)^2 / 6
        // = 1.6e-6 of the slope; Newton (to 1e-12 m here) adds 1e-7.
        const Differences d = Difference(sea, planet, p.lat, p.lon, c.time, 1e-5, 1e-5);
        const glm::dvec2 slope(-s.normal.x / s.normal.z, -s.normal.y / s.normal.z);
        EXPECT_NEAR(d.slope.x, slope.x, 2e-4 * (1.0 + std::abs(slope.x))) << x << " " << y;
        EXPECT_NEAR(d.slope.y, slope.y, 2e-4 * (1.0 + std::abs(slope.y))) << x << " " << y;
        EXPECT_NEAR(d.rate, s.height_rate, 2e-4 * (1.0 + std::abs(s.height_rate)));
        ++checked;
      }
    }
    EXPECT_GE(checked, 4);
  }
}

// The particle at the surface, carried for dt by its velocity, is the surface's particle there
// at t + dt: the same rest point, to dt^2.
TEST(SeaState, VelocityCarriesTheParticleThatRestsThere) {
  const Scene scene = MakeScene({"ocean.wind_speed=15"});
  const SeaState sea(scene);
  const Planet planet(scene.planet);
  for (double x : {0.0, 4.0, -9.5}) {
    const Geodetic p = Offset(planet, scene.camera.lat, scene.camera.lon, {x, 1.0});
    const SeaPoint s = sea.at(p.lat, p.lon, 30.0);
    ASSERT_TRUE(s.converged);
    const LocalFrame frame(planet, p.lat, p.lon, 0.0);
    const glm::dvec3 rest = frame.to_ecef({s.rest_offset.x, s.rest_offset.y, 0.0});
    double last_error = 0.0;
    for (double dt : {1e-2, 5e-3}) {
      const Geodetic moved = Offset(planet, p.lat, p.lon, glm::dvec2(s.velocity) * dt);
      const SeaPoint later = sea.at(moved.lat, moved.lon, 30.0 + dt);
      const LocalFrame later_frame(planet, moved.lat, moved.lon, 0.0);
      const glm::dvec3 later_rest =
          later_frame.to_ecef({later.rest_offset.x, later.rest_offset.y, 0.0});
      const double error = glm::length(later_rest - rest);
      // The particle's path curves by |a| dt^2 / 2, |a| at most sum omega^2 h = 18.6 m/s^2 on
      // this sea: the rest points part by about that, a quarter as much when dt halves.
      EXPECT_LT(error, 20.0 * dt * dt) << x << " dt " << dt;
      EXPECT_NEAR(later.height, s.height + s.velocity.z * dt, 20.0 * dt * dt);
      if (last_error > 0.0) {
        EXPECT_LT(error, 0.4 * last_error + 1e-9);
      }
      last_error = error;
    }
  }
}

// A time series at one point: the height's variance is the wave set's, sum h_i^2 / 2, and its
// mean the trochoids' -sum k_i h_i^2 / 2 (the Eulerian mean: averaged over the particles it is 0).
TEST(SeaState, HeightVarianceAndMeanAreTheWaveSets) {
  const Scene scene = MakeScene({"ocean.wind_speed=7"});
  const SeaState sea(scene);
  const ocean::WaveSet waves = ocean::make_wave_set(scene.ocean);
  double variance = 0.0, mean = 0.0;
  for (const ocean::Wave& w : waves.waves) {
    variance += 0.5 * w.amplitude * w.amplitude;
    mean -= 0.5 * w.wavenumber * w.amplitude * w.amplitude;
  }
  constexpr int kSamples = 20000;
  constexpr double kStep = 0.731;  // s: no multiple of a short wave's period
  double sum = 0.0, sum_square = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const SeaPoint s = sea.at(scene.camera.lat, scene.camera.lon, 100.0 + kStep * i);
    ASSERT_TRUE(s.converged) << i;
    sum += s.height;
    sum_square += s.height * s.height;
  }
  const double measured_mean = sum / kSamples;
  const double measured_variance = sum_square / kSamples - measured_mean * measured_mean;
  // 4 hours hold about 3,400 periods of the longest wave (30 m, 4.4 s): each wave's time averages
  // are within about 1/(omega T) of their limits.
  EXPECT_NEAR(measured_variance, variance, 0.01 * variance);
  EXPECT_NEAR(measured_mean, mean, 0.03 * std::abs(mean)) << "variance " << variance;
  EXPECT_LT(measured_mean, 0.0);
}

TEST(SeaState, FootprintWeighsTheWavesAsTheGridDoes) {
  const Scene scene = MakeScene({});
  const SeaState sea(scene);
  const double lat = scene.camera.lat, lon = scene.camera.lon;
  // A footprint below a tenth of the shortest wave keeps every wave at weight 1: the same sea.
  const SeaPoint all = sea.at(lat, lon, 5.0);
  const SeaPoint tiny = sea.at(lat, lon, 5.0, 1e-4);
  EXPECT_EQ(all.height, tiny.height);
  EXPECT_EQ(all.normal, tiny.normal);
  // Longer than N_min times the longest wave: none (w = 0), the sea at rest.
  const SeaPoint none = sea.at(lat, lon, 5.0, 31.0);
  EXPECT_EQ(none.height, 0.0);
  EXPECT_EQ(none.normal, glm::dvec3(0.0, 0.0, 1.0));
  EXPECT_EQ(none.velocity, glm::dvec3(0.0));
  EXPECT_EQ(none.iterations, 0);
  // A 1 m footprint leaves the waves of 2.5 m and more whole: the short ones' slopes go, so the
  // normal's tilt falls, averaged over a stretch of sea.
  const Planet planet(scene.planet);
  double tilt_all = 0.0, tilt_filtered = 0.0;
  for (int i = 0; i < 200; ++i) {
    const Geodetic p = Offset(planet, lat, lon, {0.37 * i, 0.11 * i});
    tilt_all += 1.0 - sea.at(p.lat, p.lon, 5.0).normal.z;
    tilt_filtered += 1.0 - sea.at(p.lat, p.lon, 5.0, 1.0).normal.z;
  }
  EXPECT_LT(tilt_filtered, 0.5 * tilt_all);
}

// A calm area's scale s multiplies every wave: 0 deep inside stills the sea; in the fade, the
// normal still follows the heights (the gradient of s included).
TEST(SeaState, CalmAreasScaleTheWaves) {
  const double lat = 20.0, lon = -150.0;
  const Scene open = MakeScene({"camera.lat=20", "camera.lon=-150"});
  const auto area = [&](double scale) {
    return "calm_areas=[{\"polygon\": [{\"lat\": 19.99, \"lon\": -150.01}, "
           "{\"lat\": 19.99, \"lon\": -149.99}, {\"lat\": 20.01, \"lon\": -149.99}, "
           "{\"lat\": 20.01, \"lon\": -150.01}], \"scale\": " +
           std::to_string(scale) + ", \"fade\": 200}]";
  };
  const Scene still = MakeScene({"camera.lat=20", "camera.lon=-150", area(0.0)});
  const SeaState still_sea(still);
  const SeaPoint centre = still_sea.at(lat, lon, 9.0);
  EXPECT_EQ(centre.height, 0.0);
  EXPECT_EQ(centre.calm_scale, 0.0);
  EXPECT_EQ(centre.normal, glm::dvec3(0.0, 0.0, 1.0));
  EXPECT_EQ(centre.velocity, glm::dvec3(0.0));
  // Outside, the open sea's.
  const SeaState open_sea(open);
  const Planet planet(open.planet);
  const Geodetic outside = Offset(planet, lat, lon, {3000.0, 0.0});
  EXPECT_EQ(still_sea.at(outside.lat, outside.lon, 9.0).height,
            open_sea.at(outside.lat, outside.lon, 9.0).height);
  // In the fade (100 m inside the east edge, about 1,045 m east of the centre).
  const SeaState half_sea(MakeScene({"camera.lat=20", "camera.lon=-150", area(0.3)}));
  for (double y : {0.0, 3.7}) {
    const Geodetic p = Offset(planet, lat, lon, {945.0, y});
    const SeaPoint s = half_sea.at(p.lat, p.lon, 9.0);
    ASSERT_TRUE(s.converged);
    EXPECT_GT(s.calm_scale, 0.3);
    EXPECT_LT(s.calm_scale, 1.0);
    const Differences d = Difference(half_sea, planet, p.lat, p.lon, 9.0, 1e-5, 1e-5);
    EXPECT_NEAR(d.slope.x, -s.normal.x / s.normal.z, 2e-4);
    EXPECT_NEAR(d.slope.y, -s.normal.y / s.normal.z, 2e-4);
    EXPECT_NEAR(d.rate, s.height_rate, 2e-4);
  }
}

// A ship's wake on a calm sea: at the rest point the result names, the wake's own trochoids
// (ShipWake::sample) displace it onto the asked point, and their heights are the height; ahead of
// the ship the sea is at rest.
TEST(SeaState, WakesTrochoidsAtTheRestPoint) {
  const Scene scene =
      MakeScene({"camera.lat=20", "camera.lon=-150", "ocean.wind_speed=0",
                 "wakes=[{\"lat\": 20, \"lon\": -150, \"heading\": 30, \"speed\": 8, \"time\": 0, "
                 "\"amplitude\": 0.4}]"});
  const SeaState sea(scene);
  const Planet planet(scene.planet);
  const ShipWake wake(planet, scene.wakes[0]);
  // Astern (heading 210) 150 m and a little to port, and ahead.
  const double back = 210.0 * kPi / 180.0;
  int inside = 0;
  for (double lateral : {0.0, 12.0, 30.0}) {
    const glm::dvec2 xy = 150.0 * glm::dvec2(std::sin(back), std::cos(back)) +
                          lateral * glm::dvec2(-std::cos(back), std::sin(back));
    const Geodetic p = Offset(planet, 20.0, -150.0, xy);
    const SeaPoint s = sea.at(p.lat, p.lon, 0.0);
    ASSERT_TRUE(s.converged);
    if (s.wakes == 0) continue;
    ++inside;
    const Geodetic rest = Offset(planet, p.lat, p.lon, s.rest_offset);
    const ocean::KelvinWakeSample k = wake.sample(rest.lat, rest.lon, 0.0);
    glm::dvec3 d(0.0);
    for (const ocean::WakeWave* w : {&k.transverse, &k.divergent}) {
      if (!(w->amplitude > 0.0)) continue;
      const glm::dvec2 dir = w->wave_vector / w->wavenumber;
      d += glm::dvec3(dir * (w->amplitude * std::sin(w->argument)),
                      w->amplitude * std::cos(w->argument));
    }
    EXPECT_GT(glm::length(d), 1e-3);
    // The rest offset plus the horizontal displacement is the point (the frames of p and of the
    // rest point agree to |offset| / R).
    EXPECT_LT(glm::length(s.rest_offset + glm::dvec2(d)), 1e-7) << lateral;
    EXPECT_NEAR(s.height, d.z, 1e-7) << lateral;
  }
  EXPECT_GE(inside, 2);
  // The normal and the rates are the heights' across the wake (its branches' amplitudes and wave
  // vectors change: central differences of the wakes' displacement), to 1e-5 of slopes of 0.005
  // to 0.04 (measured 3e-7; the branches taken as plane waves are off by 1-7 % of the slope).
  double worst = 0.0;
  int compared = 0;
  for (double lateral : {5.0, 20.0, 40.0}) {
    for (double astern : {80.0, 150.0, 400.0}) {
      const glm::dvec2 xy = astern * glm::dvec2(std::sin(back), std::cos(back)) +
                            lateral * glm::dvec2(-std::cos(back), std::sin(back));
      const Geodetic p = Offset(planet, 20.0, -150.0, xy);
      const SeaPoint s = sea.at(p.lat, p.lon, 0.0);
      ASSERT_TRUE(s.converged);
      if (s.wakes == 0 || s.normal.z < 0.2) continue;
      const Differences d = Difference(sea, planet, p.lat, p.lon, 0.0 + 1.0, 1e-4, 1e-4);
      const SeaPoint later = sea.at(p.lat, p.lon, 1.0);
      const double off = DifferencesOff(d, later);
      EXPECT_LT(off, 1e-5) << astern << " " << lateral;
      worst = std::max(worst, off);
      ++compared;
    }
  }
  std::printf("wake: %d points, worst slope or rate against the heights' differences %.3g\n",
              compared, worst);
  EXPECT_GE(compared, 6);
  // A calm area stills the sea's waves, not the wakes' (ocean.vert adds them after scaling): over
  // a calm of scale 0, the wake on a 12 m/s sea is the wake on a calm sea.
  const Scene stilled = MakeScene(
      {"camera.lat=20", "camera.lon=-150", "ocean.wind_speed=12",
       "wakes=[{\"lat\": 20, \"lon\": -150, \"heading\": 30, \"speed\": 8, \"time\": 0, "
       "\"amplitude\": 0.4}]",
       "calm_areas=[{\"scale\": 0, \"fade\": 10, \"polygon\": [{\"lat\": 19.98, \"lon\": "
       "-150.02}, {\"lat\": 19.98, \"lon\": -149.98}, {\"lat\": 20.02, \"lon\": -149.98}, "
       "{\"lat\": 20.02, \"lon\": -150.02}]}]"});
  const SeaState stilled_sea(stilled);
  const glm::dvec2 wake_point = 150.0 * glm::dvec2(std::sin(back), std::cos(back)) +
                                12.0 * glm::dvec2(-std::cos(back), std::sin(back));
  const Geodetic q = Offset(planet, 20.0, -150.0, wake_point);
  const SeaPoint alone = sea.at(q.lat, q.lon, 0.0), over_calm = stilled_sea.at(q.lat, q.lon, 0.0);
  EXPECT_EQ(over_calm.calm_scale, 0.0);
  EXPECT_EQ(over_calm.wakes, 1);
  EXPECT_NEAR(over_calm.height, alone.height, 1e-9);
  EXPECT_GT(std::abs(alone.height), 1e-3);
  const Geodetic ahead = Offset(planet, 20.0, -150.0, {50.0, 90.0});
  const SeaPoint calm = sea.at(ahead.lat, ahead.lon, 0.0);
  EXPECT_EQ(calm.wakes, 0);
  EXPECT_EQ(calm.height, 0.0);
}

// A wake's rates come from its coordinates: the pattern is steady in the ship frame and a fixed
// point falls astern at the ship's speed (d/dt = U d/db). That holds on a track that turned, where
// the foot lies on a segment the ship has left or at the turn itself (the fan outside it): the
// rate and the normal against the heights' differences in time and space around a 44-degree turn
// 60 s astern, with no other waves.
TEST(SeaState, WakeRatesFollowTheShipRoundATurn) {
  const Scene scene = MakeScene(
      {"camera.lat=43.29", "camera.lon=5.36", "ocean.wind_speed=0",
       "wakes=[{\"track\": [{\"lat\": 43.280, \"lon\": 5.350, \"time\": 0}, {\"lat\": 43.290, "
       "\"lon\": 5.360, \"time\": 130}, {\"lat\": 43.292, \"lon\": 5.375, \"time\": 250}], "
       "\"amplitude\": 1.0, \"draft\": 1.0}]"});
  const SeaState sea(scene);
  const Planet planet(scene.planet);
  const double time = 190.0;
  double worst = 0.0;
  int compared = 0, searches = 0;
  for (int i = -3; i <= 3; ++i) {
    for (int j = -3; j <= 3; ++j) {
      const Geodetic p = Offset(planet, 43.29, 5.36, {31.0 * i + 3.0, 29.0 * j - 2.0});
      const SeaPoint s = sea.at(p.lat, p.lon, time);
      ASSERT_TRUE(s.converged) << i << " " << j;
      if (s.wakes == 0 || s.normal.z < 0.2) continue;
      searches += s.track_searches;
      const Differences d = Difference(sea, planet, p.lat, p.lon, time, 1e-4, 1e-4);
      const double off = DifferencesOff(d, s);
      EXPECT_LT(off, 1e-5) << i << " " << j;
      worst = std::max(worst, off);
      ++compared;
    }
  }
  std::printf(
      "turn: %d points, worst slope or rate against the heights' differences %.3g, %.2f "
      "track searches a query\n",
      compared, worst, compared ? double(searches) / compared : 0.0);
  EXPECT_GE(compared, 20);
  // A slow ship's waves are centimetres long (0.5 m/s: 0.16 m on its track, shorter across it):
  // the differences' step follows them. Measured 4.7e-5 (relative to 1 + |rate| + |slope|); a
  // 1 mm step, 6.2e-4 (3 % in the velocity at worst, stop 51's review).
  const Scene slow =
      MakeScene({"camera.lat=20", "camera.lon=-150", "ocean.wind_speed=0",
                 "wakes=[{\"lat\": 20, \"lon\": -150, \"heading\": 0, \"speed\": 0.5, \"time\": 0, "
                 "\"amplitude\": 0.3, \"draft\": 0.05}]"});
  const SeaState slow_sea(slow);
  double slow_worst = 0.0;
  int slow_compared = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = -4; j <= 4; ++j) {
      const Geodetic p = Offset(planet, 20.0, -150.0, {0.37 * j + 0.01, -0.5 - 0.83 * i});
      const SeaPoint s = slow_sea.at(p.lat, p.lon, 0.0);
      ASSERT_TRUE(s.converged) << i << " " << j;
      if (s.wakes == 0 || s.normal.z < 0.2) continue;
      const Differences d = Difference(slow_sea, planet, p.lat, p.lon, 0.0 + 1.0, 1e-5, 1e-5);
      const SeaPoint later = slow_sea.at(p.lat, p.lon, 1.0);
      const double off = DifferencesOff(d, later) / (1.0 + std::abs(later.height_rate) +
                                                     glm::length(glm::dvec2(later.normal)));
      slow_worst = std::max(slow_worst, off);
      ++slow_compared;
    }
  std::printf("slow ship: %d points, worst slope or rate against the heights' differences %.3g\n",
              slow_compared, slow_worst);
  EXPECT_GE(slow_compared, 30);
  EXPECT_LT(slow_worst, 2e-4);
}

// Newton in a wake, over 20 s of a buoy in the wake demo's sea (4 m/s, the ferry's 2 m wake; the
// buoy 60 m to port of the track): it converges to the rounding of the rest point's latitude and
// longitude, 5.63 iterations on average (measured), and iterates on the wake's coordinates
// linearised between searches of the track, 2.95 searches a query (measured). Going on below that
// rounding, where the wake's waves stand still between steps, took 8.28 iterations and 5.13
// searches; a search each iteration (no linearised rounds) 5.68 searches.
TEST(SeaState, NewtonInAWakeStopsAtTheRestPointsRounding) {
  SceneBuilder builder;
  builder.load_file(std::string(THALASSA_SOURCE_DIR) + "/data/scenes/wake_demo/wake_50m.json");
  const SeaState sea(builder.build());
  int iterations = 0, searches = 0, queries = 0;
  for (double t = 60.0; t < 80.0; t += 0.1, ++queries) {
    const SeaPoint p = sea.at(36.0035611, -19.9965414, t);
    ASSERT_TRUE(p.converged) << t;
    ASSERT_EQ(p.wakes, 1) << t;
    iterations += p.iterations;
    searches += p.track_searches;
  }
  const double mean = double(iterations) / queries;
  const double mean_searches = double(searches) / queries;
  std::printf("%d queries in a wake: %.2f iterations, %.2f track searches on average\n", queries,
              mean, mean_searches);
  EXPECT_LT(mean, 6.5);
  EXPECT_LT(mean_searches, 3.5);
}

// A host samples a hull from several threads: at() keeps no state, so one SeaState answers
// queries from 4 threads at once exactly as it answers them one after another (the wake demo's
// wake and calm area, 400 points and times each).
TEST(SeaState, ConcurrentQueriesAreTheSerialOnes) {
  SceneBuilder builder;
  builder.load_file(std::string(THALASSA_SOURCE_DIR) + "/data/scenes/wake_demo/wake_50m.json");
  const SeaState sea(builder.build());
  struct Query {
    double lat, lon, time;
  };
  std::vector<Query> queries;
  for (int i = 0; i < 400; ++i)
    queries.push_back({36.0035611 + 1e-5 * (i % 20) - 1e-4, -19.9965414 + 1e-5 * (i / 20) - 1e-4,
                       60.0 + 0.05 * i});
  const auto answer = [&](const Query& q) { return sea.at(q.lat, q.lon, q.time); };
  std::vector<SeaPoint> serial;
  for (const Query& q : queries) serial.push_back(answer(q));
  constexpr int kThreads = 4;
  const std::size_t kStrides[kThreads] = {1, 3, 7, 11};
  std::vector<std::vector<SeaPoint>> concurrent(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      // Each thread in its own order (strides prime to 400), so that they query different
      // points at the same moment.
      for (std::size_t i = 0; i < queries.size(); ++i)
        concurrent[t].push_back(answer(queries[(i * kStrides[t]) % queries.size()]));
    });
  for (std::thread& thread : threads) thread.join();
  int in_wake = 0;
  for (const SeaPoint& p : serial) in_wake += p.wakes > 0 ? 1 : 0;
  EXPECT_GT(in_wake, 100);
  for (int t = 0; t < kThreads; ++t)
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const SeaPoint& a = serial[(i * kStrides[t]) % queries.size()];
      const SeaPoint& b = concurrent[t][i];
      const bool same = a.height == b.height && a.normal == b.normal && a.velocity == b.velocity &&
                        a.height_rate == b.height_rate && a.rest_offset == b.rest_offset &&
                        a.calm_scale == b.calm_scale && a.wakes == b.wakes &&
                        a.iterations == b.iterations && a.converged == b.converged &&
                        a.searched == b.searched && a.track_searches == b.track_searches;
      ASSERT_TRUE(same) << "thread " << t << " query " << i;
    }
}

// The steepest wake the scene allows (amplitude 10 m) on a 20 m/s sea: every answer finite and
// converged; on a calm sea, every answer the wake's own rest point.
TEST(SeaState, SteepestWakeGivesFiniteAnswers) {
  const Scene scene =
      MakeScene({"camera.lat=20", "camera.lon=-150", "ocean.wind_speed=20",
                 "wakes=[{\"lat\": 20, \"lon\": -150, \"heading\": 0, \"speed\": 12, \"time\": 0, "
                 "\"amplitude\": 10, \"draft\": 0.5}]"});
  const SeaState sea(scene);
  const Planet planet(scene.planet);
  int converged = 0, total = 0, folded = 0, searched = 0;
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 20; ++j) {
      const Geodetic p = Offset(planet, 20.0, -150.0, {-60.0 + 6.1 * j, -10.0 - 12.3 * i});
      const SeaPoint s = sea.at(p.lat, p.lon, 0.0);
      ++total;
      for (double v : {s.height, s.normal.x, s.normal.y, s.normal.z, s.velocity.x, s.velocity.y,
                       s.velocity.z, s.height_rate, s.rest_offset.x, s.rest_offset.y})
        ASSERT_TRUE(std::isfinite(v)) << i << " " << j;
      EXPECT_NEAR(glm::length(s.normal), 1.0, 1e-12);
      converged += s.converged ? 1 : 0;
      folded += s.normal.z < 0.0 ? 1 : 0;
      searched += s.searched ? 1 : 0;
    }
  }
  // Every point converged: where Newton from the point stalls (2 points here, beside folds) the
  // scan of the disc that holds the rest point finds it.
  EXPECT_EQ(converged, total) << "folded " << folded;
  std::printf("steepest wake: %d of %d converged (%d after a scan), %d folded\n", converged, total,
              searched, folded);
  // On a calm sea the wake alone is the field: every answer is its rest point displaced, checked
  // with ShipWake's own waves there (one point needs the scan).
  const Scene calm =
      MakeScene({"camera.lat=20", "camera.lon=-150", "ocean.wind_speed=0",
                 "wakes=[{\"lat\": 20, \"lon\": -150, \"heading\": 0, \"speed\": 12, \"time\": 0, "
                 "\"amplitude\": 10, \"draft\": 0.5}]"});
  const SeaState wake_alone(calm);
  const ShipWake wake(planet, calm.wakes[0]);
  int calm_searched = 0;
  double worst = 0.0;
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 20; ++j) {
      const Geodetic p = Offset(planet, 20.0, -150.0, {-60.0 + 6.1 * j, -10.0 - 12.3 * i});
      const SeaPoint s = wake_alone.at(p.lat, p.lon, 0.0);
      ASSERT_TRUE(s.converged) << i << " " << j;
      calm_searched += s.searched ? 1 : 0;
      const Geodetic rest = Offset(planet, p.lat, p.lon, s.rest_offset);
      const ocean::KelvinWakeSample k = wake.sample(rest.lat, rest.lon, 0.0);
      glm::dvec3 d(0.0);
      for (const ocean::WakeWave* w : {&k.transverse, &k.divergent}) {
        if (!(w->amplitude > 0.0)) continue;
        d += glm::dvec3(w->wave_vector / w->wavenumber * (w->amplitude * std::sin(w->argument)),
                        w->amplitude * std::cos(w->argument));
      }
      worst =
          std::max({worst, glm::length(s.rest_offset + glm::dvec2(d)), std::abs(s.height - d.z)});
    }
  }
  std::printf("steepest wake on a calm sea: %d after a scan; worst |rest + D_h|, height %.3g m\n",
              calm_searched, worst);
  EXPECT_LT(worst, 1e-7);
}

TEST(SeaState, RefusesWhatIsNotAPlaceTimeOrFootprint) {
  const SeaState sea(MakeScene({}));
  const double nan = std::nan("");
  const auto message = [&](auto call) {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message([&] { sea.at(nan, 0.0); }).find("lat: expected degrees in [-90, 90]"),
            std::string::npos);
  EXPECT_NE(message([&] { sea.at(90.5, 0.0); }).find("lat"), std::string::npos);
  EXPECT_NE(message([&] { sea.at(0.0, INFINITY); }).find("lon: expected finite"),
            std::string::npos);
  EXPECT_NE(message([&] { sea.at(0.0, 0.0, -1.0); }).find("time"), std::string::npos);
  EXPECT_NE(message([&] { sea.at(0.0, 0.0, nan); }).find("time"), std::string::npos);
  EXPECT_NE(message([&] { sea.at(0.0, 0.0, 2e12); }).find("time"), std::string::npos);
  EXPECT_NE(message([&] { sea.at(0.0, 0.0, 0.0, -1.0); }).find("footprint"), std::string::npos);
  EXPECT_NE(message([&] { sea.at(0.0, 0.0, 0.0, nan); }).find("footprint"), std::string::npos);
  EXPECT_NE(message([&] {
              SeaState(MakeScene({}), Geodetic{nan, 0.0, 0.0});
            }).find("wave_anchor.lat"),
            std::string::npos);
  // Farther than 1000 km from the anchor (20 N 150 W), another chart's sea.
  EXPECT_NE(message([&] { sea.at(0.0, -150.0); }).find("within 1000 km of the waves' anchor"),
            std::string::npos);
  EXPECT_NE(message([&] { sea.at(-20.0, 30.0); }).find("within 1000 km"), std::string::npos);
  // The poles and the antimeridian are places.
  const SeaState pole(MakeScene({"camera.lat=90"}));
  const SeaState antimeridian(MakeScene({"camera.lat=0", "camera.lon=180"}));
  for (const auto& [lat, lon] : {std::pair{90.0, 0.0}, {89.99999, 180.0}, {89.99999, -90.0}}) {
    const SeaPoint s = pole.at(lat, lon, 1.0);
    EXPECT_TRUE(s.converged) << lat << " " << lon;
    EXPECT_TRUE(std::isfinite(s.height));
  }
  EXPECT_EQ(antimeridian.at(0.0, 180.0, 2.0).height, antimeridian.at(0.0, -180.0, 2.0).height);
}

// The anchor decides the chart: the default is a new Renderer's, the lattice point nearest the
// camera; the same point under another anchor has another sea.
TEST(SeaState, TheAnchorIsTheRenderersAndDecidesTheWaves) {
  const Scene scene = MakeScene({"camera.lat=20.1", "camera.lon=-150.2"});
  const SeaState sea(scene);
  EXPECT_EQ(sea.wave_anchor().lat, 20.0);
  EXPECT_EQ(sea.wave_anchor().lon, -150.25);
  const SeaState other(scene, Geodetic{20.25, -150.25, 0.0});
  EXPECT_NE(sea.at(20.1, -150.2, 3.0).height, other.at(20.1, -150.2, 3.0).height);
  const SeaState copy = sea;
  EXPECT_EQ(copy.at(20.1, -150.2, 3.0).height, sea.at(20.1, -150.2, 3.0).height);
}

}  // namespace
}  // namespace thalassa
