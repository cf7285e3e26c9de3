// thalassa — conservative geodetic bounding regions, for culling features (wakes, calm areas)
// that are not on screen (issue 9, point 5). A region is a latitude band times a longitude
// interval that may cross the antimeridian; a region around a pole has the full longitude range
// and reaches +-90.
//
// Units: degrees. Longitudes in [-180, 180]. `west` is where the interval starts going east,
// `east` where it ends: west <= east is an ordinary interval, west > east one that crosses the
// antimeridian (e.g. west 170, east -170 is 20 degrees wide), and west = -180, east = 180 is
// every longitude.
#pragma once

#include <vector>

namespace thalassa {

struct GeoBounds {
  double south = 90.0;   // degrees; south > north means the empty region
  double north = -90.0;  // degrees
  double west = 0.0;     // degrees, [-180, 180]
  double east = 0.0;     // degrees, [-180, 180]

  bool empty() const { return south > north; }
  bool full_longitude() const { return west == -180.0 && east == 180.0; }
  // Width of the longitude interval, degrees, [0, 360].
  double longitude_span() const;
  // Whether the point (degrees) lies in the region (on its boundary counts as inside).
  bool contains(double lat, double lon) const;
  // Whether two regions share a point (for culling against the screen's own bounds).
  bool intersects(const GeoBounds& other) const;

  // The region grown by `metres` in every direction on an ellipsoid whose equatorial radius is
  // `equatorial_radius` (m) and flattening `flattening`: conservative (the degrees per metre
  // are taken where they are largest: the meridional radius's minimum a (1 - e^2), the parallel
  // circle's radius >= a cos(lat) at the latitude farthest from the equator). A region that then
  // reaches a pole takes every longitude.
  GeoBounds expanded(double metres, double equatorial_radius, double flattening) const;

  // The smallest longitude interval that holds every one of `arcs` (each {start, length}: from
  // `start` eastward over `length` degrees, length in [0, 360]) and the latitude band
  // [south, north]: the complement of the largest longitude gap the arcs leave.
  static GeoBounds from_arcs(double south, double north,
                             const std::vector<std::pair<double, double>>& arcs);
};

}  // namespace thalassa
