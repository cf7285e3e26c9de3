// thalassa — calm areas (calm_area.hpp).
#include "thalassa/planet/calm_area.hpp"

#include <GeographicLib/Geodesic.hpp>

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

// Squared distance (m^2) from (px, py) to the segment (ax, ay)-(bx, by) of the plane.
double segment_distance2(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double len2 = dx * dx + dy * dy;
  const double t =
      len2 > 0.0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / len2, 0.0, 1.0) : 0.0;
  const double ex = ax + t * dx - px, ey = ay + t * dy - py;
  return ex * ex + ey * ey;
}

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

// A point in the gnomonic projection centred at the area's centre (Karney 2013, sec. 8; what
// GeographicLib::Gnomonic::Forward computes, with the distance from the centre kept).
struct Projected {
  double x = NAN, y = NAN;  // m; NaN beyond the projection's horizon (rk <= 0)
  double rk = 0.0;          // the geodesic scale M12 from the centre
  double s = 0.0;           // m: geodesic distance from the centre
};

struct CalmArea::Impl {
  GeographicLib::Geodesic geodesic;
  Planet planet;
  std::vector<std::vector<GeoPoint>> rings;  // exterior first
  std::vector<PlanarRing> planar;
  std::vector<EdgeBound> edges;
  double radius = 0.0;            // m: the largest geodesic distance of a vertex from the centre
  double straightness = 0.0;      // m: bound on the gnomonic edges' distance from the geodesic ones
  double curvature_radius = 0.0;  // m: 1 / sqrt of the surface's largest Gaussian curvature
  Impl(const Planet& p) : geodesic(p.equatorial_radius(), p.flattening()), planet(p) {
    // K = 1 / (M N) is 1 / b^2 on the equator and b^2 / a^4 at the poles, the extremes.
    const double a = p.equatorial_radius(), b = p.polar_radius();
    curvature_radius = 1.0 / std::sqrt(std::max(1.0 / (b * b), b * b / (a * a * a * a)));
  }
  Projected project(const GeoPoint& centre, double lat, double lon) const {
    Projected q;
    double azi1, azi2, m12, M21, S12;
    geodesic.GenInverse(centre.lat, centre.lon, lat, lon,
                        GeographicLib::Geodesic::DISTANCE | GeographicLib::Geodesic::AZIMUTH |
                            GeographicLib::Geodesic::REDUCEDLENGTH |
                            GeographicLib::Geodesic::GEODESICSCALE,
                        q.s, azi1, azi2, m12, q.rk, M21, S12);
    if (q.rk > 0.0) {
      const double rho = m12 / q.rk;
      double sin_azi, cos_azi;
      GeographicLib::Math::sincosd(azi1, sin_azi, cos_azi);
      q.x = rho * sin_azi;
      q.y = rho * cos_azi;
    }
    return q;
  }
  bool inside(double x, double y) const {
    if (!inside_ring(planar[0], x, y)) return false;
    for (std::size_t i = 1; i < planar.size(); ++i)
      if (inside_ring(planar[i], x, y)) return false;
    return true;
  }
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
      const Projected q = impl_->project(centre_, p.lat, p.lon);
      pr.x.push_back(q.x);
      pr.y.push_back(q.y);
      impl_->radius = std::max(impl_->radius, q.s);
    }
    impl_->planar.push_back(std::move(pr));
  }
  // Karney's lowest-order bound on a gnomonic chord's distance from its geodesic, f (r/2a)^3 r
  // for ends within r of the centre, taken twice for the orders it leaves out.
  const double r = impl_->radius, a = planet.equatorial_radius();
  impl_->straightness = 2.0 * std::abs(planet.flattening()) * std::pow(r / (2.0 * a), 3) * r;

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
  const Projected q = impl_->project(centre_, lat, lon);
  if (!std::isfinite(q.x) || !std::isfinite(q.y)) return false;  // far hemisphere
  return impl_->inside(q.x, q.y);
}

// Let P be the point, d its geodesic distance to the edges, g the planar distance in the
// projection to the straight chords between the projected vertices, delta the straightness
// bound. The projection's scale (plane length over true length) lies in [1, 1/M^2] (radial
// 1/M^2, azimuthal 1/M, M = rk <= 1 on a surface of positive curvature). So
// - d <= g + delta: the chord's nearest point maps to a curve no longer than g, ending within
//   delta of the geodesic edge;
// - g <= sigma (d + delta), sigma = 1/M^2 at its smallest over the true shortest path and the
//   foot's distance from the chord; every point of those lies within S = s_P + g + delta of the
//   centre, where M >= cos(S / R_K) (Sturm comparison of M'' + K M = 0 with K <= 1/R_K^2,
//   M(0) = 1, M'(0) = 0), while S < pi/2 R_K.
// Hence |g - d| <= (sigma - 1)(g + delta) + sigma delta.
CalmArea::DistanceEstimate CalmArea::estimate_signed_distance(double lat, double lon) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!std::isfinite(lat) || !std::isfinite(lon)) return {-kInfinity, kInfinity};
  const Projected q = impl_->project(centre_, lat, lon);
  if (!std::isfinite(q.x) || !std::isfinite(q.y)) return {-kInfinity, kInfinity};
  double g2 = kInfinity;
  for (const PlanarRing& ring : impl_->planar) {
    const std::size_t n = ring.x.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++)
      g2 = std::min(g2, segment_distance2(q.x, q.y, ring.x[j], ring.y[j], ring.x[i], ring.y[i]));
  }
  const double g = std::sqrt(g2);
  const double distance = impl_->inside(q.x, q.y) ? g : -g;
  const double delta = impl_->straightness;
  const double reach = (q.s + g + delta) / impl_->curvature_radius;
  if (!(impl_->radius <= kCalmEstimateMaxRadius) || !(reach < 0.5 * std::numbers::pi))
    return {distance, kInfinity};
  const double sigma = 1.0 / (std::cos(reach) * std::cos(reach));
  return {distance, (sigma - 1.0) * (g + delta) + sigma * delta};
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
