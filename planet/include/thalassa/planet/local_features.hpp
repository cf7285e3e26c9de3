// thalassa — a scene's wakes and calm areas placed in a frame for the GPU (issue 9, points 1, 2
// and 5; docs/wakes.md "On the GPU"): culled by their geodetic bounds against the view's
// footprint, then made camera-relative in double (the nadir frame of planet/nadir_frame.hpp)
// into the ocean module's form (ocean/local_features.hpp).
#pragma once

#include "thalassa/engine/scene.hpp"
#include "thalassa/ocean/local_features.hpp"
#include "thalassa/planet/geo_bounds.hpp"
#include "thalassa/planet/geodesy.hpp"
#include "thalassa/planet/nadir_frame.hpp"

namespace thalassa {

// Samples of the calm-area chart along its longer side.
inline constexpr int kCalmChartSamples = 256;

// Conservative bounds of every point of the sea the camera of `frame` can see: the cap around
// its nadir out to the horizon (the tangent length sqrt(h (2 a + h)) from height h, longer than
// the surface distance to the horizon), grown by 1 % for the ellipsoid. A camera under the sea
// sees no feature: the empty region.
GeoBounds view_footprint(const Planet& planet, const NadirFrame& frame);

// The scene's wakes at scene.time and calm areas that intersect view_footprint and, in the
// frame's plane, the box of what the image sees of the sea (its border's rays met with the sea,
// or taken to the horizon), placed in the frame:
// each ship where ShipWake puts it, its course at the ship turned into the frame's axes; the
// calm areas' amplitude scale sampled in double (CalmArea::amplitude_scale, multiplied over
// overlapping areas) on a grid of the frame's (x, y) plane that covers the areas in view (each
// sample at the point of the sea at rest above it), kCalmChartSamples along its longer side.
// Samples far from every edge are filled from one distance per 8 x 8 block (the signed distance
// is 1-Lipschitz), so the cost follows the edges' length on the chart, not its area. Distances
// are CalmArea::estimate_signed_distance's where its bound is below 1/11 of
// calm_chart_distance_tolerance (the rest is the interpolation's), else exact.
ocean::LocalFeatures place_local_features(const Planet& planet, const Scene& scene,
                                          const NadirFrame& frame,
                                          int chart_samples = kCalmChartSamples);

// The largest error (m) of the signed distance behind a calm chart's sample, for a chart of
// `spacing` m between samples: 1.1 cm up to a 1 m spacing, 1.1 % of the spacing beyond (held at
// the points each 8 x 8 block is checked at; the samples between are interpolated). Each
// sample's s is then the exact s of a point that near it, and within 1.5 |1 - scale| times this
// over the fade of the exact value (for one area; overlapping areas add). The part relative to
// the spacing stays below the error the chart's bilinear filtering makes between its samples
// wherever the spacing exceeds fade / 45.
double calm_chart_distance_tolerance(double spacing);

}  // namespace thalassa
