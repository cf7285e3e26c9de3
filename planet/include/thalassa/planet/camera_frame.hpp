// thalassa — camera and sun directions in the local east-north-up frame at the camera's nadir
// (x east, y north, z up), from the scene's angles (DESIGN section 4), in double precision.
#pragma once

#include <glm/glm.hpp>

namespace thalassa {

struct CameraBasis {
  glm::dvec3 right;    // unit; image +x
  glm::dvec3 up;       // unit; image +y (toward the top row)
  glm::dvec3 forward;  // unit; the view direction
};

// heading: degrees clockwise from north; pitch: degrees above the horizontal (-90 looks
// straight down); roll: degrees, positive banks to the right (the right side of the image
// goes down, as an aircraft rolling right), so the horizon turns counterclockwise in the image.
// The basis is orthonormal and right-handed (right x up = -forward) at every angle, the
// vertical views included.
CameraBasis camera_basis(double heading_deg, double pitch_deg, double roll_deg);

// Unit vector toward the sun from zenith and azimuth (degrees, azimuth clockwise from north).
glm::dvec3 sun_direction(double zenith_deg, double azimuth_deg);

// Unnormalised direction through the image point (u, v) in [-1, 1]^2 (u right, v up).
glm::dvec3 view_ray(const CameraBasis& basis, double tan_half_fov_y, double aspect, double u,
                    double v);

}  // namespace thalassa
