#include "thalassa/planet/nadir_frame.hpp"

#include <algorithm>
#include <cmath>

namespace thalassa {

Geodetic nearest_wave_anchor(double lat_deg, double lon_deg) {
  Geodetic anchor;
  anchor.lat =
      std::clamp(std::round(lat_deg / kWaveAnchorSpacingDeg) * kWaveAnchorSpacingDeg, -90.0, 90.0);
  double lon = std::round(lon_deg / kWaveAnchorSpacingDeg) * kWaveAnchorSpacingDeg;
  lon = std::remainder(lon, 360.0);  // [-180, 180]
  anchor.lon = lon == -180.0 ? 180.0 : lon;
  return anchor;
}

Geodetic kept_wave_anchor(const Planet& planet, const Geodetic& anchor, double lat_deg,
                          double lon_deg) {
  const double distance =
      glm::length(planet.ecef(lat_deg, lon_deg, 0.0) - planet.ecef(anchor.lat, anchor.lon, 0.0));
  if (distance <= kWaveAnchorKeepDistance) return {anchor.lat, anchor.lon, 0.0};
  return nearest_wave_anchor(lat_deg, lon_deg);
}

ocean::SeaSurface planet_sea_surface(const Planet& planet, double lat_deg, double lon_deg) {
  const glm::dvec3 n = planet.ecef(lat_deg, lon_deg, 0.0);
  const EnuBasis enu = planet.enu_basis(lat_deg, lon_deg);
  const double a2 = planet.equatorial_radius() * planet.equatorial_radius();
  const double b2 = planet.polar_radius() * planet.polar_radius();
  const glm::dvec3 a_diagonal(1.0 / a2, 1.0 / a2, 1.0 / b2);
  const double k = glm::length(a_diagonal * n);
  const glm::dvec3 axes[3] = {enu.east, enu.north, enu.up};
  ocean::SeaSurface surface;
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row)
      surface.curvature[col][row] = glm::dot(axes[row], a_diagonal * axes[col]) / k;
  return surface;
}

NadirFrame make_nadir_frame(const Planet& planet, const CameraSettings& camera,
                            const std::optional<Geodetic>& anchor) {
  NadirFrame frame;
  frame.nadir = {camera.lat, camera.lon, 0.0};
  frame.camera_height = camera.height;
  frame.enu = planet.enu_basis(camera.lat, camera.lon);
  frame.sea_surface = planet_sea_surface(planet, camera.lat, camera.lon);
  frame.wave_anchor = anchor ? Geodetic{anchor->lat, anchor->lon, 0.0}
                             : nearest_wave_anchor(camera.lat, camera.lon);
  const LocalFrame chart = planet.local_frame(frame.wave_anchor.lat, frame.wave_anchor.lon, 0.0);
  const glm::dvec3 origin = chart.offset(camera.lat, camera.lon, 0.0);
  frame.wave_origin = {origin.x, origin.y};
  const glm::dvec3 east = chart.direction_to_enu(frame.enu.east);
  const glm::dvec3 north = chart.direction_to_enu(frame.enu.north);
  frame.wave_axes = glm::dmat2(east.x, east.y, north.x, north.y);
  return frame;
}

}  // namespace thalassa
