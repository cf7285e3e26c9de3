// thalassa — the planet's geodesy on the CPU, in double precision (DESIGN sections 3 and 4):
// geodetic latitude / longitude / height <-> ECEF, the local east-north-up (ENU) frames, the
// camera's pose in ECEF and camera-relative offsets for the GPU. Every geodetic conversion goes
// through GeographicLib (a private dependency: this header does not expose it).
//
// Frames and units: latitude and longitude in degrees (geodetic, on the scene's ellipsoid or
// sphere), heights in metres above it (the sea surface is height 0). ECEF: earth-centred,
// earth-fixed, metres, x toward (0, 0), y toward (0, 90 E), z toward the north pole. ENU: east,
// north, up at a point, where up is the ellipsoid normal (the same along the whole normal line,
// so a camera and its nadir share one ENU frame).
//
// Bad input (a latitude outside [-90, 90], a non-finite value, a radius that is not positive)
// throws std::invalid_argument naming the function, the value and what was expected.
#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "thalassa/engine/scene.hpp"
#include "thalassa/planet/camera_frame.hpp"

namespace thalassa {

// A geodetic position.
struct Geodetic {
  double lat = 0.0;     // geodetic latitude, degrees, [-90, 90]
  double lon = 0.0;     // longitude, degrees, (-180, 180] when returned by Planet::geodetic
  double height = 0.0;  // metres above the ellipsoid (sea level)
};

// The local east-north-up frame at a point, as unit vectors in ECEF. Orthonormal and
// right-handed (east x north = up).
struct EnuBasis {
  glm::dvec3 east;   // ECEF unit vector
  glm::dvec3 north;  // ECEF unit vector
  glm::dvec3 up;     // ECEF unit vector: the outward ellipsoid normal
};

class Planet;

// An ENU frame with its origin at a geodetic point (usually the camera): offsets of other points
// from the origin in the ENU axes of the origin's nadir, for camera-relative coordinates on the
// GPU. Through GeographicLib::LocalCartesian: both points go to ECEF in double (absolute error
// a few 1e-9 m at the Earth's radius), the difference is rotated to ENU. The difference of two
// nearby ECEF points loses no relative precision beyond that absolute error, so an offset is
// exact to about 1e-8 m whatever its length (measured: 4.6e-9 m worst for 1 mm offsets from a
// camera at latitudes 0, +-45, +-89.9, 90 and longitude +-180; tests/unit/geodesy_test.cpp).
class LocalFrame {
 public:
  // The origin at (lat, lon: degrees; height: m) on `planet`'s shape.
  LocalFrame(const Planet& planet, double lat_deg, double lon_deg, double height_m);
  ~LocalFrame();
  LocalFrame(const LocalFrame&);
  LocalFrame& operator=(const LocalFrame&);
  LocalFrame(LocalFrame&&) noexcept;
  LocalFrame& operator=(LocalFrame&&) noexcept;

  const Geodetic& origin() const { return origin_; }              // degrees, degrees, m
  const glm::dvec3& origin_ecef() const { return origin_ecef_; }  // m, ECEF
  const EnuBasis& basis() const { return basis_; }                // ECEF unit vectors

  // Offset (m) from the origin to the point (degrees, degrees, m), in the origin's ENU axes.
  glm::dvec3 offset(double lat_deg, double lon_deg, double height_m) const;
  // Offset (m) from the origin to an ECEF point (m), in the origin's ENU axes.
  glm::dvec3 offset(const glm::dvec3& ecef) const;
  // The ECEF point (m) at an ENU offset (m) from the origin.
  glm::dvec3 to_ecef(const glm::dvec3& enu_offset) const;
  // Directions: ENU components -> ECEF and back (rotations only, no translation).
  glm::dvec3 direction_to_ecef(const glm::dvec3& enu) const;
  glm::dvec3 direction_to_enu(const glm::dvec3& ecef) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Geodetic origin_;
  glm::dvec3 origin_ecef_{0.0};
  EnuBasis basis_;
};

// The camera's pose from the scene's camera.* keys.
struct CameraPose {
  Geodetic position;              // camera.lat, camera.lon (degrees), camera.height (m)
  glm::dvec3 ecef{0.0};           // camera position, m, ECEF
  EnuBasis enu;                   // ENU frame at the camera's nadir, ECEF unit vectors
  CameraBasis local;              // right / up / forward in that ENU frame (camera_basis)
  CameraBasis world;              // the same three unit vectors in ECEF
  double nadir_radius = 0.0;      // m: distance from the planet's centre to the nadir point
  double curvature_radius = 0.0;  // m: Gaussian radius of curvature sqrt(M N) at the nadir
};

// The planet's shape: the WGS84 ellipsoid or a sphere (scene key planet.shape). Copies are cheap
// (the GeographicLib state is shared, immutable).
class Planet {
 public:
  Planet();  // WGS84
  explicit Planet(const PlanetSettings& settings);
  static Planet wgs84();
  static Planet sphere(double radius_m);

  PlanetShape shape() const { return shape_; }
  double equatorial_radius() const { return a_; }          // m (the sphere's radius for a sphere)
  double flattening() const { return f_; }                 // dimensionless; 0 for a sphere
  double polar_radius() const { return a_ * (1.0 - f_); }  // m

  // Geodetic (degrees, degrees, m) -> ECEF (m).
  glm::dvec3 ecef(double lat_deg, double lon_deg, double height_m) const;
  glm::dvec3 ecef(const Geodetic& p) const { return ecef(p.lat, p.lon, p.height); }
  // ECEF (m) -> geodetic; longitude in (-180, 180] (0 at the poles), height in m.
  Geodetic geodetic(const glm::dvec3& ecef) const;
  // ENU frame at (lat, lon: degrees) as ECEF unit vectors; up is the ellipsoid normal.
  EnuBasis enu_basis(double lat_deg, double lon_deg) const;
  // Distance (m) from the centre to the surface point at geodetic latitude lat (degrees).
  double nadir_radius(double lat_deg) const;
  // Gaussian radius of curvature sqrt(M N) (m) at geodetic latitude lat (degrees): the radius of
  // the sphere that best fits the surface there (the atmosphere's local sphere).
  double curvature_radius(double lat_deg) const;
  // ENU frame with its origin at (degrees, degrees, m); see LocalFrame.
  LocalFrame local_frame(double lat_deg, double lon_deg, double height_m) const {
    return LocalFrame(*this, lat_deg, lon_deg, height_m);
  }
  // The camera's pose from camera.lat / lon / height / heading / pitch / roll (degrees, m).
  CameraPose camera_pose(const CameraSettings& camera) const;

 private:
  friend class LocalFrame;
  struct Impl;
  Planet(PlanetShape shape, double a, double f);
  std::shared_ptr<const Impl> impl_;
  PlanetShape shape_ = PlanetShape::Wgs84;
  double a_ = 0.0;  // m
  double f_ = 0.0;
};

}  // namespace thalassa
