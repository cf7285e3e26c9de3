// The projected grid (issue 3, point 2; issue 5, point 3): on the flat sea, the Earth's sphere
// and an ellipsoid-like sea, from 1 cm to 19,990 m up, for any heading, pitch and roll, the
// camera looking above the horizon included, the grid covers every pixel that sees the sea
// (but for a hair along the curved horizon), no triangle folds over or degenerates, every vertex
// is finite, in front of the camera and on the sea at rest, on its own image point's ray, and
// the vertices on the sky's side sit just below the horizon (on the sphere, at its distance
// sqrt(h (2R + h))).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sea_surfaces.hpp"
#include "thalassa/ocean/projected_grid.hpp"
#include "thalassa/planet/camera_frame.hpp"

namespace thalassa::ocean {
namespace {

using testing::kEarthRadius;

struct NamedSurface {
  std::string name;
  SeaSurface surface;
};

const std::vector<NamedSurface>& surfaces() {
  static const std::vector<NamedSurface> list = {{"flat", flat_sea_surface()},
                                                 {"sphere", spherical_sea_surface(kEarthRadius)},
                                                 {"ellipsoid-like", testing::ellipsoid_like_sea()}};
  return list;
}

const std::vector<double> kCameraHeights = {0.01, 4.0, 1000.0, 19990.0};  // m

GridCamera make_camera(double heading, double pitch, double roll, int width, int height,
                       double camera_height = 4.0, double fov_y = 45.0,
                       const SeaSurface& surface = {}) {
  const CameraBasis b = camera_basis(heading, pitch, roll);
  return make_grid_camera(b.right, b.up, b.forward, std::tan(0.5 * fov_y * M_PI / 180.0),
                          camera_height, width, height, surface);
}

// Twice the signed area of triangle (a, b, c) in the image plane.
double signed_area(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool inside(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  const double tolerance = -1e-12;
  return signed_area(a, b, p) >= tolerance && signed_area(b, c, p) >= tolerance &&
         signed_area(c, a, p) >= tolerance;
}

// A vertex on the kept rays' boundary (moved there) has a clearance this close to 0; kept ones
// have >= 0. (Newton stops within 1e-13 of the size of the clearance's terms, |b| + sqrt(...),
// up to ~1 below 20 km and ~10 at 36,000 km.)
constexpr double kOnBoundary = 1e-11;

// The ray's tan(dip) over that of the true horizon in its azimuth (sea_surface_horizon_dip), for
// the curved seas; on the flat sea, its z over its component along forward, over
// -kHorizonDepression. >= 1 where the ray meets the sea with the margin; +inf vertical.
double horizon_ratio(const GridCamera& c, const glm::dvec3& ray) {
  const glm::dvec2 horizontal(ray.x, ray.y);
  const double length = glm::length(horizontal);
  const double horizon =
      length > 0.0 ? sea_surface_horizon_dip(c.surface, c.height, horizontal / length) : 0.0;
  if (horizon == 0.0) return -ray.z / glm::dot(ray, c.forward) / kHorizonDepression;
  if (length < 1e-9 * glm::length(ray)) return INFINITY;
  return (-ray.z / length) / horizon;
}

glm::dvec2 pixel_centre(const GridCamera& c, int x, int y) {
  return {2.0 * (x + 0.5) / c.width - 1.0, 1.0 - 2.0 * (y + 0.5) / c.height_px};
}

// An uncovered pixel centre may lie no farther than this (pixels) from the kept rays' boundary:
// the sagitta kappa l^2 / 8 of the horizon conic's chords between moved vertices, in the image
// plane at unit distance, where a pixel spans 0.0173 (45 degrees over 48 pixels), l is up to a
// cell's diagonal (11 pixels) and the conic's curvature kappa about tan(dip) = 0.08 at 20 km:
// 0.02 pixel, more with a wide field of view. The renderer's backstop pass fills them.
constexpr double kMaxUncoveredPixels = 0.04;

struct Summary {
  int cameras = 0;               // cameras that see the sea
  int with_horizon = 0;          // ... with vertices moved onto the horizon
  double worst_uncovered = 0.0;  // pixels from the horizon
  double worst_f = 0.0;          // |f(rest)| / distance
  double worst_ratio = 1.0;      // the moved vertices' largest horizon_ratio
};

// Checks every invariant of the grid of camera c (gtest assertions; the caller checks
// HasFatalFailure).
void check_grid(const GridCamera& c, const ProjectedGrid& g, const std::string& where,
                Summary& summary, double max_uncovered_pixels = kMaxUncoveredPixels) {
  bool any_sea = false;
  for (int y = 0; y < c.height_px && !any_sea; ++y)
    for (int x = 0; x < c.width && !any_sea; ++x) {
      glm::dvec3 point;
      any_sea = sea_point(c, pixel_centre(c, x, y), point);
    }
  if (!any_sea) return;  // e.g. looking up: the sky pass covers it all
  ASSERT_GT(g.rows, 0) << where;
  ++summary.cameras;
  if (g.moved_to_horizon > 0) ++summary.with_horizon;
  const glm::dvec3 camera(0.0, 0.0, c.height);
  int on_boundary = 0;
  for (std::size_t k = 0; k < g.rest.size(); ++k) {
    const glm::dvec3 rest = g.rest[k];
    ASSERT_TRUE(std::isfinite(rest.x) && std::isfinite(rest.y) && std::isfinite(rest.z)) << where;
    ASSERT_TRUE(std::isfinite(g.cell_size[k]) && g.cell_size[k] > 0.0) << where;
    ASSERT_TRUE(std::isfinite(g.image[k].x) && std::isfinite(g.image[k].y)) << where;
    // In front of the camera, on the sea at rest, and on the ray of its image point.
    const glm::dvec3 d = rest - camera;
    ASSERT_GT(glm::dot(d, c.forward), 0.0) << where << " vertex " << k;
    const double f = std::abs(sea_surface_value(c.surface, rest)) / glm::length(d);
    ASSERT_LE(f, 1e-12) << where << " vertex " << k;
    summary.worst_f = std::max(summary.worst_f, f);
    const glm::dvec3 ray = grid_ray(c, g.image[k]);
    ASSERT_LE(glm::length(glm::normalize(ray) - glm::normalize(d)), 1e-9) << where << " " << k;
    // Inside the kept rays' cone, or on its boundary; below the true horizon of its azimuth
    // (flat: by kHorizonDepression), by the margins.
    const double clearance = grid_horizon_clearance(c, ray);
    ASSERT_GE(clearance, -kOnBoundary) << where << " vertex " << k;
    const double ratio = horizon_ratio(c, ray);
    ASSERT_GE(ratio, 1.0 - 1e-9) << where << " vertex " << k;
    if (clearance <= kOnBoundary) {
      ++on_boundary;
      // Just below the horizon: the margins are 1e-9 (curved) and 1e-6 over 1e-6 (flat).
      ASSERT_LE(ratio, 1.0 + 1e-6) << where << " vertex " << k;
      summary.worst_ratio = std::max(summary.worst_ratio, ratio);
    }
  }
  // The moved vertices are exactly those on the boundary.
  ASSERT_EQ(on_boundary, g.moved_to_horizon) << where;
  // No fold-over and no degenerate triangle: all counterclockwise with positive area.
  for (std::size_t t = 0; t < g.indices.size(); t += 3) {
    const double area =
        signed_area(g.image[g.indices[t]], g.image[g.indices[t + 1]], g.image[g.indices[t + 2]]);
    ASSERT_GT(area, 0.0) << where << " triangle " << t;
  }
  // Coverage: rasterise the triangles onto the pixel centres.
  std::vector<char> covered(static_cast<std::size_t>(c.width) * c.height_px, 0);
  for (std::size_t t = 0; t < g.indices.size(); t += 3) {
    const glm::dvec2 a = g.image[g.indices[t]], b = g.image[g.indices[t + 1]],
                     e = g.image[g.indices[t + 2]];
    // Pixel coordinates: x = (u + 1) w / 2 - 0.5, y = (1 - v) h / 2 - 0.5 at centres.
    const double u0 = std::min({a.x, b.x, e.x}), u1 = std::max({a.x, b.x, e.x});
    const double v0 = std::min({a.y, b.y, e.y}), v1 = std::max({a.y, b.y, e.y});
    const int x0 = static_cast<int>(
        std::clamp(std::floor((u0 + 1.0) * c.width / 2.0 - 0.5), 0.0, c.width - 1.0));
    const int x1 =
        static_cast<int>(std::clamp(std::ceil((u1 + 1.0) * c.width / 2.0), 0.0, c.width - 1.0));
    const int y0 = static_cast<int>(
        std::clamp(std::floor((1.0 - v1) * c.height_px / 2.0 - 0.5), 0.0, c.height_px - 1.0));
    const int y1 = static_cast<int>(
        std::clamp(std::ceil((1.0 - v0) * c.height_px / 2.0), 0.0, c.height_px - 1.0));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        if (inside(pixel_centre(c, x, y), a, b, e)) covered[y * c.width + x] = 1;
  }
  for (int y = 0; y < c.height_px; ++y)
    for (int x = 0; x < c.width; ++x) {
      if (covered[y * c.width + x]) continue;
      const glm::dvec2 p = pixel_centre(c, x, y);
      const double clearance = grid_horizon_clearance(c, grid_ray(c, p));
      if (clearance < 0.0) continue;  // outside the kept rays: sky, or within the margins
      // Distance (pixels) to the boundary, from the clearance's gradient per pixel.
      const double step = 1e-3;  // pixels
      const glm::dvec2 du(2.0 * step / c.width, 0.0), dv(0.0, 2.0 * step / c.height_px);
      const double gx = grid_horizon_clearance(c, grid_ray(c, p + du)) -
                        grid_horizon_clearance(c, grid_ray(c, p - du));
      const double gy = grid_horizon_clearance(c, grid_ray(c, p + dv)) -
                        grid_horizon_clearance(c, grid_ray(c, p - dv));
      const double distance = clearance / (std::hypot(gx, gy) / (2.0 * step));
      ASSERT_LE(distance, max_uncovered_pixels) << "pixel " << x << "," << y << " uncovered, "
                                                << distance << " px below the horizon, " << where;
      summary.worst_uncovered = std::max(summary.worst_uncovered, distance);
    }
}

constexpr int kWidth = 64;
constexpr int kHeight = 48;
constexpr double kCell = 8.0;

std::string describe(const NamedSurface& s, double h, double heading, double pitch, double roll,
                     double fov = 45.0) {
  return s.name + " h " + std::to_string(h) + " heading " + std::to_string(heading) + " pitch " +
         std::to_string(pitch) + " roll " + std::to_string(roll) + " fov " + std::to_string(fov);
}

TEST(ProjectedGrid, CoversTheSeaForAnyOrientation) {
  for (const NamedSurface& s : surfaces())
    for (double h : kCameraHeights) {
      Summary summary;
      for (double heading : {0.0, 37.0, 180.0, 300.0})
        for (double pitch : {-90.0, -45.0, -10.0, -1.0, 0.0, 3.0, 15.0, 21.0})
          for (double roll : {-180.0, -90.0, -30.0, 0.0, 10.0, 90.0, 135.0}) {
            const GridCamera c =
                make_camera(heading, pitch, roll, kWidth, kHeight, h, 45.0, s.surface);
            check_grid(c, make_projected_grid(c, kCell, 2), describe(s, h, heading, pitch, roll),
                       summary);
            if (HasFatalFailure()) return;
          }
      std::printf(
          "%-14s h %8.2f m: %3d cameras see the sea, %3d with a horizon; worst uncovered pixel "
          "%.1e px from it; worst |f| / distance %.1e; moved rays' dip / horizon's - 1 <= %.1e\n",
          s.name.c_str(), h, summary.cameras, summary.with_horizon, summary.worst_uncovered,
          summary.worst_f, summary.worst_ratio - 1.0);
      EXPECT_GT(summary.cameras, 100) << s.name << " " << h;
      EXPECT_GT(summary.with_horizon, 50) << s.name << " " << h;  // the horizon was exercised
    }
}

// Wide fields of view looking up, where the horizon in a sky vertex's own azimuth can lie behind
// the camera, and moving vertices down their vertical planes folds the grid over.
TEST(ProjectedGrid, WideFieldsOfViewLookingUp) {
  for (const NamedSurface& s : surfaces())
    for (double h : kCameraHeights) {
      Summary summary;
      for (double fov : {90.0, 120.0, 150.0})
        for (double pitch : {10.0, 30.0, 45.0, 60.0})
          for (double roll : {0.0, 30.0, 90.0, -150.0}) {
            const GridCamera c = make_camera(37.0, pitch, roll, kWidth, kHeight, h, fov, s.surface);
            // The chords' sagitta in pixels grows with the angle a pixel spans.
            check_grid(c, make_projected_grid(c, kCell, 2), describe(s, h, 37.0, pitch, roll, fov),
                       summary, kMaxUncoveredPixels * c.tan_half_fov_y / std::tan(M_PI / 8.0));
            if (HasFatalFailure()) return;
          }
      std::printf(
          "%-14s h %8.2f m, wide: %2d cameras see the sea, %2d with a horizon; worst "
          "uncovered pixel %.1e px from it\n",
          s.name.c_str(), h, summary.cameras, summary.with_horizon, summary.worst_uncovered);
      EXPECT_GT(summary.with_horizon, 20);
    }
}

// The skirt (ocean.vert leaves its ring at rest): only the outer ring is flagged and moved; the
// rest of the grid, its triangles and every cell size are the grid's without it. Each side
// vertex off the horizon and away from the corners goes straight out of its edge by
// reach x focal / its distance along the view axis (pixels, at most 1024), or by the first of its
// halvings whose ray meets the sea no nearer than half that distance or 2 cm (twice the near
// plane; a vertex already nearer, no nearer than it was), and stays where none does;
// and the grid keeps every invariant of check_grid (in front of the camera, on the sea at rest,
// on its image point's ray, no fold, the image covered), at fields of view of 45 and 120 degrees.
TEST(ProjectedGrid, SkirtMovesOnlyTheOuterRingOut) {
  int moved = 0, halved = 0, kept = 0;
  for (const NamedSurface& s : surfaces())
    for (double h : {0.01, 2.0, 4.0, 1000.0})
      for (double reach : {0.3, 3.0, 30.0})
        for (double fov : {45.0, 120.0}) {
          Summary summary;
          for (double heading : {0.0, 37.0})
            for (double pitch : {-90.0, -45.0, -10.0, 0.0, 15.0})
              for (double roll : {-30.0, 0.0, 90.0}) {
                const GridCamera c =
                    make_camera(heading, pitch, roll, kWidth, kHeight, h, fov, s.surface);
                const std::string where =
                    describe(s, h, heading, pitch, roll, fov) + " reach " + std::to_string(reach);
                const ProjectedGrid plain = make_projected_grid(c, kCell, 3);
                const ProjectedGrid g = make_projected_grid(c, kCell, 3, reach);
                if (plain.rows == 0) {
                  EXPECT_EQ(g.rows, 0) << where;
                  continue;
                }
                check_grid(c, g, where, summary,
                           kMaxUncoveredPixels * c.tan_half_fov_y / std::tan(M_PI / 8.0));
                if (HasFatalFailure()) return;
                ASSERT_EQ(g.skirt.size(), g.rest.size()) << where;
                ASSERT_TRUE(plain.skirt.empty()) << where;
                EXPECT_EQ(g.cell_size, plain.cell_size) << where;
                EXPECT_EQ(g.indices, plain.indices) << where;
                const double focal_px = 0.5 * c.height_px / c.tan_half_fov_y;
                const glm::dvec3 camera(0.0, 0.0, h);
                const glm::dvec2 step(2.0 * kCell / c.width, 2.0 * kCell / c.height_px);
                for (int j = 0; j < g.rows; ++j)
                  for (int i = 0; i < g.columns; ++i) {
                    const std::size_t k = static_cast<std::size_t>(j) * g.columns + i;
                    const glm::dvec2 out(i == 0               ? -1
                                         : i == g.columns - 1 ? 1
                                                              : 0,
                                         j == 0            ? -1
                                         : j == g.rows - 1 ? 1
                                                           : 0);
                    const bool ring = out != glm::dvec2(0.0);
                    ASSERT_EQ(g.skirt[k], ring ? 1 : 0) << where << " vertex " << k;
                    // Which may move: a side's, not a corner's or its neighbour's, on the
                    // lattice (not moved onto the horizon).
                    const int along_side = out.x != 0.0 ? j : i;
                    const int side_end = out.x != 0.0 ? g.rows - 1 : g.columns - 1;
                    const glm::dvec2 lattice = glm::dvec2(-1.0) + (glm::dvec2(i, j) - 3.0) * step;
                    const bool eligible = ring && along_side >= 2 && along_side <= side_end - 2 &&
                                          glm::length(plain.image[k] - lattice) < 1e-12;
                    if (!eligible) {
                      ASSERT_EQ(g.rest[k], plain.rest[k]) << where << " vertex " << k;
                      continue;
                    }
                    // The rule's candidates, in order: it took the first that holds (up to
                    // the rounding of the tests at the horizon's and the near limit's edge:
                    // `holds` strictly inside them, `may_hold` within 1e-12 of the horizon's and
                    // 1e-6 of the near limit, relative).
                    const double along = glm::dot(plain.rest[k] - camera, c.forward);
                    const double full = std::min(reach * focal_px / along, 1024.0);
                    const auto candidate = [&](int n, double slack) {
                      const glm::dvec2 image =
                          plain.image[k] +
                          std::ldexp(full, -n) * out * glm::dvec2(2.0 / c.width, 2.0 / c.height_px);
                      glm::dvec3 point;
                      const double nearest = std::min(along, std::max(0.5 * along, 0.02));
                      return grid_horizon_clearance(c, grid_ray(c, image)) > slack &&
                             sea_point(c, image, point) &&
                             glm::dot(point - camera, c.forward) >= nearest * (1.0 + 1e6 * slack);
                    };
                    const auto holds = [&](int n) { return candidate(n, 1e-12); };
                    const auto may_hold = [&](int n) { return candidate(n, -1e-12); };
                    const glm::dvec2 shift = (g.image[k] - plain.image[k]) *
                                             glm::dvec2(0.5 * c.width, 0.5 * c.height_px);
                    if (g.rest[k] == plain.rest[k]) {
                      for (int n = 0; n <= 10; ++n)
                        EXPECT_FALSE(holds(n))
                            << where << " vertex " << k << " kept, halving " << n;
                      ++kept;
                      continue;
                    }
                    const int taken =
                        static_cast<int>(std::lround(std::log2(full / glm::length(shift))));
                    ASSERT_TRUE(taken >= 0 && taken <= 10) << where << " vertex " << k;
                    EXPECT_NEAR(glm::length(shift), std::ldexp(full, -taken),
                                1e-9 * std::ldexp(full, -taken))
                        << where << " vertex " << k;
                    EXPECT_EQ(glm::sign(shift), out) << where << " vertex " << k;
                    EXPECT_TRUE(may_hold(taken)) << where << " vertex " << k;
                    for (int n = 0; n < taken; ++n)
                      EXPECT_FALSE(holds(n)) << where << " vertex " << k << " halving " << n;
                    ++moved;
                    if (taken > 0) ++halved;
                  }
              }
        }
  std::printf(
      "%d skirt vertices moved out (%d by a halving), %d kept where no move meets the "
      "sea in front of them\n",
      moved, halved, kept);
  EXPECT_GT(moved, 10000);
  EXPECT_GT(halved, 100);
}

TEST(ProjectedGrid, NoGridWithoutSeaOrBelowTheSurface) {
  for (const NamedSurface& s : surfaces()) {
    EXPECT_EQ(
        make_projected_grid(make_camera(0, 60, 0, kWidth, kHeight, 4.0, 45.0, s.surface), kCell, 2)
            .rows,
        0);
    for (double h : {-1.0, 0.0})
      EXPECT_EQ(
          make_projected_grid(make_camera(0, -10, 0, kWidth, kHeight, h, 45.0, s.surface), kCell, 2)
              .rows,
          0);
  }
}

TEST(ProjectedGrid, RestPositionsAreTheRayPlaneIntersections) {
  // Looking straight down from 100 m with a 90 degree field: the image's corners see the sea
  // 100 m away along each axis (times the aspect horizontally), the centre right below.
  const GridCamera c = make_camera(0, -90, 0, 64, 64, 100.0, 90.0);
  const ProjectedGrid g = make_projected_grid(c, 8.0, 0);
  ASSERT_EQ(g.columns, 9);
  EXPECT_EQ(g.moved_to_horizon, 0);
  const std::size_t centre = 4 * 9 + 4, corner = 0;
  EXPECT_NEAR(glm::length(g.rest[centre]), 0.0, 1e-9);
  // Image corner (-1, -1): right = east, up = north when looking down with heading 0.
  EXPECT_NEAR(g.rest[corner].x, -100.0, 1e-9);
  EXPECT_NEAR(g.rest[corner].y, -100.0, 1e-9);
  EXPECT_EQ(g.rest[corner].z, 0.0);
  EXPECT_NEAR(g.cell_size[centre], 25.0, 1e-9);  // 8 of 64 pixels over 200 m
  // On the sphere the corner's ray goes on below the plane to meet the sea a sag lower.
  const GridCamera sphere =
      make_camera(0, -90, 0, 64, 64, 100.0, 90.0, spherical_sea_surface(kEarthRadius));
  const glm::dvec3 p = make_projected_grid(sphere, 8.0, 0).rest[corner];
  const double sag = (p.x * p.x + p.y * p.y) / (2.0 * kEarthRadius);
  EXPECT_NEAR(-p.z / sag, 1.0, 1e-6);
  EXPECT_NEAR(p.x / -100.0, 1.0 + sag / 100.0, 1e-9);  // farther along the same ray
}

TEST(ProjectedGrid, SphereHorizonIsAtItsDistance) {
  const SeaSurface sphere = spherical_sea_surface(kEarthRadius);
  for (double h : kCameraHeights) {
    const double horizon = std::sqrt(h * (2.0 * kEarthRadius + h));
    double worst = 0.0;
    int moved = 0;
    for (double heading : {0.0, 37.0, 180.0, 300.0})
      for (double pitch : {-10.0, -1.0, 0.0, 3.0, 15.0, 21.0})
        for (double roll : {-180.0, -30.0, 0.0, 90.0}) {
          const GridCamera c = make_camera(heading, pitch, roll, kWidth, kHeight, h, 45.0, sphere);
          const ProjectedGrid g = make_projected_grid(c, kCell, 2);
          for (std::size_t k = 0; k < g.rest.size(); ++k) {
            if (grid_horizon_clearance(c, grid_ray(c, g.image[k])) > kOnBoundary) continue;
            ++moved;
            const glm::dvec3 d = g.rest[k] - glm::dvec3(0.0, 0.0, h);
            const double error = std::abs(glm::length(d) / horizon - 1.0);
            ASSERT_LE(error, 1e-3) << h << " " << heading << " " << pitch << " " << roll;
            ASSERT_LE(std::abs(sea_surface_value(sphere, g.rest[k])), 1e-12 * glm::length(d));
            worst = std::max(worst, error);
          }
        }
    std::printf("sphere, h %8.2f m: %5d moved vertices at %.6g m, worst relative error %.2e\n", h,
                moved, horizon, worst);
    EXPECT_GT(moved, 100);
  }
}

// At 4 m the curved grid and the flat grid agree near the camera: the same image points (kept
// vertices do not move), the same rays, the curved points a sag d^2 / (2R) lower, hence farther
// along the ray by sag / sin(dip) (horizontally sag / tan(dip): 20 m at 1 km, 250 times the
// sag, since the ray descends 4 m over that km).
TEST(ProjectedGrid, CurvedMatchesFlatNearTheCamera) {
  const double h = 4.0;
  double worst_vertical = 0.0, worst_along = 0.0, largest_horizontal = 0.0;
  int compared = 0;
  for (double heading : {0.0, 37.0, 180.0, 300.0})
    for (double pitch : {-90.0, -45.0, -10.0, -1.0, 0.0, 3.0})
      for (double roll : {-90.0, 0.0, 10.0}) {
        const GridCamera flat = make_camera(heading, pitch, roll, kWidth, kHeight, h);
        const GridCamera curved = make_camera(heading, pitch, roll, kWidth, kHeight, h, 45.0,
                                              spherical_sea_surface(kEarthRadius));
        const ProjectedGrid gf = make_projected_grid(flat, kCell, 2);
        const ProjectedGrid gc = make_projected_grid(curved, kCell, 2);
        ASSERT_EQ(gf.rest.size(), gc.rest.size());
        for (std::size_t k = 0; k < gf.rest.size(); ++k) {
          const glm::dvec3 pf = gf.rest[k], pc = gc.rest[k];
          const double d = glm::length(glm::dvec2(pc));
          if (d > 1000.0 || d < 1.0 ||
              grid_horizon_clearance(curved, grid_ray(curved, gc.image[k])) <= kOnBoundary)
            continue;
          ++compared;
          ASSERT_EQ(gf.image[k], gc.image[k]);
          EXPECT_EQ(pf.z, 0.0);
          const double sag = d * d / (2.0 * kEarthRadius);
          // Vertically: the sag, to its second order d^2 / (4 R^2) (< 1e-8 relative).
          const double vertical = std::abs((pf.z - pc.z) / sag - 1.0);
          ASSERT_LE(vertical, 1e-7) << heading << " " << pitch << " " << roll << " " << d;
          // Along the common ray: the curved point a sag lower, so farther by sag / (-d_z).
          const glm::dvec3 ray = glm::normalize(grid_ray(curved, gc.image[k]));
          const glm::dvec3 camera(0.0, 0.0, h);
          const double along = glm::length(pc - camera) - glm::length(pf - camera);
          const double expected = -pc.z / -ray.z;
          const double along_error = std::abs(along - expected) / expected;
          ASSERT_LE(along_error, 1e-6) << heading << " " << pitch << " " << roll << " " << d;
          worst_vertical = std::max(worst_vertical, vertical);
          worst_along = std::max(worst_along, along_error);
          largest_horizontal = std::max(largest_horizontal, glm::length(glm::dvec2(pc - pf)));
        }
      }
  std::printf(
      "4 m, within 1 km: %d vertices; curved - flat: vertical = sag to %.1e, along the "
      "ray = sag / sin(dip) to %.1e; largest horizontal offset %.2f m\n",
      compared, worst_vertical, worst_along, largest_horizontal);
  EXPECT_GT(compared, 1000);
}

// Why vertices are not moved down their own vertical planes (to the horizon's dip in their
// azimuth): looking up, those planes meet in the zenith's image point, on the sky's side, and
// on a curved horizon column neighbours swap order along it. Upside down (roll 180) and 3
// degrees up at 19,990 m, the cell at column 3, row 5 of the grid has its left column on the
// sky's side and its top right corner in the sea; the vertical-plane rule folds its triangle
// (a, d, c) over, the grid's rule keeps it counterclockwise.
TEST(ProjectedGrid, VerticalPlaneRuleWouldFoldOver) {
  const GridCamera c =
      make_camera(0, 3, -180, kWidth, kHeight, 19990.0, 45.0, spherical_sea_surface(kEarthRadius));
  const ProjectedGrid g = make_projected_grid(c, kCell, 2);
  ASSERT_EQ(g.columns, 13);
  const glm::dvec2 step(2.0 * kCell / kWidth, 2.0 * kCell / kHeight);
  const glm::dvec2 origin = glm::dvec2(-1.0) - 2.0 * step;
  auto vertical_plane = [&](int i, int j) {
    const glm::dvec3 ray = grid_ray(c, origin + glm::dvec2(i, j) * step);
    const glm::dvec2 azimuth = glm::normalize(glm::dvec2(ray));
    if (grid_horizon_clearance(c, ray) >= 0.0) return origin + glm::dvec2(i, j) * step;
    const double tau = sea_surface_horizon_dip(c.surface, c.height, azimuth) * (1.0 + 1e-9);
    const glm::dvec3 d(azimuth, -tau);
    return glm::dvec2(glm::dot(d, c.right) / (glm::dot(d, c.forward) * c.tan_half_fov_y * c.aspect),
                      glm::dot(d, c.up) / (glm::dot(d, c.forward) * c.tan_half_fov_y));
  };
  const int a = 5 * 13 + 3, c_index = 6 * 13 + 3, d = 6 * 13 + 4;
  EXPECT_LT(grid_horizon_clearance(c, grid_ray(c, origin + glm::dvec2(3, 5) * step)), 0.0);
  EXPECT_LT(grid_horizon_clearance(c, grid_ray(c, origin + glm::dvec2(3, 6) * step)), 0.0);
  EXPECT_GT(grid_horizon_clearance(c, grid_ray(c, origin + glm::dvec2(4, 6) * step)), 0.0);
  EXPECT_LT(signed_area(vertical_plane(3, 5), vertical_plane(4, 6), vertical_plane(3, 6)), 0.0);
  EXPECT_GT(signed_area(g.image[a], g.image[d], g.image[c_index]), 0.0);
}

// From 36,000 km the Earth's disc can lie strictly inside the image (every corner and edge sees
// sky), or cross one edge between its corners: the grid must still be made, and cover it.
TEST(ProjectedGrid, SeaInsideTheImageOrAcrossOneEdge) {
  const SeaSurface sphere = spherical_sea_surface(kEarthRadius);
  const double h = 3.6e7;
  Summary summary;
  // The disc is ~10 pixels in radius: with 2-pixel cells the chords between moved vertices
  // (<= 2.8 pixels) leave slivers of up to 2.8^2 / (8 * 10) = 0.1 pixel.
  const double cell = 2.0, sagitta = 0.15;
  // Straight down with 40 degrees: the disc (8.7 degrees in radius) is inside.
  const GridCamera inside = make_camera(0, -90, 0, kWidth, kHeight, h, 40.0, sphere);
  ASSERT_GT(make_projected_grid(inside, cell, 0).rows, 0);
  check_grid(inside, make_projected_grid(inside, cell, 0), "inside", summary, sagitta);
  ASSERT_FALSE(HasFatalFailure());
  // Pitched so that the disc crosses the bottom edge's middle only: the corners see sky.
  const GridCamera edge = make_camera(0, -62.5, 0, kWidth, kHeight, h, 40.0, sphere);
  for (glm::dvec2 corner :
       {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)}) {
    glm::dvec3 point;
    ASSERT_FALSE(sea_point(edge, corner, point));
  }
  ASSERT_GT(make_projected_grid(edge, cell, 0).rows, 0);
  check_grid(edge, make_projected_grid(edge, cell, 0), "edge", summary, sagitta);
  EXPECT_EQ(summary.cameras, 2);
}

// image_sees_sea / image_sees_sky (what the renderer builds its passes from) against a dense
// sampling of the image: a sampled ray that meets the sea (or misses it) must be found by the
// exact test, and every camera whose samples all agree must be decided the same way. The cases
// include the disc from geostationary orbit inside the image, across one edge and missed
// entirely, where border samples alone would miss the inside case.
TEST(ProjectedGrid, ImageSeesSeaAndSkyExactly) {
  constexpr int kSamples = 41;  // per image axis
  int decided_sea = 0, decided_sky = 0, both = 0;
  auto check = [&](const GridCamera& c, const std::string& where) {
    bool sampled_sea = false, sampled_sky = false;
    for (int i = 0; i < kSamples; ++i)
      for (int j = 0; j < kSamples; ++j) {
        const glm::dvec2 p(-1.0 + 2.0 * i / (kSamples - 1), -1.0 + 2.0 * j / (kSamples - 1));
        glm::dvec3 point;
        (sea_point(c, p, point) ? sampled_sea : sampled_sky) = true;
      }
    const bool sea = image_sees_sea(c, glm::dvec2(-1.0), glm::dvec2(1.0));
    const bool sky = image_sees_sky(c, glm::dvec2(-1.0), glm::dvec2(1.0));
    EXPECT_TRUE(sea || !sampled_sea) << where;
    EXPECT_TRUE(sky || !sampled_sky) << where;
    EXPECT_TRUE(sea || sky) << where;
    decided_sea += sea;
    decided_sky += sky;
    both += sea && sky;
  };
  for (const NamedSurface& s : surfaces())
    for (double h : {0.01, 4.0, 19990.0, 4e5, 3.6e7})
      for (double pitch : {-90.0, -62.5, -30.0, -1.0, 0.0, 10.0, 60.0, 90.0})
        for (double roll : {0.0, 45.0, 180.0})
          for (double fov : {1.0, 20.0, 45.0, 150.0}) {
            if (s.name == "flat" && h > 2e4) continue;  // no orbit above a plane
            check(make_camera(37.0, pitch, roll, 64, 48, h, fov, s.surface),
                  describe(s, h, 37.0, pitch, roll, fov));
          }
  std::printf("%d cameras see the sea, %d the sky, %d both\n", decided_sea, decided_sky, both);
  EXPECT_GT(both, 100);
  // Straight down from 36,000 km with a 20 degree field: the Earth's disc (8.7 degrees in radius)
  // lies inside the image, no border ray meets it, and the sky is around it.
  const GridCamera geostationary =
      make_camera(0, -90, 0, 64, 64, 3.6e7, 20.0, spherical_sea_surface(kEarthRadius));
  for (double s : {-1.0, -0.5, 0.0, 0.5, 1.0})
    for (glm::dvec2 border :
         {glm::dvec2(s, -1.0), glm::dvec2(s, 1.0), glm::dvec2(-1.0, s), glm::dvec2(1.0, s)}) {
      glm::dvec3 point;
      ASSERT_FALSE(sea_point(geostationary, border, point));
    }
  EXPECT_TRUE(image_sees_sea(geostationary, glm::dvec2(-1.0), glm::dvec2(1.0)));
  EXPECT_TRUE(image_sees_sky(geostationary, glm::dvec2(-1.0), glm::dvec2(1.0)));
  // Looking straight up from 4 m with 45 degrees: no sea at all.
  const GridCamera up =
      make_camera(0, 90, 0, 64, 48, 4.0, 45.0, spherical_sea_surface(kEarthRadius));
  EXPECT_FALSE(image_sees_sea(up, glm::dvec2(-1.0), glm::dvec2(1.0)));
}


// The ocean node keeps its grid while the camera is the same (ocean_node.cpp, draw_grid): two
// cameras are the same only when every field is, bit for bit, and one with a NaN is none.
TEST(ProjectedGrid, CamerasAreTheSameOnlyWhenEveryFieldIs) {
  const GridCamera a = make_camera(37.0, -10.0, 0.0, 128, 72, 100.0, 45.0,
                                   spherical_sea_surface(kEarthRadius));
  const GridCamera copy = a;
  EXPECT_TRUE(copy == a);
  // The same view's grid, made twice: the same vertices (the cache hands back what a new grid
  // would be).
  const ProjectedGrid g1 = make_projected_grid(a, 1.0, 2), g2 = make_projected_grid(copy, 1.0, 2);
  ASSERT_GT(g1.rows, 0);
  EXPECT_EQ(g1.rest, g2.rest);
  EXPECT_EQ(g1.indices, g2.indices);
  const double ulp = 1.0 + 1e-15;
  std::vector<GridCamera> changed(11, a);
  changed[0].right.x = std::nextafter(a.right.x, 2.0);
  changed[1].up.y = std::nextafter(a.up.y, 2.0);
  changed[2].forward.z = std::nextafter(a.forward.z, 2.0);
  changed[3].tan_half_fov_y *= ulp;
  changed[4].aspect *= ulp;
  changed[5].height *= ulp;
  changed[6].width += 1;
  changed[7].height_px += 1;
  changed[8].surface.curvature[1][1] *= ulp;
  changed[9].surface = flat_sea_surface();
  changed[10].height = std::nan("");
  for (std::size_t k = 0; k < changed.size(); ++k) EXPECT_FALSE(changed[k] == a) << "field " << k;
  EXPECT_FALSE(changed[10] == changed[10]);
}

}  // namespace
}  // namespace thalassa::ocean
