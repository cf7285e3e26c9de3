// Tests of scripted flights: the monotone cubic (C1, exact at the keys, no overshoot), the
// channels (log-height pacing, never below the sea, headings and longitudes the short way round,
// latitude clamped, UTC times), the scene of each frame, every class of bad flight file, and
// that the embedded default flight is data/flights/orbit_to_surface.json.
#include "thalassa/planet/flight.hpp"

#include <gtest/gtest.h>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

#include <unistd.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#ifndef THALASSA_SOURCE_DIR
#define THALASSA_SOURCE_DIR ""
#endif

namespace thalassa {
namespace {

using json = nlohmann::json;

// The message of the SceneError that `f` throws; fails the test when it throws nothing.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
    return msg;
  }
  ADD_FAILURE() << "no SceneError";
  return {};
}

std::string flight_error(const std::string& text) {
  return error_of([&] { Flight::parse(text, "f.json"); });
}

// A flight of the given keyframes (JSON array text) and extra top-level members.
std::string flight_text(const std::string& keyframes, const std::string& extra = "") {
  return "{" + extra + (extra.empty() ? "" : ", ") + "\"keyframes\": " + keyframes + "}";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// --- the monotone cubic ----------------------------------------------------------------------

TEST(MonotoneCubic, ExactAtTheKeysAndConstantOutside) {
  const std::vector<double> t = {0.0, 1.0, 2.5, 4.0, 7.0};
  const std::vector<double> v = {3.0, -1.0, 2.0, 2.0, 10.0};
  const MonotoneCubic f(t, v);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_EQ(f(t[i]), v[i]) << i;
  EXPECT_EQ(f(-5.0), 3.0);
  EXPECT_EQ(f(100.0), 10.0);
  EXPECT_EQ(f.derivative(-5.0), 0.0);
  EXPECT_EQ(MonotoneCubic({1.0}, {4.0})(0.0), 4.0);
  EXPECT_EQ(MonotoneCubic({1.0}, {4.0})(9.0), 4.0);
}

TEST(MonotoneCubic, TwoKeysGiveTheStraightLine) {
  const MonotoneCubic f({2.0, 6.0}, {1.0, 9.0});
  for (double t = 2.0; t <= 6.0; t += 0.125) EXPECT_NEAR(f(t), 1.0 + 2.0 * (t - 2.0), 1e-12);
}

TEST(MonotoneCubic, IsC1AtEveryKey) {
  // Uneven times, a local extremum, a flat step: the one-sided difference quotients on both
  // sides of each inner key agree with each other and with derivative() to O(eps).
  const std::vector<double> t = {0.0, 0.7, 2.0, 2.3, 5.0, 6.0};
  const std::vector<double> v = {0.0, 4.0, 1.0, 1.0, 8.0, 8.5};
  const MonotoneCubic f(t, v);
  constexpr double kStep = 1e-6;
  for (std::size_t i = 1; i + 1 < t.size(); ++i) {
    const double left = (f(t[i]) - f(t[i] - kStep)) / kStep;
    const double right = (f(t[i] + kStep) - f(t[i])) / kStep;
    EXPECT_NEAR(left, right, 1e-4 * (1.0 + std::fabs(left))) << "key " << i;
    EXPECT_NEAR(f.derivative(t[i]), right, 1e-4 * (1.0 + std::fabs(right))) << "key " << i;
    // Value continuity too.
    EXPECT_NEAR(f(t[i] - 1e-12), v[i], 1e-9);
  }
  // derivative() is itself continuous: no jump larger than the step's worth anywhere.
  double previous = f.derivative(0.0);
  for (double x = 1e-3; x <= 6.0; x += 1e-3) {
    const double d = f.derivative(x);
    EXPECT_LT(std::fabs(d - previous), 0.2) << "t = " << x;
    previous = d;
  }
}

TEST(MonotoneCubic, NeverLeavesTheRangeOfItsTwoNeighbouringKeys) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> step(0.05, 3.0), value(-100.0, 100.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> t = {0.0}, v = {value(rng)};
    const int n = 2 + trial % 9;
    for (int i = 1; i < n; ++i) {
      t.push_back(t.back() + step(rng));
      // Monotone runs and flat steps as well as random jumps.
      v.push_back(trial % 3 == 0            ? v.back() + std::fabs(value(rng))
                  : trial % 3 == 1 && i % 2 ? v.back()
                                            : value(rng));
    }
    const MonotoneCubic f(t, v);
    for (int i = 0; i + 1 < n; ++i) {
      const double lo = std::min(v[i], v[i + 1]), hi = std::max(v[i], v[i + 1]);
      double previous = v[i];
      for (int j = 1; j <= 64; ++j) {
        const double x = t[i] + (t[i + 1] - t[i]) * j / 64.0;
        const double y = f(x);
        ASSERT_GE(y, lo) << "trial " << trial << " piece " << i;
        ASSERT_LE(y, hi) << "trial " << trial << " piece " << i;
        // Monotone on each piece, in the direction of its keys.
        if (v[i + 1] >= v[i])
          ASSERT_GE(y, previous - 1e-12);
        else
          ASSERT_LE(y, previous + 1e-12);
        previous = y;
      }
    }
  }
}

TEST(MonotoneCubic, FlatEndsEaseInAndOut) {
  const MonotoneCubic natural({0.0, 1.0}, {0.0, 1.0});
  const MonotoneCubic flat({0.0, 1.0}, {0.0, 1.0}, MonotoneCubic::End::Flat,
                           MonotoneCubic::End::Flat);
  EXPECT_DOUBLE_EQ(natural.derivative(0.0), 1.0);
  EXPECT_EQ(flat.derivative(0.0), 0.0);
  EXPECT_EQ(flat.derivative(1.0), 0.0);
  EXPECT_NEAR(flat(0.5), 0.5, 1e-12);  // smoothstep: symmetric
  const MonotoneCubic three({0.0, 1.0, 3.0}, {0.0, 2.0, 3.0}, MonotoneCubic::End::Natural,
                            MonotoneCubic::End::Flat);
  EXPECT_GT(three.derivative(0.0), 0.0);
  EXPECT_EQ(three.derivative(3.0), 0.0);
  for (double t = 0.0; t <= 3.0; t += 0.01) {
    EXPECT_GE(three(t), 0.0);
    EXPECT_LE(three(t), 3.0);
  }
}

TEST(MonotoneCubic, RefusesBadKeys) {
  EXPECT_THROW(MonotoneCubic({}, {}), std::invalid_argument);
  EXPECT_THROW(MonotoneCubic({0.0, 1.0}, {1.0}), std::invalid_argument);
  EXPECT_THROW(MonotoneCubic({0.0, 0.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(MonotoneCubic({1.0, 0.0}, {1.0, 2.0}), std::invalid_argument);
}

// --- channels ---------------------------------------------------------------------------------

TEST(Flight, DescentSpendsEqualTimesOnEqualLogHeightsAndNeverDipsBelowTheSea) {
  const Flight f = Flight::parse(flight_text(R"([{"time": 0, "camera": {"height": 400000}},
                      {"time": 20, "camera": {"height": 2}}])"),
                                 "f.json");
  // Dense samples: never below the lowest key, never below the sea, never above the highest.
  for (int i = 0; i <= 20000; ++i) {
    const double h = *f.sample(20.0 * i / 20000.0).height;
    ASSERT_GE(h, 2.0) << i;
    ASSERT_GE(h, 0.0);
    ASSERT_LE(h, 400000.0);
  }
  // Equal time steps cover equal steps of log(height + h0) (2 keys: the straight line there).
  constexpr int kSteps = 20;
  const double total =
      std::log(400000.0 + kFlightHeightOffset) - std::log(2.0 + kFlightHeightOffset);
  for (int i = 0; i < kSteps; ++i) {
    const double a = *f.sample(20.0 * i / kSteps).height;
    const double b = *f.sample(20.0 * (i + 1) / kSteps).height;
    const double step = std::log(a + kFlightHeightOffset) - std::log(b + kFlightHeightOffset);
    EXPECT_NEAR(step, total / kSteps, 1e-3 * total / kSteps) << "step " << i;
  }
  // Half way down in time is the geometric mean of the heights (+ h0), about 1 km, not 200 km.
  EXPECT_NEAR(*f.sample(10.0).height + kFlightHeightOffset,
              std::sqrt((400000.0 + kFlightHeightOffset) * (2.0 + kFlightHeightOffset)), 1e-6);
}

TEST(Flight, HeightsStayBetweenNeighbouringKeysAndAtOrAboveTheSea) {
  const Flight f = Flight::parse(
      flight_text(R"([{"time": 0, "camera": {"height": 1000}}, {"time": 1, "camera": {"height": 2}},
                      {"time": 3, "camera": {"height": 500}}, {"time": 4, "camera": {"height": 0}},
                      {"time": 4.5, "camera": {"height": 300}}])"),
      "f.json");
  const std::vector<double> t = {0, 1, 3, 4, 4.5}, h = {1000, 2, 500, 0, 300};
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    for (int j = 0; j <= 1000; ++j) {
      const double height = *f.sample(t[k] + (t[k + 1] - t[k]) * j / 1000.0).height;
      ASSERT_GE(height, std::min(h[k], h[k + 1]));
      ASSERT_LE(height, std::max(h[k], h[k + 1]));
      ASSERT_GE(height, 0.0);
    }
  }
}

TEST(Flight, ChannelsAreC1AtInnerKeyframes) {
  const Flight f = Flight::parse(
      flight_text(R"([{"time": 0, "camera": {"height": 100000, "pitch": -90, "heading": 10}},
                      {"time": 4, "camera": {"height": 3000, "pitch": -50, "heading": 350}},
                      {"time": 9, "camera": {"height": 20, "pitch": -5, "heading": 300}}])"),
      "f.json");
  constexpr double kStep = 1e-5;  // s
  const auto log_height = [&](double t) {
    return std::log(*f.sample(t).height + kFlightHeightOffset);
  };
  const auto pitch = [&](double t) { return *f.sample(t).pitch; };
  // Heading unwrapped around the key at 350 (no wrap happens within kStep of it).
  const auto heading = [&](double t) { return *f.sample(t).heading; };
  for (const auto& channel :
       {std::function<double(double)>(log_height), std::function<double(double)>(pitch),
        std::function<double(double)>(heading)}) {
    const double t = 4.0;
    const double left = (channel(t) - channel(t - kStep)) / kStep;
    const double right = (channel(t + kStep) - channel(t)) / kStep;
    EXPECT_NEAR(left, right, 1e-3 * (1.0 + std::fabs(left)));
  }
}

TEST(Flight, ChannelsHeldWithinTheFlightStayC1WhereTheHoldBegins) {
  // Pitch has keys at 1 and 3 s in a flight of 0 to 4 s: held before 1 s and after 3 s, it eases
  // in and out there; height, keyed at the flight's ends, keeps its pace (the straight line in
  // log height).
  const Flight f = Flight::parse(flight_text(R"([{"time": 0, "camera": {"height": 1000}},
                      {"time": 1, "camera": {"pitch": -80}},
                      {"time": 3, "camera": {"pitch": -10}},
                      {"time": 4, "camera": {"height": 10}}])"),
                                 "f.json");
  constexpr double kStep = 1e-5;  // s
  const auto pitch = [&](double t) { return *f.sample(t).pitch; };
  for (double key : {1.0, 3.0}) {
    const double left = (pitch(key) - pitch(key - kStep)) / kStep;
    const double right = (pitch(key + kStep) - pitch(key)) / kStep;
    EXPECT_NEAR(left, 0.0, 1e-3) << key;
    EXPECT_NEAR(right, 0.0, 1e-3) << key;
  }
  const auto log_height = [&](double t) {
    return std::log(*f.sample(t).height + kFlightHeightOffset);
  };
  const double pace = (log_height(4.0) - log_height(0.0)) / 4.0;
  EXPECT_NEAR((log_height(kStep) - log_height(0.0)) / kStep, pace, 1e-6);
  EXPECT_NEAR(log_height(2.0), 0.5 * (log_height(0.0) + log_height(4.0)), 1e-9);
}

TEST(Flight, ExactValuesAtKeyframeTimes) {
  const Flight f = Flight::parse(
      flight_text(R"([{"time": 0, "camera": {"lat": 10.25, "lon": 179.5, "height": 400000,
                                              "heading": -90, "pitch": -90, "roll": 5,
                                              "fov_y": 60},
                       "sun": {"zenith": 88, "azimuth": 271}},
                      {"time": 1.5, "camera": {"lat": -3, "lon": -179.25, "height": 2.5,
                                                "heading": 359.5, "pitch": 12.5, "roll": -170,
                                                "fov_y": 30.5},
                       "sun": {"zenith": 91.5, "azimuth": -1}},
                      {"time": 2, "camera": {"height": 0}}])"),
      "f.json");
  FlightValues a = f.sample(0.0);
  EXPECT_EQ(*a.lat, 10.25);
  EXPECT_EQ(*a.lon, 179.5);
  EXPECT_EQ(*a.height, 400000.0);
  EXPECT_EQ(*a.heading, 270.0);  // -90 wrapped into [0, 360)
  EXPECT_EQ(*a.pitch, -90.0);
  EXPECT_EQ(*a.roll, 5.0);
  EXPECT_EQ(*a.fov_y, 60.0);
  EXPECT_EQ(*a.sun_zenith, 88.0);
  EXPECT_EQ(*a.sun_azimuth, 271.0);
  FlightValues b = f.sample(1.5);
  EXPECT_EQ(*b.lat, -3.0);
  EXPECT_EQ(*b.lon, -179.25);
  EXPECT_EQ(*b.height, 2.5);
  EXPECT_EQ(*b.heading, 359.5);
  EXPECT_EQ(*b.pitch, 12.5);
  EXPECT_EQ(*b.roll, -170.0);
  EXPECT_EQ(*b.fov_y, 30.5);
  EXPECT_EQ(*b.sun_zenith, 91.5);
  EXPECT_EQ(*b.sun_azimuth, 359.0);
  EXPECT_EQ(*f.sample(2.0).height, 0.0);
  EXPECT_FALSE(f.sample(1.0).sun_utc);
  // The scene of a keyframe's time carries the same values.
  const Scene s = f.scene_at(1.5);
  EXPECT_EQ(s.camera.height, 2.5);
  EXPECT_EQ(s.camera.lon, -179.25);
  EXPECT_EQ(s.sun.zenith, 91.5);
}

TEST(Flight, HeadingsAndLongitudesGoTheShortWayRound) {
  const Flight f = Flight::parse(
      flight_text(R"([{"time": 0, "camera": {"heading": 350, "lon": 179}, "sun": {"azimuth": 5}},
                      {"time": 1, "camera": {"heading": 10, "lon": -179}, "sun": {"azimuth": 355}}])"),
      "f.json");
  for (int i = 0; i <= 1000; ++i) {
    const FlightValues v = f.sample(i / 1000.0);
    // 350 -> 10 through north: never the 340 degrees through south.
    ASSERT_TRUE(*v.heading >= 350.0 || *v.heading <= 10.0) << *v.heading;
    ASSERT_GE(*v.heading, 0.0);
    ASSERT_LT(*v.heading, 360.0);
    // 179 -> -179 across the antimeridian: never through 0.
    ASSERT_GE(std::fabs(*v.lon), 179.0 - 1e-9) << *v.lon;
    ASSERT_LE(*v.lon, 180.0);
    ASSERT_GT(*v.lon, -180.0);
    ASSERT_TRUE(*v.sun_azimuth >= 355.0 || *v.sun_azimuth <= 5.0) << *v.sun_azimuth;
  }
  EXPECT_NEAR(f.sample(0.5).heading.value_or(-1), 0.0, 1e-9);
  EXPECT_NEAR(f.sample(0.5).lon.value_or(0), 180.0, 1e-9);  // (-180, 180]: 180, not -180
  EXPECT_NEAR(*f.sample(0.25).heading, 355.0, 1e-9);
  // The scene accepts every sample (heading in [0, 360), longitude in (-180, 180]).
  for (int i = 0; i <= 40; ++i) EXPECT_NO_THROW(f.scene_at(i / 40.0));
  // Exactly 180 degrees apart turns clockwise (increasing).
  const Flight half = Flight::parse(
      flight_text(
          R"([{"time": 0, "camera": {"heading": 90}}, {"time": 1, "camera": {"heading": 270}}])"),
      "f.json");
  EXPECT_NEAR(*half.sample(0.5).heading, 180.0, 1e-9);
  const Flight back = Flight::parse(
      flight_text(
          R"([{"time": 0, "camera": {"heading": 270}}, {"time": 1, "camera": {"heading": 90}}])"),
      "f.json");
  EXPECT_NEAR(*back.sample(0.5).heading, 0.0, 1e-9);
}

TEST(Flight, LatitudeStaysWithinThePoles) {
  const Flight f = Flight::parse(
      flight_text(R"([{"time": 0, "camera": {"lat": 85}}, {"time": 1, "camera": {"lat": 90}},
                      {"time": 2, "camera": {"lat": 89}}, {"time": 3, "camera": {"lat": -90}}])"),
      "f.json");
  for (int i = 0; i <= 3000; ++i) {
    const double lat = *f.sample(i / 1000.0).lat;
    ASSERT_LE(lat, 90.0);
    ASSERT_GE(lat, -90.0);
  }
}

TEST(Flight, ChannelsAreHeldOutsideTheirKeysAndUnanimatedOnesComeFromTheBaseScene) {
  const Flight f = Flight::parse(
      flight_text(R"([{"time": 0, "camera": {"height": 100}}, {"time": 2, "camera": {"pitch": -10}},
                      {"time": 4, "camera": {"height": 10, "pitch": 0}}])",
                  R"("scene": {"camera": {"lat": 45, "pitch": -30}, "time": 100}, "fps": 2)"),
      "f.json");
  EXPECT_EQ(f.frame_count(), 9);  // 0, 0.5, ..., 4 s
  EXPECT_EQ(f.animated_keys(), (std::vector<std::string>{"camera.height", "camera.pitch"}));
  const FlightValues v = f.sample(1.0);
  EXPECT_FALSE(v.lat);
  EXPECT_EQ(*v.pitch, -10.0);        // before pitch's first key at 2 s
  const Scene s = f.frame_scene(2);  // t = 1 s
  EXPECT_EQ(s.camera.lat, 45.0);
  EXPECT_EQ(s.camera.pitch, -10.0);
  EXPECT_EQ(s.time, 101.0);  // the base scene's time + t: the waves move with the flight
  EXPECT_EQ(f.frame_scene(8).camera.height, 10.0);
  EXPECT_EQ(f.scene_at(50.0).camera.height, 10.0);
}

TEST(Flight, FrameCountFromDurationOrFrames) {
  const std::string keys = R"([{"time": 0}, {"time": 20}])";
  EXPECT_EQ(Flight::parse(flight_text(keys, R"("fps": 24, "duration": 20)"), "f").frame_count(),
            481);
  EXPECT_EQ(Flight::parse(flight_text(keys, R"("fps": 24)"), "f").frame_count(), 481);
  EXPECT_EQ(Flight::parse(flight_text(keys, R"("fps": 30, "duration": 0.1)"), "f").frame_count(),
            4);
  EXPECT_EQ(Flight::parse(flight_text(keys, R"("frames": 5)"), "f").frame_count(), 5);
  EXPECT_EQ(Flight::parse(flight_text(R"([{"time": 0}])"), "f").frame_count(), 1);
  const Flight f = Flight::parse(flight_text(keys, R"("fps": 24)"), "f");
  EXPECT_DOUBLE_EQ(f.frame_time(480), 20.0);
}

// `fly --fps`: another frame rate keeps the flight's length and its path. The default flight at
// 60 fps has 1201 frames over its 20 s, and its frames at the same times are the 24-fps ones to
// the bit; a flight given by `frames` keeps (frames - 1) / fps; bad rates change nothing.
TEST(Flight, SetFpsKeepsTheLengthAndThePath) {
  Flight f = Flight::default_flight();
  const Flight at24 = Flight::default_flight();
  f.set_fps(60.0);
  EXPECT_EQ(f.frame_count(), 1201);
  EXPECT_DOUBLE_EQ(f.frame_time(1200), 20.0);
  for (const auto& [frame60, frame24] : {std::pair{0, 0}, {150, 60}, {600, 240}, {1200, 480}}) {
    const Scene a = f.frame_scene(frame60), b = at24.frame_scene(frame24);
    EXPECT_EQ(a.camera.height, b.camera.height) << frame60;
    EXPECT_EQ(a.camera.pitch, b.camera.pitch) << frame60;
    EXPECT_EQ(a.time, b.time) << frame60;
  }
  f.set_fps(2.5);
  EXPECT_EQ(f.frame_count(), 51);
  Flight counted = Flight::parse(
      flight_text(R"([{"time": 0}, {"time": 1}])", R"("fps": 10, "frames": 11)"), "f");
  counted.set_fps(20.0);
  EXPECT_EQ(counted.frame_count(), 21);
  EXPECT_DOUBLE_EQ(counted.frame_time(20), 1.0);
  for (const double bad : {0.0, -24.0, 1001.0, double(NAN), double(INFINITY)}) {
    const std::string message = error_of([&] { counted.set_fps(bad); });
    EXPECT_NE(message.find("--fps: expected a number in (0, 1000]"), std::string::npos) << message;
  }
  Flight long_flight =
      Flight::parse(flight_text(R"([{"time": 0}, {"time": 100000}])", R"("fps": 1)"), "f");
  EXPECT_NE(error_of([&] { long_flight.set_fps(1000.0); }).find("at most 10000000 frames"),
            std::string::npos);
  EXPECT_EQ(counted.frame_count(), 21);
  EXPECT_EQ(counted.fps(), 20.0);
  EXPECT_EQ(long_flight.frame_count(), 100001);
}

TEST(Flight, UtcTimesAreInterpolatedLinearlyAndPlaceTheSun) {
  const Flight f =
      Flight::parse(flight_text(R"([{"time": 0, "sun": {"utc": "2026-06-21T18:00:00Z"}},
                      {"time": 10, "sun": {"utc": "2026-06-21T19:00:00Z"}}])",
                                R"("scene": {"camera": {"lat": 45, "lon": 0}})"),
                    "f.json");
  EXPECT_EQ(*f.sample(0.0).sun_utc, "2026-06-21T18:00:00Z");
  EXPECT_EQ(*f.sample(2.5).sun_utc, "2026-06-21T18:15:00.000Z");
  EXPECT_EQ(*f.sample(10.0).sun_utc, "2026-06-21T19:00:00Z");
  EXPECT_EQ(*f.sample(20.0).sun_utc, "2026-06-21T19:00:00Z");
  // Evening in Europe at midsummer: the sun sinks as the flight goes on.
  double previous = f.scene_at(0.0).sun.zenith;
  for (int i = 1; i <= 10; ++i) {
    const double zenith = f.scene_at(i).sun.zenith;
    EXPECT_GT(zenith, previous);
    previous = zenith;
  }
}

TEST(Flight, UtcTextRoundTrips) {
  const double t = *parse_utc_seconds("2026-06-21T18:30:00.250Z");
  EXPECT_EQ(format_utc(t), "2026-06-21T18:30:00.250Z");
  EXPECT_EQ(*parse_utc_seconds("1970-01-01T00:00:00Z"), 0.0);
  EXPECT_EQ(format_utc(0.0), "1970-01-01T00:00:00.000Z");
  EXPECT_EQ(format_utc(*parse_utc_seconds("2024-02-29T23:59:59.999Z")), "2024-02-29T23:59:59.999Z");
  EXPECT_EQ(format_utc(*parse_utc_seconds("1969-12-31T23:59:59Z")), "1969-12-31T23:59:59.000Z");
  EXPECT_FALSE(parse_utc_seconds("2026-02-30T00:00:00Z"));
}

TEST(Flight, SceneTimeKeysStopOrSpeedTheClockAndRunItAtRateOneBeyond) {
  // From 2 to 4 s the clock stopped at 10 s, from 4 to 6 s at rate 3: the waves' time.
  const Flight f = Flight::parse(flight_text(R"([{"time": 2, "scene_time": 10},
                      {"time": 4, "scene_time": 10}, {"time": 6, "scene_time": 16}])",
                                             R"("scene": {"time": 500}, "duration": 8)"),
                                 "f.json");
  const std::vector<std::string>& animated = f.animated_keys();
  EXPECT_NE(std::find(animated.begin(), animated.end(), "time"), animated.end());
  EXPECT_EQ(f.frame_count(), 193);
  // Rate 1 before the first key and after the last; the base scene's 500 s plays no part.
  EXPECT_EQ(*f.sample(0.0).scene_time, 8.0);
  EXPECT_EQ(f.scene_at(1.5).time, 9.5);
  EXPECT_EQ(f.scene_at(2.0).time, 10.0);
  for (double t = 2.0; t <= 4.0; t += 0.125) EXPECT_EQ(f.scene_at(t).time, 10.0) << t;
  // Three times the flight's rate, to rounding: the clock's steps between frames are equal.
  for (int frame = 4 * 24; frame < 6 * 24; ++frame) {
    const double step = f.frame_scene(frame + 1).time - f.frame_scene(frame).time;
    EXPECT_NEAR(step, 3.0 / 24.0, 1e-12) << frame;
  }
  EXPECT_EQ(f.scene_at(5.0).time, 13.0);
  EXPECT_EQ(f.scene_at(6.0).time, 16.0);
  EXPECT_EQ(f.scene_at(8.0).time, 18.0);
  EXPECT_EQ(f.frame_scene(f.frame_count() - 1).time, 18.0);
  // A flight without scene_time runs from the base scene's time, as before.
  const Flight plain = Flight::parse(
      flight_text(R"([{"time": 0}, {"time": 2}])", R"("scene": {"time": 500})"), "f.json");
  EXPECT_FALSE(plain.sample(1.0).scene_time);
  EXPECT_EQ(plain.scene_at(1.5).time, 501.5);
  // The clock may run backwards (a rewind), and stays exact at every key.
  const Flight rewind = Flight::parse(
      flight_text(R"([{"time": 0, "scene_time": 100}, {"time": 10, "scene_time": 90}])"), "f.json");
  EXPECT_EQ(rewind.scene_at(5.0).time, 95.0);
  EXPECT_EQ(rewind.scene_at(10.0).time, 90.0);
  // The keyframes own the scene's time: --set time=... is refused, and changes nothing.
  Flight copy = f;
  EXPECT_EQ(error_of([&] { copy.set("time=3"); }),
            "--set: time: expected a key the flight's keyframes do not animate (f.json gives time "
            "in its keyframes), got an override of it");
  EXPECT_EQ(copy.scene_at(0.0).time, 8.0);
  // A frame rate that takes the last frame's clock out of the scene's range is refused.
  // (At 1 fps the 0.5 s flight is one frame, at 0 s; at 24 fps its last is at 0.5 s.)
  Flight late = Flight::parse(
      flight_text(R"([{"time": 0, "scene_time": 999999999999.75}, {"time": 0.5}])", R"("fps": 1)"),
      "f.json");
  EXPECT_EQ(error_of([&] { late.set_fps(24.0); }),
            "--fps: expected a rate whose last frame (at 0.5 s) keeps the scene's time at most "
            "1e12 s, got 24 (it would be 1000000000000.25 s)");
  EXPECT_EQ(late.fps(), 1.0);  // unchanged
  EXPECT_EQ(late.frame_count(), 1);
  EXPECT_EQ(late.frame_scene(0).time, 999999999999.75);
}

TEST(Flight, ExposureIsInterpolatedInItsLogarithm) {
  // A factor 100 over 2 s, between two keys: the straight line in log exposure, a factor 10 a
  // second, as a camera's exposure steps in stops.
  const Flight f = Flight::parse(flight_text(R"([{"time": 0, "image": {"exposure": 1}},
                      {"time": 2, "image": {"exposure": 100}}])",
                                             R"("scene": {"image": {"exposure": 7}})"),
                                 "f.json");
  EXPECT_EQ(f.scene_at(0.0).image.exposure, 1.0);
  EXPECT_NEAR(f.scene_at(1.0).image.exposure, 10.0, 1e-12);
  EXPECT_NEAR(f.scene_at(0.5).image.exposure, std::sqrt(10.0), 1e-12);
  EXPECT_EQ(f.scene_at(2.0).image.exposure, 100.0);
  EXPECT_EQ(f.scene_at(3.0).image.exposure, 100.0);  // held
  // Three keys: monotone, never outside its neighbouring keys, C1 at the inner key.
  const Flight g = Flight::parse(flight_text(R"([{"time": 0, "image": {"exposure": 0.5}},
                      {"time": 1, "image": {"exposure": 40}}, {"time": 3, "image": {"exposure": 50}}])"),
                                 "f.json");
  double previous = 0.0;
  for (int i = 0; i <= 300; ++i) {
    const double e = g.scene_at(i / 100.0).image.exposure;
    EXPECT_GE(e, previous) << i;
    EXPECT_LE(e, i <= 100 ? 40.0 : 50.0) << i;
    EXPECT_GE(e, i <= 100 ? 0.5 : 40.0) << i;
    previous = e;
  }
  const double h = 1e-6;
  const double left = std::log(g.scene_at(1.0).image.exposure / g.scene_at(1.0 - h).image.exposure);
  const double right =
      std::log(g.scene_at(1.0 + h).image.exposure / g.scene_at(1.0).image.exposure);
  EXPECT_NEAR(left / h, right / h, 1e-3 * std::fabs(left / h));
  const Flight none = Flight::parse(
      flight_text(R"([{"time": 0}, {"time": 1}])", R"("scene": {"image": {"exposure": 7}})"),
      "f.json");
  EXPECT_EQ(none.scene_at(0.5).image.exposure, 7.0);
}

// --- the position on great circles ------------------------------------------------------------

constexpr double kPi = 3.14159265358979323846;

std::array<double, 3> unit_of(double lat, double lon) {
  const double p = lat * kPi / 180.0, l = lon * kPi / 180.0;
  return {std::cos(p) * std::cos(l), std::cos(p) * std::sin(l), std::sin(p)};
}
double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double arc(const std::array<double, 3>& a, const std::array<double, 3>& b) {  // radians
  const auto c = cross(a, b);
  return std::atan2(std::sqrt(dot(c, c)), dot(a, b));
}

TEST(Flight, PositionFollowsTheGreatCircleBetweenTwoKeysAtAnEvenPace) {
  // From Hawaii toward the Great Lakes in 60 s: 6,500 km, where latitude and longitude
  // interpolated apart would pass 680 km south of the great circle half way (32.5 N 117.5 W
  // against 37.0 N 122.6 W).
  const Flight f = Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 20, "lon": -150}},
                      {"time": 60, "camera": {"lat": 45, "lon": -85}}])"),
                                 "f.json");
  const auto a = unit_of(20, -150), b = unit_of(45, -85);
  const auto normal = cross(a, b);
  const double total = arc(a, b);
  double worst_plane = 0.0, worst_pace = 0.0;
  for (int i = 0; i <= 600; ++i) {
    const double t = i * 0.1;
    const FlightValues v = f.sample(t);
    const auto p = unit_of(*v.lat, *v.lon);
    worst_plane = std::max(worst_plane, std::fabs(dot(p, normal)) / std::sqrt(dot(normal, normal)));
    worst_pace = std::max(worst_pace, std::fabs(arc(a, p) - total * t / 60.0));
  }
  std::printf("off the great circle %.1e rad, off the even pace %.1e rad\n", worst_plane,
              worst_pace);
  EXPECT_LT(worst_plane, 1e-12);
  EXPECT_LT(worst_pace, 1e-12);
  // On the ellipsoid: the geodesic's midpoint (GeographicLib) against the path's half way.
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  const GeographicLib::GeodesicLine line = wgs84.InverseLine(20, -150, 45, -85);
  double mid_lat, mid_lon;
  line.Position(0.5 * line.Distance(), mid_lat, mid_lon);
  const FlightValues half = f.sample(30.0);
  double apart;
  wgs84.Inverse(mid_lat, mid_lon, *half.lat, *half.lon, apart);
  std::printf("half way %.0f m from the geodesic's midpoint (of %.0f km)\n", apart,
              line.Distance() / 1e3);
  EXPECT_LT(apart, 10e3);  // measured 4.3 km: the great circle of geodetic coordinates
}

TEST(Flight, PositionCrossesThePoleAndTheAntimeridian) {
  const Flight pole = Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 89, "lon": 0}},
                      {"time": 2, "camera": {"lat": 89, "lon": 180}}])"),
                                    "f.json");
  EXPECT_NEAR(*pole.sample(1.0).lat, 90.0, 1e-9);  // over the pole, not around it at 89
  const Flight date_line =
      Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 0, "lon": 179}},
                      {"time": 1, "camera": {"lat": 0, "lon": -179}}])"),
                    "f.json");
  for (int i = 0; i <= 100; ++i) {
    const FlightValues v = date_line.sample(i / 100.0);
    EXPECT_GE(std::fabs(*v.lon), 179.0 - 1e-9) << i;
    EXPECT_NEAR(*v.lat, 0.0, 1e-9) << i;
  }
  EXPECT_NEAR(*date_line.sample(0.5).lon, 180.0, 1e-9);
  EXPECT_EQ(flight_error(flight_text(R"([{"time": 0, "camera": {"lat": 0, "lon": 0}},
                      {"time": 1, "camera": {"lat": 0.5, "lon": 180}}])")),
            "f.json: keyframes[1].camera: expected a position at most 179 degrees of arc from "
            "keyframes[0]'s (the great circle between antipodes is undefined), got 179.5 degrees");
  // Exact antipodes, where the secant has no direction at all.
  EXPECT_EQ(flight_error(flight_text(R"([{"time": 0, "camera": {"lat": 0, "lon": 30}},
                      {"time": 10, "camera": {"lat": 0, "lon": -150}}])")),
            "f.json: keyframes[1].camera: expected a position at most 179 degrees of arc from "
            "keyframes[0]'s (the great circle between antipodes is undefined), got 180 degrees");
  // Through a keyframe at the pole: along the meridian, at an even pace on both sides.
  const Flight over = Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 89, "lon": 0}},
                      {"time": 1, "camera": {"lat": 90, "lon": 0}},
                      {"time": 2, "camera": {"lat": 89, "lon": 180}}])"),
                                    "f.json");
  EXPECT_NEAR(*over.sample(0.5).lat, 89.5, 1e-9);
  EXPECT_NEAR(*over.sample(0.5).lon, 0.0, 1e-9);
  EXPECT_NEAR(*over.sample(1.5).lat, 89.5, 1e-9);
  EXPECT_NEAR(*over.sample(1.5).lon, 180.0, 1e-9);
}

TEST(Flight, PositionDoesNotOvershootWhereASlowLegFollowsAFastOne) {
  // North at 1 degree a second, then 10 s to a point 0.17 degrees further north and 1 east: the
  // camera neither passes that point's latitude nor leaves the leg's longitudes (a weighted
  // arithmetic mean of the two legs' velocities carried it 0.29 degrees north of both).
  const Flight f = Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 0, "lon": 0}},
                      {"time": 1, "camera": {"lat": 1, "lon": 0}},
                      {"time": 11, "camera": {"lat": 1.17, "lon": 1}}])"),
                                 "f.json");
  // A slow leg east between a fast one north and a fast one south: it stays at 1 N.
  const Flight c = Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 0, "lon": 0.02}},
                      {"time": 1, "camera": {"lat": 1, "lon": 0.02}},
                      {"time": 11, "camera": {"lat": 1, "lon": 1}},
                      {"time": 12, "camera": {"lat": 0, "lon": 1}}])"),
                                 "f.json");
  // The great circles between the keys bow north of their latitudes, by 3.7e-5 degrees for the
  // slow leg east; the path takes the legs' rates at the keys, their north parts too, and may
  // pass that by a few times (1.0001 N measured). 2e-4 degrees is 22 m; the fast leg's
  // direction carried on overshot by 0.29 and 0.73 degrees.
  constexpr double kBow = 2e-4;
  for (double t = 1.0; t <= 11.0; t += 0.01) {
    const FlightValues v = f.sample(t);
    EXPECT_LE(*v.lat, 1.17 + kBow) << t;
    EXPECT_GE(*v.lat, 1.0 - kBow) << t;
    EXPECT_GE(*v.lon, -kBow) << t;
    EXPECT_LE(*v.lon, 1.0 + kBow) << t;
    const FlightValues w = c.sample(t);
    EXPECT_LE(*w.lat, 1.0 + kBow) << t;
    EXPECT_GE(*w.lon, 0.02 - kBow) << t;
    EXPECT_LE(*w.lon, 1.0 + kBow) << t;
  }
}

TEST(Flight, PositionEasesIntoAHoldWithinTheFlightAndFollowsSetFps) {
  // Keys at 0 and 10 s, the flight 10.01 s long: at 24 fps its last frame is at 10 s, the key's,
  // and the pace is even; at 100 fps it runs on to 10.01 s, the position is held after 10 s and
  // eases into the hold (the Hermite curve with a zero end velocity: 0.625 of the arc half way).
  Flight f = Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 0, "lon": 0}},
                      {"time": 10, "camera": {"lat": 0, "lon": 20}}])",
                                       R"("duration": 10.01)"),
                           "f.json");
  EXPECT_NEAR(*f.sample(5.0).lon, 10.0, 1e-9);
  f.set_fps(100.0);
  EXPECT_NEAR(*f.sample(5.0).lon, 12.5, 1e-9);
  EXPECT_EQ(f.frame_scene(f.frame_count() - 1).camera.lon, 20.0);
}

TEST(Flight, PositionIsC1AtInnerKeysAndStopsWithoutOvershoot) {
  // A turn at 10 s (north, then north-east), a stop from 20 to 25 s, and on.
  const Flight f = Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 40, "lon": 10}},
                      {"time": 10, "camera": {"lat": 41, "lon": 10}},
                      {"time": 20, "camera": {"lat": 41.8, "lon": 11.5}},
                      {"time": 25, "camera": {"lat": 41.8, "lon": 11.5}},
                      {"time": 30, "camera": {"lat": 41.3, "lon": 12}}])"),
                                 "f.json");
  const auto at = [&](double t) {
    const FlightValues v = f.sample(t);
    return unit_of(*v.lat, *v.lon);
  };
  // The velocity (rad/s) just before and just after each inner key agree, to the differences'
  // O(h) against the path's speeds of about 2e-3 rad/s (a kink would differ by about that).
  const double h = 1e-4;
  constexpr double kSpeed = 1e-3;  // rad/s
  for (const double key : {10.0, 20.0, 25.0}) {
    const auto p = at(key), before = at(key - h), after = at(key + h);
    std::array<double, 3> v_in, v_out;
    for (int k = 0; k < 3; ++k) {
      v_in[k] = (p[k] - before[k]) / h;
      v_out[k] = (after[k] - p[k]) / h;
    }
    const double speed = std::sqrt(dot(v_out, v_out)) + std::sqrt(dot(v_in, v_in));
    std::array<double, 3> d{v_out[0] - v_in[0], v_out[1] - v_in[1], v_out[2] - v_in[2]};
    EXPECT_LE(std::sqrt(dot(d, d)), 1e-3 * std::max(speed, kSpeed)) << key;
  }
  // The stop: still from 20 to 25 s, and never beyond the stop's point on the way there.
  const auto stop = unit_of(41.8, 11.5), previous = unit_of(41, 10);
  for (double t = 20.0; t <= 25.0; t += 0.25) {
    EXPECT_EQ(*f.sample(t).lat, 41.8) << t;  // the keyframes' own values, to the bit
    EXPECT_EQ(*f.sample(t).lon, 11.5) << t;
  }
  for (double t = 10.0; t <= 20.0; t += 0.05)
    EXPECT_LE(arc(previous, at(t)), arc(previous, stop) + 1e-12) << t;
  // A key given as latitude alone keeps the channels apart, as before (the path is then not on
  // great circles): half way between (20, -150) and (45, -85) at the mean longitude.
  const Flight apart =
      Flight::parse(flight_text(R"([{"time": 0, "camera": {"lat": 20, "lon": -150}},
                      {"time": 30, "camera": {"lat": 30}},
                      {"time": 60, "camera": {"lat": 45, "lon": -85}}])"),
                    "f.json");
  EXPECT_NEAR(*apart.sample(30.0).lon, -117.5, 1e-9);
}

TEST(Flight, NaNTimeGivesTheFirstKeys) {
  const Flight f = Flight::parse(
      flight_text(R"([{"time": 0, "scene_time": 5, "camera": {"height": 100, "lat": 10},
                       "sun": {"utc": "2026-06-21T18:00:00Z"}, "image": {"exposure": 2}},
                      {"time": 1, "scene_time": 9, "camera": {"height": 10, "lat": 11},
                       "sun": {"utc": "2026-06-21T19:00:00Z"}, "image": {"exposure": 4}}])"),
      "f.json");
  const FlightValues v = f.sample(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(*v.height, 100.0);
  EXPECT_EQ(*v.lat, 10.0);
  EXPECT_EQ(*v.exposure, 2.0);
  EXPECT_EQ(*v.scene_time, 5.0);
  EXPECT_EQ(*v.sun_utc, "2026-06-21T18:00:00Z");
}

// --- overrides ---------------------------------------------------------------------------------

TEST(Flight, SetOverridesTheBaseSceneButNotAnimatedKeys) {
  Flight f = Flight::parse(
      flight_text(
          R"([{"time": 0, "camera": {"height": 100}}, {"time": 1, "camera": {"height": 10}}])"),
      "f.json");
  f.set("image.width=32");
  f.set("camera.lat=-33");
  EXPECT_EQ(f.frame_scene(0).image.width, 32);
  EXPECT_EQ(f.frame_scene(0).camera.lat, -33.0);
  EXPECT_EQ(error_of([&] { f.set("camera.height=5"); }),
            "--set: camera.height: expected a key the flight's keyframes do not animate (f.json "
            "gives camera.height in its keyframes), got an override of it");
  EXPECT_EQ(error_of([&] { f.set("image.width=0"); }),
            "--set: image.width: expected an integer in [1, 8192] (pixels), got 0");
  EXPECT_EQ(f.frame_scene(0).image.width, 32);  // a failed --set changes nothing
  // One that takes the last frame's scene time past 1e12 s is refused too, and changes nothing.
  EXPECT_NE(error_of([&] { f.set("time=999999999999.5"); }).find("time: expected a number"),
            std::string::npos);
  EXPECT_EQ(f.frame_scene(0).time, 0.0);
  EXPECT_EQ(f.frame_scene(f.frame_count() - 1).time, 1.0);
  const Flight sun = Flight::parse(
      flight_text(R"([{"time": 0, "sun": {"zenith": 80}}, {"time": 1, "sun": {"zenith": 90}}])"),
      "f.json");
  Flight copy = sun;
  EXPECT_NE(error_of([&] { copy.set("sun.utc=2026-06-21T18:00:00Z"); }).find("the sun"),
            std::string::npos);
}

// --- bad files --------------------------------------------------------------------------------

TEST(FlightErrors, NameTheFileTheKeyPathAndTheExpectation) {
  const std::string two = R"({"time": 0}, {"time": 1})";
  struct Case {
    std::string text;
    std::string message;
  };
  const std::vector<Case> cases = {
      {flight_text(
           R"([{"time": 0}, {"time": 1}, {"time": 2}, {"time": 3, "camera": {"height": "x"}}])"),
       "f.json: keyframes[3].camera.height: expected a number in [0, 1e9] (m; a flight stays "
       "above the sea), got \"x\""},
      {flight_text(R"([{"time": 0, "camera": {"height": -1}}])"),
       "f.json: keyframes[0].camera.height: expected a number in [0, 1e9] (m; a flight stays "
       "above the sea), got -1"},
      {flight_text(R"([{"time": 0, "camera": {"lat": 91}}])"),
       "f.json: keyframes[0].camera.lat: expected a number in [-90, 90] (degrees), got 91"},
      {flight_text(R"([{"time": 0, "camera": {"pitch": true}}])"),
       "f.json: keyframes[0].camera.pitch: expected a number in [-90, 90] (degrees), got true"},
      {flight_text(R"([{"time": 0, "camera": {"hieght": 3}}])"),
       "f.json: keyframes[0].camera.hieght: expected a known key (lat, lon, height, heading, "
       "pitch, roll, fov_y; see docs/flight.md), got an unknown key"},
      {flight_text(R"([{"time": 0, "sun": {"utc": "yesterday"}}])"),
       "f.json: keyframes[0].sun.utc: expected an ISO 8601 UTC time "
       "YYYY-MM-DDTHH:MM:SS[.fff]Z, got \"yesterday\""},
      {flight_text(R"([{"time": 0}, {"time": 5}, {"time": 5}])"),
       "f.json: keyframes[2].time: expected a time after keyframes[1].time (5 s), got 5"},
      {flight_text(R"([{"time": 0}, {"time": -1}])"),
       "f.json: keyframes[1].time: expected a number in [0, 1e6] (s), got -1"},
      {flight_text(R"([{"camera": {"lat": 1}}])"),
       "f.json: keyframes[0].time: expected a number (s), got no time"},
      {flight_text(R"([{"time": 0, "speed": 3}])"),
       "f.json: keyframes[0].speed: expected a known key (time, scene_time, camera, sun, image; "
       "see docs/flight.md), got an unknown key"},
      {flight_text(R"([{"time": 0, "image": {"width": 64}}])"),
       "f.json: keyframes[0].image.width: expected a known key (exposure; see docs/flight.md), got "
       "an unknown key"},
      {flight_text(R"([{"time": 0, "image": {"exposure": 0}}])"),
       "f.json: keyframes[0].image.exposure: expected a number in (0, 1e6] (1/(W m^-2 sr^-1 "
       "nm^-1)), got 0"},
      {flight_text(R"([{"time": 0, "scene_time": -1}])"),
       "f.json: keyframes[0].scene_time: expected a number in [0, 1e12] (s), got -1"},
      {flight_text(R"([{"time": 0}, {"time": 4, "scene_time": 3}])"),
       "f.json: keyframes[1].scene_time: expected at least its keyframe's time (4 s): before its "
       "first key the scene's time runs at rate 1, and may not be negative at the flight's "
       "start, got 3"},
      {flight_text(R"([{"time": 0, "scene_time": 1e12}, {"time": 1}])"),
       "f.json: keyframes[0].scene_time: expected at most 999999999999 (s): after its last key "
       "the scene's time runs at rate 1, and may not pass 1e12 s by the flight's last frame "
       "(1 s), got 1e12"},
      {flight_text(R"([{"time": 0, "camera": 3}])"),
       "f.json: keyframes[0].camera: expected an object of camera keys, got 3"},
      {flight_text(R"([3])"),
       "f.json: keyframes[0]: expected an object {\"time\": ..., \"camera\": {...}, \"sun\": "
       "{...}}, got 3"},
      {flight_text("[]"),
       "f.json: keyframes: expected an array of 1 to 100000 keyframes, got an empty array"},
      {"{}", "f.json: keyframes: expected an array of keyframes, got none"},
      {flight_text("[" + two + "]", R"("fsp": 24)"),
       "f.json: fsp: expected a known key (description, scene, fps, duration, frames, keyframes; "
       "see docs/flight.md), got an unknown key"},
      {flight_text("[" + two + "]", R"("fps": 0)"),
       "f.json: fps: expected a number in (0, 1000] (frames per second), got 0"},
      {flight_text("[" + two + "]", R"("duration": 1, "frames": 3)"),
       "f.json: frames: expected either duration or frames, got both"},
      {flight_text("[" + two + "]", R"("frames": 2.5)"),
       "f.json: frames: expected an integer in [1, 10000000], got 2.5"},
      {flight_text("[" + two + "]", R"("fps": 1000, "duration": 1e6)"),
       "f.json: duration: expected at most 10000000 frames (duration x fps + 1), got 1000000001 "
       "frames"},
      {flight_text(R"([{"time": 0, "sun": {"utc": "2026-06-21T18:00:00Z"}},
                       {"time": 1, "sun": {"zenith": 80}}])"),
       "f.json: keyframes[1].sun.zenith: expected the sun given one way in all keyframes, as "
       "sun.utc in keyframes[0], got sun.zenith/sun.azimuth"},
      {flight_text(R"([{"time": 0, "sun": {"utc": "2026-06-21T18:00:00Z", "azimuth": 3}}])"),
       "f.json: keyframes[0].sun.utc: expected either sun.utc or sun.zenith/sun.azimuth, got both "
       "in one keyframe"},
      {flight_text(R"([{"time": 0, "sun": {"zenith": 80}}])",
                   R"("scene": {"sun": {"utc": "2026-06-21T18:00:00Z"}})"),
       "f.json: keyframes[0].sun.zenith: expected the sun given as the base scene gives it "
       "(sun.utc in f.json), got sun.zenith/sun.azimuth"},
      // The base scene, inline: its keys named with "scene." in front.
      {flight_text("[" + two + "]", R"("scene": {"camera": {"height": "high"}})"),
       "f.json: scene.camera.height: expected a number in [-11000, 1e9] (m), got \"high\""},
      {flight_text("[" + two + "]", R"("scene": {"camera": {"hieght": 3}})"),
       "f.json: scene.camera.hieght: expected a known key (did you mean camera.height?), got an "
       "unknown key"},
      {flight_text("[" + two + "]", R"("scene": 3)"),
       "f.json: scene: expected a scene object or the path of a scene file, got 3"},
      {flight_text("[" + two + "]", R"("scene": "nowhere.json")"),
       "f.json: scene: expected a readable scene file (relative to the flight file's folder), got "
       "\"nowhere.json\", no such file"},
      {flight_text("[" + two + "]", R"("scene": {"ocean": {"lambda_min": 50, "lambda_max": 10}})"),
       "f.json: ocean.lambda_min: expected a value <= ocean.lambda_max (10 m), got 50"},
      {R"({"keyframes": [{"time": 0}], "fps": 24, "fps": 25})",
       "f.json: fps: expected each key once, got \"fps\" a second time"},
      {"[1, 2]", "f.json: expected a JSON object (a flight, see docs/flight.md), got an array"},
  };
  for (const Case& c : cases) EXPECT_EQ(flight_error(c.text), c.message) << c.text;
  // Syntax errors name the file, the line and column, and say what the parser found.
  const std::string syntax = flight_error("{\"keyframes\": [\n  1,,");
  EXPECT_EQ(syntax.rfind("f.json:2:5: expected valid JSON, got ", 0), 0u) << syntax;
}

TEST(FlightErrors, FilesAndSceneFilesBesideThem) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("thalassa_flight_" + std::to_string(getpid()));
  fs::create_directories(dir / "scenes");
  std::ofstream(dir / "scenes" / "base.json") << R"({"camera": {"lat": -12.5}})";
  std::ofstream(dir / "bad_base.json") << R"({"camera": {"lat": 100}})";
  std::ofstream(dir / "flight.json")
      << flight_text(R"([{"time": 0}])", R"("scene": "scenes/base.json")");
  std::ofstream(dir / "bad.json") << flight_text(R"([{"time": 0}])", R"("scene": "bad_base.json")");
  // A scene path is relative to the flight file's folder, wherever the program runs.
  const Flight f = Flight::load_file((dir / "flight.json").string());
  EXPECT_EQ(f.frame_scene(0).camera.lat, -12.5);
  // Errors inside the scene file name that file.
  EXPECT_EQ(error_of([&] { Flight::load_file((dir / "bad.json").string()); }),
            (dir / "bad_base.json").string() +
                ": camera.lat: expected a number in [-90, 90] (degrees), got 100");
  EXPECT_EQ(
      error_of([&] { Flight::load_file((dir / "missing.json").string()); }),
      (dir / "missing.json").string() + ": expected a readable flight file, got no such file");
  fs::remove_all(dir);
}

// --- the default flight -----------------------------------------------------------------------

TEST(DefaultFlight, IsTheDataFileAndDescendsFromOrbitToTheSurfaceAtSunset) {
  const std::string path = std::string(THALASSA_SOURCE_DIR) + "/data/flights/orbit_to_surface.json";
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  EXPECT_EQ(json::parse(read_text(path)), json::parse(default_flight_json()));
  const Flight file = Flight::load_file(path);
  const Flight f = Flight::default_flight();
  EXPECT_EQ(f.frame_count(), file.frame_count());
  EXPECT_EQ(f.fps(), 24.0);
  EXPECT_EQ(f.frame_count(), 481);  // 20 s at 24 frames per second, both ends included
  const Scene first = f.frame_scene(0), last = f.frame_scene(f.frame_count() - 1);
  EXPECT_EQ(first.camera.height, 400000.0);
  EXPECT_EQ(last.camera.height, 2.0);
  EXPECT_GT(last.camera.pitch, -5.0);
  EXPECT_EQ(first.sun.zenith, 88.0);
  EXPECT_EQ(first.camera.heading, first.sun.azimuth);  // facing the sun
  double previous = first.camera.height;
  for (int i = 0; i < f.frame_count(); ++i) {
    const Scene s = f.frame_scene(i);
    const double h = s.camera.height;
    if (i > 0) {
      ASSERT_LT(h, previous) << "frame " << i;
    }
    ASSERT_GE(h, 2.0);
    previous = h;
    // The horizon (the limb from orbit) stays in view, at least 5 degrees inside the image's
    // top and bottom: its dip below the horizontal on a sphere of the Earth's mean radius is
    // acos(R / (R + h)), the camera's pitch puts it -dip - pitch above the image's centre.
    constexpr double kRadius = 6371e3, kMargin = 5.0;
    const double dip = std::acos(kRadius / (kRadius + h)) * 180.0 / M_PI;
    ASSERT_LT(std::abs(-dip - s.camera.pitch), 0.5 * s.camera.fov_y - kMargin) << "frame " << i;
  }
}

}  // namespace
}  // namespace thalassa
