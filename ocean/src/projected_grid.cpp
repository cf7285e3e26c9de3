// The projected grid on the sea at rest: see ocean/include/thalassa/ocean/projected_grid.hpp for
// the frames, units and the reasoning.
#include "thalassa/ocean/projected_grid.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace thalassa::ocean {
namespace {

// Newton steps onto the kept rays' boundary stop once the clearance is within this fraction of
// |b| + sqrt(...) (the two terms it is the difference of) of 0, four orders inside the margins,
// or within its rounding, kRounding |beta| |ray| (b is a sum of terms up to that size, which
// cancel to ~1e-6 of it near the flat sea's horizon): the moved ray still meets the sea by
// nearly all of the margins (the curved sea's, ~kHorizonMargin |b| / 2, is about 6e-14 |ray| at
// 1 cm up, 20 times kRounding |beta| |ray|; the flat sea's 1e-6 |ray|).
constexpr double kNewtonTolerance = 1e-13;
constexpr double kRounding = 8.0 * 2.220446049250313e-16;
// Newton converges in 1 step on the flat sea (its clearance is linear in the image point), in at
// most 7 (2.4 on average) on the curved seas of the tests; see make_projected_grid for a vertex
// that has not converged after these.
constexpr int kMaxNewtonSteps = 32;

// The cone of kept rays (grid_horizon_clearance) for one camera: clearance(r) = -b(r) -
// sqrt(q(r)), b(r) = beta . r, q(r) = (2 c r^T C r + mu (r . forward)^2) / (1 - kHorizonMargin)
// (2 c r^T C r is 4ac).
struct KeptCone {
  glm::dmat3 curvature{0.0};  // C, 1/m
  glm::dvec3 beta{0.0};       // z-hat + h C z-hat: b = beta . r
  double beta_length = 0.0;
  glm::dvec3 forward{0.0};
  double c = 0.0;   // m: the quadratic's c, h (1 + h C_zz / 2)
  double mu = 0.0;  // kHorizonDepression^2 on the flat sea, 0 on a curved one
};

KeptCone kept_cone(const GridCamera& camera) {
  const glm::dmat3& m = camera.surface.curvature;
  const double h = camera.height;
  // Curved: C positive definite in the horizontal, so every azimuth has a horizon at a finite
  // distance and the relative margin alone keeps the moved rays' points finite.
  const bool curved = m[0][0] > 0.0 && m[0][0] * m[1][1] - m[1][0] * m[1][0] > 0.0;
  KeptCone cone;
  cone.curvature = m;
  cone.beta = glm::dvec3(0.0, 0.0, 1.0) + h * glm::dvec3(m[2]);
  cone.beta_length = glm::length(cone.beta);
  cone.forward = camera.forward;
  cone.c = h * (1.0 + 0.5 * h * m[2][2]);
  cone.mu = curved ? 0.0 : kHorizonDepression * kHorizonDepression;
  return cone;
}

struct Clearance {
  double value = 0.0;        // clearance(r), unnormalised
  double tolerance = 0.0;    // |value| within this: on the boundary (see kNewtonTolerance)
  glm::dvec3 gradient{0.0};  // d clearance / d r
};

Clearance clearance(const KeptCone& k, const glm::dvec3& r) {
  const glm::dvec3 cr = k.curvature * r;
  const double along = glm::dot(r, k.forward);
  const double b = glm::dot(k.beta, r);
  const double q =
      std::max(2.0 * k.c * glm::dot(r, cr) + k.mu * along * along, 0.0) / (1.0 - kHorizonMargin);
  const double root = std::sqrt(q);
  Clearance result;
  result.value = -b - root;
  // |r| bounded by its L1 norm.
  const double r_bound = std::abs(r.x) + std::abs(r.y) + std::abs(r.z);
  result.tolerance = kNewtonTolerance * (std::abs(b) + root) + kRounding * k.beta_length * r_bound;
  result.gradient = -k.beta;
  if (root > 0.0)
    result.gradient -=
        (4.0 * k.c * cr + 2.0 * k.mu * along * k.forward) / (2.0 * (1.0 - kHorizonMargin) * root);
  return result;
}

// Whether the grid keeps the ray: clearance >= 0, that is b < 0 and b^2 >= q (no square root).
bool kept_ray(const KeptCone& k, const glm::dvec3& r) {
  const double b = glm::dot(k.beta, r);
  if (!(b < 0.0)) return false;
  const double along = glm::dot(r, k.forward);
  const double q =
      (2.0 * k.c * glm::dot(r, k.curvature * r) + k.mu * along * along) / (1.0 - kHorizonMargin);
  return b * b >= q;
}

// Whether the ray (any length) from the camera meets the sea at rest: b < 0 and b^2 >= 4ac.
bool meets_sea(const GridCamera& camera, const glm::dvec3& ray) {
  const glm::dvec3 q = sea_surface_ray_coefficients(camera.surface, camera.height, ray);
  return q.y < 0.0 && q.y * q.y - 4.0 * q.x * q.z >= 0.0;
}

// Whether some ray through the image segment from p0 to p1 meets the sea. The rays d0 + s e,
// s in [0, 1], span a plane; those meeting the convex sea form an interval of s whose ends graze
// it, roots of g(s) = b(s)^2 - 4 a(s) c, a quadratic (b is linear in the ray, a quadratic). An
// interval strictly inside (0, 1) has g >= 0 between its ends, so g is concave and its vertex
// -g1 / (2 g2), the ends' midpoint, meets the sea: the ends and that vertex decide, exactly.
bool segment_meets_sea(const GridCamera& camera, glm::dvec2 p0, glm::dvec2 p1) {
  const glm::dvec3 d0 = grid_ray(camera, p0);
  const glm::dvec3 e = grid_ray(camera, p1) - d0;
  if (meets_sea(camera, d0) || meets_sea(camera, d0 + e)) return true;
  const glm::dmat3& m = camera.surface.curvature;
  const double h = camera.height;
  const double c = h * (1.0 + 0.5 * h * m[2][2]);  // the quadratic's c, the same for all rays
  const glm::dvec3 m_z = m[2];                     // C z-hat
  const double b0 = d0.z + h * glm::dot(m_z, d0);
  const double b1 = e.z + h * glm::dot(m_z, e);
  const double g2 = b1 * b1 - 2.0 * c * glm::dot(e, m * e);
  const double g1 = 2.0 * b0 * b1 - 4.0 * c * glm::dot(d0, m * e);
  if (!(g2 < 0.0)) return false;
  const double s = std::clamp(-g1 / (2.0 * g2), 0.0, 1.0);
  return meets_sea(camera, d0 + s * e);
}

// The image point (u, v) of a direction in front of the camera.
glm::dvec2 image_point(const GridCamera& c, const glm::dvec3& direction) {
  const double along = glm::dot(direction, c.forward);
  return {glm::dot(direction, c.right) / (along * c.tan_half_fov_y * c.aspect),
          glm::dot(direction, c.up) / (along * c.tan_half_fov_y)};
}

// The point (m, nadir ENU) at distance t along `ray` from the camera, its z the surface's sag
// at its x, y (the ray's own z, h + t d_z, would carry the rounding of h, 1e-16 h, into a sag
// that can be far smaller).
glm::dvec3 surface_point(const GridCamera& camera, const glm::dvec3& ray, double t) {
  const glm::dvec2 xy(t * ray.x, t * ray.y);
  return {xy, sea_surface_sag(camera.surface, xy)};
}

// m along the view axis: twice the ocean's near plane (shaders/ocean/ocean.vert,
// OCEAN_NEAR_PLANE, 1 cm), which must not clip the skirt. A skirt vertex comes no nearer than half
// its distance, nor than this unless it was already nearer (then not at all).
constexpr double kSkirtNearest = 0.02;

// The outer ring made a skirt (make_projected_grid): flagged, and each of its vertices on a side
// (not a corner or a corner's neighbour) and not on the horizon moved outward in the image,
// perpendicularly to its edge, by reach times the focal length (pixels) over its distance along
// the view axis: about how far a displacement of `reach` moves a point there on screen (more off
// the axis, by up to 1 / cos of the angle, and near the camera). The coverage does not depend on
// that distance: the ring at rest encloses the image wherever it lies, so the displaced mesh
// inside it covers the image. The move spreads the rest positions the triangles between the two
// rings interpolate over about the sea they cover, instead of one cell stretched across a gap.
// At rest each side's quads keep their inner edge and have their outer corners moved straight
// out of it, so none folds; the corner cells keep their skirt one cell out (a diagonal move can
// fold one). The cell sizes are already set.
void add_skirt(const GridCamera& camera, const KeptCone& cone, double reach,
               const std::vector<char>& moved, ProjectedGrid& grid) {
  // The most a skirt vertex moves, pixels: a camera a centimetre over the sea would otherwise
  // move its near ring by thousands of image widths. The cap binds where the ring is nearer than
  // reach times the focal length over it (1.6 m over the 10 m/s sea at 1080 lines and 45
  // degrees; 14 m with a 10 m/s ship's wake in view, whose bound is U^2 / g).
  constexpr double kMaxSkirtPixels = 1024.0;
  // Halvings of the move while the moved ray misses the kept cone (the skirt on the horizon's
  // side of a tilted image) or would come nearer the camera than the vertex's nearest
  // (nearest_along): 2^-10 of the move is below a pixel's thousandth.
  constexpr int kMaxHalvings = 10;
  const auto nearest_along = [](double along) {
    return std::min(along, std::max(0.5 * along, kSkirtNearest));
  };
  grid.skirt.assign(grid.rest.size(), 0);
  const double focal_px = 0.5 * camera.height_px / camera.tan_half_fov_y;
  const glm::dvec3 eye(0.0, 0.0, camera.height);
  const int last_column = grid.columns - 1, last_row = grid.rows - 1;
  for (int j = 0; j <= last_row; ++j)
    for (int i = 0; i <= last_column; ++i) {
      const glm::dvec2 side(i == 0             ? -1.0
                            : i == last_column ? 1.0
                                               : 0.0,
                            j == 0          ? -1.0
                            : j == last_row ? 1.0
                                            : 0.0);
      if (side == glm::dvec2(0.0)) continue;
      const std::size_t k = static_cast<std::size_t>(j) * grid.columns + i;
      grid.skirt[k] = 1;
      const bool near_corner =
          side.x != 0.0 ? j <= 1 || j >= last_row - 1 : i <= 1 || i >= last_column - 1;
      // On the horizon the waves displace nothing (their cells are at least the distance from
      // the nadir, above).
      if (moved[k] || near_corner) continue;
      const double along = glm::dot(grid.rest[k] - eye, camera.forward);
      const double pixels =
          along > 0.0 ? std::min(reach * focal_px / along, kMaxSkirtPixels) : kMaxSkirtPixels;
      // Image units per pixel: 2 / width across, 2 / height up.
      glm::dvec2 move = pixels * side * glm::dvec2(2.0 / camera.width, 2.0 / camera.height_px);
      for (int halvings = 0; halvings <= kMaxHalvings; ++halvings, move *= 0.5) {
        const glm::dvec2 image = grid.image[k] + move;
        glm::dvec3 rest;
        if (!kept_ray(cone, grid_ray(camera, image)) || !sea_point(camera, image, rest)) continue;
        // (A vertex on a flat sea under a camera looking straight down keeps its distance: the
        // rounding of its moved point's must not refuse it.)
        if (!(glm::dot(rest - eye, camera.forward) >= nearest_along(along) * (1.0 - 1e-9)))
          continue;
        grid.image[k] = image;
        grid.rest[k] = rest;
        break;
      }
    }
}

}  // namespace

// The image region whose rays meet the sea is convex: it contains a corner of the rectangle,
// crosses an edge, or lies strictly inside, where it contains the nadir's image point (the nadir
// always meets a convex sea from above).
bool image_sees_sea(const GridCamera& camera, glm::dvec2 lo, glm::dvec2 hi) {
  const glm::dvec2 corners[4] = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  for (int k = 0; k < 4; ++k)
    if (segment_meets_sea(camera, corners[k], corners[(k + 1) % 4])) return true;
  const glm::dvec3 nadir(0.0, 0.0, -1.0);
  if (!(glm::dot(nadir, camera.forward) > 0.0)) return false;
  const glm::dvec2 p = image_point(camera, nadir);
  return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && meets_sea(camera, nadir);
}

// The rectangle lies in the convex region of rays meeting the sea iff its four corners do.
bool image_sees_sky(const GridCamera& camera, glm::dvec2 lo, glm::dvec2 hi) {
  for (const glm::dvec2 corner : {lo, glm::dvec2(hi.x, lo.y), hi, glm::dvec2(lo.x, hi.y)})
    if (!meets_sea(camera, grid_ray(camera, corner))) return true;
  return false;
}

double grid_horizon_clearance(const GridCamera& camera, const glm::dvec3& ray) {
  const double length = glm::length(ray);
  return length > 0.0 ? clearance(kept_cone(camera), ray).value / length : 0.0;
}

GridCamera make_grid_camera(const glm::dvec3& right, const glm::dvec3& up,
                            const glm::dvec3& forward, double tan_half_fov_y, double height,
                            int width_px, int height_px, const SeaSurface& surface) {
  GridCamera camera;
  camera.right = right;
  camera.up = up;
  camera.forward = forward;
  camera.tan_half_fov_y = tan_half_fov_y;
  camera.aspect = double(width_px) / double(height_px);
  camera.height = height;
  camera.width = width_px;
  camera.height_px = height_px;
  camera.surface = surface;
  return camera;
}

glm::dvec3 grid_ray(const GridCamera& c, glm::dvec2 image) {
  return c.forward + (image.x * c.tan_half_fov_y * c.aspect) * c.right +
         (image.y * c.tan_half_fov_y) * c.up;
}

bool sea_point(const GridCamera& camera, glm::dvec2 image, glm::dvec3& point) {
  const glm::dvec3 ray = glm::normalize(grid_ray(camera, image));
  const std::optional<double> t = sea_surface_distance(camera.surface, camera.height, ray);
  if (!t) return false;
  point = surface_point(camera, ray, *t);
  return true;
}

ProjectedGrid make_projected_grid(const GridCamera& camera, double cell_px, int margin_cells,
                                  double skirt_reach) {
  ProjectedGrid grid;
  if (!(camera.height > 0.0) || camera.width < 1 || camera.height_px < 1 || !(cell_px > 0.0))
    return grid;
  const int margin = std::max(margin_cells, 0);
  const int cells_x = static_cast<int>(std::ceil(camera.width / cell_px)) + 2 * margin;
  const int cells_y = static_cast<int>(std::ceil(camera.height_px / cell_px)) + 2 * margin;
  // Image units per cell: 2 / width per pixel horizontally, 2 / height vertically.
  const glm::dvec2 step(2.0 * cell_px / camera.width, 2.0 * cell_px / camera.height_px);
  const glm::dvec2 origin = glm::dvec2(-1.0, -1.0) - double(margin) * step;
  if (!image_sees_sea(camera, origin, origin + glm::dvec2(cells_x, cells_y) * step)) return grid;

  const KeptCone cone = kept_cone(camera);
  // Image units per unit of the image plane at unit distance (isotropic, as square pixels):
  // the Newton steps below follow the gradient in that plane, so the moves are perpendicular to
  // the horizon as the pixels see it.
  const glm::dvec2 plane_to_image(1.0 / (camera.tan_half_fov_y * camera.aspect),
                                  1.0 / camera.tan_half_fov_y);
  grid.columns = cells_x + 1;
  grid.rows = cells_y + 1;
  const std::size_t count = static_cast<std::size_t>(grid.columns) * grid.rows;
  grid.rest.resize(count);
  grid.cell_size.resize(count);
  grid.image.resize(count);
  // Onto the kept rays' boundary: Newton steps along the clearance's gradient in the image
  // plane. The clearance is concave, so a step lands where it is <= 0 (on the tangent plane's
  // zero, above the function): from the sky's side the steps approach the boundary without
  // crossing into the sea; from the sea's side the first step lands on the sky's. Every point
  // visited is in the image plane.
  auto onto_horizon = [&](glm::dvec2 image) {
    Clearance kept = clearance(cone, grid_ray(camera, image));
    for (int n = 0; n < kMaxNewtonSteps && std::abs(kept.value) > kept.tolerance; ++n) {
      // d clearance / d (plane point): ray = forward + x right + y up.
      const glm::dvec2 gradient(glm::dot(kept.gradient, camera.right),
                                glm::dot(kept.gradient, camera.up));
      const double gradient2 = glm::dot(gradient, gradient);
      if (!(gradient2 > 0.0)) break;
      image -= (kept.value / gradient2) * gradient * plane_to_image;
      kept = clearance(cone, grid_ray(camera, image));
    }
    return image;
  };
  std::vector<char> moved(count, 0);
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * grid.columns + i;
      grid.image[k] = origin + glm::dvec2(i, j) * step;
      if (!kept_ray(cone, grid_ray(camera, grid.image[k]))) {
        grid.image[k] = onto_horizon(grid.image[k]);
        moved[k] = 1;
      }
    }
  // On a curved horizon the chord between two moved vertices cuts off a sliver of the sea (its
  // sagitta, kappa l^2 / 8 for a chord l on a conic of curvature kappa). A kept vertex inside
  // that sliver lies beyond the chord, and the triangle of the three is folded over: move such
  // kept vertices onto the horizon too (by at most the sagitta), until no triangle with a kept
  // vertex is folded; each pass moves at least one vertex more.
  auto twice_area = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const glm::dvec2 pa = grid.image[a], pb = grid.image[b], pc = grid.image[c];
    return (pb.x - pa.x) * (pc.y - pa.y) - (pb.y - pa.y) * (pc.x - pa.x);
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (int j = 0; j < cells_y; ++j)
      for (int i = 0; i < cells_x; ++i) {
        const std::uint32_t a = j * grid.columns + i, b = a + 1, c = a + grid.columns, d = c + 1;
        const std::uint32_t triangles[2][3] = {{a, b, d}, {a, d, c}};
        for (const auto& t : triangles) {
          const int moved_corners = moved[t[0]] + moved[t[1]] + moved[t[2]];
          if (moved_corners == 0 || moved_corners == 3 || twice_area(t[0], t[1], t[2]) > 0.0)
            continue;
          for (std::uint32_t v : t)
            if (!moved[v]) {
              grid.image[v] = onto_horizon(grid.image[v]);
              moved[v] = 1;
            }
          changed = true;
        }
      }
  }
  for (std::size_t k = 0; k < count; ++k) {
    // Kept rays, and moved ones to within kNewtonTolerance, meet the sea by the margins. One
    // that still misses after kMaxNewtonSteps means that no ray of the image plane clears them
    // (the image sees the sea only within the margins, at the image plane's infinity looking
    // up): nothing to draw.
    const glm::dvec3 ray = glm::normalize(grid_ray(camera, grid.image[k]));
    const std::optional<double> t = sea_surface_distance(camera.surface, camera.height, ray);
    if (!t) return ProjectedGrid{};
    grid.rest[k] = surface_point(camera, ray, *t);
    if (moved[k]) ++grid.moved_to_horizon;
  }
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * grid.columns + i;
      // The next vertex along the row and along the column (the previous one on the last).
      const std::size_t right = i + 1 < grid.columns ? k + 1 : k - 1;
      const std::size_t above = j + 1 < grid.rows ? k + grid.columns : k - grid.columns;
      grid.cell_size[k] = std::max(glm::length(grid.rest[right] - grid.rest[k]),
                                   glm::length(grid.rest[above] - grid.rest[k]));
      // Vertices moved onto the horizon crowd together along it, so their neighbours say
      // nothing of the footprint, which is unbounded there: take their distance from the nadir
      // (on the flat sea at least 1e5 times any wave it could hold; on the Earth's sphere 7 km
      // at 4 m up, 500 km at 20 km), so that no wave displaces them. (With a small cell the
      // shader would evaluate short waves far away, where float arguments of 1e9 rad make sin()
      // meaningless, NaN on some drivers.)
      if (moved[k]) grid.cell_size[k] = std::max(grid.cell_size[k], glm::length(grid.rest[k]));
    }
  if (skirt_reach > 0.0) add_skirt(camera, cone, skirt_reach, moved, grid);
  grid.indices.reserve(static_cast<std::size_t>(cells_x) * cells_y * 6);
  // A triangle whose three vertices were all moved onto the horizon is degenerate by
  // construction on the flat sea (they lie on one line of the image); on the curved one it is a
  // sliver between three points of the horizon conic, whose corners need not keep the cell's
  // order along it. Leaving them out keeps rasterisers from dividing by a zero area (llvmpipe
  // then interpolates NaN) and the grid from folding over.
  auto add_triangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (moved[a] && moved[b] && moved[c]) return;
    grid.indices.insert(grid.indices.end(), {a, b, c});
  };
  for (int j = 0; j < cells_y; ++j)
    for (int i = 0; i < cells_x; ++i) {
      const std::uint32_t a = j * grid.columns + i, b = a + 1, c = a + grid.columns, d = c + 1;
      add_triangle(a, b, d);
      add_triangle(a, d, c);
    }
  return grid;
}

}  // namespace thalassa::ocean
