// thalassa — a ship's wake placed by latitude and longitude (ship_wake.hpp).
#include "thalassa/planet/ship_wake.hpp"

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/GeodesicLine.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geodesic_segment.hpp"

namespace thalassa {
namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;
// The fastest ship accepted, m/s (194 knots: beyond any displacement hull; the scene's range).
constexpr double kMaxShipSpeed = 100.0;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw std::invalid_argument("thalassa::ShipWake" + (name.empty() ? "" : " \"" + name + "\"") +
                              ": " + what);
}

bool valid_point(double lat, double lon) {
  return std::isfinite(lat) && std::isfinite(lon) && std::abs(lat) <= 90.0 &&
         std::abs(lon) <= 180.0;
}

struct PolyPoint {
  double lat, lon;
};

}  // namespace

struct ShipWake::Impl {
  GeographicLib::Geodesic geodesic;
  std::vector<double> segment_length;  // m, track form
  std::vector<double> cumulative;      // m from the first point, track form
  explicit Impl(double a, double f) : geodesic(a, f) {}

  // The past track from the ship back to `length` astern (or the track's start): points from
  // the newest (the ship) to the oldest, and the distance sailed since the start (inf for the
  // position form).
  double past(const WakeSettings& s, const State& st, double time, double length,
              std::vector<PolyPoint>& out) const {
    out.clear();
    out.push_back({st.lat, st.lon});
    if (s.track.empty()) {
      const GeographicLib::GeodesicLine line = geodesic.Line(st.lat, st.lon, st.heading + 180.0);
      double lat, lon;
      line.Position(length, lat, lon);
      out.push_back({lat, lon});
      return std::numeric_limits<double>::infinity();
    }
    // The segment the ship is on: the last point with time <= t.
    std::size_t i = static_cast<std::size_t>(
        std::upper_bound(s.track.begin(), s.track.end(), time,
                         [](double t, const TrackPoint& p) { return t < p.time; }) -
        s.track.begin());
    i = std::min(std::max<std::size_t>(i, 1), s.track.size()) - 1;  // point i: time_i <= t
    double sailed_back = 0.0;
    double lat0 = st.lat, lon0 = st.lon;
    for (std::size_t j = i + 1; j-- > 0;) {
      const TrackPoint& p = s.track[j];
      double d;
      geodesic.Inverse(lat0, lon0, p.lat, p.lon, d);
      if (d > 0.0) out.push_back({p.lat, p.lon});
      sailed_back += d;
      lat0 = p.lat;
      lon0 = p.lon;
      if (sailed_back >= length) break;
    }
    double sailed;
    geodesic.Inverse(s.track[i].lat, s.track[i].lon, st.lat, st.lon, sailed);
    return cumulative[i] + sailed;
  }
};

ShipWake::ShipWake(const Planet& planet, const WakeSettings& settings)
    : impl_(std::make_unique<Impl>(planet.equatorial_radius(), planet.flattening())),
      settings_(settings) {
  const std::string& name = settings.name;
  params_.amplitude = settings.amplitude;
  params_.draft = settings.draft;
  params_.length = settings.length;
  params_.speed = settings.speed;
  try {
    (void)ocean::kelvin_wake_half_width(params_);
  } catch (const std::invalid_argument& e) {
    fail(name, e.what());
  }
  if (settings.track.empty()) {
    if (!valid_point(settings.lat, settings.lon)) fail(name, "position out of range or not finite");
    if (!std::isfinite(settings.heading) || !std::isfinite(settings.time))
      fail(name, "heading and time must be finite");
    if (!(settings.speed >= 0.0 && settings.speed <= kMaxShipSpeed))
      fail(name, "speed: expected a number of m/s in [0, 100]");
    return;
  }
  if (settings.track.size() < 2) fail(name, "a track needs at least 2 points");
  impl_->cumulative.push_back(0.0);
  for (std::size_t i = 0; i < settings.track.size(); ++i) {
    const TrackPoint& p = settings.track[i];
    if (!valid_point(p.lat, p.lon) || !std::isfinite(p.time))
      fail(name, "track point " + std::to_string(i) + " out of range or not finite");
    if (i == 0) continue;
    const TrackPoint& q = settings.track[i - 1];
    if (!(p.time > q.time))
      fail(name, "track times must increase strictly (point " + std::to_string(i) + ")");
    double d;
    impl_->geodesic.Inverse(q.lat, q.lon, p.lat, p.lon, d);
    if (!(d <= kMaxTrackSegment))
      fail(name, "track segment " + std::to_string(i - 1) + " is longer than 10000 km");
    impl_->segment_length.push_back(d);
    impl_->cumulative.push_back(impl_->cumulative.back() + d);
  }
}

ShipWake::~ShipWake() = default;
ShipWake::ShipWake(ShipWake&&) noexcept = default;
ShipWake& ShipWake::operator=(ShipWake&&) noexcept = default;
ShipWake::ShipWake(const ShipWake& o)
    : impl_(std::make_unique<Impl>(*o.impl_)), settings_(o.settings_), params_(o.params_) {}
ShipWake& ShipWake::operator=(const ShipWake& o) {
  if (this != &o) *this = ShipWake(o);
  return *this;
}

ShipWake::State ShipWake::ship_at(double time) const {
  State st;
  if (!std::isfinite(time)) return st;
  const WakeSettings& s = settings_;
  if (s.track.empty()) {
    const GeographicLib::GeodesicLine line = impl_->geodesic.Line(s.lat, s.lon, s.heading);
    line.Position(s.speed * (time - s.time), st.lat, st.lon, st.heading);
    st.speed = s.speed;
    st.present = true;
    return st;
  }
  if (time < s.track.front().time || time > s.track.back().time) return st;
  std::size_t i = static_cast<std::size_t>(
      std::upper_bound(s.track.begin(), s.track.end(), time,
                       [](double t, const TrackPoint& p) { return t < p.time; }) -
      s.track.begin());
  i = std::min(i, s.track.size() - 1);  // segment i - 1 .. i
  if (i == 0) i = 1;
  const TrackPoint& a = s.track[i - 1];
  const TrackPoint& b = s.track[i];
  const double fraction = (time - a.time) / (b.time - a.time);
  const GeographicLib::GeodesicLine line = impl_->geodesic.InverseLine(a.lat, a.lon, b.lat, b.lon);
  line.Position(fraction * line.Distance(), st.lat, st.lon, st.heading);
  st.speed = line.Distance() / (b.time - a.time);
  st.present = true;
  return st;
}

std::optional<ShipWake::Coordinates> ShipWake::coordinates(double lat, double lon,
                                                           double time) const {
  if (!valid_point(lat, lon)) return std::nullopt;
  const State st = ship_at(time);
  if (!st.present || st.speed < ocean::kMinimumWakeSpeed) return std::nullopt;
  ocean::KelvinWakeParams p = params_;
  p.speed = st.speed;
  const double width = ocean::kelvin_wake_half_width(p);
  std::vector<PolyPoint> poly;
  const double sailed = impl_->past(settings_, st, time, p.length, poly);
  double best = std::numeric_limits<double>::infinity();
  Coordinates c;
  double behind_so_far = 0.0;
  for (std::size_t j = 0; j + 1 < poly.size() && behind_so_far < p.length; ++j) {
    // A = the older point, B = the newer: the segment's azimuth is the direction of travel.
    const PolyPoint& newer = poly[j];
    const PolyPoint& older = poly[j + 1];
    double len;
    impl_->geodesic.Inverse(older.lat, older.lon, newer.lat, newer.lon, len);
    const detail::SegmentFoot foot = detail::nearest_on_segment(
        impl_->geodesic, older.lat, older.lon, newer.lat, newer.lon, lat, lon);
    if (foot.distance < best) {
      best = foot.distance;
      c.behind = behind_so_far + (len - foot.along);
      const double side = std::sin((foot.point_azimuth - foot.azimuth) / kDegrees);
      c.lateral = side < 0.0 ? foot.distance : -foot.distance;  // left of travel = port = +
      c.heading = foot.azimuth;
    }
    behind_so_far += len;
  }
  if (!(best <= width) || !(c.behind > 0.0) || c.behind >= p.length ||
      c.behind >= sailed * (1.0 - 1e-12))
    return std::nullopt;
  return c;
}

std::vector<GeoPoint> ShipWake::past_track(double time) const {
  const State st = ship_at(time);
  if (!st.present) return {};
  std::vector<PolyPoint> poly;
  impl_->past(settings_, st, time, params_.length, poly);
  std::vector<GeoPoint> out;
  for (const PolyPoint& p : poly) out.push_back({p.lat, p.lon});
  return out;
}

ocean::KelvinWakeSample ShipWake::sample(double lat, double lon, double time) const {
  const std::optional<Coordinates> c = coordinates(lat, lon, time);
  ocean::KelvinWakeParams p = params_;
  if (!c) {
    p.speed = 0.0;
    return ocean::kelvin_wake_at(p, 0.0, 0.0);  // two empty waves
  }
  p.speed = ship_at(time).speed;
  ocean::KelvinWakeSample s = ocean::kelvin_wake_at(p, c->behind, c->lateral);
  // Ship frame (e, n) -> east-north: e = (sin h, cos h), n = e turned 90 deg counterclockwise.
  const double h = c->heading / kDegrees;
  const glm::dvec2 e(std::sin(h), std::cos(h)), n(-std::cos(h), std::sin(h));
  for (ocean::WakeWave* w : {&s.transverse, &s.divergent})
    w->wave_vector = w->wave_vector.x * e + w->wave_vector.y * n;
  return s;
}

GeoBounds ShipWake::bounds(double time) const {
  const State st = ship_at(time);
  if (!st.present || st.speed < ocean::kMinimumWakeSpeed || settings_.amplitude == 0.0)
    return GeoBounds{};
  ocean::KelvinWakeParams p = params_;
  p.speed = st.speed;
  std::vector<PolyPoint> poly;
  impl_->past(settings_, st, time, p.length, poly);
  double south = 90.0, north = -90.0;
  std::vector<std::pair<double, double>> arcs;
  for (std::size_t j = 0; j + 1 < poly.size(); ++j)
    detail::segment_extent(impl_->geodesic, poly[j + 1].lat, poly[j + 1].lon, poly[j].lat,
                           poly[j].lon, south, north, arcs);
  if (poly.size() == 1) arcs.emplace_back(poly[0].lon, 0.0), south = north = poly[0].lat;
  // 1 m of margin over the half-width: the degrees-per-metre bounds are already conservative.
  return GeoBounds::from_arcs(south, north, arcs)
      .expanded(ocean::kelvin_wake_half_width(p) + 1.0, impl_->geodesic.EquatorialRadius(),
                impl_->geodesic.Flattening());
}

}  // namespace thalassa
