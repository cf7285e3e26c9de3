// thalassa — the sea's surface at a latitude and longitude, on the CPU in double precision: how
// high the water stands there, which way it faces and how it moves, for whatever floats on it
// (a ship's hull, a buoy, a camera that must stay above the waves) and for comparing with wave
// records (docs/sea_state.md).
//
// The surface is the one the renderer draws (paper 000, eq. 2): the scene's trochoids, in the
// waves' chart of an anchor (planet/nadir_frame.hpp), their amplitudes times the calm areas'
// scale s, plus the ships' Kelvin wakes (planet/ship_wake.hpp), each displaced from its rest point
// on the sea at rest (the planet's ellipsoid or sphere). Every wave is geometry, as in the
// reference method (w_p = 1), unless a footprint L is given: then each wave is weighted by the
// paper's w(N_min, N_max, lambda / L) (sec. 3.2), as the projected grid filters the waves for a
// cell of L metres. A hull of length L feels the waves much shorter than itself averaged out.
//
// Trochoids move the water sideways: the particle at the surface above a point rests elsewhere.
// SeaState::at finds that rest point by Newton's method on the horizontal map p -> p + D_h(p)
// (to 1e-12 m where it gains, 1e-9 m with calm areas or wakes, whose waves are placed by the rest
// point's latitude and longitude; kSeaStateTolerance at least; where it stalls beside a fold, from
// the best nodes of a scan of the disc |p| <= max |D_h| that holds the rest point; in a wake, on
// its ship-frame coordinates linearised between searches of its track, each round ended by a
// search at the root found) and evaluates everything there, so the height is the surface's height
// above the point itself (Eulerian), not the height of the particle that rests below it. A single
// trochoid's mean height over a wavelength is then -k h^2 / 2, below the sea at rest (tested).
//
// Frame and units: the point's east-north-up frame (x east, y north, z up along the ellipsoid's
// normal), metres, seconds. The waves displace each rest point in its own tangent frame; the rest
// point lies |D_h| (metres) from the asked point, whose frame turns from the rest point's by
// |D_h| / R (1e-6 rad for 6 m) and whose sea at rest sags by |D_h|^2 / 2R (3e-6 m): both are
// below what is resolved here and left out.
//
// Consistency with a Renderer: the waves' chart depends on its anchor, so a query agrees with the
// frames only with the renderer's anchor (Renderer::sea_state; RenderStats::wave_anchor), and
// points farther than 1000 km from the anchor are refused. The renderer evaluates the waves in its
// camera's nadir frame, mapped affinely into the chart; this evaluates them in the asked point's,
// mapped the same way: the two places in the chart differ by about d^2 D / 2 R^2 for a point d
// from the camera's nadir and D from the anchor (0.2 mm at d = 1 km and D = 14 km, 12 cm at
// d = 10 km and D = 100 km), a shift of the wave field, not of its heights. Where they differ
// otherwise: the GPU reads s from a chart of the areas in view, bilinearly (within
// calm_chart_distance_tolerance of the exact s here, planet/local_features.hpp), and shades with
// eq. 3's normals, which leave out the gradient of s and take each wake branch as a plane wave;
// the normals here are the heights' own.
#pragma once

#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "thalassa/engine/scene.hpp"
#include "thalassa/planet/geodesy.hpp"

namespace thalassa {

// The sea at one point and time.
struct SeaPoint {
  // m above the sea at rest (the planet's surface) at the point, along its up.
  double height = 0.0;
  // The surface's unit normal, east-north-up: eq. 3's cross product of the rest point's tangents
  // (1, 0, 0) + dD/dx and (0, 1, 0) + dD/dy, with the calm areas' gradient of s and the wakes'
  // change across them; its z is negative where the surface folds over (the trochoids' sum
  // loops: det J < 0).
  glm::dvec3 normal{0.0, 0.0, 1.0};
  // m/s, east-north-up: the velocity of the water particle at the surface there (the trochoids'
  // orbital motion, the wakes' moving with their ships).
  glm::dvec3 velocity{0.0};
  // m/s: d height / dt at the fixed point (the surface rising and falling under a moored buoy):
  // dD_z/dt + grad D_z . dp/dt, with dp/dt = -J^-1 dD_h/dt the rest point's drift under the fixed
  // point (J = I + dD_h/dp); dD_z/dt where J is singular.
  double height_rate = 0.0;
  // m, east and north: the rest point of that particle, relative to the point.
  glm::dvec2 rest_offset{0.0};
  // The calm areas' amplitude scale s at the rest point (1 outside them) and the wakes whose waves
  // reach it.
  double calm_scale = 1.0;
  int wakes = 0;
  // Newton's iterations, and whether they met the tolerance. Where Newton from the point stalls
  // (beside a fold, det J near 0) the disc that holds the rest point is scanned and Newton goes
  // on from the best nodes (`searched`; a few milliseconds). If that fails too, the values are
  // those of the best iterate, finite.
  int iterations = 0;
  bool converged = true;
  bool searched = false;
  // The ships' tracks searched for the rest point's wake coordinates (ShipWake::Instant::
  // coordinates, a few microseconds each): 2-3 for each wake whose bounds hold the point, where
  // Newton iterates on the coordinates linearised between searches (hundreds where the disc is
  // scanned); 0 where no wake's bounds hold it.
  int track_searches = 0;
};

// Newton's tolerance on the horizontal map: |p + D_h(p) - point| at most this, m, for
// SeaPoint::converged (it goes on while it gains, to 1e-12 m; to 1e-9 m where calm areas or wakes
// place their waves by the rest point's latitude and longitude, whose last bits are about that).
inline constexpr double kSeaStateTolerance = 1e-8;

// The footprint (m) that makes SeaState::at give the surface a Renderer of `scene` draws at
// (lat, lon) (degrees) with the `full`, `basic` and `normals` methods: the projected grid's cell
// there (eq. 2's L, the larger of the distances on the sea at rest to the next vertex along a row
// and along a column, ocean/projected_grid.hpp; the one the point's image point would have if it
// lies outside the image; beside the horizon, to the horizon's point where the grid moved its
// next vertex), over the waves' hand-over to the view from space
// (ocean::resolved_wave_scale, 1 below 10 km). A query with it leaves out the waves the grid
// leaves out (w_p); what remains is the grid's linear interpolation between vertices a cell apart
// (docs/sea_state.md, "Against the drawn surface": 4 mm rms at 2-pixel cells 12 m over a 10 m/s
// sea, 17 mm at 8). A host floating a buoy on the water it sees asks with this; one moving a hull
// with the sea, with the hull's length (or 0: every wave). std::nullopt where the grid draws no
// waves at the point: behind the camera, beyond the horizon (or the grid's last row, a relative
// 4.5e-5 of the distance short of it), a camera under the sea or in space mode
// (kSpaceModeHeight, planet/renderer.hpp). About a microsecond a call. The reference method draws
// every wave (footprint 0). Throws std::invalid_argument for lat outside [-90, 90] or a lon not
// finite.
std::optional<double> drawn_footprint(const Scene& scene, double lat, double lon);

class SeaState {
 public:
  // The scene's sea (its waves, wakes and calm areas; planet; `time` the default time of at())
  // in the chart of `wave_anchor`: by default the one a new Renderer of this scene takes, the
  // lattice point nearest the camera's nadir (nearest_wave_anchor). Throws std::invalid_argument
  // for an anchor out of range, and what ShipWake and CalmArea throw for settings a scene
  // builder would have refused.
  explicit SeaState(const Scene& scene, const std::optional<Geodetic>& wave_anchor = std::nullopt);
  ~SeaState();
  SeaState(const SeaState&);
  SeaState& operator=(const SeaState&);
  SeaState(SeaState&&) noexcept;
  SeaState& operator=(SeaState&&) noexcept;

  const Scene& scene() const;
  const Geodetic& wave_anchor() const;  // degrees, height 0

  // The sea at (lat, lon: degrees; lat in [-90, 90], lon finite, within 1000 km of the anchor) at
  // `time` (s, the scene's clock, [0, kSceneMaxTime]), with every wave, or weighted for a
  // footprint of `footprint` m (>= 0; 0: every wave). Throws std::invalid_argument naming the
  // argument for anything else, and std::runtime_error rather than return a value that is not
  // finite (none is known). (A moved-from SeaState may only be assigned or destroyed.) It keeps
  // no state between queries: one SeaState may answer from many threads at once.
  SeaPoint at(double lat, double lon, double time, double footprint = 0.0) const;
  // At the scene's time, every wave.
  SeaPoint at(double lat, double lon) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace thalassa
