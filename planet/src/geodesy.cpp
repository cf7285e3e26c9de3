// thalassa — geodesy through GeographicLib (Geocentric, LocalCartesian), double precision.
#include "thalassa/planet/geodesy.hpp"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace thalassa {
namespace {

[[noreturn]] void fail(const char* function, const char* name, double value, const char* expected) {
  std::ostringstream message;
  message.precision(17);
  message << "thalassa::" << function << ": " << name << ": expected " << expected << ", got "
          << value;
  throw std::invalid_argument(message.str());
}

void check_finite(const char* function, const char* name, double value) {
  if (!std::isfinite(value)) fail(function, name, value, "a finite number");
}

// Latitude in degrees: finite and in [-90, 90].
void check_lat(const char* function, double lat_deg) {
  if (!std::isfinite(lat_deg) || lat_deg < -90.0 || lat_deg > 90.0)
    fail(function, "latitude", lat_deg, "a finite number of degrees in [-90, 90]");
}

void check_geodetic(const char* function, double lat_deg, double lon_deg, double height_m) {
  check_lat(function, lat_deg);
  check_finite(function, "longitude (degrees)", lon_deg);
  check_finite(function, "height (m)", height_m);
}

void check_ecef(const char* function, const glm::dvec3& p) {
  check_finite(function, "ECEF x (m)", p.x);
  check_finite(function, "ECEF y (m)", p.y);
  check_finite(function, "ECEF z (m)", p.z);
}

// GeographicLib's rotation M (row-major) takes ENU components to ECEF: its columns are the ENU
// unit vectors in ECEF.
EnuBasis basis_from_rotation(const std::vector<double>& m) {
  return {{m[0], m[3], m[6]}, {m[1], m[4], m[7]}, {m[2], m[5], m[8]}};
}

}  // namespace

// ---------------------------------------------------------------------------------------------
struct Planet::Impl {
  GeographicLib::Geocentric earth;
};

Planet::Planet(PlanetShape shape, double a, double f)
    : impl_(std::make_shared<const Impl>(Impl{GeographicLib::Geocentric(a, f)})),
      shape_(shape),
      a_(a),
      f_(f) {}

Planet::Planet()
    : Planet(PlanetShape::Wgs84, GeographicLib::Constants::WGS84_a(),
             GeographicLib::Constants::WGS84_f()) {}

Planet Planet::wgs84() { return Planet(); }

Planet Planet::sphere(double radius_m) {
  if (!std::isfinite(radius_m) || radius_m <= 0.0)
    fail("Planet::sphere", "radius", radius_m, "a finite positive number of metres");
  return Planet(PlanetShape::Sphere, radius_m, 0.0);
}

Planet::Planet(const PlanetSettings& settings)
    : Planet(settings.shape == PlanetShape::Sphere ? sphere(settings.radius) : wgs84()) {}

glm::dvec3 Planet::ecef(double lat_deg, double lon_deg, double height_m) const {
  check_geodetic("Planet::ecef", lat_deg, lon_deg, height_m);
  glm::dvec3 p;
  impl_->earth.Forward(lat_deg, lon_deg, height_m, p.x, p.y, p.z);
  return p;
}

Geodetic Planet::geodetic(const glm::dvec3& ecef) const {
  check_ecef("Planet::geodetic", ecef);
  Geodetic g;
  impl_->earth.Reverse(ecef.x, ecef.y, ecef.z, g.lat, g.lon, g.height);
  return g;
}

EnuBasis Planet::enu_basis(double lat_deg, double lon_deg) const {
  check_geodetic("Planet::enu_basis", lat_deg, lon_deg, 0.0);
  double x, y, z;
  std::vector<double> m(9);
  impl_->earth.Forward(lat_deg, lon_deg, 0.0, x, y, z, m);
  return basis_from_rotation(m);
}

double Planet::nadir_radius(double lat_deg) const {
  check_lat("Planet::nadir_radius", lat_deg);
  return glm::length(ecef(lat_deg, 0.0, 0.0));
}

double Planet::curvature_radius(double lat_deg) const {
  check_lat("Planet::curvature_radius", lat_deg);
  // M = a (1 - e2) / W^3 (meridian), N = a / W (prime vertical), W = sqrt(1 - e2 sin^2 lat):
  // sqrt(M N) = a sqrt(1 - e2) / W^2 = b / W^2, with b = a (1 - f) the polar radius.
  const double e2 = f_ * (2.0 - f_);
  const double s = std::sin(lat_deg * (GeographicLib::Math::pi() / 180.0));
  return polar_radius() / (1.0 - e2 * s * s);
}

CameraPose Planet::camera_pose(const CameraSettings& camera) const {
  check_geodetic("Planet::camera_pose", camera.lat, camera.lon, camera.height);
  check_finite("Planet::camera_pose", "camera.heading (degrees)", camera.heading);
  check_finite("Planet::camera_pose", "camera.pitch (degrees)", camera.pitch);
  check_finite("Planet::camera_pose", "camera.roll (degrees)", camera.roll);
  CameraPose pose;
  pose.position = {camera.lat, camera.lon, camera.height};
  std::vector<double> m(9);
  impl_->earth.Forward(camera.lat, camera.lon, camera.height, pose.ecef.x, pose.ecef.y, pose.ecef.z,
                       m);
  pose.enu = basis_from_rotation(m);
  pose.local = camera_basis(camera.heading, camera.pitch, camera.roll);
  const auto to_ecef = [&](const glm::dvec3& v) {
    return v.x * pose.enu.east + v.y * pose.enu.north + v.z * pose.enu.up;
  };
  pose.world = {to_ecef(pose.local.right), to_ecef(pose.local.up), to_ecef(pose.local.forward)};
  pose.nadir_radius = nadir_radius(camera.lat);
  pose.curvature_radius = curvature_radius(camera.lat);
  return pose;
}

// ---------------------------------------------------------------------------------------------
struct LocalFrame::Impl {
  GeographicLib::LocalCartesian cartesian;
};

LocalFrame::LocalFrame(const Planet& planet, double lat_deg, double lon_deg, double height_m) {
  check_geodetic("LocalFrame", lat_deg, lon_deg, height_m);
  impl_ = std::make_unique<Impl>(
      Impl{GeographicLib::LocalCartesian(lat_deg, lon_deg, height_m, planet.impl_->earth)});
  origin_ = {lat_deg, lon_deg, height_m};
  std::vector<double> m(9);
  planet.impl_->earth.Forward(lat_deg, lon_deg, height_m, origin_ecef_.x, origin_ecef_.y,
                              origin_ecef_.z, m);
  basis_ = basis_from_rotation(m);
}

LocalFrame::~LocalFrame() = default;
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;
LocalFrame::LocalFrame(const LocalFrame& other)
    : impl_(std::make_unique<Impl>(*other.impl_)),
      origin_(other.origin_),
      origin_ecef_(other.origin_ecef_),
      basis_(other.basis_) {}
LocalFrame& LocalFrame::operator=(const LocalFrame& other) {
  if (this != &other) *this = LocalFrame(other);
  return *this;
}

glm::dvec3 LocalFrame::offset(double lat_deg, double lon_deg, double height_m) const {
  check_geodetic("LocalFrame::offset", lat_deg, lon_deg, height_m);
  // LocalCartesian: both points to ECEF in double, their difference rotated to ENU.
  glm::dvec3 enu;
  impl_->cartesian.Forward(lat_deg, lon_deg, height_m, enu.x, enu.y, enu.z);
  return enu;
}

glm::dvec3 LocalFrame::offset(const glm::dvec3& ecef) const {
  check_ecef("LocalFrame::offset", ecef);
  return direction_to_enu(ecef - origin_ecef_);
}

glm::dvec3 LocalFrame::to_ecef(const glm::dvec3& enu_offset) const {
  return origin_ecef_ + direction_to_ecef(enu_offset);
}

glm::dvec3 LocalFrame::direction_to_ecef(const glm::dvec3& enu) const {
  return enu.x * basis_.east + enu.y * basis_.north + enu.z * basis_.up;
}

glm::dvec3 LocalFrame::direction_to_enu(const glm::dvec3& ecef) const {
  return {glm::dot(ecef, basis_.east), glm::dot(ecef, basis_.north), glm::dot(ecef, basis_.up)};
}

}  // namespace thalassa
