#include "thalassa/planet/sea_state.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "thalassa/ocean/kelvin_wake.hpp"
#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/ocean/wave_set.hpp"
#include "thalassa/planet/calm_area.hpp"
#include "thalassa/planet/geo_bounds.hpp"
#include "thalassa/planet/nadir_frame.hpp"
#include "thalassa/planet/ship_wake.hpp"
#include "trochoids_reference.hpp"

namespace thalassa {

namespace {

// Newton's most iterations. From the rest point's first guess (the point itself) the map's
// residual falls quadratically: 3-6 iterations on the default sea, 4-5 in 95 % (docs/sea_state.md).
constexpr int kMaxIterations = 60;
// m: Newton goes on while it gains, down to this; kSeaStateTolerance, ten thousand times more,
// says whether it converged.
constexpr double kNewtonTarget = 1e-12;
// m: the same where calm areas or wakes place their waves by the rest point's latitude and
// longitude, whose last bits are 3e-10 to 8e-10 m. Below that their displacement stands still
// between steps, and Newton's steps only shrink the residual by |1 - 1 / J| (0.33 per iteration
// at the wake demo's buoy, where J's yy is 0.75): 4-5 iterations a query that moved the rest
// point by less than its rounding.
constexpr double kGeodeticNewtonTarget = 1e-9;
// Halvings of a Newton step that does not lower the residual, before Newton stops at its best
// iterate.
constexpr int kMaxStepHalvings = 12;
// Where Newton from the point stalls, the disc that holds the rest point is scanned on a grid of
// this many nodes a side (those within the disc: 0.8 of them), and Newton goes on from the
// kScanStarts nodes with the least |F|.
constexpr int kScanNodes = 17;
constexpr std::size_t kScanStarts = 4;
// Below this |det J| the map p -> p + D_h(p) is taken as singular (a fold's edge): a fixed-point
// step -F replaces Newton's, and height_rate is dD_z/dt. Where det J < 0 (inside a fold) the map
// is still locally invertible, and both are Newton's and the implicit derivative's.
constexpr double kSingularJacobian = 1e-9;
// m: the central differences' step of the calm areas' scale s, fade / 100 within [1 mm, 0.25 m].
// s is a C1 smoothstep over the fade F: the error is step^2 |d3s/dd3| / 6 = 2e-4 |1 - scale| / F
// (1/m) inside the fade, and up to about 0.03 |1 - scale| / F within a step of its ends, where
// the second derivative jumps (against a gradient of 1.5 |1 - scale| / F mid-fade: 2 %).
constexpr double kCalmGradientMinStep = 1e-3;
constexpr double kCalmGradientMaxStep = 0.25;
// The wakes' derivatives are central differences of their displacement, taken in the ship
// frame's coordinates moved by their gradients (so the rest point's 1e-9 m of rounding through
// latitude and longitude does not enter them), over kWakeStep m or kWakeStepPerWavelength of the
// shorter branch's wavelength there where that is less: (k step)^2 / 6 = 7e-8 at most. A ship's
// waves are 2 pi U^2 / g long on its track and shorter across it: 0.16 m at 0.5 m/s, whose
// divergent waves of a few centimetres a 1 mm step differentiated 3 % wrong (stop 51's review).
// In time too: the pattern is steady in the ship frame and a fixed point falls astern at the
// ship's speed U, so dD/dt = U dD/db.
constexpr double kWakeStep = 1e-3;  // m
constexpr double kWakeStepPerWavelength = 1e-4;
// Rounds of Newton on the wakes' coordinates linearised about the last searched rest point, each
// ended by one search of the track at the root found: the coordinates' error there is about
// |step|^2 / rho (rho the planet's radius on a geodesic; in the fan outside a turn, the distance
// to its apex), so 2-3 rounds meet the tolerance. Exact Newton (a search each iteration) finishes
// where they do not: near a turn's apex or the track's start (docs/sea_state.md).
constexpr int kMaxLinearisedRounds = 6;
// m of chord: the farthest a queried point may be from the waves' anchor. A renderer keeps its
// anchor while its camera stays within 100 km of it (kWaveAnchorKeepDistance) and sees waves
// well inside the horizon from 20 km up (500 km). Within this reach the chart's axes stay a
// rotation of the point's east and north.
constexpr double kAnchorReach = 1.0e6;

[[noreturn]] void refuse(const std::string& name, const std::string& expected, double got) {
  std::ostringstream message;
  message.precision(17);
  message << "thalassa::SeaState: " << name << ": expected " << expected << ", got " << got;
  throw std::invalid_argument(message.str());
}

// One wave as the query sees it in the point's frame: unit direction, wavenumber (rad/m),
// amplitude (m, times its filter weight), argument at the point (rad) and angular frequency
// (rad/s).
struct FrameWave {
  glm::dvec2 direction{1.0, 0.0};
  double wavenumber = 0.0;
  double amplitude = 0.0;
  double argument = 0.0;
  double angular_frequency = 0.0;
};

// The displacement field at a rest point: D (m), its derivatives along the rest point's east and
// north (dimensionless) and in time (m/s).
struct Field {
  glm::dvec3 d{0.0};
  glm::dvec3 d_dx{0.0};
  glm::dvec3 d_dy{0.0};
  glm::dvec3 d_dt{0.0};
  double calm_scale = 1.0;
  int wakes = 0;
};

// Adds one trochoid at argument theta (shaders/ocean/trochoids.glsl): eq. 2's displacement (m),
// its derivatives along the rest point (dimensionless) and in time (m/s; dtheta/dt = omega).
void add_trochoid(glm::dvec2 direction, double wavenumber, double amplitude, double theta,
                  double omega, Field& f) {
  f.d += glsl::TrochoidDisplacement(direction, amplitude, theta);
  glm::dvec3 d_dx, d_dy;
  glsl::TrochoidDisplacementDerivatives(direction, wavenumber, amplitude, theta, d_dx, d_dy);
  f.d_dx += d_dx;
  f.d_dy += d_dy;
  const double c = omega * amplitude * std::cos(theta);
  f.d_dt += glm::dvec3(direction * c, -omega * amplitude * std::sin(theta));
}

}  // namespace

struct SeaState::Impl {
  Scene scene;
  Geodetic anchor;
  Planet planet;
  glm::dvec3 anchor_ecef{0.0};  // m
  ocean::WaveSet waves;
  std::vector<CalmArea> calm;
  double min_fade = 0.0;  // m: the calm areas' shortest fade
  std::vector<ShipWake> wakes;

  Impl(const Scene& s, const Geodetic& a)
      : scene(s),
        anchor(a),
        planet(s.planet),
        anchor_ecef(planet.ecef(a.lat, a.lon, 0.0)),
        waves(ocean::make_wave_set(s.ocean)) {
    for (const CalmAreaSettings& c : s.calm_areas) {
      calm.emplace_back(planet, c);
      min_fade = calm.size() == 1 ? c.fade : std::min(min_fade, c.fade);
    }
    for (const WakeSettings& w : s.wakes) wakes.emplace_back(planet, w);
  }
};

namespace {

// The filter weight (paper sec. 3.2) of a wave of `wavelength` m for the footprint (m; 0: 1).
double filter_weight(const OceanSettings& ocean, double wavelength, double footprint) {
  if (footprint <= 0.0) return 1.0;
  return glsl::WaveFilterWeight(ocean.n_min, ocean.n_max, wavelength / footprint);
}

// The wakes' ship-frame coordinates found by searching their tracks at one rest offset (m, the
// point's east and north): one per Query::wakes, nullopt where the rest point is in none.
struct WakeFeet {
  glm::dvec2 offset{0.0};
  std::vector<std::optional<ShipWake::Coordinates>> feet;
  bool in_bounds = false;  // whether any wake's bounds held the rest point (it was searched)
};

// The coordinates c moved by the rest offset dp (m, east-north) along their gradients. The
// gradients are in the searched rest point's east-north frame, which turns from the point's by
// |D_h| / R (1e-6 rad): that only slows the linearised rounds, each of which ends in a search.
ShipWake::Coordinates moved(const ShipWake::Coordinates& c, glm::dvec2 dp) {
  ShipWake::Coordinates m = c;
  m.behind += glm::dot(c.behind_gradient, dp);
  m.lateral += glm::dot(c.lateral_gradient, dp);
  return m;
}

// m: the step of a wake's central differences where its branches are `sample` (kWakeStep).
double wake_step(const ocean::KelvinWakeSample& sample) {
  double h = kWakeStep;
  for (const ocean::WakeWave* w : {&sample.transverse, &sample.divergent})
    if (w->amplitude > 0.0 && w->wavelength > 0.0)
      h = std::min(h, kWakeStepPerWavelength * w->wavelength);
  return h;
}

// What one query needs, fixed while Newton moves the rest point.
struct Query {
  const Planet* planet = nullptr;
  const OceanSettings* ocean = nullptr;
  const std::vector<CalmArea>* calm = nullptr;
  double time = 0.0;
  double footprint = 0.0;
  std::vector<FrameWave> waves;        // the scene's, in the point's frame
  // The wakes with waves somewhere at `time`: each at that time and where it can be non-zero.
  struct WakeNow {
    ShipWake::Instant now;
    GeoBounds bounds;
  };
  std::vector<WakeNow> wakes;
  std::optional<LocalFrame> frame;     // the point's, where calm areas or wakes need lat/lon
  ocean::SeaSurface surface;           // the sea at rest in that frame
  double calm_step = kCalmGradientMaxStep;  // m, see kCalmGradientMinStep
  double target = kNewtonTarget;            // m: Newton's, kGeodeticNewtonTarget with a frame
  // m: a bound of |D_h| anywhere: the waves' amplitudes (s <= 1) and each wake's
  // kelvin_wake_displacement_bound.
  double horizontal_bound = 0.0;
  mutable int track_searches = 0;  // SeaPoint::track_searches

  // The rest point at `offset` (m, the point's east and north) on the sea at rest, geodetic.
  Geodetic rest_point(glm::dvec2 offset) const {
    const double z = ocean::sea_surface_sag(surface, offset);
    return planet->geodetic(frame->to_ecef({offset.x, offset.y, z}));
  }

  double calm_scale(glm::dvec2 offset) const {
    const Geodetic g = rest_point(offset);
    return calm_amplitude_scale(*calm, g.lat, g.lon);
  }

  // The field at the rest offset, less the wakes' time derivative (Newton needs none; it is
  // add_wake_rates', once, at the rest point found). Each wake's ship-frame coordinates come from
  // a search of its track at the rest point, kept in `searched` if given; or, with `linearised`,
  // from those searched at another rest offset moved by their gradients (no search: what Newton
  // iterates on between searches).
  Field field(glm::dvec2 offset, WakeFeet* searched = nullptr,
              const WakeFeet* linearised = nullptr) const {
    Field f;
    for (const FrameWave& w : waves) {
      const double theta = w.argument - w.wavenumber * glm::dot(w.direction, offset);
      add_trochoid(w.direction, w.wavenumber, w.amplitude, theta, w.angular_frequency, f);
    }
    if (!frame) return f;
    const Geodetic g = rest_point(offset);  // what the calm areas and the wakes are placed by
    if (!calm->empty()) {
      // s multiplies every wave's amplitude (ocean.vert): D = s B, dD = s dB + B ds. Its gradient
      // is 0 outside the areas (s = 1) and deep inside (s = scale): s is C1, flat at both ends.
      double s = 1.0;
      bool flat = true;
      for (const CalmArea& area : *calm) {
        const double s_area = area.amplitude_scale(g.lat, g.lon);
        s *= s_area;
        if (s_area != 1.0 && s_area != area.settings().scale) flat = false;
      }
      glm::dvec2 gradient(0.0);
      if (!flat) {
        const double h = calm_step;
        gradient.x =
            (calm_scale(offset + glm::dvec2(h, 0.0)) - calm_scale(offset - glm::dvec2(h, 0.0))) /
            (2.0 * h);
        gradient.y =
            (calm_scale(offset + glm::dvec2(0.0, h)) - calm_scale(offset - glm::dvec2(0.0, h))) /
            (2.0 * h);
      }
      f.d_dx = s * f.d_dx + gradient.x * f.d;
      f.d_dy = s * f.d_dy + gradient.y * f.d;
      f.d *= s;
      f.d_dt *= s;
      f.calm_scale = s;
    }
    if (!wakes.empty()) {
      // The wakes add their own trochoids, unscaled by s (ocean.vert). Their derivatives are
      // central differences of their displacement, so that the normal and the rates are the
      // heights': a branch's amplitude and wave vector change across the wake, which the
      // renderer's eq. 3 leaves out (each branch a plane wave there, local_waves.glsl). The
      // differences along east and north move the ship-frame coordinates by their gradients
      // (ShipWake::Coordinates), exact to O(step^2 / R) against a search at each offset.
      if (searched) {
        searched->offset = offset;
        searched->feet.assign(wakes.size(), std::nullopt);
        searched->in_bounds = false;
      }
      for (std::size_t k = 0; k < wakes.size(); ++k) {
        const WakeNow& wake = wakes[k];
        std::optional<ShipWake::Coordinates> c;
        if (linearised) {
          // Where the search found no wake, none: the next search says whether the rest point
          // has moved into one. sample(c) has only the pattern's own fades, which are 0 at
          // coordinates()' cuts but for the track's start.
          if (linearised->feet[k]) c = moved(*linearised->feet[k], offset - linearised->offset);
        } else if (wake.bounds.contains(g.lat, g.lon)) {
          c = wake.now.coordinates(g.lat, g.lon);
          ++track_searches;
          if (searched) {
            searched->feet[k] = c;
            searched->in_bounds = true;
          }
        }
        if (!c) continue;
        bool reaches = false;
        const ocean::KelvinWakeSample sample = wake.now.sample(*c);
        f.d += wake_displacement(sample, &reaches);
        if (!reaches) continue;
        ++f.wakes;
        const double h = wake_step(sample);
        f.d_dx += wake_difference(wake, *c, glm::dvec2(h, 0.0));
        f.d_dy += wake_difference(wake, *c, glm::dvec2(0.0, h));
      }
    }
    return f;
  }

  // A wake's central difference (m per m) over the rest offset `step` (m, east-north), its
  // coordinates moved by their gradients.
  glm::dvec3 wake_difference(const WakeNow& wake, const ShipWake::Coordinates& c,
                             glm::dvec2 step) const {
    return (wake_displacement(wake.now.sample(moved(c, step))) -
            wake_displacement(wake.now.sample(moved(c, -step)))) /
           (2.0 * glm::length(step));
  }

  // Adds to f, the field at a rest offset whose tracks were searched (`feet`), the time
  // derivative of each wake whose waves reach the rest point: the pattern is steady in the ship
  // frame and the point falls astern at the ship's speed, so d/dt = U d/db at fixed y (the
  // foot stays where it is while the ship sails its segment). U is the current segment's: at a
  // track point's time the ship is on the next one, and this is the derivative after it, as at
  // the track's end the one before it (a difference in time across either, stop 50's, gave
  // thousands of m/s). The rest of the field is not evaluated again.
  void add_wake_rates(const WakeFeet& feet, Field& f) const {
    for (std::size_t k = 0; k < wakes.size() && k < feet.feet.size(); ++k) {
      if (!feet.feet[k]) continue;
      const ShipWake::Coordinates& c = *feet.feet[k];
      bool reaches = false;
      const ocean::KelvinWakeSample sample = wakes[k].now.sample(c);
      (void)wake_displacement(sample, &reaches);
      if (!reaches) continue;
      const double h = wake_step(sample);
      ShipWake::Coordinates later = c, earlier = c;
      later.behind += h;
      earlier.behind -= h;
      f.d_dt += wakes[k].now.ship().speed *
                (wake_displacement(wakes[k].now.sample(later)) -
                 wake_displacement(wakes[k].now.sample(earlier))) /
                (2.0 * h);
    }
  }

  // One wake's displacement (m, east-north-up) from its two branches at a point
  // (ShipWake::Instant::sample), each a local trochoid weighted for the footprint; `reaches`
  // says whether any of it is left.
  glm::dvec3 wake_displacement(const ocean::KelvinWakeSample& sample,
                               bool* reaches = nullptr) const {
    glm::dvec3 d(0.0);
    for (const ocean::WakeWave* w : {&sample.transverse, &sample.divergent}) {
      if (!(w->amplitude > 0.0) || !(w->wavenumber > 0.0)) continue;
      const double h = filter_weight(*ocean, w->wavelength, footprint) * w->amplitude;
      if (!(h > 0.0)) continue;
      d += glsl::TrochoidDisplacement(w->wave_vector / w->wavenumber, h, w->argument);
      if (reaches) *reaches = true;
    }
    return d;
  }
};

// |p + D_h(p) - point| for the rest offset p.
double residual(glm::dvec2 offset, const Field& f) { return glm::length(offset + glm::dvec2(f.d)); }

// A Newton iterate: the rest offset (m), its field and its residual |F| (m), and the wakes'
// coordinates where the field's tracks were searched there (empty where it was linearised).
struct Iterate {
  glm::dvec2 offset{0.0};
  Field f;
  double r = 0.0;
  WakeFeet searched;
};

// The field at `offset`, its tracks searched.
Iterate evaluate(const Query& q, glm::dvec2 offset) {
  Iterate it;
  it.offset = offset;
  it.f = q.field(offset, &it.searched);
  it.r = residual(offset, it.f);
  return it;
}

// Newton on F(p) = p + D_h(p) from `it`, while it gains, to q.target: the best iterate. With
// `linearised`, on the field whose wakes' coordinates are those moved from it (Query::field),
// which must be `it`'s own there. Adds its iterations to `iterations`.
Iterate newton(const Query& q, Iterate it, const WakeFeet* linearised, int& iterations) {
  for (int n = 0; it.r > q.target && n < kMaxIterations; ++n) {
    ++iterations;
    const Field& f = it.f;
    const glm::dmat2 jacobian(1.0 + f.d_dx.x, f.d_dx.y, f.d_dy.x, 1.0 + f.d_dy.y);
    const glm::dvec2 residual_vector = it.offset + glm::dvec2(f.d);
    glm::dvec2 step = std::abs(glm::determinant(jacobian)) > kSingularJacobian
                          ? -(glm::inverse(jacobian) * residual_vector)
                          : -residual_vector;
    Iterate next;
    for (int halving = 0;; ++halving) {
      next.offset = it.offset + step;
      next.f = linearised ? q.field(next.offset, nullptr, linearised)
                          : q.field(next.offset, &next.searched);
      next.r = residual(next.offset, next.f);
      if (next.r < it.r || halving == kMaxStepHalvings) break;
      step *= 0.5;
    }
    if (!(next.r < it.r)) break;  // no gain: the best iterate stays
    const bool stalled = it.r <= kSeaStateTolerance && next.r > 0.5 * it.r;  // rounding's floor
    it = std::move(next);
    if (stalled) break;
  }
  return it;
}

// The rest point from `start`: where a wake's bounds hold it, rounds of Newton on the wakes'
// coordinates linearised about the last searched rest point, each ended by a search at the root
// it found and kept while it gains (2-3 searches a wake against one each iteration); then exact
// Newton where that stops short of kSeaStateTolerance (near a turn's apex or the track's start,
// where the coordinates bend within metres). The best iterate, its tracks searched.
Iterate solve(const Query& q, glm::dvec2 start, int& iterations) {
  Iterate best = evaluate(q, start);
  // Outside every wake's bounds exact Newton searches nothing (and searches if it moves in).
  if (!best.searched.in_bounds) return newton(q, std::move(best), nullptr, iterations);
  for (int round = 0; round < kMaxLinearisedRounds && best.r > q.target; ++round) {
    const Iterate root = newton(q, best, &best.searched, iterations);
    if (root.offset == best.offset) break;
    Iterate searched = evaluate(q, root.offset);
    if (!(searched.r < best.r)) break;
    const bool stalled = best.r <= kSeaStateTolerance && searched.r > 0.5 * best.r;
    best = std::move(searched);
    if (stalled) break;
  }
  if (best.r > kSeaStateTolerance) best = newton(q, std::move(best), nullptr, iterations);
  return best;
}

}  // namespace

SeaState::SeaState(const Scene& scene, const std::optional<Geodetic>& wave_anchor) {
  Geodetic anchor = wave_anchor ? Geodetic{wave_anchor->lat, wave_anchor->lon, 0.0}
                                : nearest_wave_anchor(scene.camera.lat, scene.camera.lon);
  if (!(anchor.lat >= -90.0 && anchor.lat <= 90.0))
    refuse("wave_anchor.lat", "degrees in [-90, 90]", anchor.lat);
  if (!std::isfinite(anchor.lon)) refuse("wave_anchor.lon", "finite degrees", anchor.lon);
  impl_ = std::make_unique<Impl>(scene, anchor);
}

SeaState::~SeaState() = default;
SeaState::SeaState(const SeaState& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
SeaState& SeaState::operator=(const SeaState& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
SeaState::SeaState(SeaState&&) noexcept = default;
SeaState& SeaState::operator=(SeaState&&) noexcept = default;

const Scene& SeaState::scene() const { return impl_->scene; }
const Geodetic& SeaState::wave_anchor() const { return impl_->anchor; }

SeaPoint SeaState::at(double lat, double lon) const { return at(lat, lon, impl_->scene.time); }

SeaPoint SeaState::at(double lat, double lon, double time, double footprint) const {
  if (!(lat >= -90.0 && lat <= 90.0)) refuse("lat", "degrees in [-90, 90]", lat);
  if (!std::isfinite(lon)) refuse("lon", "finite degrees", lon);
  if (!(time >= 0.0 && time <= kSceneMaxTime)) refuse("time", "seconds in [0, 1e12]", time);
  if (!(footprint >= 0.0 && std::isfinite(footprint)))
    refuse("footprint", "finite metres >= 0", footprint);

  const Impl& sea = *impl_;
  const double reach = glm::length(sea.planet.ecef(lat, lon, 0.0) - sea.anchor_ecef);
  if (!(reach <= kAnchorReach)) {
    std::ostringstream message;
    message << "thalassa::SeaState: (lat, lon) = (" << lat << ", " << lon
            << "): expected a point within 1000 km of the waves' anchor (" << sea.anchor.lat << ", "
            << sea.anchor.lon << "), got one " << reach / 1e3 << " km from it";
    throw std::invalid_argument(message.str());
  }
  CameraSettings at_point;
  at_point.lat = lat;
  at_point.lon = lon;
  at_point.height = 0.0;
  // The point's frame exactly as a camera's nadir frame there: the chart's origin and axes
  // (planet/nadir_frame.hpp), so that the waves are the renderer's.
  const NadirFrame nadir = make_nadir_frame(sea.planet, at_point, sea.anchor);
  Query q;
  q.planet = &sea.planet;
  q.ocean = &sea.scene.ocean;
  q.calm = &sea.calm;
  q.time = time;
  q.footprint = footprint;
  const std::vector<double> phases = ocean::wrapped_phases(sea.waves, time, nadir.wave_origin);
  for (std::size_t i = 0; i < sea.waves.waves.size(); ++i) {
    const ocean::Wave& w = sea.waves.waves[i];
    const double h = filter_weight(sea.scene.ocean, w.wavelength, footprint) * w.amplitude;
    if (!(h > 0.0)) continue;
    q.waves.push_back({ocean::chart_direction_in_frame(nadir.wave_axes, w.direction), w.wavenumber,
                       h, phases[i], w.angular_frequency});
  }
  for (const FrameWave& w : q.waves) q.horizontal_bound += w.amplitude;
  for (const ShipWake& wake : sea.wakes) {
    ShipWake::Instant now = wake.at(time);
    GeoBounds bounds = now.bounds();
    if (bounds.empty()) continue;
    q.horizontal_bound += ocean::kelvin_wake_displacement_bound(now.ship().speed);
    q.wakes.push_back({std::move(now), bounds});
  }
  if (!sea.calm.empty() || !q.wakes.empty()) {
    q.frame.emplace(sea.planet, lat, lon, 0.0);
    q.surface = nadir.sea_surface;
    q.calm_step = std::clamp(sea.min_fade / 100.0, kCalmGradientMinStep, kCalmGradientMaxStep);
    q.target = kGeodeticNewtonTarget;
  }

  // Newton on F(p) = p + D_h(p) (the point is the origin), from p = 0.
  SeaPoint out;
  Iterate best = solve(q, glm::dvec2(0.0), out.iterations);
  if (!(best.r <= kSeaStateTolerance)) {
    // Newton stalled (beside a fold, where J is near singular, or on a local minimum of |F|). A
    // rest point exists: the map is p plus a bounded displacement, so it covers the plane. It
    // lies within the displacement's bound of the point: scan that disc and go on from the
    // nodes where |F| is least.
    const double radius = q.horizontal_bound;
    std::vector<std::pair<double, glm::dvec2>> nodes;
    for (int i = 0; i < kScanNodes; ++i) {
      for (int j = 0; j < kScanNodes; ++j) {
        const glm::dvec2 p =
            radius * (2.0 * glm::dvec2(i, j) / double(kScanNodes - 1) - glm::dvec2(1.0));
        if (glm::length(p) > radius * (1.0 + 1e-9)) continue;
        nodes.emplace_back(residual(p, q.field(p)), p);
      }
    }
    std::sort(nodes.begin(), nodes.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t k = 0; k < nodes.size() && k < kScanStarts; ++k) {
      Iterate tried = solve(q, nodes[k].second, out.iterations);
      if (tried.r < best.r) best = std::move(tried);
      if (best.r <= kSeaStateTolerance) break;
    }
    out.searched = true;
  }
  glm::dvec2 offset = best.offset;
  Field f = best.f;
  const double r = best.r;
  out.converged = r <= kSeaStateTolerance;
  q.add_wake_rates(best.searched, f);

  out.height = f.d.z;
  const glm::dvec3 tangent_x = glm::dvec3(1.0, 0.0, 0.0) + f.d_dx;
  const glm::dvec3 tangent_y = glm::dvec3(0.0, 1.0, 0.0) + f.d_dy;
  const glm::dvec3 n = glm::cross(tangent_x, tangent_y);
  const double n_length = glm::length(n);
  out.normal = n_length > 0.0 && std::isfinite(n_length) ? n / n_length : glm::dvec3(0, 0, 1);
  out.velocity = f.d_dt;
  const glm::dmat2 jacobian(tangent_x.x, tangent_x.y, tangent_y.x, tangent_y.y);
  const double det = glm::determinant(jacobian);
  out.height_rate = f.d_dt.z;
  if (std::abs(det) > kSingularJacobian) {
    const glm::dvec2 drift = -(glm::inverse(jacobian) * glm::dvec2(f.d_dt));
    out.height_rate += f.d_dx.z * drift.x + f.d_dy.z * drift.y;
  }
  out.rest_offset = offset;
  out.calm_scale = f.calm_scale;
  out.wakes = f.wakes;
  out.track_searches = q.track_searches;
  // Finite or a clear error (DESIGN section 4): no input in range is known to get here.
  for (double v : {out.height, out.normal.x, out.normal.y, out.normal.z, out.velocity.x,
                   out.velocity.y, out.velocity.z, out.height_rate, offset.x, offset.y}) {
    if (!std::isfinite(v)) {
      std::ostringstream message;
      message.precision(17);
      message << "thalassa::SeaState: the sea at (" << lat << ", " << lon << ") at " << time
              << " s is not finite (height " << out.height << ", normal z " << out.normal.z << ")";
      throw std::runtime_error(message.str());
    }
  }
  return out;
}

}  // namespace thalassa
