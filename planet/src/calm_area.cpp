// thalassa — calm areas (calm_area.hpp).
#include "thalassa/planet/calm_area.hpp"

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/Gnomonic.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "geodesic_segment.hpp"

namespace thalassa {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw std::invalid_argument("thalassa::CalmArea" + (name.empty() ? "" : " \"" + name + "\"") +
                              ": " + what);
}

// The paper's w(0, 1, x) = 3 x^2 - 2 x^3 on [0, 1], C1 at both ends.
double smooth(double x) {
  const double u = std::clamp(x, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

struct PlanarRing {
  std::vector<double> x, y;  // gnomonic coordinates, m
};

// Crossing-number test of a closed planar ring.
bool inside_ring(const PlanarRing& r, double px, double py) {
  bool in = false;
  const std::size_t n = r.x.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    if ((r.y[i] > py) != (r.y[j] > py)) {
      const double x = r.x[j] + (py - r.y[j]) * (r.x[i] - r.x[j]) / (r.y[i] - r.y[j]);
      if (px < x) in = !in;
    }
  }
  return in;
}

}  // namespace

// An edge's geodesic midpoint (ECEF, m) and half its length (m): for a point P and any point Q
// of the edge, geodesic(P, Q) >= |P - Q| >= |P - M| - |M - Q| >= |P - M| - half, a lower bound
// of P's distance to the edge that lets signed_distance skip the edges that cannot be nearest.
struct EdgeBound {
  std::size_t ring = 0, index = 0;  // the edge from rings[ring][index] to the next vertex
  glm::dvec3 middle{0.0};
  double half = 0.0;
};

struct CalmArea::Impl {
  GeographicLib::Geodesic geodesic;
  GeographicLib::Gnomonic gnomonic;
  Planet planet;
  std::vector<std::vector<GeoPoint>> rings;  // exterior first
  std::vector<PlanarRing> planar;
  std::vector<EdgeBound> edges;
  Impl(const Planet& p)
      : geodesic(p.equatorial_radius(), p.flattening()), gnomonic(geodesic), planet(p) {}
};

CalmArea::CalmArea(const Planet& planet, const CalmAreaSettings& settings)
    : impl_(std::make_unique<Impl>(planet)), settings_(settings) {
  const std::string& name = settings.name;
  if (!std::isfinite(settings.scale) || settings.scale < 0.0 || settings.scale > 1.0)
    fail(name, "scale: expected a number in [0, 1]");
  if (!std::isfinite(settings.fade) || settings.fade < 0.0)
    fail(name, "fade: expected a finite number of metres >= 0");
  impl_->rings.push_back(settings.exterior);
  for (const auto& hole : settings.holes) impl_->rings.push_back(hole);
  // The centre: the normalised mean of the exterior's vertex directions (ECEF).
  glm::dvec3 mean(0.0);
  for (auto& ring : impl_->rings) {
    // Drop a repeated closing vertex and consecutive duplicates.
    std::vector<GeoPoint> clean;
    for (const GeoPoint& p : ring) {
      if (!std::isfinite(p.lat) || !std::isfinite(p.lon) || std::abs(p.lat) > 90.0 ||
          std::abs(p.lon) > 180.0)
        fail(name, "vertex out of range or not finite");
      if (!clean.empty() && clean.back().lat == p.lat && clean.back().lon == p.lon) continue;
      clean.push_back(p);
    }
    if (clean.size() > 1 && clean.front().lat == clean.back().lat &&
        clean.front().lon == clean.back().lon)
      clean.pop_back();
    if (clean.size() < 3) fail(name, "a ring needs at least 3 distinct vertices");
    ring = std::move(clean);
  }
  for (const GeoPoint& p : impl_->rings[0]) mean += glm::normalize(planet.ecef(p.lat, p.lon, 0.0));
  if (!(glm::length(mean) > 1e-9 * static_cast<double>(impl_->rings[0].size())))
    fail(name, "the exterior ring's vertices surround no centre (they balance out on the globe)");
  const Geodetic c = planet.geodetic(glm::normalize(mean) * planet.equatorial_radius());
  centre_ = {c.lat, c.lon};
  for (const auto& ring : impl_->rings) {
    PlanarRing pr;
    for (const GeoPoint& p : ring) {
      double s12;
      impl_->geodesic.Inverse(centre_.lat, centre_.lon, p.lat, p.lon, s12);
      if (!(s12 <= kMaxCalmAreaRadius))
        fail(name, "a vertex is farther than 5000 km from the polygon's centre");
      double x, y, azi, rk;
      impl_->gnomonic.Forward(centre_.lat, centre_.lon, p.lat, p.lon, x, y, azi, rk);
      pr.x.push_back(x);
      pr.y.push_back(y);
    }
    impl_->planar.push_back(std::move(pr));
  }

  // Bounds: the edges' latitude extents and longitude spans (geodesic_segment.hpp), every
  // longitude when a pole is inside.
  double south = 90.0, north = -90.0;
  std::vector<std::pair<double, double>> arcs;
  for (const auto& ring : impl_->rings) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const GeoPoint& a = ring[i];
      const GeoPoint& b = ring[(i + 1) % ring.size()];
      detail::segment_extent(impl_->geodesic, a.lat, a.lon, b.lat, b.lon, south, north, arcs);
    }
  }
  for (std::size_t r = 0; r < impl_->rings.size(); ++r) {
    const auto& ring = impl_->rings[r];
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const GeoPoint& a = ring[i];
      const GeoPoint& b = ring[(i + 1) % ring.size()];
      double s12, azi1, azi2, lat, lon;
      impl_->geodesic.Inverse(a.lat, a.lon, b.lat, b.lon, s12, azi1, azi2);
      impl_->geodesic.Direct(a.lat, a.lon, azi1, 0.5 * s12, lat, lon);
      impl_->edges.push_back({r, i, planet.ecef(lat, lon, 0.0), 0.5 * s12});
    }
  }
  bounds_ = GeoBounds::from_arcs(south, north, arcs);
  if (contains(90.0, 0.0)) bounds_ = {south, 90.0, -180.0, 180.0};
  if (contains(-90.0, 0.0)) bounds_ = {-90.0, bounds_.north, -180.0, 180.0};
}

CalmArea::~CalmArea() = default;
CalmArea::CalmArea(CalmArea&&) noexcept = default;
CalmArea& CalmArea::operator=(CalmArea&&) noexcept = default;
CalmArea::CalmArea(const CalmArea& o)
    : impl_(std::make_unique<Impl>(*o.impl_)),
      settings_(o.settings_),
      centre_(o.centre_),
      bounds_(o.bounds_) {}
CalmArea& CalmArea::operator=(const CalmArea& o) {
  if (this != &o) *this = CalmArea(o);
  return *this;
}

bool CalmArea::contains(double lat, double lon) const {
  if (!std::isfinite(lat) || !std::isfinite(lon)) return false;
  double x, y, azi, rk;
  impl_->gnomonic.Forward(centre_.lat, centre_.lon, lat, lon, x, y, azi, rk);
  if (!(rk > 0.0) || !std::isfinite(x) || !std::isfinite(y)) return false;  // far hemisphere
  if (!inside_ring(impl_->planar[0], x, y)) return false;
  for (std::size_t i = 1; i < impl_->planar.size(); ++i) {
    if (inside_ring(impl_->planar[i], x, y)) return false;
  }
  return true;
}

double CalmArea::signed_distance(double lat, double lon) const {
  if (!std::isfinite(lat) || !std::isfinite(lon)) return -std::numeric_limits<double>::infinity();
  // The edges in the order of their lower bounds (EdgeBound); the search stops at the first
  // edge whose bound is not below the best distance found: the result is the exact minimum.
  const glm::dvec3 p = impl_->planet.ecef(lat, lon, 0.0);
  std::vector<std::pair<double, const EdgeBound*>> order;
  order.reserve(impl_->edges.size());
  for (const EdgeBound& e : impl_->edges)
    order.emplace_back(glm::length(p - e.middle) - e.half, &e);
  std::sort(order.begin(), order.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [bound, e] : order) {
    if (bound >= best) break;
    const auto& ring = impl_->rings[e->ring];
    const GeoPoint& a = ring[e->index];
    const GeoPoint& b = ring[(e->index + 1) % ring.size()];
    const detail::SegmentFoot foot =
        detail::nearest_on_segment(impl_->geodesic, a.lat, a.lon, b.lat, b.lon, lat, lon);
    best = std::min(best, foot.distance);
  }
  return contains(lat, lon) ? best : -best;
}

double calm_fade(double d, double scale, double fade) {
  if (!(d > 0.0)) return 1.0;
  if (!(fade > 0.0) || d >= fade) return scale;
  return 1.0 + (scale - 1.0) * smooth(d / fade);
}

double CalmArea::amplitude_scale(double lat, double lon) const {
  if (!bounds_.contains(lat, lon) || !contains(lat, lon)) return 1.0;
  return calm_fade(signed_distance(lat, lon), settings_.scale, settings_.fade);
}

double calm_amplitude_scale(const std::vector<CalmArea>& areas, double lat, double lon) {
  double s = 1.0;
  for (const CalmArea& area : areas) s *= area.amplitude_scale(lat, lon);
  return s;
}

}  // namespace thalassa
