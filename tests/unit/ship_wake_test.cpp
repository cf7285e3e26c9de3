// Tests of a ship's wake placed by latitude and longitude (planet/include/thalassa/planet/
// ship_wake.hpp): the track interpolated by time along geodesics, the position-heading-speed
// form, the ship-frame coordinates of points built from known (b, y) with GeographicLib (mid
// latitudes, across the antimeridian, near a pole), the wave vectors in east-north, the wake
// following a turning track, a track of many short segments searched as every segment would be,
// the coordinates' gradients, and the culling bounds holding every point where the wake is
// non-zero.

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "geodesic_segment.hpp"
#include "thalassa/ocean/kelvin_wake.hpp"
#include "thalassa/planet/ship_wake.hpp"

namespace thalassa {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

WakeSettings Steady(double lat, double lon, double heading, double speed, double time = 0.0) {
  WakeSettings s;
  s.name = "steady";
  s.lat = lat;
  s.lon = lon;
  s.heading = heading;
  s.speed = speed;
  s.time = time;
  s.amplitude = 0.3;
  s.draft = 2.0;
  s.length = 3000.0;
  return s;
}

TEST(ShipWake, TrackIsInterpolatedAlongGeodesicsByTime) {
  const Planet planet;
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  WakeSettings s;
  s.name = "ferry";
  s.track = {{59.0, 179.9, 100.0}, {59.01, -179.95, 700.0}, {59.05, -179.9, 1500.0}};
  const ShipWake wake(planet, s);
  EXPECT_FALSE(wake.ship_at(99.9).present);
  EXPECT_FALSE(wake.ship_at(1500.1).present);
  for (std::size_t i = 0; i < s.track.size(); ++i) {
    const ShipWake::State st = wake.ship_at(s.track[i].time);
    ASSERT_TRUE(st.present);
    double d;
    g.Inverse(st.lat, st.lon, s.track[i].lat, s.track[i].lon, d);
    EXPECT_LT(d, 1e-6) << i;
  }
  for (std::size_t i = 0; i + 1 < s.track.size(); ++i) {
    const TrackPoint& a = s.track[i];
    const TrackPoint& b = s.track[i + 1];
    double len, azi1, azi2;
    g.Inverse(a.lat, a.lon, b.lat, b.lon, len, azi1, azi2);
    for (double f : {0.1, 0.5, 0.93}) {
      const double t = a.time + f * (b.time - a.time);
      const ShipWake::State st = wake.ship_at(t);
      ASSERT_TRUE(st.present);
      double from_a, to_b, azi_a, azi_at;
      g.Inverse(a.lat, a.lon, st.lat, st.lon, from_a, azi_a, azi_at);
      g.Inverse(st.lat, st.lon, b.lat, b.lon, to_b);
      EXPECT_NEAR(from_a, f * len, 1e-6);     // covered the fraction f of the segment
      EXPECT_NEAR(from_a + to_b, len, 1e-6);  // on the geodesic
      EXPECT_NEAR(st.speed, len / (b.time - a.time), 1e-9);
      EXPECT_NEAR(std::remainder(st.heading - azi_at, 360.0), 0.0, 1e-7);
    }
  }
}

// Points built from known ship-frame coordinates: go b metres back along the wake's geodesic,
// then y metres to port at a right angle; the wake must give (b, y) back.
void ExpectCoordinatesRoundTrip(double lat, double lon, double heading, double speed) {
  const Planet planet;
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  const ShipWake wake(planet, Steady(lat, lon, heading, speed, 50.0));
  const double time = 170.0;
  const ShipWake::State st = wake.ship_at(time);
  ASSERT_TRUE(st.present);
  double moved;
  g.Inverse(lat, lon, st.lat, st.lon, moved);
  EXPECT_NEAR(moved, speed * (time - 50.0), 1e-6);
  const GeographicLib::GeodesicLine back = g.Line(st.lat, st.lon, st.heading + 180.0);
  double worst = 0.0;
  for (double b : {40.0, 400.0, 1500.0, 2700.0}) {
    for (double y_over_b : {-0.3, -0.1, 0.0, 0.05, 0.2, 0.34}) {
      const double y = y_over_b * b;
      double flat, flon, fazi;
      back.Position(b, flat, flon, fazi);
      const double travel = fazi + 180.0;  // direction of travel at the foot
      double plat, plon;
      g.Direct(flat, flon, travel - 90.0, y, plat, plon);  // port = left of travel
      const auto c = wake.coordinates(plat, plon, time);
      ASSERT_TRUE(c.has_value()) << b << " " << y;
      worst = std::max({worst, std::abs(c->behind - b), std::abs(c->lateral - y)});
      EXPECT_NEAR(std::remainder(c->heading - travel, 360.0), 0.0, 1e-6);
      // The transverse wave on the track points along the heading (east-north frame).
      if (y == 0.0) {
        const ocean::KelvinWakeSample s = wake.sample(plat, plon, time);
        const glm::dvec2 k = s.transverse.wave_vector / s.transverse.wavenumber;
        EXPECT_NEAR(k.x, std::sin(travel * kDeg), 1e-9);
        EXPECT_NEAR(k.y, std::cos(travel * kDeg), 1e-9);
        EXPECT_NEAR(s.transverse.wavelength, 2 * std::numbers::pi * speed * speed / 9.81, 1e-9);
      }
    }
  }
  std::printf("lat %g lon %g heading %g: worst (b, y) error %.3g m\n", lat, lon, heading, worst);
  EXPECT_LT(worst, 1e-6);
  // Ahead of the ship, and abeam farther than the wake's half-width: no wake.
  double alat, alon;
  g.Direct(st.lat, st.lon, st.heading, 100.0, alat, alon);
  EXPECT_FALSE(wake.coordinates(alat, alon, time).has_value());
  EXPECT_EQ(wake.sample(alat, alon, time).transverse.amplitude, 0.0);
}

TEST(ShipWake, CoordinatesRoundTripAtMidLatitude) {
  ExpectCoordinatesRoundTrip(43.3, 5.3, 210.0, 8.0);
}
TEST(ShipWake, CoordinatesRoundTripAcrossTheAntimeridian) {
  ExpectCoordinatesRoundTrip(-12.0, 179.99, 95.0, 12.0);  // sails east across 180
}
TEST(ShipWake, CoordinatesRoundTripNearAPole) {
  ExpectCoordinatesRoundTrip(89.95, 30.0, 10.0, 6.0);
}

TEST(ShipWake, WakeFollowsATurningTrack) {
  const Planet planet;
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  // North for 1500 m, then east for 1500 m, at 10 m/s.
  WakeSettings s = Steady(0, 0, 0, 0);
  s.track.push_back({10.0, 20.0, 0.0});
  double lat, lon;
  g.Direct(10.0, 20.0, 0.0, 1500.0, lat, lon);
  s.track.push_back({lat, lon, 150.0});
  double lat2, lon2;
  g.Direct(lat, lon, 90.0, 1500.0, lat2, lon2);
  s.track.push_back({lat2, lon2, 300.0});
  const ShipWake wake(planet, s);
  // At t = 300 the ship is at the end; a point on the first leg, 500 m before the turn, is
  // 1500 + 500 m astern along the track.
  double plat, plon;
  g.Direct(10.0, 20.0, 0.0, 1000.0, plat, plon);
  const auto c = wake.coordinates(plat, plon, 300.0);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->behind, 2000.0, 1e-5);
  EXPECT_NEAR(c->lateral, 0.0, 1e-5);
  // Before the track's start there is no wake (the ship was not there).
  double blat, blon;
  g.Direct(10.0, 20.0, 180.0, 200.0, blat, blon);
  EXPECT_FALSE(wake.coordinates(blat, blon, 300.0).has_value());
  // A stationary point in time: speed below the capillary minimum gives no wake.
  WakeSettings slow = Steady(10.0, 20.0, 45.0, 0.1);
  const ShipWake still(planet, slow);
  EXPECT_FALSE(still.coordinates(10.0, 20.0, 10.0).has_value());
  EXPECT_TRUE(still.bounds(10.0).empty());
}

// A track as an AIS receiver gives it: a point every 5 s (50 m at 10 m/s) round a turn of 2 km
// radius, so that the wake's 3 km astern span 60 segments. Each point's coordinates are the
// nearest segment's, as a search of every segment finds them (the Instant skips the segments
// whose lower bound is beyond the best found).
WakeSettings TurningAisTrack() {
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  WakeSettings s = Steady(0, 0, 0, 0);
  s.name = "ais";
  double lat = 51.0, lon = 1.5, heading = 20.0;
  const double step = 50.0, radius = 2000.0;
  for (int i = 0; i <= 120; ++i) {
    s.track.push_back({lat, lon, 5.0 * i});
    double azi;
    g.Direct(lat, lon, heading, step, lat, lon, azi);
    heading = azi + step / radius * 180.0 / std::numbers::pi;  // turning to starboard
  }
  return s;
}

TEST(ShipWake, ManySegmentTrackGivesTheNearestSegmentsCoordinates) {
  const Planet planet;
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  const WakeSettings settings = TurningAisTrack();
  const ShipWake wake(planet, settings);
  const double time = 600.0;  // exactly the last point's time
  const ShipWake::Instant now = wake.at(time);
  ASSERT_TRUE(now.ship().present);
  const std::vector<GeoPoint> past = now.past_track();
  ASSERT_GE(past.size(), 60u);
  const double half_width = ocean::kelvin_wake_half_width(
      {.speed = now.ship().speed, .amplitude = 0.3, .draft = 2.0, .length = 3000.0});
  // Round the ship, the track's turning points themselves (equally near two segments) and points
  // ahead of the ship.
  std::vector<GeoPoint> points;
  for (int i = 0; i < 72; ++i) {
    for (int j = 0; j < 40; ++j) {
      double lat, lon;
      g.Direct(now.ship().lat, now.ship().lon, 5.0 * i, 3200.0 * (j + 0.5) / 40.0, lat, lon);
      points.push_back({lat, lon});
    }
  }
  for (std::size_t k = 1; k + 1 < past.size(); ++k) points.push_back(past[k]);
  for (double ahead : {1e-3, 10.0, 100.0}) {
    double lat, lon;
    g.Direct(now.ship().lat, now.ship().lon, now.ship().heading, ahead, lat, lon);
    points.push_back({lat, lon});
  }
  int with_wake = 0, vertices = 0;
  for (const GeoPoint& p : points) {
    const auto c = now.coordinates(p.lat, p.lon);
    // Every segment searched: the nearest foot, the newer segment's of two equally near.
    double best = INFINITY, behind = 0.0, lateral = 0.0, heading = 0.0, sum = 0.0;
    for (std::size_t k = 0; k + 1 < past.size(); ++k) {
      const detail::SegmentFoot foot = detail::nearest_on_segment(
          g, past[k + 1].lat, past[k + 1].lon, past[k].lat, past[k].lon, p.lat, p.lon);
      if (foot.distance < best) {
        best = foot.distance;
        behind = sum + (foot.length - foot.along);
        lateral = std::sin((foot.point_azimuth - foot.azimuth) * kDeg) < 0.0 ? best : -best;
        heading = foot.azimuth;
      }
      sum += foot.length;
    }
    const bool expected = best <= half_width && behind > 0.0 && behind < 3000.0;
    ASSERT_EQ(c.has_value(), expected) << p.lat << " " << p.lon << " b " << behind;
    if (!c) continue;
    ++with_wake;
    if (best == 0.0) ++vertices;
    EXPECT_NEAR(c->behind, behind, 1e-6) << p.lat << " " << p.lon;
    EXPECT_NEAR(c->lateral, lateral, 1e-9) << p.lat << " " << p.lon;
    EXPECT_NEAR(std::remainder(c->heading - heading, 360.0), 0.0, 1e-9) << p.lat << " " << p.lon;
  }
  EXPECT_GT(with_wake, 100);
  EXPECT_GE(vertices, 50);
}

// The coordinates' gradients against central differences of the coordinates of points 5 cm east,
// west, north and south: straight wakes at mid-latitude, across the antimeridian and 5 km from
// the pole, and the turning track (inside and outside the turn, where outside the foot is a
// turning point of the track and b does not change). Points within 5 cm of where b's gradient
// jumps are left out.
TEST(ShipWake, CoordinateGradientsAreTheCoordinatesDifferences) {
  const Planet planet;
  const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
  const double h = 0.05;  // m
  double worst = 0.0;
  int points = 0, fans = 0, kinks = 0, on_track = 0;
  for (const WakeSettings& s : {Steady(43.3, 5.3, 210.0, 8.0), Steady(-12.0, 179.99, 95.0, 12.0),
                                Steady(89.95, 30.0, 10.0, 6.0), TurningAisTrack()}) {
    const ShipWake wake(planet, s);
    const double time = s.track.empty() ? 170.0 : 600.0;
    const ShipWake::Instant now = wake.at(time);
    for (int i = 0; i < 36; ++i) {
      for (int j = 0; j < 12; ++j) {
        double lat, lon;
        g.Direct(now.ship().lat, now.ship().lon, 10.0 * i + 3.0, 2800.0 * (j + 0.5) / 12.0, lat,
                 lon);
        if (j == 0 && s.track.empty()) {
          // On the track: the gradients are the foot's -e and n.
          const GeographicLib::GeodesicLine back =
              g.Line(now.ship().lat, now.ship().lon, now.ship().heading + 180.0);
          back.Position(250.0 * (i + 1) / 3.0, lat, lon);
        }
        const auto c = now.coordinates(lat, lon);
        if (!c) continue;
        if (std::abs(c->lateral) < 1e-3) ++on_track;
        glm::dvec2 db(0.0), dy(0.0);
        bool all = true;
        for (int axis = 0; axis < 2; ++axis) {
          double lp, op, lm, om;
          g.Direct(lat, lon, axis == 0 ? 90.0 : 0.0, h, lp, op);
          g.Direct(lat, lon, axis == 0 ? 270.0 : 180.0, h, lm, om);
          const auto plus = now.coordinates(lp, op), minus = now.coordinates(lm, om);
          if (!plus || !minus) {
            all = false;
            break;
          }
          db[axis] = (plus->behind - minus->behind) / (2.0 * h);
          dy[axis] = (plus->lateral - minus->lateral) / (2.0 * h);
          // Within h of a kink (the edge of a turn's fan, where b's gradient jumps to 0) the
          // one-sided differences disagree: such a point is not compared.
          const double forward = (plus->behind - c->behind) / h;
          const double backward = (c->behind - minus->behind) / h;
          if (std::abs(forward - backward) > 1e-3) all = false;
        }
        if (!all) {
          ++kinks;
          continue;
        }
        ++points;
        if (c->behind_gradient == glm::dvec2(0.0)) ++fans;
        worst = std::max(
            {worst, glm::length(db - c->behind_gradient), glm::length(dy - c->lateral_gradient)});
        EXPECT_NEAR(glm::length(c->lateral_gradient), 1.0, 1e-12);
        EXPECT_LT(glm::length(db - c->behind_gradient), 1e-6) << s.name << " " << i << " " << j;
        EXPECT_LT(glm::length(dy - c->lateral_gradient), 1e-6) << s.name << " " << i << " " << j;
      }
    }
  }
  std::printf(
      "%d points (%d on the track, %d in a turn's fan, %d within 5 cm of a kink or the "
      "wake's edge): worst gradient against the differences %.3g\n",
      points, on_track, fans, kinks, worst);
  EXPECT_GT(points, 200);
  EXPECT_GT(on_track, 50);
  EXPECT_GT(fans, 0);
}

TEST(ShipWake, BoundsHoldEveryPointWithAWake) {
  const Planet planet;
  for (const WakeSettings& s :
       {Steady(43.3, 5.3, 210.0, 8.0), Steady(-12.0, 179.99, 95.0, 12.0),
        Steady(89.97, 30.0, 10.0, 6.0), Steady(-60.0, -179.98, 270.0, 15.0)}) {
    const ShipWake wake(planet, s);
    const double time = 100.0;
    const GeoBounds b = wake.bounds(time);
    ASSERT_FALSE(b.empty());
    const ShipWake::State st = wake.ship_at(time);
    int with_wake = 0;
    const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
    for (int i = 0; i < 120; ++i) {
      for (int j = 0; j < 120; ++j) {
        // A disc of 4 km around the ship, by azimuth and distance.
        double lat, lon;
        g.Direct(st.lat, st.lon, 3.0 * i, 4000.0 * (j + 0.5) / 120.0, lat, lon);
        const ocean::KelvinWakeSample w = wake.sample(lat, lon, time);
        if (w.transverse.amplitude > 0.0 || w.divergent.amplitude > 0.0) {
          ++with_wake;
          EXPECT_TRUE(b.contains(lat, lon)) << lat << " " << lon;
        }
      }
    }
    EXPECT_GT(with_wake, 100);
    // And the bounds are not the whole globe (except near the pole).
    if (std::abs(s.lat) < 89.0) {
      EXPECT_LT(b.longitude_span(), 1.0);
    }
  }
}

TEST(ShipWake, RefusesBadTracks) {
  const Planet planet;
  WakeSettings s = Steady(0, 0, 0, 5);
  s.track = {{0, 0, 0}};
  EXPECT_THROW(ShipWake(planet, s), std::invalid_argument);
  s.track = {{0, 0, 0}, {0, 0.01, 0}};
  EXPECT_THROW(ShipWake(planet, s), std::invalid_argument);
  s.track = {{0, 0, 0}, {0, 0.01, -5}};
  EXPECT_THROW(ShipWake(planet, s), std::invalid_argument);
  s.track = {{0, 0, 0}, {0, 100, 1e6}};  // 11000 km in one segment
  EXPECT_THROW(ShipWake(planet, s), std::invalid_argument);
  s.track = {{0, 0, 0}, {std::nan(""), 1, 10}};
  EXPECT_THROW(ShipWake(planet, s), std::invalid_argument);
  EXPECT_THROW(ShipWake(planet, Steady(0, 0, 0, 150)), std::invalid_argument);
  WakeSettings bad = Steady(0, 0, 0, 5);
  bad.draft = 0.0;
  EXPECT_THROW(ShipWake(planet, bad), std::invalid_argument);
}

}  // namespace
}  // namespace thalassa
