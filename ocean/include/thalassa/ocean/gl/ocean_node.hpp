// thalassa — the paper's ocean as a scene-graph node (GL layer, not installed).
//
// Bruneton, Neyret & Holzschuch 2010: the projected grid displaced by the waves longer than a
// grid cell (ocean.vert), per-pixel normals from the waves longer than a pixel and the unresolved
// slope variance of the shorter ones (ocean_geometry.frag), then the Ross BRDF lit by the sun,
// the sky and the refracted light from the sky provider, seen through the aerial perspective
// (ocean_lighting.frag).
#pragma once

#include <memory>

#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/scene_graph.hpp"
#include "thalassa/engine/scene.hpp"
#include "thalassa/ocean/local_features.hpp"
#include "thalassa/ocean/method.hpp"
#include "thalassa/ocean/scattered_sun_cache.hpp"

namespace thalassa::ocean {

struct OceanNodeOptions {
  OceanSettings settings;  // the wave set, filter weights, grid cell and Fresnel reflectance
  bool sun_glint = true;   // the reflected sun (eq. 15); left out when the sun has set
  bool sky = true;         // the reflected sky (eq. 21)
  bool sea = true;         // the light refracted from the water (eq. 28)
  bool air = true;         // the in-scattered light between the camera and the sea
  // Eq. 27's single anisotropic fetch (false) or the average of nine samples (true).
  bool sky_nine_samples = false;
  // Ramamoorthi & Hanrahan 2002's frequency-space prefiltering instead (overrides
  // sky_nine_samples): the sky term reads glossy sky maps (atmosphere/gl/sky_shrm.hpp) and L_sea
  // takes the sky's irradiance from the same SH projection.
  bool sky_shrm = false;
  // All sky light: the sky map, sun radiance, irradiance and aerial perspective.
  std::shared_ptr<atmosphere::SkyProvider> provider;
  // The shading method (ocean/method.hpp). The reference's node draws one sample per pixel, at
  // the frame's pixel_offset; the renderer averages many.
  OceanMethod method = OceanMethod::full;
  // The reference's sun (planet/renderer.hpp, ReferenceSun): with reference_sun_scatter (the
  // default), scattered once per image from a lattice of the sea
  // (shaders/ocean/reference_sun_scatter.comp), at most reference_sun_cells^2 cells per pixel's
  // footprint in whatever shape, reference_sun_cells in [1, 16384]; without it, gathered per sample
  // (shaders/ocean/reference_sun.glsl), at most reference_sun_cells per side of a sample's pixel
  // stratum, [1, 64]. Either way each cell is at most the shortest wavelength /
  // reference_cells_per_wavelength wide ([1, 128]); a stratum or pixel whose footprint needs more
  // is drawn with the most and marked unresolved.
  int reference_sun_cells = 256;
  double reference_cells_per_wavelength = 16.0;
  // With the scatter: each cell whose slopes come near the mirror slope is cut into this many
  // subcells per side, [1, 8] (1: none; reference_sun_scatter.comp, ScatterCell).
  int reference_sun_refine = 4;
  // The reference's grid cell, pixels, [kReferenceMinGridCell, 1] (ocean/method.hpp).
  double reference_grid_cell = kReferenceGridCell;
  bool reference_sun_scatter = true;
  // With the scatter: also the lattice of half the cells, for its convergence (ReferenceSampling::
  // measure_lattice).
  bool reference_measure_lattice = true;
  // With it: while a compared row moves by reference_lattice_tolerance (relative) or more, the
  // lattice doubles its cells (cells per wavelength and reference_sun_cells times sqrt 2) up to
  // reference_max_cells_per_wavelength (below reference_cells_per_wavelength: no doubling). Its
  // cap grows with it up to reference_max_sun_cells (at least reference_sun_cells) and is held
  // there while the cells per wavelength go on doubling: the footprints past the held cap, which a
  // finer lattice no longer resolves, drop out of the comparison (ReferenceSampling::
  // sun_max_cells_per_wavelength and sun_max_cells; the limits in ocean/method.hpp).
  double reference_max_cells_per_wavelength = 0.0;
  int reference_max_sun_cells = kReferenceHeldSunCells;
  double reference_lattice_tolerance = 0.01;
  // With the scatter: float atomic adds where the context has GL_NV_shader_atomic_float
  // (ReferenceSampling::sun_float_atomics), else compare-and-swap.
  bool reference_float_atomics = true;
  // With the scatter: the cells of a row each invocation of its cells' pass takes (its
  // segment; ReferenceSampling::sun_segment), [0, kReferenceMaxSunCells]. 0: the most that
  // llvmpipe's loop limit allows where the renderer has it (reference_sun_scatter.comp, "Why
  // segments"; at 8 x 8 subcells, 64 cells at 60 waves and 32 at 120 in blocks of 4 rows with
  // the refined cells queued; refined in place, 1 cell in blocks of 4 rows at 60 waves and of 3
  // at 120), kScatterFreeSegment where it has none. Else as asked, held to that most on
  // llvmpipe. The image does not depend on it but for float rounding; the time does, since an
  // invocation evaluates every corner of its cells, (block rows + 1)(segment + 1) for block rows
  // x segment cells.
  int reference_sun_segment = 0;
  // With the scatter: the rows of cells each invocation of its cells' pass takes (a column of
  // block_rows + 1 corners serves block_rows cells), [0, kReferenceMaxSunBlockRows]. 0:
  // kScatterFreeBlockRows (4). Else as asked. Held on llvmpipe to what one column's worst case
  // fits. Like the segment, it changes only the float rounding and the time.
  int reference_sun_block_rows = 0;
  // With the scatter: the places of its refined cells' queue (reference_sun_scatter.comp, stop
  // 42; ReferenceSampling::sun_refined_queue), [-1, kReferenceMaxSunRefinedQueue]. -1: the
  // default, the most (4,194,240 places, 64 MiB). 0: every refined cell is refined in place, by the
  // invocation that meets it, as before stop 42. Else the cells' pass runs in chunks, each
  // followed by a pass of their own for the refined cells it queued; a cell past a full queue is
  // refined in place. A chunk takes 16 times the queue's cells, or, on llvmpipe where a refined
  // cell would not fit its loop budget beside its invocation's block (then sized for unrefined
  // cells), no more cells than the queue holds, so that none is refined in place. Each chunk is
  // two dispatches: a queue of a few places (for tests) makes millions of them. Like the segment,
  // it changes only the float rounding and the time.
  std::int64_t reference_sun_refined_queue = -1;
  // With the scatter: the most invocations per batch of its cells' pass (ReferenceSampling::
  // sun_batch_invocations), [1, kReferenceMaxSunBatch].
  std::uint64_t reference_sun_batch = kReferenceMaxSunBatch;
  // With the scatter: a lattice another render of the same view scattered, drawn instead of
  // scattering it again where everything it depends on matches, and where this render's lattice
  // is stored (ocean/scattered_sun_cache.hpp). Null: every render scatters its own.
  std::shared_ptr<ScatteredSunCache> reference_sun_cache;
  // For tests: the first this many lattices the node scatters, or draws from
  // reference_sun_cache, have their sums overwritten on the GPU, with text (as the H200 read
  // back, ocean/src/scattered_sun_sums.hpp) and zeros in turn, before they are checked, so that
  // they are scattered (or sent) again (RenderStats::sun_lattice_rescatters, warnings); past
  // two in a row the render fails.
  int reference_sun_test_faults = 0;
  // The wakes and calm areas in view (issue 9), placed in the frame by the planet module; null
  // or empty: none, and none of their shader code is compiled.
  std::shared_ptr<const LocalFeatures> features;
  // Every option the same (the pointers: the same objects); Renderer::set_scene keeps a node made
  // with the same options.
  bool operator==(const OceanNodeOptions&) const = default;
};

std::unique_ptr<gl::Node> make_ocean_node(const OceanNodeOptions& options);

// The seamless switch to the view from space (issue 5, point 4; Bruneton et al. 2010 sec. 6): at
// 20 km the planet's ocean becomes a surface shaded with the Ross BRDF of every wave, with no
// geometry and no normals. So that nothing pops there, the projected grid hands its waves over
// to the BRDF before it: between kResolvedFadeStart and kResolvedFadeEnd of camera height, every
// wavelength is scaled by this factor in the filter weights w_p and w_n (eq. 2, 3), 1 below the
// band, 0 at its top (a C1 smoothstep), as if the pixels and cells grew without bound. A wave
// leaving the normals goes to the unresolved slope variance (eq. 4, w_r = 1 - w_n), so the
// hierarchy's energy is kept all the way, and at 20 km the grid shades exactly what the view
// from space does. The band starts at half the switch height: a 10 km camera resolves, at
// 1024 x 768 and 45 degrees, waves longer than about 25 m as normals; over the next 10 km they
// fade into the glint's width, as they would from the growing distance alone.
inline constexpr double kResolvedFadeStart = 10000.0;  // m
inline constexpr double kResolvedFadeEnd = 20000.0;    // m: the switch height (kSpaceModeHeight)
double resolved_wave_scale(double camera_height_m);

}  // namespace thalassa::ocean
