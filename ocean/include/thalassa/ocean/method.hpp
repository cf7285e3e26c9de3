// thalassa — the ocean's shading methods (issue 6; Bruneton, Neyret & Holzschuch 2010, sec. 7.2
// and fig. 10), so that the paper's hierarchy can be measured against simpler methods and a
// reference, and so that users can render each.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace thalassa::ocean {

enum class OceanMethod {
  // The paper's hierarchy: positions filtered by w_p (eq. 2), normals by w_n (eq. 3), and the
  // Ross BRDF of the unresolved waves (eq. 4) with the pixel's own normal variation.
  full,
  // Fig. 10's "basic" method: the same filtered positions and normals, with a constant BRDF: the
  // slope variance the full method has in the image's foreground (its smallest footprint),
  // everywhere, not adapted to the sub-pixel details farther away.
  basic,
  // The full method without the BRDF: filtered positions and normals, and a mirror (the slope
  // variance 0; the sun keeps the width of its disc).
  normals,
  // Every wave as geometry and normals (w_p = w_n = 1, 1-pixel grid cells) and a mirror, each
  // pixel averaged over many samples (the renderer supersamples it: planet/renderer.hpp).
  reference,
};

// The reference's sun's limits (planet/renderer.hpp, ReferenceSampling; its lattice,
// shaders/ocean/reference_sun_scatter.comp), checked by everything that takes them (the renderer,
// the suite file, the command line). Cells per shortest wavelength: the 30-wave variant's
// references, a few isolated glints a row in the foreground, still moved rows by 1.4 % between
// 45.25 and 64 (stop 29, docs/validation.md), so the lattice may double twice more. The cap,
// scattered (sun_cells): a footprint has at most cap^2 cells, in whatever shape (since stop 34).
// 16,384 (2.7e8 cells a pixel) resolves the default suite's views at 16 per wavelength down to
// the row below the horizon's, which needs 8.9e7 (the horizon's row, 1.7e9, stays out of reach:
// docs/validation.md, "Footprints cut by their cells"); a footprint's invocations (at most one
// per cell) then fit one batch of the shader's 32-bit index, and each side's cells (at most
// 333,000 on the horizon's row) a float's whole numbers. The cap grows with the cells as the
// lattice doubles (times sqrt 2 each doubling) up to sun_max_cells, kReferenceHeldSunCells by
// default: the default suite's 2,048 is held there, and a reference that must double gives up
// the far rows its finer cells no longer fit rather than doubling their cost.
inline constexpr double kReferenceMaxCellsPerWavelength = 128.0;
inline constexpr int kReferenceMaxSunCells = 16384;
inline constexpr int kReferenceHeldSunCells = 2048;
// The most invocations of one batch of the scattered sun's cells' pass: its shader counts them in
// 32 bits (reference_sun_scatter.comp). A footprint's are at most kReferenceMaxSunCells^2.
inline constexpr std::uint64_t kReferenceMaxSunBatch = std::uint64_t(1) << 31;
static_assert(std::uint64_t(kReferenceMaxSunCells) * kReferenceMaxSunCells <= kReferenceMaxSunBatch);
// The most rows of cells one invocation of the scattered sun's cells' pass may take (its column
// of corners is one longer: reference_sun_scatter.comp, REFERENCE_ROWS).
inline constexpr int kReferenceMaxSunBlockRows = 8;
// The most places of the scattered sun's refined cells' queue (reference_sun_scatter.comp, stop
// 42; 16 bytes each, 64 MiB): the refined cells of one chunk of its cells' pass, one invocation
// each of a dispatch of at most 65535 work groups of 64 (GL's least guaranteed work-group count).
inline constexpr std::int64_t kReferenceMaxSunRefinedQueue = std::int64_t(65535) * 64;
// The reference's grid cell, pixels (ReferenceSampling::grid_cell): its vertices one per pixel by
// default, down to this many per pixel side, so that a crest hides what lies behind it inside
// a pixel for waves down to two cells (stop 44, docs/validation.md).
inline constexpr double kReferenceGridCell = 1.0;
inline constexpr double kReferenceMinGridCell = 0.125;
// The most samples per pixel a reference may double to (issue 6, point 1): the 20 m/s sea's sky
// at 4 m still moved a row by 1.2 % between 2,048 and 4,096 (stop 28, docs/validation.md).
inline constexpr int kReferenceMaxPixelSamples = 16384;

std::string_view method_name(OceanMethod method);
// "full", "basic", "normals", "reference" -> the method; nullopt otherwise.
std::optional<OceanMethod> parse_method(std::string_view name);

}  // namespace thalassa::ocean
