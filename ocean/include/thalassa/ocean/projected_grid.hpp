// thalassa — the projected grid of Bruneton et al. 2010 sec. 3.2 (fig. 3), after Hinsinger et
// al. 2002, computed on the CPU in double: a regular grid in screen space, each vertex's view
// ray met with the sea at rest (the plane z = 0 of the local east-north-up frame at the camera's
// nadir, the camera at height h on the z axis), so that the GPU only displaces and projects back.
//
// Any pitch and roll work, the camera looking above the horizon included:
// - the vertical component of the (unnormalised) ray through image point (u, v) is linear in u
//   and v, so the image region that sees the sea is a half-plane bounded by the horizon line;
//   vertices on the sky's side are moved, in image space, onto the sea's side of that line at a
//   fixed tiny depression (kHorizonDepression), so rows never fold over the horizon, no vertex
//   lies behind the camera (every point of the image plane is in front of it) and the grid
//   reaches the horizon to a small fraction of a pixel: no gap, no line;
// - the grid extends `margin_cells` beyond every image edge, so that waves displacing the edge
//   vertices inward do not uncover the image's border.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

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
};

struct ProjectedGrid {
  int columns = 0;  // vertices per row
  int rows = 0;     // rows of vertices
  // Per vertex: the rest position on the sea (m east, m north of the camera's nadir) and the
  // size of a grid cell there (m, the larger of the distances to the next vertex along a row
  // and along a column: eq. 2's L).
  std::vector<glm::dvec2> rest;
  std::vector<double> cell_size;
  std::vector<glm::dvec2> image;       // the vertex's image point (u, v) in [-1, 1] (+margin)
  std::vector<std::uint32_t> indices;  // two triangles per cell, counterclockwise in the image
  int moved_to_horizon = 0;            // vertices moved from the sky's side onto the horizon
};

// Vertex rays are depressed at least this much below the horizon (the vertical component of
// the unit-forward-normalised ray, dimensionless): at 4 m, 4e-6 puts the far row 1,000 km away,
// far enough that no wave moves it visibly and close enough for float positions.
constexpr double kHorizonDepression = 1e-6;

// The camera of a frame, from its basis, vertical field of view and image size.
GridCamera make_grid_camera(const glm::dvec3& right, const glm::dvec3& up,
                            const glm::dvec3& forward, double tan_half_fov_y, double height,
                            int width_px, int height_px);

// The unnormalised view ray through image point (u, v) in [-1, 1]^2 (u right, v up); its
// component along `forward` is 1.
glm::dvec3 grid_ray(const GridCamera& camera, glm::dvec2 image);

// Where the ray through image point `image` meets the sea at rest (m east, m north of the
// nadir); false when it does not (at or above the horizon, or a camera not above the sea).
bool sea_point(const GridCamera& camera, glm::dvec2 image, glm::dvec2& point);

// cell_px: the grid cell's size in pixels (the paper's default 8); margin_cells: cells added
// beyond each edge. Returns an empty grid (0 rows) when no part of the image sees the sea.
ProjectedGrid make_projected_grid(const GridCamera& camera, double cell_px, int margin_cells);

}  // namespace thalassa::ocean
