// thalassa — the projected grid of Bruneton et al. 2010 sec. 3.2 (fig. 3), after Hinsinger et
// al. 2002, computed on the CPU in double: a regular grid in screen space, each vertex's view
// ray met with the sea at rest, so that the GPU only displaces and projects back. The sea at rest
// is a SeaSurface (sea_surface.hpp) in the east-north-up frame at the camera's nadir, the camera
// at height h on the z axis: the flat plane z = 0 of the paper's sec. 3.2, or the planet's
// sphere or ellipsoid of its sec. 6 ("for altitudes below 20,000 m, we switch to the projected
// grid method, with a projection on the sphere").
//
// Any pitch and roll work, the camera looking above the horizon included:
// - the rays that meet a convex sea form a convex cone around the nadir; the grid keeps the rays
//   a hair inside it (grid_horizon_clearance >= 0: b^2 - 4ac >= kHorizonMargin b^2, and on the
//   flat sea a depression of kHorizonDepression), again a convex cone, whose boundary dips below
//   the horizontal by the horizon's dip in each azimuth (plus the margin): on an ellipsoid the
//   dip depends on the azimuth, and the cone holds that exactly. The image region it covers is
//   convex: a half-plane bounded by a line for the flat sea, the inside of a conic for the
//   curved one;
// - a vertex outside it (the sky's side) is moved in the image plane onto its boundary, by
//   Newton steps along the gradient of its clearance (a concave function of the image point, so
//   the steps never overshoot into the sea): on the flat sea one step, perpendicular to the
//   horizon line, as the flat-only grid did; on the curved sea, near the nearest point of the
//   conic. Rows keep their order along the horizon and no triangle folds over. (Moving a vertex
//   down its own vertical plane instead, to the horizon's dip in its azimuth, moves it along the
//   line through the nadir's image point: looking up, that point is the zenith's, outside the
//   sea's region, and column neighbours on a curved horizon swap order along it; with a wide
//   field of view it folds over even on the flat sea. projected_grid_test.cpp has such cameras.)
// - every vertex stays in the image plane, so in front of the camera, wherever the horizon is;
// - the grid reaches the horizon to a small fraction of a pixel: on the curved sea, less the
//   sagitta of the conic's chords between moved vertices (~1e-3 pixel for 8-pixel cells at
//   1024x768 and 45 degrees, 20 km up), which the ocean's backstop pass fills. A kept vertex
//   that falls inside such a sliver would fold its triangle over: it is moved onto the horizon
//   too;
// - the grid extends `margin_cells` beyond every image edge, so that waves displacing the edge
//   vertices inward do not uncover the image's border;
// - optionally its outer ring is a skirt: vertices the waves leave at rest (shaders/ocean/
//   ocean.vert), those of each side (but a corner's cells) moved straight out of the image by
//   about as far as a displacement of `skirt_reach` metres moves a point there on screen. The
//   ring at rest encloses the image, so the triangles between it and the displaced ring inside
//   reach from outside the image to wherever the waves moved that ring: the border stays covered
//   however far a crest near the camera or a ship's wake moves it (before, those pixels were
//   holes that the backstop shaded with the sea at rest, visibly darker beside a wake). The move
//   spreads the rest positions those triangles interpolate (the per-pixel normals' arguments)
//   over about as much sea as they cover on screen, instead of one cell stretched across the gap.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "thalassa/ocean/sea_surface.hpp"

namespace thalassa::ocean {

struct GridCamera {
  glm::dvec3 right{1, 0, 0};    // unit, east-north-up
  glm::dvec3 up{0, 0, 1};       // unit
  glm::dvec3 forward{0, 1, 0};  // unit
  double tan_half_fov_y = 0.41421356237309503;
  double aspect = 1.0;  // width / height
  double height = 4.0;  // camera height above the sea at rest, m (> 0)
  int width = 1;        // image size in pixels
  int height_px = 1;
  // The sea at rest, nadir ENU: C = 0 (flat, the default) or positive definite (convex).
  SeaSurface surface;
  // Exact (a NaN field makes a camera equal to none): whether a grid made for one is the other's.
  bool operator==(const GridCamera&) const = default;
};

struct ProjectedGrid {
  int columns = 0;  // vertices per row
  int rows = 0;     // rows of vertices
  // Per vertex: the rest position on the sea at rest (m, nadir ENU: x east, y north of the
  // camera's nadir, z the surface's sag there, 0 for the flat sea) and the size of a grid cell
  // there (m, the larger of the 3D distances to the next vertex along a row and along a column:
  // eq. 2's L).
  std::vector<glm::dvec3> rest;
  std::vector<double> cell_size;
  std::vector<glm::dvec2> image;       // the vertex's image point (u, v) in [-1, 1] (+margin)
  std::vector<std::uint32_t> indices;  // two triangles per cell, counterclockwise in the image
  int moved_to_horizon = 0;            // vertices moved from the sky's side onto the horizon
  // Per vertex: 1 on the outer ring of a grid made with a skirt (its vertices are drawn at rest),
  // else 0; empty for a grid made without one. A skirt vertex keeps the cell size it had before
  // it was moved out, and the ring inside keeps its own.
  std::vector<std::uint8_t> skirt;
};

// The flat sea's margin: kept rays dip at least this much (their z over their component along
// `forward`, dimensionless). At 4 m it puts the far row 4,000 km away, far enough that no wave
// moves it visibly and close enough for float positions. It applies where C is not positive
// definite in the horizontal (the flat sea); on a curved sea, kHorizonMargin.
constexpr double kHorizonDepression = 1e-6;

// The curved sea's margin: kept rays have b^2 - 4ac >= kHorizonMargin b^2 (sea_surface.hpp),
// seven orders above its rounding (~1e-16 b^2), so moved rays surely meet the sea. Their dip
// exceeds the horizon's by a relative kHorizonMargin / 2 (tans) and they meet the sea short of
// the horizon by a relative sqrt(kHorizonMargin) cos(dip): 4.5e-5 (0.3 m at 4 m up, 23 m at
// 20 km).
constexpr double kHorizonMargin = 2e-9;

// How far inside the cone of kept rays the ray (any length, nadir ENU) is: -b - sqrt((4ac +
// mu (ray . forward)^2) / (1 - kHorizonMargin)) over |ray|, with mu = kHorizonDepression^2 on
// the flat sea and 0 on a curved one; dimensionless, about the sine of the ray's dip below the
// grid's horizon (times 1 + h C_zz). >= 0: the grid keeps the ray (it meets the sea); 0 on the
// boundary, where moved vertices go. Concave in the ray.
double grid_horizon_clearance(const GridCamera& camera, const glm::dvec3& ray);

// The camera of a frame, from its basis, vertical field of view, image size and sea at rest.
GridCamera make_grid_camera(const glm::dvec3& right, const glm::dvec3& up,
                            const glm::dvec3& forward, double tan_half_fov_y, double height,
                            int width_px, int height_px, const SeaSurface& surface = {});

// The unnormalised view ray through image point (u, v) in [-1, 1]^2 (u right, v up); its
// component along `forward` is 1.
glm::dvec3 grid_ray(const GridCamera& camera, glm::dvec2 image);

// Where the ray through image point `image` first meets the sea at rest (m, nadir ENU, z the
// sag); false when it does not (at or above the horizon, or a camera not above the sea).
bool sea_point(const GridCamera& camera, glm::dvec2 image, glm::dvec3& point);

// Whether any ray through the image rectangle [lo, hi] (image units, (u, v) in [-1, 1] spans
// the image) meets the sea at rest, and whether any misses it (sees the sky), decided exactly
// for any pitch, roll and field of view (the rays meeting a convex sea form a convex cone).
bool image_sees_sea(const GridCamera& camera, glm::dvec2 lo, glm::dvec2 hi);
bool image_sees_sky(const GridCamera& camera, glm::dvec2 lo, glm::dvec2 hi);

// cell_px: the grid cell's size in pixels (the paper's default 8); margin_cells: cells added
// beyond each edge. skirt_reach (m, a bound of the waves' displacement): 0, no skirt; > 0, the
// outer ring is a skirt (ProjectedGrid::skirt), and each of its vertices on a side, not on the
// horizon and not a corner or a corner's neighbour, is moved perpendicularly out of its edge by
// skirt_reach times the focal length over its distance along the view axis (pixels; at most
// 1024), or by half that, a quarter... where that ray would not meet the sea or would meet it
// nearer the camera along the view axis than half the vertex's distance or 2 cm (twice the
// ocean's near plane; a vertex already nearer stays); its rest position is where the moved ray
// meets the sea at rest. Returns an empty grid (0 rows) when no part of the
// image sees the sea.
ProjectedGrid make_projected_grid(const GridCamera& camera, double cell_px, int margin_cells,
                                  double skirt_reach = 0.0);

}  // namespace thalassa::ocean
