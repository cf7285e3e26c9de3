// The sea at rest as a quadric (ocean/include/thalassa/ocean/sea_surface.hpp): the ray distance
// against the quadratic solved in long double, the point returned on the surface, the flat
// limit, the sphere's horizon, the horizon dip's closed form against bisection, the WGS84 C
// against the ECEF ellipsoid, the sag, the normal, and finite answers (or none) for every input,
// from 1 mm to 36,000 km up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sea_surfaces.hpp"
#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/planet/nadir_frame.hpp"

namespace thalassa::ocean {
namespace {

using testing::ellipsoid_like_sea;
using testing::kEarthRadius;
using testing::wgs84_frame;
using thalassa::Planet;
using thalassa::planet_sea_surface;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

const std::vector<double> kHeights = {1e-3, 1.0, 4.0, 100.0, 1e3, 2e4, 4e5, 3.6e7};  // m
const std::vector<double> kAzimuths = {0.0, 30.0, 90.0, 135.0, 200.0, 300.0};        // degrees

struct NamedSurface {
  std::string name;
  SeaSurface surface;
};

std::vector<NamedSurface> curved_surfaces() {
  return {{"sphere", spherical_sea_surface(kEarthRadius)},
          {"ellipsoid-like", ellipsoid_like_sea()},
          {"wgs84 at 45", wgs84_frame(45.0).surface}};
}

glm::dvec2 azimuth_direction(double degrees) {
  return {std::sin(degrees * kDegree), std::cos(degrees * kDegree)};  // clockwise from north
}

// The unit ray of horizontal direction `azimuth` whose dip below the horizontal has tangent tau.
glm::dvec3 dipping_ray(glm::dvec2 azimuth, double tau) {
  return glm::normalize(glm::dvec3(azimuth, -tau));
}

using Real = long double;

struct Quadratic {
  Real a, b, c;
};

// a, b, c of sea_surface.hpp from the same double inputs, in long double.
Quadratic long_double_coefficients(const SeaSurface& s, double height, const glm::dvec3& d) {
  const glm::dmat3& c = s.curvature;
  Real dcd = 0.0L, czd = 0.0L;
  for (int i = 0; i < 3; ++i) {
    czd += Real(c[2][i]) * d[i];
    for (int j = 0; j < 3; ++j) dcd += Real(d[i]) * Real(c[j][i]) * Real(d[j]);
  }
  const Real h = height;
  return {0.5L * dcd, Real(d.z) + h * czd, h * (1.0L + 0.5L * h * Real(c[2][2]))};
}

// f(x) in long double.
Real long_double_value(const SeaSurface& s, const Real x[3]) {
  Real xcx = 0.0L;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) xcx += x[i] * Real(s.curvature[j][i]) * x[j];
  return x[2] + 0.5L * xcx;
}

TEST(SeaSurface, DistanceMatchesLongDoubleAndLiesOnTheSurface) {
  double worst_error = 0.0, worst_conditioned = 0.0, worst_f = 0.0;
  int rays = 0, hits = 0;
  for (const NamedSurface& named : curved_surfaces())
    for (double h : kHeights)
      for (double azimuth_deg : kAzimuths) {
        const glm::dvec2 azimuth = azimuth_direction(azimuth_deg);
        const double tau_h = sea_surface_horizon_dip(named.surface, h, azimuth);
        std::vector<double> taus;
        for (double factor : {1.0 - 1e-9, 1.0 + 1e-9, 1.0 + 1e-6, 1.001, 1.1, 2.0})
          taus.push_back(tau_h * factor);
        for (double dip : {0.1, 0.5, 1.0, 1.5}) taus.push_back(std::tan(dip));
        for (double tau : taus) {
          const glm::dvec3 d = dipping_ray(azimuth, tau);
          const Quadratic q = long_double_coefficients(named.surface, h, d);
          const Real discriminant = q.b * q.b - 4.0L * q.a * q.c;
          const std::optional<double> t = sea_surface_distance(named.surface, h, d);
          ++rays;
          const std::string where =
              named.name + " h " + std::to_string(h) + " azimuth " + std::to_string(azimuth_deg) +
              " tan dip " + std::to_string(tau) + " (horizon " + std::to_string(tau_h) + ")";
          ASSERT_EQ(t.has_value(), q.b < 0.0L && discriminant >= 0.0L) << where;
          if (!t) continue;
          ++hits;
          const Real root = std::sqrt(discriminant);
          const Real reference = 2.0L * q.c / (-q.b + root);
          const double error = double(std::abs(Real(*t) - reference) / reference);
          // The distance's condition number near grazing: |b| / sqrt(b^2 - 4ac).
          const double condition = double(-q.b / root);
          ASSERT_TRUE(std::isfinite(*t) && *t > 0.0) << where;
          ASSERT_LE(error, 1e-15 * (1.0 + condition)) << where;
          worst_error = std::max(worst_error, error);
          worst_conditioned = std::max(worst_conditioned, error / (1.0 + condition));
          // On the surface: f at camera + t d, in long double, relative to the distance.
          const Real x[3] = {Real(*t) * d.x, Real(*t) * d.y, Real(h) + Real(*t) * d.z};
          const double f = double(std::abs(long_double_value(named.surface, x)) / Real(*t));
          // Rounding of t moves the point along the ray, where f changes at the rate
          // sqrt(b^2 - 4ac) <= |b| (up to ~7 at 36,000 km): |f| / t ~ 1e-16 |b|.
          ASSERT_LE(f, 2e-15) << where;
          worst_f = std::max(worst_f, f);
        }
      }
  std::printf(
      "rays %d, hits %d: worst relative distance error %.2e (%.2e per unit of the "
      "condition number), worst |f| / t %.2e\n",
      rays, hits, worst_error, worst_conditioned, worst_f);
}

TEST(SeaSurface, FlatLimit) {
  const SeaSurface flat = flat_sea_surface();
  for (double h : kHeights)
    for (double dip : {1e-6, 1e-3, 0.1, 1.0, kPi / 2}) {
      const glm::dvec3 d = dipping_ray(azimuth_direction(37.0), std::tan(dip));
      const std::optional<double> t = sea_surface_distance(flat, h, d);
      ASSERT_TRUE(t.has_value());
      EXPECT_NEAR(*t / (h / -d.z), 1.0, 4e-16);
    }
  EXPECT_EQ(sea_surface_horizon_dip(flat, 4.0, azimuth_direction(10.0)), 0.0);
  EXPECT_FALSE(sea_surface_distance(flat, 4.0, glm::dvec3(0.0, 1.0, 0.0)).has_value());
  EXPECT_EQ(sea_surface_sag(flat, glm::dvec2(1e6, -3e5)), 0.0);
}

TEST(SeaSurface, SphereHorizon) {
  const double r = kEarthRadius;
  const SeaSurface sphere = spherical_sea_surface(r);
  double worst_dip = 0.0, worst_distance = 0.0;
  for (double h : kHeights)
    for (double azimuth_deg : kAzimuths) {
      const glm::dvec2 azimuth = azimuth_direction(azimuth_deg);
      const double horizon_distance = std::sqrt(h * (2.0 * r + h));
      const double tau_h = sea_surface_horizon_dip(sphere, h, azimuth);
      const double dip_error = std::abs(tau_h / (horizon_distance / r) - 1.0);
      EXPECT_LE(dip_error, 4e-16) << h;
      worst_dip = std::max(worst_dip, dip_error);
      // The grazing ray: b^2 = 4ac to rounding, its double root at the horizon distance.
      const glm::dvec3 grazing = dipping_ray(azimuth, tau_h);
      const glm::dvec3 q = sea_surface_ray_coefficients(sphere, h, grazing);
      EXPECT_LE(std::abs(q.y * q.y - 4.0 * q.x * q.z), 1e-15 * q.y * q.y) << h;
      EXPECT_NEAR(-q.y / (2.0 * q.x) / horizon_distance, 1.0, 1e-15) << h;
      // Just above the horizon the ray misses; just below it meets the sea at the horizon.
      EXPECT_FALSE(sea_surface_distance(sphere, h, dipping_ray(azimuth, tau_h * (1.0 - 1e-9))));
      for (double margin : {1e-12, 1e-9}) {
        const std::optional<double> t =
            sea_surface_distance(sphere, h, dipping_ray(azimuth, tau_h * (1.0 + margin)));
        ASSERT_TRUE(t.has_value()) << h << " " << margin;
        // Short of the horizon by a relative sqrt(b^2 - 4ac) / |b| = sqrt(2 margin) cos(dip) =
        // sqrt(2 margin) R / (R + h), to first order in the margin (4e-3 off at 36,000 km).
        const double shortfall = 1.0 - *t / horizon_distance;
        EXPECT_NEAR(shortfall / (std::sqrt(2.0 * margin) * r / (r + h)), 1.0, 1e-2)
            << h << " " << margin;
        if (margin == 1e-9) worst_distance = std::max(worst_distance, shortfall);
      }
    }
  std::printf(
      "sphere: worst horizon dip error %.2e; rays 1e-9 below the horizon's dip meet "
      "the sea short of sqrt(h (2R + h)) by at most %.2e (relative)\n",
      worst_dip, worst_distance);
}

// The largest tan(dip) of azimuth's rays that miss, by bisection on the quadratic's test.
double bisected_horizon(const SeaSurface& s, double h, glm::dvec2 azimuth) {
  auto meets = [&](double tau) {
    const glm::dvec3 q = sea_surface_ray_coefficients(s, h, dipping_ray(azimuth, tau));
    return q.y < 0.0 && q.y * q.y - 4.0 * q.x * q.z >= 0.0;
  };
  double lo = 0.0, hi = 1.0;
  while (!meets(hi)) hi *= 2.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (meets(mid) ? hi : lo) = mid;
  }
  return hi;
}

TEST(SeaSurface, HorizonDipMatchesBisection) {
  double worst = 0.0;
  for (const NamedSurface& named : curved_surfaces())
    for (double h : kHeights)
      for (double azimuth_deg : kAzimuths) {
        const glm::dvec2 azimuth = azimuth_direction(azimuth_deg);
        const double closed = sea_surface_horizon_dip(named.surface, h, azimuth);
        const double bisected = bisected_horizon(named.surface, h, azimuth);
        const double error = std::abs(closed / bisected - 1.0);
        EXPECT_LE(error, 1e-14) << named.name << " " << h << " " << azimuth_deg;
        worst = std::max(worst, error);
      }
  // The ellipsoid's horizon dips differently to the east and to the north (C_xx != C_yy).
  const SeaSurface e = ellipsoid_like_sea();
  EXPECT_GT(std::abs(sea_surface_horizon_dip(e, 1e3, {1.0, 0.0}) /
                         sea_surface_horizon_dip(e, 1e3, {0.0, 1.0}) -
                     1.0),
            1e-3);
  std::printf("horizon dip, closed form against bisection: worst relative difference %.2e\n",
              worst);
}

TEST(SeaSurface, Wgs84CurvatureIsTheEllipsoid) {
  const long double a = testing::kWgs84A, b = a * (1.0L - testing::kWgs84F);
  const long double inverse_squares[3] = {1.0L / (a * a), 1.0L / (a * a), 1.0L / (b * b)};
  double worst = 0.0;
  for (double lat : {0.0, 45.0, -60.0, 89.0}) {
    const testing::Wgs84Frame frame = wgs84_frame(lat);
    // The horizontal block holds the principal curvatures: 1 / N east, 1 / M north.
    const long double e2 = 1.0L - (b * b) / (a * a);
    const long double s = std::sin(lat * kPi / 180.0);
    const long double w = 1.0L - e2 * s * s;
    const long double n = a / std::sqrt(w), m = a * (1.0L - e2) / (w * std::sqrt(w));
    EXPECT_NEAR(frame.surface.curvature[0][0] * double(n), 1.0, 1e-15);
    EXPECT_NEAR(frame.surface.curvature[1][1] * double(m), 1.0, 1e-15);
    EXPECT_EQ(frame.surface.curvature[1][0], 0.0);
    // The planet module's C (through GeographicLib's ENU frame) is the same.
    const SeaSurface planet = planet_sea_surface(Planet::wgs84(), lat, 0.0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(planet.curvature[i][j], frame.surface.curvature[i][j], 1e-22)
            << lat << " " << i << " " << j;
    // Points of the quadric (z the sag) are points of the ellipsoid p^T A p = 1 in ECEF.
    for (double x : {-6e5, -1e3, 0.0, 2.5e4, 5e5})
      for (double y : {-4e5, -7.0, 3e3, 6e5}) {
        const double z = sea_surface_sag(frame.surface, {x, y});
        const long double enu[3] = {x, y, z};
        long double p[3], ap_length2 = 0.0L, pap = 0.0L;
        for (int k = 0; k < 3; ++k) {
          p[k] = frame.nadir[k];
          for (int i = 0; i < 3; ++i) p[k] += frame.axes[i][k] * enu[i];
        }
        for (int k = 0; k < 3; ++k) {
          pap += p[k] * inverse_squares[k] * p[k];
          ap_length2 += (inverse_squares[k] * p[k]) * (inverse_squares[k] * p[k]);
        }
        // Height above the ellipsoid, to first order: (p^T A p - 1) / (2 |A p|).
        const double height = double((pap - 1.0L) / (2.0L * std::sqrt(ap_length2)));
        EXPECT_LE(std::abs(height), 1e-8) << lat << " " << x << " " << y;
        worst = std::max(worst, std::abs(height));
      }
  }
  std::printf("WGS84 C: worst height of the quadric's points above the ellipsoid %.2e m\n", worst);
}

TEST(SeaSurface, SagAndNormalOfTheSphere) {
  const double r = kEarthRadius;
  const SeaSurface sphere = spherical_sea_surface(r);
  for (double rho : {1e-3, 1.0, 1e3, 1e5, 1e6, 0.99 * r}) {
    const double x = 0.6 * rho, y = -0.8 * rho;
    const long double rho2 = (long double)x * x + (long double)y * y;
    const long double exact = -rho2 / (r + std::sqrt((long double)r * r - rho2));
    EXPECT_NEAR(sea_surface_sag(sphere, {x, y}) / double(exact), 1.0, 1e-15) << rho;
    // The normal points away from the centre (0, 0, -r).
    const glm::dvec3 point(x, y, sea_surface_sag(sphere, {x, y}));
    const glm::dvec3 expected = (point - glm::dvec3(0.0, 0.0, -r)) / r;
    EXPECT_LE(glm::length(sea_surface_normal(sphere, point) - expected), 1e-15) << rho;
    EXPECT_LE(std::abs(sea_surface_value(sphere, point)), 1e-15 * std::max(rho, 1.0)) << rho;
  }
  // Beyond the radius the vertical line misses the sphere: its closest approach, the centre.
  EXPECT_EQ(sea_surface_sag(sphere, {2.0 * r, 0.0}), -r);
  EXPECT_EQ(sea_surface_normal(sphere, glm::dvec3(0.0)), glm::dvec3(0.0, 0.0, 1.0));
}

TEST(SeaSurface, FiniteForEveryInput) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<NamedSurface> surfaces = curved_surfaces();
  surfaces.push_back({"flat", flat_sea_surface()});
  // Unit rays (the contract), the zero vector, and a NaN.
  const std::vector<glm::dvec3> rays = {{0.0, 0.0, -1.0}, {0.0, 0.0, 1.0},     {1.0, 0.0, 0.0},
                                        {0.6, 0.8, 0.0},  {0.0, 1.0, -1e-300}, {0.0, 0.0, 0.0},
                                        {nan, 0.0, -1.0}};
  for (const NamedSurface& named : surfaces)
    for (double h : {-inf, -1.0, -0.0, 0.0, 1e-300, 1e-3, 4.0, 3.6e7, 1e300, inf, nan}) {
      // Up to 36,000 km everything is finite; beyond, a distance or a tan(dip) may overflow to
      // +inf (1e300 m over a ray dipping 1e-300), never NaN.
      const bool in_range = std::abs(h) <= 3.6e7;
      for (const glm::dvec3& ray : rays) {
        const std::optional<double> t = sea_surface_distance(named.surface, h, ray);
        if (t) {
          EXPECT_TRUE(!std::isnan(*t) && *t > 0.0) << named.name << " " << h;
          EXPECT_TRUE(!in_range || std::isfinite(*t)) << named.name << " " << h;
          EXPECT_TRUE(h > 0.0 && ray.z < 0.0) << named.name << " " << h;
        }
        const glm::dvec3 q = sea_surface_ray_coefficients(named.surface, h, ray);
        if (in_range && !std::isnan(ray.x)) {
          EXPECT_TRUE(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z));
        }
      }
      for (double azimuth_deg : kAzimuths) {
        const double tau =
            sea_surface_horizon_dip(named.surface, h, azimuth_direction(azimuth_deg));
        EXPECT_TRUE(!std::isnan(tau) && tau >= 0.0) << named.name << " " << h << " " << tau;
        EXPECT_TRUE(!in_range || std::isfinite(tau)) << named.name << " " << h;
      }
    }
  // Below or on the sea, nothing is met, whatever the ray.
  for (const NamedSurface& named : surfaces)
    for (double h : {-1.0, 0.0})
      EXPECT_FALSE(sea_surface_distance(named.surface, h, glm::dvec3(0.0, 0.0, -1.0)));
}

}  // namespace
}  // namespace thalassa::ocean
