// thalassa — calm areas placed by latitude and longitude (issue 9, point 2; docs/wakes.md): a
// geodetic polygon (geodesic edges, holes allowed) inside which the sea's wave amplitudes are
// scaled by a factor, faded in over a distance inside the edge. CPU, double precision, through
// GeographicLib (private dependency).
//
// Inside is the region the ring encloses that holds the polygon's centre (the normalised mean of
// its vertices' directions), i.e. the smaller side: the orientation of the rings does not
// matter (RFC 7946 asks readers to accept both). Works across the antimeridian and around a
// pole. A polygon must fit in a cap of kMaxCalmAreaRadius around its centre.
//
// Amplitude scale at a point at signed distance d (m, > 0 inside) from the polygon's edge:
//   s(d) = 1                                     d <= 0 (outside, on the edge)
//   s(d) = 1 + (scale - 1) w(0, fade, d)        d > 0, w the paper's C1 smoothstep (sec. 3.2)
// so s is 1 outside, `scale` deeper than `fade` inside, continuous with a continuous first
// derivative across the edge and the fade's inner end (a step when fade = 0). The renderer
// multiplies every wave's amplitude h_i by s: geometry and normals directly, and the slope
// variance of eq. 4 through trochoid_slope_variance(wave, w_r s) (wave_set.hpp: the weight
// multiplies h), so that all three levels of the hierarchy change consistently.
#pragma once

#include <memory>
#include <vector>

#include "thalassa/engine/scene.hpp"
#include "thalassa/planet/geo_bounds.hpp"
#include "thalassa/planet/geodesy.hpp"

namespace thalassa {

// Largest distance (m) of a calm area's vertex from its centre: 5000 km (45 degrees of arc),
// well inside the gnomonic projection's hemisphere.
inline constexpr double kMaxCalmAreaRadius = 5.0e6;

// Largest distance (m) of a calm area's vertex from its centre for which
// CalmArea::estimate_signed_distance gives a bound: 1000 km, where the gnomonic straightness
// term's next order is a few percent of it (its ratio about (r / a)^2), well inside the factor 2
// the bound allows.
inline constexpr double kCalmEstimateMaxRadius = 1.0e6;

class CalmArea {
 public:
  // Throws std::invalid_argument for a ring with fewer than 3 distinct vertices, a vertex out of
  // range or not finite, scale outside [0, 1], fade < 0 or not finite, or a polygon too large.
  CalmArea(const Planet& planet, const CalmAreaSettings& settings);
  ~CalmArea();
  CalmArea(const CalmArea&);
  CalmArea& operator=(const CalmArea&);
  CalmArea(CalmArea&&) noexcept;
  CalmArea& operator=(CalmArea&&) noexcept;

  const CalmAreaSettings& settings() const { return settings_; }
  const GeoPoint& centre() const { return centre_; }
  // Whether (lat, lon: degrees) is inside the polygon (in the exterior ring, in no hole).
  bool contains(double lat, double lon) const;
  // Geodesic distance (m) from (lat, lon) to the nearest edge of any ring, positive inside,
  // negative outside (the exact ellipsoidal distance: geodesic_segment.hpp).
  double signed_distance(double lat, double lon) const;
  // A cheaper signed distance and a bound on its error, both m: the planar distance to the
  // rings in the gnomonic projection centred at centre() (one geodesic inverse problem instead
  // of the iterative one per edge that signed_distance solves; the sign is contains()'s).
  // For the sea's calm-area chart (local_features.hpp), which takes it where `error` is small
  // and signed_distance elsewhere. The bound (calm_area.cpp, estimate_signed_distance): the
  // projection's scale lies between 1 and 1/M^2, M the geodesic scale from the centre, which on
  // a surface of Gaussian curvature at most K is at least cos(S sqrt(K)) within S of the centre
  // (Sturm comparison); its geodesics are straight to within f (r / 2a)^3 r (Karney 2013,
  // sec. 8; GeographicLib's Gnomonic), r the vertices' largest distance from the centre. The
  // error is infinite where the bound does not hold: vertices farther than
  // kCalmEstimateMaxRadius from the centre, or a point too far for the cosine.
  // Typical: 1e-5 m at 150 m from the edge of a 2 km slick; 4 cm at 150 m from the edge of a
  // 200 km area, 100 km from its centre.
  struct DistanceEstimate {
    double distance = 0.0;  // m, > 0 inside
    double error = 0.0;     // m, >= 0: |distance - signed_distance| <= error
  };
  DistanceEstimate estimate_signed_distance(double lat, double lon) const;
  // s(d) above: 1 outside, settings().scale deep inside.
  double amplitude_scale(double lat, double lon) const;
  // Conservative bounds of the region where amplitude_scale != 1 (the polygon itself): latitude
  // from the vertices and the geodesic edges' highest points, longitude from the edges' spans,
  // every longitude when a pole is inside.
  const GeoBounds& bounds() const { return bounds_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  CalmAreaSettings settings_;
  GeoPoint centre_;
  GeoBounds bounds_;
};

// The fade s(d) of a signed distance d (m) for a factor and a fade distance (m).
double calm_fade(double signed_distance, double scale, double fade);

// The product of the amplitude scales of all areas at (lat, lon): overlapping areas compound.
double calm_amplitude_scale(const std::vector<CalmArea>& areas, double lat, double lon);

}  // namespace thalassa
