// thalassa — the point of a geodesic segment nearest to a point, on the ellipsoid (private to
// the planet module; used by calm areas and ship tracks). Karney's method ("Algorithms for
// geodesics", J. Geodesy 87, 2013, sec. 8, the interception problem): project the segment's
// ends and the point with the gnomonic projection centred at the current estimate, take the
// foot of the perpendicular in the plane, unproject, repeat. At the fixed point the centre lies
// on the geodesic AB (the geodesics from the centre to A and to B are straight lines through it
// in opposite directions) and the geodesic to the point meets AB at a right angle (azimuths at
// the centre are true), so the answer is exact, not an approximation of the projection.
#pragma once

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/Gnomonic.hpp>

#include <utility>
#include <vector>

namespace thalassa::detail {

struct SegmentFoot {
  double lat = 0.0, lon = 0.0;  // degrees: the nearest point of the segment
  double distance = 0.0;        // m: geodesic distance from the point to it
  double along = 0.0;           // m: geodesic distance from A to it (0 .. length)
  double length = 0.0;          // m: |AB|; along == length exactly for a foot at B
  double azimuth = 0.0;         // degrees: azimuth of the segment A -> B at the foot
  double point_azimuth = 0.0;   // degrees: azimuth of the geodesic foot -> point at the foot
  // degrees: azimuth of the geodesic foot -> point at the point (its direction there, away from
  // the segment; the gradient of the distance to the segment for a foot inside it).
  double azimuth_at_point = 0.0;
  bool at_end = false;  // the foot is A or B (the point is beyond the segment's end)
  int iterations = 0;   // of the gnomonic projection's fixed point (kFootMaxIterations at most)
};

// The most iterations of the gnomonic fixed point: 1-3 from the segment's middle.
inline constexpr int kFootMaxIterations = 30;

// Segments must be shorter than about 1/4 of a meridian (the gnomonic centred on them must see
// both ends); callers check their lengths.
SegmentFoot nearest_on_segment(const GeographicLib::Geodesic& geodesic, double lat_a, double lon_a,
                               double lat_b, double lon_b, double lat_p, double lon_p);

// Grows [south, north] (degrees) by the latitudes the geodesic segment A -> B reaches (its ends
// and, when it lies between them, the geodesic's vertex, where its azimuth is +-90 degrees:
// Clairaut's cos(beta) sin(azi) = sin(azi0) on the auxiliary sphere gives the vertex's reduced
// latitude acos|sin(azi0)|, and tan(lat) = tan(beta) / (1 - f)), and appends its longitude span
// {start, eastward length} (degrees) to `arcs` (a geodesic's longitude is monotonic: sin(azi)
// keeps its sign along it).
void segment_extent(const GeographicLib::Geodesic& geodesic, double lat_a, double lon_a,
                    double lat_b, double lon_b, double& south, double& north,
                    std::vector<std::pair<double, double>>& arcs);

}  // namespace thalassa::detail
