// thalassa — a scene's wakes and calm areas placed in a frame (planet/local_features.hpp).
#include "thalassa/planet/local_features.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/planet/calm_area.hpp"
#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/ship_wake.hpp"

namespace thalassa {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
// The footprint's margin for the ellipsoid (the tangent length is computed on a sphere of the
// equatorial radius), relative.
constexpr double kFootprintMargin = 1.01;
// Samples per side of the blocks whose distance is taken at their centre only.
constexpr int kChartBlock = 8;
// The chart's precision (calm_chart_distance_tolerance): a sample's signed distance is within
// max(1.1 cm, 1.1 % of the chart's spacing h) of the exact one, the estimate's tolerance plus the
// interpolation's below, so that its s is the exact s of a point that near it (the distance is
// 1-Lipschitz with a unit gradient): within 1.5 |1 - scale| 0.011 max(1 m, h) / fade of the
// exact value (the smoothstep's slope 1.5 / fade). The part relative to h stays below the
// chart's own error between its samples, which bilinear filtering of the fade's smoothstep
// leaves: up to h^2 / 8 times its largest curvature 6 |1 - scale| / fade^2, more than the
// tolerance's 1.5 |1 - scale| 0.011 h / fade wherever h > fade / 45 (3.3 m for a 150 m fade).
// Stop 46 held 1.1 cm at every spacing; a 200 km area seen whole from 100 km then took 43 ms of
// exact distances near its edge, 7 ms with the relative part (docs/wakes.md). (The bounds hold
// at the points a block is checked at, its corners, centre and edge midpoints; between them
// the interpolated distance is taken to be as close.)
// Largest difference (m) between a block's signed distance and the bilinear interpolation of its
// corners' for the block to be filled by interpolation: the larger of kChartDistanceTolerance
// and kChartRelativeDistanceTolerance (m per m of spacing) times the spacing.
constexpr double kChartDistanceTolerance = 0.01;
constexpr double kChartRelativeDistanceTolerance = 0.01;
// Largest error bound (m) of CalmArea::estimate_signed_distance for a sample's value to be taken
// from it rather than from the exact CalmArea::signed_distance: a tenth of the interpolation's,
// the larger of kChartEstimateTolerance and kChartRelativeEstimateTolerance (m per m of spacing)
// times the spacing. Where the bound is larger, the estimate still decides, with its bound,
// whether a block is wholly outside or deeper than the fade.
constexpr double kChartEstimateTolerance = 1e-3;
constexpr double kChartRelativeEstimateTolerance = 1e-3;

double estimate_tolerance(double spacing) {
  return std::max(kChartEstimateTolerance, kChartRelativeEstimateTolerance * spacing);
}
double interpolation_tolerance(double spacing) {
  return std::max(kChartDistanceTolerance, kChartRelativeDistanceTolerance * spacing);
}
// Samples of s = 1 kept around the areas' projected extent, so the chart's border is outside.
constexpr int kChartBorderSamples = 2;

// The past track's geodesics are laid in the frame's plane as straight pieces. A geodesic whose
// nearest point is r from the nadir projects (orthographically) to a curve of curvature about
// r / R^2, so a piece of length l bows from its chord by r l^2 / (8 R^2): pieces are cut to keep
// that below kTrackBow (a 6 km wake 10 km away needs one piece, from 1000 km 1.8 km pieces), at
// most kMaxTrackPieces per geodesic (fewer than that from the farthest views only, where the
// wake is a few pixels).
constexpr double kTrackBow = 0.01;  // m
constexpr int kMaxTrackPieces = 64;

// Rays sampled along each side of the image for its footprint on the sea.
constexpr int kFootprintRaysPerSide = 16;
// The footprint box's margin around each sampled point, relative to its distance from the nadir
// (the footprint's border bulges between two sampled rays by a small fraction of their distance:
// the horizon arc between azimuths delta apart by L (1 - cos(delta / 2)) < 1e-3 L here), and at
// least kFootprintMinMargin metres (the waves' horizontal displacement, a pixel's own size).
constexpr double kFootprintRelativeMargin = 0.02;
constexpr double kFootprintMinMargin = 5.0;

double horizon_length(const Planet& planet, double height) {
  const double h = std::max(height, 0.0);
  return std::sqrt(h * (2.0 * planet.equatorial_radius() + h));
}

// Builds the chart of the areas in view over [lo, hi] (m, frame plane). The signed distances
// are computed at block centres, corners and edge midpoints, as CalmArea's estimate where its
// bound is below the estimate's tolerance, else exactly (CalmArea::signed_distance). A block of
// samples is filled without computing more of them when
// - for every area the block is wholly outside (d + e + r <= 0) or wholly deeper than the fade
//   (d - e - r >= fade), e the distance's error bound, r the block's radius (the distance is
//   1-Lipschitz): s is exact there;
// - or every area's distance at the block's centre and edge midpoints is within the
//   interpolation's tolerance of the bilinear interpolation of its corners: s = fade(d) of the
//   interpolated d (exact for a straight edge; near a vertex the block is split instead);
// otherwise it is split in four, down to single cells.
class ChartBuilder {
 public:
  ChartBuilder(const Planet& planet, const NadirFrame& frame, const std::vector<CalmArea>& areas,
               ocean::CalmScaleChart& chart)
      : planet_(planet),
        frame_(frame),
        local_(planet, frame.nadir.lat, frame.nadir.lon, 0.0),
        areas_(areas),
        chart_(chart),
        distances_(areas.size() * chart.scale.size()),
        estimate_tolerance_(estimate_tolerance(chart.spacing)),
        interpolation_tolerance_(interpolation_tolerance(chart.spacing)) {}

  void fill(int i0, int j0, int size) {
    const int ci = i0 + size / 2, cj = j0 + size / 2, h = size / 2;
    const glm::dvec3 centre = ecef(ci, cj);
    double radius = 0.0;
    for (int i : {i0, i0 + size})
      for (int j : {j0, j0 + size}) radius = std::max(radius, glm::length(ecef(i, j) - centre));
    radius = radius * 1.001 + 1e-6;  // the chord, a little under the geodesic
    // Each area is constant over the block (s_a), bilinear in d, or neither (split).
    double constant = 1.0;
    std::vector<std::size_t> interpolated;
    for (std::size_t a = 0; a < areas_.size(); ++a) {
      // Outside (-1), deeper than the fade (1), or neither (0), for d within +-e of the centre's.
      const double fade = areas_[a].settings().fade;
      auto side = [&](const Distance& c) {
        return c.d + c.e + radius <= 0.0 ? -1 : c.d - c.e - radius >= fade ? 1 : 0;
      };
      int where = side(estimate(a, ci, cj));
      if (where == 0) where = side(precise(a, ci, cj));
      if (where < 0) continue;
      if (where > 0) {
        constant *= areas_[a].settings().scale;
        continue;
      }
      const double d = distance(a, ci, cj);
      if (size == 1) {
        interpolated.push_back(a);  // the corners' own values
        continue;
      }
      const double d00 = distance(a, i0, j0), d10 = distance(a, i0 + size, j0);
      const double d01 = distance(a, i0, j0 + size), d11 = distance(a, i0 + size, j0 + size);
      const double checks[5][2] = {{d, 0.25 * (d00 + d10 + d01 + d11)},
                                   {distance(a, i0 + h, j0), 0.5 * (d00 + d10)},
                                   {distance(a, i0 + h, j0 + size), 0.5 * (d01 + d11)},
                                   {distance(a, i0, j0 + h), 0.5 * (d00 + d01)},
                                   {distance(a, i0 + size, j0 + h), 0.5 * (d10 + d11)}};
      bool bilinear = true;
      for (const auto& c : checks)
        bilinear = bilinear && std::abs(c[0] - c[1]) <= interpolation_tolerance_;
      if (!bilinear) {
        for (int dj : {0, h})
          for (int di : {0, h}) fill(i0 + di, j0 + dj, h);
        return;
      }
      interpolated.push_back(a);
    }
    for (int j = j0; j <= j0 + size; ++j)
      for (int i = i0; i <= i0 + size; ++i) {
        const double u = double(i - i0) / size, v = double(j - j0) / size;
        double product = constant;
        for (std::size_t a : interpolated) {
          const double d =
              (1 - u) * (1 - v) * distance(a, i0, j0) + u * (1 - v) * distance(a, i0 + size, j0) +
              (1 - u) * v * distance(a, i0, j0 + size) + u * v * distance(a, i0 + size, j0 + size);
          product *= calm_fade(d, areas_[a].settings().scale, areas_[a].settings().fade);
        }
        chart_.scale[index(i, j)] = float(product);
      }
  }

 private:
  std::size_t index(int i, int j) const { return std::size_t(j) * chart_.width + i; }
  // The point of the sea at rest above sample (i, j), ECEF (m).
  glm::dvec3 ecef(int i, int j) const {
    const glm::dvec2 xy = chart_.origin + chart_.spacing * glm::dvec2(i, j);
    return local_.to_ecef({xy.x, xy.y, ocean::sea_surface_sag(frame_.sea_surface, xy)});
  }
  // A sample's signed distance d (m) from area a's edge and the bound e (m) on its error.
  struct Distance {
    double d = NAN, e = INFINITY;
  };
  const Distance& estimate(std::size_t a, int i, int j) {
    Distance& x = distances_[a * chart_.scale.size() + index(i, j)];
    if (std::isnan(x.d)) {
      const Geodetic g = planet_.geodetic(ecef(i, j));
      const CalmArea::DistanceEstimate estimate = areas_[a].estimate_signed_distance(g.lat, g.lon);
      x = {estimate.distance, estimate.error};
    }
    return x;
  }
  // The same, to within the estimate's tolerance.
  const Distance& precise(std::size_t a, int i, int j) {
    Distance& x = distances_[a * chart_.scale.size() + index(i, j)];
    if (estimate(a, i, j).e > estimate_tolerance_) {
      const Geodetic g = planet_.geodetic(ecef(i, j));
      x = {areas_[a].signed_distance(g.lat, g.lon), 0.0};
    }
    return x;
  }
  double distance(std::size_t a, int i, int j) { return precise(a, i, j).d; }

  const Planet& planet_;
  const NadirFrame& frame_;
  const LocalFrame local_;
  const std::vector<CalmArea>& areas_;
  ocean::CalmScaleChart& chart_;
  std::vector<Distance> distances_;  // per area and sample; NaN until computed
  const double estimate_tolerance_, interpolation_tolerance_;  // m
};

// The chart: the areas in view, sampled over [lo, hi] (m, frame plane) with a border of s = 1,
// its sides a whole number of kChartBlock cells.
ocean::CalmScaleChart sample_chart(const Planet& planet, const NadirFrame& frame,
                                   const std::vector<CalmArea>& areas, glm::dvec2 lo, glm::dvec2 hi,
                                   int samples) {
  ocean::CalmScaleChart chart;
  chart.areas = static_cast<int>(areas.size());
  const glm::dvec2 extent = hi - lo;
  chart.spacing =
      std::max(std::max(extent.x, extent.y) / (samples - 1 - 2 * kChartBorderSamples), 1e-3);
  chart.origin = lo - double(kChartBorderSamples) * chart.spacing;
  auto side = [&](double length) {
    const int cells = int(std::ceil(length / chart.spacing)) + 2 * kChartBorderSamples;
    return (cells + kChartBlock - 1) / kChartBlock * kChartBlock + 1;
  };
  chart.width = side(extent.x);
  chart.height = side(extent.y);
  chart.scale.assign(std::size_t(chart.width) * chart.height, 1.0f);
  ChartBuilder builder(planet, frame, areas, chart);
  for (int j = 0; j + 1 < chart.height; j += kChartBlock)
    for (int i = 0; i + 1 < chart.width; i += kChartBlock) builder.fill(i, j, kChartBlock);
  return chart;
}

// The box of the frame's (x, y) plane (m) that holds every point of the sea the image sees: the
// image border's rays met with the sea at rest, or, for a ray above the horizon, the point of
// the horizon's tangent length along its azimuth (the sea below that ray, in the image column,
// reaches no farther); the border's image is the boundary of the footprint.
struct FootprintBox {
  glm::dvec2 lo{INFINITY}, hi{-INFINITY};
  bool intersects(glm::dvec2 a, glm::dvec2 b) const {
    return a.x <= hi.x && b.x >= lo.x && a.y <= hi.y && b.y >= lo.y;
  }
};

FootprintBox screen_footprint(const Planet& planet, const Scene& scene, const NadirFrame& frame) {
  FootprintBox box;
  const CameraBasis basis =
      camera_basis(scene.camera.heading, scene.camera.pitch, scene.camera.roll);
  const double tan_half = std::tan(0.5 * scene.camera.fov_y * kDegree);
  const double aspect = double(scene.image.width) / scene.image.height;
  const double height = std::max(frame.camera_height, 1e-3);
  const double reach = kFootprintMargin * horizon_length(planet, height) + 1.0;
  auto add = [&](double u, double v) {
    const glm::dvec3 ray = glm::normalize(view_ray(basis, tan_half, aspect, u, v));
    glm::dvec2 p;
    if (const auto t = ocean::sea_surface_distance(frame.sea_surface, height, ray)) {
      p = glm::dvec2(ray) * *t;
    } else {
      const double horizontal = std::hypot(ray.x, ray.y);
      if (!(horizontal > 0.0)) return;  // straight up
      p = glm::dvec2(ray) / horizontal * reach;
    }
    const double margin = std::max(kFootprintRelativeMargin * glm::length(p), kFootprintMinMargin);
    box.lo = glm::min(box.lo, p - margin);
    box.hi = glm::max(box.hi, p + margin);
  };
  for (int k = 0; k <= kFootprintRaysPerSide; ++k) {
    const double w = -1.0 + 2.0 * k / kFootprintRaysPerSide;
    add(w, -1.0);
    add(w, 1.0);
    add(-1.0, w);
    add(1.0, w);
  }
  return box;
}

}  // namespace

double calm_chart_distance_tolerance(double spacing) {
  return estimate_tolerance(spacing) + interpolation_tolerance(spacing);
}

GeoBounds view_footprint(const Planet& planet, const NadirFrame& frame) {
  if (frame.camera_height < 0.0) return GeoBounds{};
  const GeoBounds nadir{frame.nadir.lat, frame.nadir.lat, frame.nadir.lon, frame.nadir.lon};
  return nadir.expanded(kFootprintMargin * horizon_length(planet, frame.camera_height) + 1.0,
                        planet.equatorial_radius(), planet.flattening());
}

ocean::LocalFeatures place_local_features(const Planet& planet, const Scene& scene,
                                          const NadirFrame& frame, int chart_samples) {
  ocean::LocalFeatures features;
  if (scene.wakes.empty() && scene.calm_areas.empty()) return features;
  const GeoBounds footprint = view_footprint(planet, frame);
  if (footprint.empty()) return features;
  const LocalFrame local(planet, frame.nadir.lat, frame.nadir.lon, 0.0);
  const FootprintBox screen = screen_footprint(planet, scene, frame);
  const GeographicLib::Geodesic geodesic(planet.equatorial_radius(), planet.flattening());

  for (const WakeSettings& settings : scene.wakes) {
    // The ship and its past track found once for the bounds, the ship and the track below.
    const ShipWake::Instant wake = ShipWake(planet, settings).at(scene.time);
    const GeoBounds bounds = wake.bounds();
    if (bounds.empty() || !bounds.intersects(footprint)) continue;
    const ShipWake::State ship = wake.ship();
    if (!ship.present || !(ship.speed >= ocean::kMinimumWakeSpeed)) continue;
    ocean::WakeInFrame placed;
    placed.name = settings.name;
    placed.params = {.speed = ship.speed,
                     .amplitude = settings.amplitude,
                     .draft = settings.draft,
                     .length = settings.length};
    // The past track in the frame's plane, each geodesic cut into pieces (kTrackBow).
    const std::vector<GeoPoint> past = wake.past_track();
    const double radius = planet.equatorial_radius();
    placed.track.push_back(glm::dvec2(local.offset(past[0].lat, past[0].lon, 0.0)));
    for (std::size_t k = 0; k + 1 < past.size(); ++k) {
      double length, azi1, azi2;
      geodesic.Inverse(past[k].lat, past[k].lon, past[k + 1].lat, past[k + 1].lon, length, azi1,
                       azi2);
      const glm::dvec2 a = placed.track.back();
      const glm::dvec2 b(local.offset(past[k + 1].lat, past[k + 1].lon, 0.0));
      const double r = std::max({glm::length(a), glm::length(b), 1.0});
      const double piece = std::sqrt(8.0 * radius * radius * kTrackBow / r);
      const int pieces = std::clamp(int(std::ceil(length / piece)), 1, kMaxTrackPieces);
      for (int m = 1; m < pieces; ++m) {
        double lat, lon;
        geodesic.Direct(past[k].lat, past[k].lon, azi1, length * m / pieces, lat, lon);
        placed.track.push_back(glm::dvec2(local.offset(lat, lon, 0.0)));
      }
      placed.track.push_back(b);
    }
    if (placed.track.size() < 2) continue;
    // On screen: the track's box grown by the half-width against the image's footprint.
    const double half_width = ocean::kelvin_wake_half_width(placed.params);
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    for (const glm::dvec2& q : placed.track) {
      lo = glm::min(lo, q - half_width);
      hi = glm::max(hi, q + half_width);
    }
    if (!screen.intersects(lo, hi)) continue;
    features.wakes.push_back(placed);
  }

  std::vector<CalmArea> areas;
  glm::dvec2 lo(INFINITY), hi(-INFINITY);
  for (const CalmAreaSettings& settings : scene.calm_areas) {
    CalmArea area(planet, settings);
    if (!area.bounds().intersects(footprint)) continue;
    // The projected extent: the vertices, grown by the bulge of the geodesic edges between them
    // on the frame's plane (below l^2 / (4 a) for an edge of length l, taken generously).
    glm::dvec3 previous =
        local.offset(settings.exterior.back().lat, settings.exterior.back().lon, 0.0);
    double bulge = 0.0;
    for (const GeoPoint& p : settings.exterior) {
      const glm::dvec3 x = local.offset(p.lat, p.lon, 0.0);
      lo = glm::min(lo, glm::dvec2(x));
      hi = glm::max(hi, glm::dvec2(x));
      const double l = glm::length(x - previous);
      bulge = std::max(bulge, l * l / planet.equatorial_radius());
      previous = x;
    }
    lo -= bulge;
    hi += bulge;
    areas.push_back(std::move(area));
  }
  if (!areas.empty()) {
    // Only what the image sees.
    lo = glm::max(lo, screen.lo);
    hi = glm::min(hi, screen.hi);
    if (lo.x < hi.x && lo.y < hi.y)
      features.calm = sample_chart(planet, frame, areas, lo, hi, chart_samples);
  }
  return features;
}

}  // namespace thalassa
