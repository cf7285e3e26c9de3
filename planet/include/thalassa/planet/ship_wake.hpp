// thalassa — a ship's Kelvin wake placed by latitude and longitude (issue 9, point 1; docs/
// wakes.md): where the ship is at a time (its track interpolated along geodesics, or a
// position, heading and speed), the ship-frame coordinates of a point of the sea behind it, the
// wake's waves there (ocean/kelvin_wake.hpp) with their wave vectors in the point's east-north
// frame, and conservative bounds for culling. CPU, double precision, GeographicLib.
//
// Track-following coordinates: for a point P and time t, b is the distance along the ship's
// past track from the ship back to the track's point nearest to P (the foot), y the geodesic
// distance from the foot to P, positive to port (left of the direction of travel). On a
// straight track (a geodesic) these are exactly the ship frame of kelvin_wake.hpp; on a curved
// one the wedge bends with the track, which holds while the track's radius of curvature is
// large against the wake's width (docs/wakes.md). The pattern is the steady one of the ship's
// CURRENT speed (a change of speed changes the whole wake at once).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "thalassa/engine/scene.hpp"
#include "thalassa/ocean/kelvin_wake.hpp"
#include "thalassa/planet/geo_bounds.hpp"
#include "thalassa/planet/geodesy.hpp"

namespace thalassa {

// The longest track segment accepted, m (10000 km, 90 degrees of arc: the nearest-point
// search projects a segment with the gnomonic centred on it).
inline constexpr double kMaxTrackSegment = 1.0e7;

class ShipWake {
 public:
  // Throws std::invalid_argument for a track with fewer than 2 points, times not strictly
  // increasing, a segment longer than kMaxTrackSegment, a point out of range, a position form's
  // speed outside [0, 100] m/s or wake parameters kelvin_wake_at refuses. (The scene checks a
  // track's segment speeds, <= 100 m/s on a sphere; any finite speed works here.)
  ShipWake(const Planet& planet, const WakeSettings& settings);
  ~ShipWake();
  ShipWake(const ShipWake&);
  ShipWake& operator=(const ShipWake&);
  ShipWake(ShipWake&&) noexcept;
  ShipWake& operator=(ShipWake&&) noexcept;

  const WakeSettings& settings() const { return settings_; }

  struct State {
    bool present = false;  // false before the track's first time or after its last
    double lat = 0.0;      // degrees
    double lon = 0.0;      // degrees
    double heading = 0.0;  // degrees clockwise from north: the direction of travel
    double speed = 0.0;    // m/s: the current segment's (constant on a segment)
  };
  // The ship at time t (s): on a track, between points i and i + 1 it has covered the fraction
  // (t - t_i) / (t_{i+1} - t_i) of the geodesic from point i to point i + 1.
  State ship_at(double time) const;

  struct Coordinates {
    double behind = 0.0;   // b, m
    double lateral = 0.0;  // y, m, > 0 to port
    double heading = 0.0;  // degrees: direction of travel at the foot (the ship frame's e)
    // The gradients of b and y at the point, east-north (m per m). y's is the unit direction, at
    // the point, of the geodesic from the foot (away from the track to port, toward it to
    // starboard): n carried to the point. b's is -e, with e (the course carried to the point) y's
    // gradient turned 90 degrees clockwise seen from above (Gauss's lemma: the geodesic from the
    // foot meets the lines of constant b at a right angle). Their lengths are 1 to O(y^2 / R^2),
    // 4e-9 at 600 m. Where the foot is a turning point of the track (the fan outside a turn) b is
    // constant: its gradient is 0. On the track (|y| below 1 mm) they are the foot's -e and n.
    glm::dvec2 behind_gradient{0.0};
    glm::dvec2 lateral_gradient{0.0};
  };
  // (b, y) of the point (lat, lon: degrees) at time t, or nullopt where there is no wake (no
  // ship, a speed below ocean::kMinimumWakeSpeed, the point farther than the wake's half-width
  // from the track or more than its length astern, or beyond the track's start).
  std::optional<Coordinates> coordinates(double lat, double lon, double time) const;

  // The wake's two waves at the point, wave vectors turned into the point's east-north frame
  // (x east, y north, rad/m; the frame of the foot, which differs from the point's by the
  // meridians' convergence over y: below 1e-4 rad for y < 600 m at 80 degrees of latitude).
  // Empty waves where coordinates() is nullopt.
  ocean::KelvinWakeSample sample(double lat, double lon, double time) const;

  // The past track at time t from the ship back to `length` astern or to the track's start
  // (degrees; the ship first, then the track's points it passed, newest first; consecutive
  // points joined by geodesics): the polyline coordinates() measures b along. Empty when there
  // is no ship.
  std::vector<GeoPoint> past_track(double time) const;

  // Conservative bounds of where the wake can be non-zero at time t (the past track within
  // `length` astern, grown by the wake's half-width); empty when there is no wake.
  GeoBounds bounds(double time) const;

  // The wake at one time: the ship and its past track found once, for many points at that time
  // (a hull's, a solver's iterations). The functions above are each an Instant's. A value: it
  // holds what it needs and may outlive its ShipWake.
  class Instant {
   public:
    double time() const { return time_; }
    const State& ship() const { return ship_; }
    std::optional<Coordinates> coordinates(double lat, double lon) const;
    ocean::KelvinWakeSample sample(double lat, double lon) const;
    // The waves at the ship-frame coordinates c.behind and c.lateral, turned into east-north by
    // c.heading: sample(lat, lon) for c = *coordinates(lat, lon). With b and y moved by their
    // gradients times a small offset dp (m, east-north), the waves at the point + dp without a
    // search of the track (what SeaState differentiates). The foot's heading is kept over dp: it
    // turns by sin(heading) tan(lat) / R per metre along the course (1e-7 rad/m at mid
    // latitudes, 2e-4 rad/m 5 km from a pole), which is the east-north frame's own turning. Only
    // kelvin_wake_at's fades apply (ahead of the ship, past the wake's length, outside the
    // wedge), not coordinates()' cuts at the half-width and the track's start. Empty waves where
    // the ship is too slow.
    ocean::KelvinWakeSample sample(const Coordinates& c) const;
    std::vector<GeoPoint> past_track() const;
    GeoBounds bounds() const;

   private:
    friend class ShipWake;
    struct Data;  // the geodesic, the past track's segments, the wake's parameters
    explicit Instant(std::shared_ptr<const Data> data);
    std::shared_ptr<const Data> data_;
    double time_ = 0.0;
    State ship_;
  };
  Instant at(double time) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  WakeSettings settings_;
  ocean::KelvinWakeParams params_;
};

}  // namespace thalassa
