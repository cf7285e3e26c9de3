// thalassa — a ship's wake placed by latitude and longitude (ship_wake.hpp).
#include "thalassa/planet/ship_wake.hpp"

#include <GeographicLib/Geocentric.hpp>
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
// m: closer to the track than this a point's coordinate gradients are the foot's e and n (the
// azimuth of the geodesic from the foot is not defined on the track).
constexpr double kOnTrack = 1e-3;
// m: how far a segment's lower bound may exceed the best distance found and the segment still be
// searched (the bound's chords hold about 1e-9 m through ECEF).
constexpr double kBoundMargin = 1e-6;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw std::invalid_argument("thalassa::ShipWake" + (name.empty() ? "" : " \"" + name + "\"") +
                              ": " + what);
}

bool valid_point(double lat, double lon) {
  return std::isfinite(lat) && std::isfinite(lon) && std::abs(lat) <= 90.0 &&
         std::abs(lon) <= 180.0;
}

}  // namespace

struct ShipWake::Impl {
  GeographicLib::Geodesic geodesic;
  std::vector<double> segment_length;  // m, track form
  std::vector<double> cumulative;      // m from the first point, track form
  explicit Impl(double a, double f) : geodesic(a, f) {}

  // The past track from the ship back to `length` astern (or the track's start): points from
  // the newest (the ship) to the oldest, the geodesic lengths (m) between consecutive ones, and
  // the distance sailed since the start (inf for the position form).
  double past(const WakeSettings& s, const State& st, double time, double length,
              std::vector<GeoPoint>& out, std::vector<double>& lengths) const {
    out.clear();
    lengths.clear();
    out.push_back({st.lat, st.lon});
    if (s.track.empty()) {
      const GeographicLib::GeodesicLine line = geodesic.Line(st.lat, st.lon, st.heading + 180.0);
      double lat, lon;
      line.Position(length, lat, lon);
      out.push_back({lat, lon});
      lengths.push_back(length);
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
      if (d > 0.0) {
        out.push_back({p.lat, p.lon});
        lengths.push_back(d);
      }
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

namespace {

// Two empty waves: kelvin_wake_at's for a ship too slow to make any.
ocean::KelvinWakeSample no_waves(ocean::KelvinWakeParams params) {
  params.speed = 0.0;
  return ocean::kelvin_wake_at(params, 0.0, 0.0);
}

}  // namespace

struct ShipWake::Instant::Data {
  GeographicLib::Geodesic geodesic;
  ocean::KelvinWakeParams params;  // speed: the ship's at the instant
  std::vector<GeoPoint> past;      // the ship first, then the track's points passed
  std::vector<double> length;      // m: of the segment from past[j] (newer) to past[j + 1]
  std::vector<double> behind;      // m: b at past[j], the sum of the lengths before it
  std::vector<glm::dvec3> ecef;    // m: past[j] on the ellipsoid, for the segments' lower bounds
  double sailed = 0.0;             // m since the track's start (inf for the position form)
  double half_width = 0.0;         // m; 0 where there is no wake
  bool wake = false;               // a ship fast enough to make waves
  GeographicLib::Geocentric earth;
  Data(const GeographicLib::Geodesic& g, const ocean::KelvinWakeParams& p)
      : geodesic(g), params(p), earth(g.EquatorialRadius(), g.Flattening()) {}
};

ShipWake::Instant::Instant(std::shared_ptr<const Data> data) : data_(std::move(data)) {}

ShipWake::Instant ShipWake::at(double time) const {
  auto data = std::make_shared<Instant::Data>(impl_->geodesic, params_);
  const State st = ship_at(time);
  if (st.present) {
    data->params.speed = st.speed;
    data->sailed = impl_->past(settings_, st, time, params_.length, data->past, data->length);
    double behind = 0.0;
    for (std::size_t j = 0; j < data->past.size(); ++j) {
      glm::dvec3 x;
      data->earth.Forward(data->past[j].lat, data->past[j].lon, 0.0, x.x, x.y, x.z);
      data->ecef.push_back(x);
      data->behind.push_back(behind);
      if (j < data->length.size()) behind += data->length[j];
    }
    data->wake = st.speed >= ocean::kMinimumWakeSpeed;
    if (data->wake) data->half_width = ocean::kelvin_wake_half_width(data->params);
  }
  Instant instant(std::move(data));
  instant.time_ = time;
  instant.ship_ = st;
  return instant;
}

std::optional<ShipWake::Coordinates> ShipWake::Instant::coordinates(double lat, double lon) const {
  const Data& d = *data_;
  if (!valid_point(lat, lon) || !d.wake) return std::nullopt;
  // The segments in the order of a lower bound of their distance, and the search stops at the
  // first whose bound exceeds the best distance found: the exact minimum, found with one or two
  // searches on a track of many short segments. For a point X of a segment AB of length L,
  // |P - X| >= (|P - A| + |P - B| - L) / 2 (chords are no longer than the geodesics), and the
  // geodesic distance is no shorter than the chord.
  glm::dvec3 p;
  d.earth.Forward(lat, lon, 0.0, p.x, p.y, p.z);
  std::vector<std::pair<double, std::size_t>> order;
  order.reserve(d.length.size());
  for (std::size_t j = 0; j < d.length.size() && d.behind[j] < d.params.length; ++j)
    order.emplace_back(
        0.5 * (glm::length(p - d.ecef[j]) + glm::length(p - d.ecef[j + 1]) - d.length[j]), j);
  std::sort(order.begin(), order.end());
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_segment = 0;
  detail::SegmentFoot best_foot;
  Coordinates c;
  for (const auto& [bound, j] : order) {
    // The margin keeps a segment whose bound only rounding (1e-9 m in ECEF) puts above the best
    // in the search, so that of equally near feet the newer segment's wins as below.
    if (bound > best + kBoundMargin) break;
    // A = the older point, B = the newer: the segment's azimuth is the direction of travel.
    const GeoPoint& newer = d.past[j];
    const GeoPoint& older = d.past[j + 1];
    const detail::SegmentFoot foot = detail::nearest_on_segment(d.geodesic, older.lat, older.lon,
                                                                newer.lat, newer.lon, lat, lon);
    // Of two feet equally near (a turning point of the track), the newer segment's.
    if (foot.distance < best || (foot.distance == best && j < best_segment)) {
      best = foot.distance;
      best_segment = j;
      best_foot = foot;
      c.behind = d.behind[j] + (foot.length - foot.along);  // exactly d.behind[j] at B
      const double side = std::sin((foot.point_azimuth - foot.azimuth) / kDegrees);
      c.lateral = side < 0.0 ? foot.distance : -foot.distance;  // left of travel = port = +
      c.heading = foot.azimuth;
    }
  }
  if (!(best <= d.half_width) || !(c.behind > 0.0) || c.behind >= d.params.length ||
      c.behind >= d.sailed * (1.0 - 1e-12))
    return std::nullopt;
  // The gradients: n at the point is y's (the geodesic from the foot, away from the track to
  // port), e = n turned 90 degrees clockwise. On the track the azimuth at the point is not
  // defined; there they are the foot's.
  glm::dvec2 n;
  if (best < kOnTrack) {
    const double h = c.heading / kDegrees;
    n = glm::dvec2(-std::cos(h), std::sin(h));
  } else {
    const double a = best_foot.azimuth_at_point / kDegrees;
    n = (c.lateral > 0.0 ? 1.0 : -1.0) * glm::dvec2(std::sin(a), std::cos(a));
  }
  c.lateral_gradient = n;
  c.behind_gradient = best_foot.at_end ? glm::dvec2(0.0) : glm::dvec2(-n.y, n.x);
  return c;
}

ocean::KelvinWakeSample ShipWake::Instant::sample(const Coordinates& c) const {
  if (!data_->wake || !std::isfinite(c.heading)) return no_waves(data_->params);
  const ocean::KelvinWakeParams& p = data_->params;
  ocean::KelvinWakeSample s = ocean::kelvin_wake_at(p, c.behind, c.lateral);
  // Ship frame (e, n) -> east-north: e = (sin h, cos h), n = e turned 90 deg counterclockwise.
  const double h = c.heading / kDegrees;
  const glm::dvec2 e(std::sin(h), std::cos(h)), n(-std::cos(h), std::sin(h));
  for (ocean::WakeWave* w : {&s.transverse, &s.divergent})
    w->wave_vector = w->wave_vector.x * e + w->wave_vector.y * n;
  return s;
}

ocean::KelvinWakeSample ShipWake::Instant::sample(double lat, double lon) const {
  const std::optional<Coordinates> c = coordinates(lat, lon);
  return c ? sample(*c) : no_waves(data_->params);
}

std::vector<GeoPoint> ShipWake::Instant::past_track() const { return data_->past; }

GeoBounds ShipWake::Instant::bounds() const {
  const Data& d = *data_;
  if (!d.wake || d.params.amplitude == 0.0) return GeoBounds{};
  double south = 90.0, north = -90.0;
  std::vector<std::pair<double, double>> arcs;
  for (std::size_t j = 0; j + 1 < d.past.size(); ++j)
    detail::segment_extent(d.geodesic, d.past[j + 1].lat, d.past[j + 1].lon, d.past[j].lat,
                           d.past[j].lon, south, north, arcs);
  if (d.past.size() == 1) arcs.emplace_back(d.past[0].lon, 0.0), south = north = d.past[0].lat;
  // 1 m of margin over the half-width: the degrees-per-metre bounds are already conservative.
  return GeoBounds::from_arcs(south, north, arcs)
      .expanded(d.half_width + 1.0, d.geodesic.EquatorialRadius(), d.geodesic.Flattening());
}

std::optional<ShipWake::Coordinates> ShipWake::coordinates(double lat, double lon,
                                                           double time) const {
  return at(time).coordinates(lat, lon);
}

ocean::KelvinWakeSample ShipWake::sample(double lat, double lon, double time) const {
  return at(time).sample(lat, lon);
}

std::vector<GeoPoint> ShipWake::past_track(double time) const { return at(time).past_track(); }

GeoBounds ShipWake::bounds(double time) const { return at(time).bounds(); }

}  // namespace thalassa
