// thalassa — where the camera is on the planet, as the renderer needs it each frame (issue 5,
// points 1, 3 and 5), computed on the CPU in double precision.
//
// The GPU works in the east-north-up frame tangent at the camera's nadir (x east, y north, z up
// along the surface normal; origin the nadir point on the sea; metres): the camera is at
// (0, 0, height), and every position it sees is a small camera-relative number, never an
// absolute ECEF float (DESIGN section 4). The frame carries:
// - the sea at rest in that frame, exactly (ocean/sea_surface.hpp: the quadric of the WGS84
//   ellipsoid or of the sphere through the nadir);
// - the waves' chart: the scene's waves are a field fixed to the planet, defined in the tangent
//   plane of a world-fixed anchor point (its east and north axes, metres). A point x of the nadir
//   frame has the chart coordinates wave_origin + wave_axes * (x.x, x.y), so a wave of wave
//   vector k (chart) has the phase  omega t - k . wave_origin - (wave_axes^T k) . (x.x, x.y):
//   the first two terms are wrapped in double on the CPU (ocean::wrapped_phase), the GPU sees the
//   rotated wave vector and small offsets only. Moving the camera by 1 mm moves wave_origin by
//   1 mm in double; the waves stay where they are on the planet.
//
// Why an anchor and not the nadir itself: waves defined relative to the nadir would travel with
// the camera. Why a tangent plane: within the few tens of km of its anchor, it is the planet's
// surface to (d / R)^2 ~ 1e-5 in length and its axes turn from the local east and north by the
// meridians' convergence (below 0.2 degrees), far below what a wave's look could show.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "thalassa/engine/scene.hpp"
#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/planet/geodesy.hpp"

namespace thalassa {

// Spacing of the lattice of wave anchors, degrees of latitude and of longitude: a render's
// anchor is the lattice point nearest its nadir (at most 0.125 degree, 14 km, from it at the
// equator; less toward the poles), so the same place always gets the same waves, whatever the
// camera does. A flight fixes one anchor for all its frames (RendererOptions::wave_anchor) so
// that no frame crosses from one lattice cell's waves to the next.
inline constexpr double kWaveAnchorSpacingDeg = 0.25;

// How far from its waves' anchor a Renderer's camera may move and keep it (Renderer::set_scene),
// m of chord: 100 km, where the chart's tangent plane is the surface to (d / R)^2 = 2.5e-4 in
// length and its axes turn from the local east and north by the meridians' convergence, about
// d tan(lat) / R: 0.9 degree at 45 degrees of latitude (the wind's direction off by as much).
// Farther, the camera takes the lattice point nearest it, and the waves under it change once.
inline constexpr double kWaveAnchorKeepDistance = 100e3;

// The lattice point nearest (lat, lon) (degrees; height 0), longitude in (-180, 180].
Geodetic nearest_wave_anchor(double lat_deg, double lon_deg);

// The anchor a camera at (lat, lon) (degrees) keeps on `planet`: `anchor` while the camera is
// within kWaveAnchorKeepDistance of it (chord, m), else the lattice point nearest the camera
// (Renderer::set_scene; a host asking for the water under the next frame's camera before it).
Geodetic kept_wave_anchor(const Planet& planet, const Geodetic& anchor, double lat_deg,
                          double lon_deg);

struct NadirFrame {
  Geodetic nadir;                 // the camera's latitude and longitude (degrees), height 0
  double camera_height = 0.0;     // m above the sea
  EnuBasis enu;                   // the frame's axes as ECEF unit vectors
  ocean::SeaSurface sea_surface;  // the sea at rest, in the frame (m)
  Geodetic wave_anchor;           // the waves' chart's origin (degrees, height 0)
  glm::dvec2 wave_origin{0.0};    // m: the nadir's coordinates in the waves' chart
  // Columns: the frame's east and north unit vectors in the chart (dimensionless; a rotation to
  // about 1e-5 within the lattice cell).
  glm::dmat2 wave_axes{1.0};
};

// The frame of a camera (camera.lat, camera.lon in degrees, camera.height in m) on `planet`;
// `anchor` fixes the waves' chart (nearest_wave_anchor of the nadir when not given). Throws
// std::invalid_argument for positions Planet rejects.
NadirFrame make_nadir_frame(const Planet& planet, const CameraSettings& camera,
                            const std::optional<Geodetic>& anchor = std::nullopt);

// The sea-surface quadric of `planet` at the nadir (lat, lon: degrees) in its ENU frame:
// C = R^T A R / |A N| (ocean/sea_surface.hpp), A = diag(1/a^2, 1/a^2, 1/b^2).
ocean::SeaSurface planet_sea_surface(const Planet& planet, double lat_deg, double lon_deg);

}  // namespace thalassa
