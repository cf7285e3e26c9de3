// thalassa — a free-flying camera for interactive viewers and host applications (`thalassa
// view`): motion in the camera's own terms (forward, sideways, climb, turn) turned into the
// scene's camera keys on the planet, in double precision.
//
// The ground speed is proportional to the height and the height changes by a factor per second,
// so that the same keys fly a metre above the waves and across a continent from orbit: at the
// defaults the camera covers half its height of ground a second and doubles its height in one
// second of climbing. Horizontal moves follow the geodesic from the camera's nadir (GeographicLib),
// and the heading turns with the geodesic's azimuth, so that flying "straight on" is a great
// circle and crosses the poles and the antimeridian without a jump.
#pragma once

#include "thalassa/engine/scene.hpp"
#include "thalassa/planet/geodesy.hpp"

namespace thalassa {

// What the user holds or drags, for one step.
struct CameraMotion {
  double forward = 0.0;    // along the heading, [-1, 1] (1: ahead, at full speed)
  double right = 0.0;      // across it, [-1, 1] (1: to the right); (forward, right) is clamped
                           // to length 1, so that a diagonal is no faster
  double climb = 0.0;      // [-1, 1] (1: up)
  double turn_deg = 0.0;   // heading to add, degrees (clockwise; a mouse's drag)
  double pitch_deg = 0.0;  // pitch to add, degrees (up); the pitch is held to [-90, 90]
  double boost = 1.0;      // speed factor for the moves and the climb, > 0 (a held Shift: 5)
};

struct CameraControlSettings {
  // Horizontal speed, camera heights per second, and its floor (m/s) for a camera at the sea.
  double ground_speed = 0.5;
  double min_ground_speed = 1.0;
  // Growth rate of the height while climbing, 1/s: ln 2, the height doubling each second.
  double climb_rate = 0.6931471805599453;
  // The heights a climb or a descent stops at, m: half a metre above the sea at rest (below
  // the waves' crests of a calm sea's views; a camera set lower by a scene stays there until it
  // climbs) and the scene's highest camera.
  double min_height = 0.5;
  double max_height = 1e9;
};

// `camera` after `motion` held for `dt` seconds over `planet`: latitude, longitude, height,
// heading (in [0, 360)) and pitch; roll and the field of view unchanged. Throws
// std::invalid_argument for a dt or a motion that is not finite, a negative dt or a boost that
// is not positive.
CameraSettings move_camera(const Planet& planet, const CameraSettings& camera,
                           const CameraMotion& motion, double dt,
                           const CameraControlSettings& settings = {});

}  // namespace thalassa
