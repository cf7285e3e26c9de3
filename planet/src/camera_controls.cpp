#include "thalassa/planet/camera_controls.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace thalassa {

namespace {
constexpr double kDegree = 3.14159265358979323846 / 180.0;

// Degrees in [0, 360).
double wrap_degrees(double degrees) {
  const double wrapped = std::fmod(degrees, 360.0);
  return wrapped < 0.0 ? (wrapped + 360.0 < 360.0 ? wrapped + 360.0 : 0.0) : wrapped;
}
}  // namespace

CameraSettings move_camera(const Planet& planet, const CameraSettings& camera,
                           const CameraMotion& motion, double dt,
                           const CameraControlSettings& settings) {
  if (!std::isfinite(dt) || dt < 0.0)
    throw std::invalid_argument("move_camera: expected a finite dt >= 0 s, got " +
                                std::to_string(dt));
  for (const double value : {motion.forward, motion.right, motion.climb, motion.turn_deg,
                             motion.pitch_deg, motion.boost})
    if (!std::isfinite(value)) throw std::invalid_argument("move_camera: expected a finite motion");
  if (!(motion.boost > 0.0))
    throw std::invalid_argument("move_camera: expected a boost > 0, got " +
                                std::to_string(motion.boost));
  CameraSettings next = camera;
  // The view's turn first, so that a drag and a move in one step move along the new heading.
  next.heading = wrap_degrees(camera.heading + motion.turn_deg);
  next.pitch = std::clamp(camera.pitch + motion.pitch_deg, -90.0, 90.0);

  // Along the ground: the geodesic from the nadir at the heading turned toward `right`.
  double forward = std::clamp(motion.forward, -1.0, 1.0);
  double right = std::clamp(motion.right, -1.0, 1.0);
  if (const double length = std::hypot(forward, right); length > 1.0) {
    forward /= length;
    right /= length;
  }
  const double speed =
      std::max(settings.ground_speed * std::abs(camera.height), settings.min_ground_speed) *
      motion.boost;
  const double distance = speed * std::hypot(forward, right) * dt;
  if (distance > 0.0) {
    const double turn = std::atan2(right, forward) / kDegree;  // from the heading, degrees
    const GeographicLib::Geodesic geodesic(planet.equatorial_radius(), planet.flattening());
    double lat = 0.0, lon = 0.0, azimuth_end = 0.0;
    const double azimuth = next.heading + turn;
    geodesic.Direct(camera.lat, camera.lon, azimuth, distance, lat, lon, azimuth_end);
    next.lat = std::clamp(lat, -90.0, 90.0);
    next.lon = std::remainder(lon, 360.0);  // [-180, 180]
    // The heading turns with the geodesic (a great circle flown straight on), and by 180 degrees
    // where it crossed a pole.
    next.heading = wrap_degrees(azimuth_end - turn);
  }

  // Up and down: the height grows or shrinks by exp(rate t), between min_height and max_height;
  // a camera already outside them (a scene's, below the sea say) moves toward them only.
  if (motion.climb != 0.0 && dt > 0.0) {
    const double climb = std::clamp(motion.climb, -1.0, 1.0);
    const double base = std::max(camera.height, settings.min_height);
    double height = base * std::exp(climb * settings.climb_rate * motion.boost * dt);
    height = std::clamp(height, settings.min_height, settings.max_height);
    next.height = climb > 0.0 ? std::max(height, camera.height) : std::min(height, camera.height);
  }
  return next;
}

}  // namespace thalassa
