// The atmosphere's ray-sphere intersections in their stiff regions (issue 7, point 2, last item;
// DESIGN section 4, "Numerics"): DistanceToTopAtmosphereBoundary,
// DistanceToBottomAtmosphereBoundary, RayIntersectsGround and the transmittance table's
// parameterisation of shaders/atmosphere/model.glsl, compiled as C++ in double, against the same
// geometry evaluated in binary128 (__float128, 113-bit significand) on exactly the same double
// inputs. Swept: the camera near the ground (r -> bottom) looking down, rays grazing the ground
// from either side (mu -> mu_horizon = -sqrt(1 - (bottom / r)^2)), the camera near the top
// (r -> top) looking up, and rays tangent to the top (mu -> 0 at the top). The GPU (float)
// versions are compared over the same regions in tests/gpu/numerics_test.cpp; docs/numerics.md,
// section 6, tabulates both. Prints the table:
//   build/tests/unit_tests --gtest_filter='AtmosphereNumerics*'
//
// Units: radii and distances in metres, mu a cosine. Relative errors are |value - reference| /
// |reference|.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "model_reference.hpp"

namespace thalassa::glsl {
namespace {

using Quad = __float128;

// Earth's mean radius (m) and a 60 km atmosphere, as AtmosphereParameters::earth().
constexpr double kBottom = 6371008.8;
constexpr double kTop = kBottom + 60000.0;
constexpr double kEpsilon = 1.1102230246251565e-16;  // double's unit roundoff, 2^-53

AtmosphereParameters Earth() {
  AtmosphereParameters a{};
  a.bottom_radius = kBottom;
  a.top_radius = kTop;
  return a;
}

// sqrt in binary128 without libquadmath: two Newton steps from the double root (53 -> 106 ->
// 212 correct bits, beyond binary128's 113).
Quad SqrtQ(Quad a) {
  if (a <= 0) return 0;
  Quad x = std::sqrt(static_cast<double>(a));
  x = (x + a / x) / 2;
  x = (x + a / x) / 2;
  return x;
}

// The printed roots r mu +- sqrt(r^2 (mu^2 - 1) + R^2) of |x + d v| = R (with the sign of the
// ray: d = -r mu +- sqrt(...)), in binary128 on the given doubles: the products of two doubles
// are exact in it, and the cancellations below lose at most 1e14 (47 bits) of its 113.
Quad DiscriminantQ(double r, double mu, double radius) {
  const Quad rq = r, muq = mu, radius_q = radius;
  return rq * rq * (muq * muq - 1) + radius_q * radius_q;
}
Quad DistanceToTopQ(double r, double mu) {
  return -Quad(r) * mu + SqrtQ(DiscriminantQ(r, mu, kTop));
}
Quad DistanceToBottomQ(double r, double mu) {
  return -Quad(r) * mu - SqrtQ(DiscriminantQ(r, mu, kBottom));
}

// The printed form in double, for the "before" column: r^2 (mu^2 - 1) + R^2 cancels two squares
// of 4e13 m^2.
double PrintedDistanceToBottom(double r, double mu) {
  return -r * mu - std::sqrt(std::max(r * r * (mu * mu - 1.0) + kBottom * kBottom, 0.0));
}
// The form before this change: the discriminant (R - r)(R + r) + (r mu)^2 (no cancellation of
// the squares), but the near root -r mu - sqrt(disc) still a difference of two nearly equal
// numbers when the camera is low and looks down.
double PreviousDistanceToBottom(double r, double mu) {
  return std::max(-r * mu - std::sqrt(std::max(SphereDiscriminant(r, mu, kBottom), 0.0)), 0.0);
}
double PreviousDistanceToTop(double r, double mu) {
  return std::max(-r * mu + std::sqrt(std::max(SphereDiscriminant(r, mu, kTop), 0.0)), 0.0);
}

double Relative(double value, Quad reference) {
  const Quad difference = Quad(value) - reference;
  return static_cast<double>((difference < 0 ? -difference : difference) /
                             (reference < 0 ? -reference : reference));
}

// cos of the horizon's zenith angle at r (< 0), in binary128, and as the double nearest it.
Quad MuHorizonQ(double r) {
  const Quad ratio = Quad(kBottom) / r;
  return -SqrtQ(1 - ratio * ratio);
}

std::string Format(const char* format, double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, x);
  return buffer;
}

// One row of the table: the worst error of a function over a region, the printed form's and the
// previous form's worst over the same inputs, and the bound asserted on the current form.
struct Row {
  Row(std::string f, std::string r, double b)
      : function(std::move(f)), region(std::move(r)), bound(b) {}
  std::string function, region;
  double bound;
  double worst = 0.0, printed = 0.0, previous = 0.0;
  std::string where;
  int samples = 0;
  bool compared = true;  // whether the printed and previous forms are measured too
  void add(double error, double printed_error, double previous_error, const std::string& at) {
    ++samples;
    EXPECT_TRUE(std::isfinite(error)) << function << ", " << region << " at " << at;
    if (!(error <= worst)) {
      worst = error;
      where = at;
    }
    printed = std::max(printed, printed_error);
    previous = std::max(previous, previous_error);
  }
};

std::vector<Row>& Table() {
  static std::vector<Row> table;
  return table;
}

class AtmosphereNumerics : public ::testing::Test {
 protected:
  static void TearDownTestSuite() {
    std::printf(
        "\n| function | region | samples | printed form | previous form | now | at | asserted "
        "|\n|---|---|---|---|---|---|---|---|\n");
    for (const Row& row : Table()) {
      const std::string printed = row.compared ? Format("%.2g", row.printed) : "";
      const std::string previous = row.compared ? Format("%.2g", row.previous) : "";
      std::printf("| %s | %s | %d | %s | %s | %.2g | %s | %.0e |\n", row.function.c_str(),
                  row.region.c_str(), row.samples, printed.c_str(), previous.c_str(), row.worst,
                  row.where.c_str(), row.bound);
    }
    Table().clear();
  }
  static void Finish(const Row& row) {
    EXPECT_LE(row.worst, row.bound) << row.function << ", " << row.region << " at " << row.where;
    Table().push_back(row);
  }
};

// Heights (m) of the camera above the ground, and depths below the top: 1 cm to 10 km.
std::vector<double> Heights() {
  std::vector<double> h;
  for (int k = -8; k <= 16; ++k) h.push_back(std::pow(10.0, k / 4.0));
  return h;
}

// The condition number of the ground's near root with respect to the rounding of its
// discriminant's two terms, (r mu)^2 and (R - r)(R + r): kappa = (r mu)^2 / disc, 1 for rays
// straight down, infinite at the horizon. No form in double does better than eps kappa there.
double Kappa(double r, double mu) {
  return static_cast<double>(Quad(r) * mu * r * mu / DiscriminantQ(r, mu, kBottom));
}

TEST_F(AtmosphereNumerics, DistanceToTheGroundFromALowCamera) {
  // The camera h above the ground looking down, mu from -1 to 1.001 mu_h (kappa up to 500):
  // the near root -r mu - sqrt(disc) ~ h / |mu| is a difference of two numbers of r |mu|, which
  // loses r mu^2 / h ulps (5e8 at h = 1 cm, mu = -1) unless written (r^2 - R^2) / (far root).
  // Errors over 1 + kappa (2 for rays straight down).
  const AtmosphereParameters a = Earth();
  Row row{"DistanceToBottomAtmosphereBoundary",
          "h in [1 cm, 10 km], mu in [-1, 1.001 mu_h]: error / (1 + kappa)", 8 * kEpsilon};
  for (double h : Heights()) {
    const double r = kBottom + h;
    const double mu_h = static_cast<double>(MuHorizonQ(r));
    for (int i = 0; i <= 40; ++i) {
      const double mu = -1.0 + (1.0 + 1.001 * mu_h) * i / 40.0;  // -1 .. 1.001 mu_h
      const Quad reference = DistanceToBottomQ(r, mu);
      const double scale = 1.0 / (1.0 + Kappa(r, mu));
      row.add(Relative(DistanceToBottomAtmosphereBoundary(a, r, mu), reference) * scale,
              Relative(PrintedDistanceToBottom(r, mu), reference) * scale,
              Relative(PreviousDistanceToBottom(r, mu), reference) * scale,
              Format("h = %.3g m, ", h) + Format("mu = %.3g", mu));
    }
  }
  Finish(row);
  // The cancellation was real: the previous form lost more than 1e7 ulps somewhere here.
  EXPECT_GT(row.previous, 1e7 * kEpsilon);
}

TEST_F(AtmosphereNumerics, DistanceToTheGroundAtGrazing) {
  // Rays just below the horizon, mu = mu_h (1 + 10^-k), k = 3..15: the distance tends to the
  // horizon's rho = sqrt(r^2 - R^2) with an infinite derivative in mu, so the result's error is
  // the condition number kappa = (r mu)^2 / disc times the rounding of mu^2 and of
  // (R - r)(R + r): asserted as error <= 8 eps (1 + kappa). Neither form cancels beyond that.
  const AtmosphereParameters a = Earth();
  Row row{"DistanceToBottomAtmosphereBoundary",
          "grazing below the horizon, mu = mu_h (1 + 10^-k), k = 3..15: error / (1 + kappa)",
          8 * kEpsilon};
  for (double h : Heights()) {
    const double r = kBottom + h;
    const Quad mu_h = MuHorizonQ(r);
    for (int k = 3; k <= 15; ++k) {
      const double mu = static_cast<double>(mu_h * (1 + Quad(std::pow(10.0, -k))));
      const Quad disc = DiscriminantQ(r, mu, kBottom);
      if (!(disc > 0) || mu >= static_cast<double>(mu_h)) continue;
      const double kappa = Kappa(r, mu);
      const Quad reference = DistanceToBottomQ(r, mu);
      row.add(Relative(DistanceToBottomAtmosphereBoundary(a, r, mu), reference) / (1.0 + kappa),
              Relative(PrintedDistanceToBottom(r, mu), reference) / (1.0 + kappa),
              Relative(PreviousDistanceToBottom(r, mu), reference) / (1.0 + kappa),
              Format("h = %.3g m, ", h) + Format("k = %.0f", k));
    }
  }
  Finish(row);
}

TEST_F(AtmosphereNumerics, DistanceToTheTopFromNearTheTop) {
  // The camera h below the top looking up (mu in [1e-3, 1]): the far root -r mu + sqrt(disc) ~
  // h / mu cancels like the ground's near root unless written (R^2 - r^2) / (r mu + sqrt(disc)).
  const AtmosphereParameters a = Earth();
  Row row{"DistanceToTopAtmosphereBoundary", "top - r in [1 cm, 10 km], mu in [1e-3, 1]",
          8 * kEpsilon};
  for (double h : Heights()) {
    const double r = kTop - h;
    for (int i = 0; i <= 36; ++i) {
      const double mu = std::pow(10.0, -3.0 + i / 12.0);
      const Quad reference = DistanceToTopQ(r, mu);
      const double printed = -r * mu + std::sqrt(r * r * (mu * mu - 1.0) + kTop * kTop);
      row.add(Relative(DistanceToTopAtmosphereBoundary(a, r, mu), reference),
              Relative(printed, reference), Relative(PreviousDistanceToTop(r, mu), reference),
              Format("top - r = %.3g m, ", h) + Format("mu = %.3g", mu));
    }
  }
  Finish(row);
  EXPECT_GT(row.previous, 1e7 * kEpsilon);
}

TEST_F(AtmosphereNumerics, DistanceToTheTopTangent) {
  // mu -> 0 near the top (mu = +-10^-k, k = 1..12) and rays grazing the ground from above
  // (mu = mu_h (1 - 10^-k)) from low cameras: sums of positive terms or a root of a well-scaled
  // discriminant; no cancellation beyond a few ulps.
  const AtmosphereParameters a = Earth();
  Row tangent{"DistanceToTopAtmosphereBoundary",
              "mu = +-10^-k (k = 1..12), top - r in [1 cm, 10 km]", 8 * kEpsilon};
  Row grazing{"DistanceToTopAtmosphereBoundary",
              "grazing above the horizon, mu = mu_h (1 - 10^-k), h in [1 cm, 10 km]", 8 * kEpsilon};
  for (double h : Heights()) {
    for (int k = 1; k <= 12; ++k) {
      for (double sign : {-1.0, 1.0}) {
        const double r = kTop - h, mu = sign * std::pow(10.0, -k);
        const Quad reference = DistanceToTopQ(r, mu);
        const double printed = -r * mu + std::sqrt(r * r * (mu * mu - 1.0) + kTop * kTop);
        tangent.add(Relative(DistanceToTopAtmosphereBoundary(a, r, mu), reference),
                    Relative(printed, reference), Relative(PreviousDistanceToTop(r, mu), reference),
                    Format("top - r = %.3g m, ", h) + Format("mu = %.0e", mu));
      }
      const double r = kBottom + h;
      const double mu = static_cast<double>(MuHorizonQ(r) * (1 - Quad(std::pow(10.0, -k))));
      const Quad reference = DistanceToTopQ(r, mu);
      const double printed = -r * mu + std::sqrt(r * r * (mu * mu - 1.0) + kTop * kTop);
      grazing.add(Relative(DistanceToTopAtmosphereBoundary(a, r, mu), reference),
                  Relative(printed, reference), Relative(PreviousDistanceToTop(r, mu), reference),
                  Format("h = %.3g m, ", h) + Format("k = %.0f", k));
    }
  }
  Finish(tangent);
  Finish(grazing);
}

TEST_F(AtmosphereNumerics, RayIntersectsGroundAtTheHorizon) {
  // The classification flips at mu_h: it must be right for every double mu farther than a few
  // ulps of mu^2's rounding from it (|mu - mu_h| > 4 eps |mu_h| (1 + 1 / mu_h^2)... bounded
  // here by 8 eps / |mu_h|, the discriminant's rounding over its derivative 2 r^2 |mu|).
  const AtmosphereParameters a = Earth();
  int checked = 0;
  for (double h : Heights()) {
    const double r = kBottom + h;
    const Quad mu_h = MuHorizonQ(r);
    const double tolerance = 8.0 * kEpsilon / -static_cast<double>(mu_h);
    for (int k = 0; k <= 16; ++k) {
      for (double side : {-1.0, 1.0}) {
        const double mu = static_cast<double>(mu_h * (1 + Quad(side * std::pow(10.0, -k))));
        const Quad gap = Quad(mu) - mu_h;
        if (static_cast<double>(gap < 0 ? -gap : gap) <= tolerance * -static_cast<double>(mu_h))
          continue;
        ++checked;
        EXPECT_EQ(RayIntersectsGround(a, r, mu), gap < 0) << "h = " << h << ", k = " << k;
      }
    }
  }
  EXPECT_GT(checked, 500);
}

TEST_F(AtmosphereNumerics, TransmittanceParameterisationAtTheHorizon) {
  // x_mu = (d - d_min) / (d_max - d_min) tends to 1 as mu -> mu_h (d -> d_max = rho + H) and the
  // inverse mu = (H^2 - rho^2 - d^2) / (2 r d) cancels there (to mu_h ~ 0 at the ground): both are
  // measured in absolute terms, x_mu in texels (1 / 255) and mu against the exact round trip.
  const AtmosphereParameters a = Earth();
  const double H = std::sqrt((kTop - kBottom) * (kTop + kBottom));
  Row uv{"GetTransmittanceTextureUvFromRMu, x_mu", "mu from mu_h to 1, h in [1 cm, 10 km]: texels",
         1e-12};
  Row inverse{"GetRMuFromTransmittanceTextureUv, mu",
              "round trip of the previous row: absolute error of mu", 2e-15};
  uv.compared = inverse.compared = false;
  for (double h : Heights()) {
    const double r = kBottom + h;
    const Quad mu_h = MuHorizonQ(r);
    for (int i = 0; i <= 60; ++i) {
      // Half the samples within 1e-6 of the horizon, 10^-k above it.
      const double mu = i < 30 ? static_cast<double>(mu_h * (1 - Quad(std::pow(10.0, -i / 2.0))))
                               : static_cast<double>(mu_h + (1 - mu_h) * Quad(i - 30) / 30);
      const Quad rho = SqrtQ(Quad(r) * r - Quad(kBottom) * kBottom);
      const Quad d = DistanceToTopQ(r, mu);
      const Quad d_min = Quad(kTop) - r, d_max = rho + H;
      const Quad x_mu = (d - d_min) / (d_max - d_min);
      const vec2 texture_uv = GetTransmittanceTextureUvFromRMu(a, r, mu);
      const double x = GetUnitRangeFromTextureCoord(texture_uv.x, TRANSMITTANCE_TEXTURE_WIDTH);
      const double texels =
          std::abs(static_cast<double>(Quad(x) - x_mu)) * (TRANSMITTANCE_TEXTURE_WIDTH - 1);
      const std::string where = Format("h = %.3g m, ", h) + Format("mu = %.6g", mu);
      uv.add(texels, 0.0, 0.0, where);
      double r_back, mu_back;
      GetRMuFromTransmittanceTextureUv(a, texture_uv, r_back, mu_back);
      inverse.add(std::abs(mu_back - mu), 0.0, 0.0, where);
    }
  }
  Finish(uv);
  Finish(inverse);
}

}  // namespace
}  // namespace thalassa::glsl
