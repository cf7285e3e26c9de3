// thalassa — renders a scene: the entry point for applications and the command-line program.
//
// A Renderer turns a validated Scene into a graph of nodes (sky, sea, ...), creating only what
// the scene needs, and draws frames into a linear HDR framebuffer in the GL context that is
// current: one from create_context()/create_headless_context(), or the host application's own
// (attach_host_context()). This header exposes no GL types.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "thalassa/engine/context.hpp"
#include "thalassa/engine/image.hpp"
#include "thalassa/engine/scene.hpp"
#include "thalassa/ocean/method.hpp"
#include "thalassa/ocean/scattered_sun_cache.hpp"
#include "thalassa/planet/geodesy.hpp"
#include "thalassa/planet/sea_state.hpp"

namespace thalassa {

// Camera heights at and above this are rendered in `space` mode (DESIGN section 1), in metres.
constexpr double kSpaceModeHeight = 20000.0;
// Lowest camera height drawn, m: 1 mm, below anything a pixel of the sea can show from there
// (the issue 7 stress cases go down to 0.01 m). A camera exactly on the sea (height 0) sees it
// from here, since the sea's quadric meets rays from a positive height only.
constexpr double kSurfaceCameraHeight = 1e-3;

struct RenderStats {
  std::string backend;   // "egl", "osmesa", "glfw", "host"
  std::string renderer;  // GL_RENDERER
  // GL_VERSION, which holds the driver's version ("4.5 (Core Profile) Mesa 22.3.6", "4.6.0
  // NVIDIA 580.159.04"), and how the context was made (GlContext::description: "EGL 1.5 device
  // platform (NVIDIA), told of GPU resets"): what a frame time or a fault is to be read with.
  std::string gl_version;
  std::string context;
  int width = 0;         // pixels
  int height = 0;
  std::string mode;     // "space" or "surface"
  int frames = 0;       // frames rendered so far
  double frame_ms = 0;  // GPU time of a frame, median over the frames rendered
  // How the GPU times were taken: "gl_timestamp_query" on hardware drivers, or
  // "finish_wall_clock" on Mesa's software rasterisers, whose timestamp queries miss the
  // rasterisation (see thalassa/engine/gl/gpu_timer.hpp).
  std::string timing;
  // Frames (a reference's samples each count) whose timestamp queries were unusable: their
  // time is the host's, from the frame's first command to its results read back, an upper
  // bound (thalassa/engine/gl/gpu_timer.hpp).
  int timing_fallback_frames = 0;
  std::vector<std::pair<std::string, double>> passes;  // pass -> GPU ms, median over frames
  int resolved_waves = 0;          // waves summed as geometry or normals (surface mode)
  // Modules and shader features this scene caused to exist, and "shader:" the programs its
  // frames drew with.
  std::vector<std::string> built;
  std::string sky_provider;        // "atmosphere" or "environment_map"
  std::string method = "full";     // the ocean's shading method (ocean/method.hpp)
  // The reference method: samples averaged per pixel, and the largest relative change of an
  // image row's total luminance of the sea between the average of the first samples / 2 and of
  // all of them (its convergence test, ReferenceSampling); 1 sample and 0 for the other methods.
  int samples = 1;
  double sample_row_change = 0.0;
  // The same change per image row (top first; NaN in the rows the test does not count: without
  // sea, or below 1e-3 of the brightest row); empty when the samples were not doubled.
  std::vector<double> sample_row_changes;
  // The reference method with the sun term: how its sun was integrated, "scattered" or
  // "gathered" (ReferenceSun); empty otherwise.
  std::string reference_sun;
  // The reference method with the sun scattered (ReferenceSun::scattered), else 0: the
  // largest relative change of an image row's total sun between its lattice and one with half
  // the cells (the sun's convergence test: its "normal samples",
  // shaders/ocean/reference_sun_scatter.comp), measured on the sun_lattice_rows rows whose sea
  // both lattices resolve; the wall-clock ms of the two lattices (counted once in the
  // reference's frame time); the pixels the lattice reached beyond each image edge; the
  // fraction of the front-facing sea's solid angle that the grid's crests hid; and the subcells
  // per side its cells near the mirror slope were cut into (ReferenceSampling::sun_refine, lower
  // where the shader's loop budget on llvmpipe would not hold one refined cell).
  double sun_lattice_row_change = 0.0;
  int sun_lattice_rows = 0;
  double sun_lattice_ms = 0.0;
  int sun_lattice_margin = 0;
  double sun_lattice_hidden = 0.0;
  int sun_lattice_refine = 0;
  int sun_lattice_segment = 0;  // the cells of a row per invocation of the scatter, as run
  int sun_lattice_block_rows = 0;  // and its rows of cells per invocation
  // Its refined cells' queue as run (places per chunk of the cells' pass; 0: every refined cell
  // refined in place; ReferenceSampling::sun_refined_queue), and the lattice's cells, those of
  // them refined (cut into sun_lattice_refine^2 subcells) and those refined in place (all of
  // them with no queue, else those past a full queue).
  double sun_lattice_refined_queue = 0.0;
  double sun_lattice_scattered_cells = 0.0;
  double sun_lattice_refined_cells = 0.0;
  double sun_lattice_refined_in_place = 0.0;
  // The lattice's change per image row (top first; NaN in the rows it does not count); empty
  // when the lattice was not measured.
  std::vector<double> sun_lattice_row_changes;
  // The lattice as drawn, after sun_lattice_doublings doublings of its cells
  // (ReferenceSampling::sun_max_cells_per_wavelength): its cells per shortest wavelength and cap
  // (at most its square per pixel's footprint). The change above is against the lattice before
  // its last doubling.
  double sun_lattice_cells_per_wavelength = 0.0;
  int sun_lattice_cells = 0;
  // Per image row (top first), the cells along the image's x and y of the lattice's footprint
  // with the most cells in that row (a footprint is resolved when they are at most
  // sun_lattice_cells^2 together, in whatever shape); empty when the lattice was kept
  // (sun_lattice_reused) or not scattered.
  std::vector<std::array<int, 2>> sun_lattice_row_cells;
  int sun_lattice_doublings = 0;
  bool sun_lattice_float_atomics = false;  // its sums added by float atomics (sun_float_atomics)
  // Its sums taken from ReferenceSampling::sun_cache, as another render scattered them: then
  // sun_lattice_ms is that lattice's own scatter time (what the image cost, not spent by this
  // render), and the lattice is not measured (sun_lattice_rows 0).
  bool sun_lattice_reused = false;
  // Lattices scattered again because their sums held what no scatter writes (the H200's text
  // of stop 40: ocean/src/scattered_sun_sums.hpp); 0 as a rule.
  int sun_lattice_rescatters = 0;
  // What the scene graph's nodes had to work around in this render, in words (gl::Node::
  // warnings: a rescattered lattice and what its sums held); empty as a rule.
  std::vector<std::string> warnings;
  // The reference method with the sun term: per image row (top first), the fraction of its
  // pixels whose sun was integrated over cells that resolve every wave (sky pixels count as
  // resolved); the validation compares methods on the resolved rows only. Empty otherwise.
  std::vector<double> resolved_rows;
  // The reference method: its samples whose radiance was not finite (a pixel's mean over its
  // samples is then not finite either), the pixels that had any, and the first of them (x, y
  // from the image's top left; -1, -1 when none) with its count of them. A pixel whose every
  // sample is not finite points at what its samples share (the scattered sun's sums,
  // Renderer::reference_sun_sums), one with a few at a sample's own shading.
  long long reference_nonfinite_samples = 0;
  int reference_nonfinite_pixels = 0;
  int reference_first_nonfinite_x = -1;
  int reference_first_nonfinite_y = -1;
  int reference_first_nonfinite_samples = 0;
  // One-off costs this scene paid, wall-clock ms: "sky.provider" (creating it, the atmosphere's
  // tables computed or loaded from the cache included), "atmosphere.precompute" /
  // "atmosphere.load", "sky.map", "sky.map_array", "features.place" (culling and placing the
  // scene's wakes and calm areas, their chart sampled on the CPU: planet/local_features.hpp;
  // only with some), "shaders.compile" (the programs its frames compiled, the constructor's
  // first frame included; none where every program was compiled for an earlier scene) and
  // "renderer.set_scene" (Renderer::set_scene's own time, of which the others but the shaders'
  // are parts; only after set_scene). A provider kept from an earlier Renderer or scene
  // (sky_provider_kept) adds none of its own, and its maps only where this scene built them
  // again.
  std::vector<std::pair<std::string, double>> setup_ms;
  // The sky provider came from RendererOptions::sky_cache, or from the Renderer's own cache,
  // made for an earlier Renderer or scene.
  bool sky_provider_kept = false;
  // The scene graph's nodes ("sky", "ocean") that Renderer::set_scene kept from the last scene,
  // their GPU objects and tables with them, rather than make them again; empty after the
  // constructor.
  std::vector<std::string> kept_nodes;
  // The waves' chart's origin (degrees, height 0; planet/nadir_frame.hpp): the lattice point
  // nearest the camera, RendererOptions::wave_anchor, or the one an earlier scene kept
  // (Renderer::set_scene).
  Geodetic wave_anchor;
  // Renderer::set_scene kept the last scene's chart of the calm areas in view (planet/
  // local_features.hpp), where the camera, the image's size, the planet and the areas were the
  // same (the clock alone moved): "features.place" then placed the wakes alone.
  bool calm_chart_kept = false;
  // The reference: its grid's cell, pixels (ReferenceSampling::grid_cell); 0 for the others.
  double reference_grid_cell = 0.0;
};

// The ocean's light terms (Bruneton et al. 2010 sec. 5): all by default; validation renders
// them one by one.
struct LightTerms {
  bool sun = true;  // reflected sun (eq. 15)
  bool sky = true;  // reflected sky (eq. 21)
  bool sea = true;  // light refracted from the water (eq. 28)
  // Light the atmosphere scatters toward the camera between it and the sea (aerial
  // perspective's in-scattered part; its transmittance applies to the other terms always).
  bool air = true;
};
// Parses "sun,sky,sea,air" (a comma-separated, non-empty subset, in any order) into `terms`;
// returns "" or a message saying what was expected (the command line puts "--terms" before it).
std::string parse_light_terms(std::string_view text, LightTerms& terms);

// How the reference's reflected sun is integrated (ReferenceSampling). Its 0.27 degree disc would
// need millions of point samples per pixel, so both integrate it over cells of the sea no wider
// than the shortest wavelength / sun_cells_per_wavelength, each a bilinear patch of exact normals
// whose glint is the sun's parallelogram (shaders/ocean/reference_cell.glsl).
enum class ReferenceSun {
  // Once per image: each pixel's footprint on the sea at rest is cut into a lattice of cells (at
  // most sun_cells^2 per footprint, in whatever shape it needs: the footprints near the horizon
  // are thousands of cells along the view and tens across; sun_cells in [1, 16384]) and each
  // cell's sun is added to the pixel that sees
  // its glint (shaders/ocean/reference_sun_scatter.comp). The same for every sample: the sun
  // adds no noise between sample counts, and its convergence is measured instead against a
  // lattice of half the cells (RenderStats::sun_lattice_row_change). It does not depend on the
  // image's resolution (tests/gpu/method_test.cpp, docs/validation.md).
  scattered,
  // Per sample: the sample's stratum's footprint, differenced from the rasterised rest
  // positions across a 2 x 2 quad, is cut into cells (sun_cells per pixel side shared among the
  // s strata of a side, at most 64 per stratum side; shaders/ocean/reference_sun.glsl). Kept to
  // compare with: its far rows darken as the pixels shrink (5-28 % in far bands at 96x64 against
  // 48x32, docs/validation.md, stop 19), because its footprint no longer tiles the sea there.
  gathered,
};

// Parses "scattered" or "gathered"; nullopt otherwise.
std::optional<ReferenceSun> parse_reference_sun(std::string_view name);
const char* reference_sun_name(ReferenceSun sun);

// How the reference method samples each pixel: frames drawn at stratified pixel offsets and
// averaged, doubling from min_samples until doubling changes every image row's total luminance
// of the sea by less than row_tolerance (relative), or max_samples are reached (Bruneton et al.
// 2010 sec. 7.2's supersampled reference; issue 6, point 1). A row's sea is its pixels' samples
// of the sea (their share of each pixel; the sky's samples, the same for every method, do not
// count). Rows darker than 1e-3 of the brightest row do not count. The pixel is cut into s x s
// strata, s = floor(sqrt(min(min_samples, max_samples))), each sampled once per round at the Halton
// (2, 3) point of the round; sample counts are whole rounds (max_samples is rounded down to a
// multiple of s^2).
//
// The reflected sun is integrated over cells of the sea (ReferenceSun); sun_cells,
// sun_cells_per_wavelength and sun_refine size them. Pixels that would need more than sun_cells^2
// (scattered) or strata more than their share of sun_cells per side (gathered) are drawn with
// fewer and reported unresolved (RenderStats::resolved_rows).
// Measured (docs/validation.md, stop 22): the scattered sun's resolved rows move by 1.0 % at
// most between 16 cells per wavelength refined 4 x 4 and its lattice of half the cells, 24 %
// unrefined.
struct ReferenceSampling {
  int min_samples = 16;
  int max_samples = 1024;
  double row_tolerance = 0.01;
  // Draw max_samples (rounded down to whole rounds) whatever the rows do: the same sample
  // points as another frame that converged at that count (validate's flicker frames, whose
  // difference is then the sea's motion, not two estimates' noise).
  bool fixed_samples = false;
  int sun_cells = 256;
  double sun_cells_per_wavelength = 16.0;
  ReferenceSun sun = ReferenceSun::scattered;
  // Scattered: cells whose slopes come near the mirror slope (the few that reflect the sun) are
  // cut into sun_refine x sun_refine subcells, [1, 8] (1: none), as if the lattice were that much
  // finer where the glints are (shaders/ocean/reference_sun_scatter.comp, ScatterCell).
  int sun_refine = 4;
  // The grid the reference rasterises every wave on: its cell in pixels, [1/8, 1]
  // (ocean::kReferenceMinGridCell). Each sample's normal is exact whatever the cell; the cell
  // decides the positions, so which facets a crest hides inside a pixel: those behind waves of
  // two cells and longer. Finer costs the square in vertices (docs/validation.md, stop 44).
  double grid_cell = ocean::kReferenceGridCell;
  // Scattered: also scatter the lattice of half the cells, whose difference is the sun's
  // convergence (RenderStats::sun_lattice_row_change; about a third more time). Off, the
  // statistics report no lattice rows (sun_lattice_rows 0): for frames whose convergence is
  // measured on another frame of the same view (validate's flicker frames).
  bool measure_lattice = true;
  // Scattered and measured: while its lattice moves a compared row by row_tolerance or more
  // against the lattice of half its cells, the sun doubles its cells (sun_cells_per_wavelength
  // and sun_cells times sqrt 2: the same footprints resolved, so the same rows compared) and
  // measures again, up to this many cells per wavelength: the samples' doubling, for the sun's
  // normal samples (issue 6, point 1). Each doubling costs about twice the lattice before it. 0
  // (the default): none, the lattice as sun_cells_per_wavelength says; else in
  // [sun_cells_per_wavelength, 128] (ocean/method.hpp's limits).
  double sun_max_cells_per_wavelength = 0.0;
  // Scattered, doubling: the most the cap grows to, [1, 16384] (below sun_cells: sun_cells). Past
  // it the cap is held while the cells per wavelength go on doubling; the footprints the finer
  // lattice then no longer resolves (the farthest compared) drop out of the comparison, which
  // takes the rows both lattices of a doubling resolve. With sun_cells at 2048 (the default
  // suite's) the far rows are resolved at the first lattice and the doublings give them up
  // only if they must (docs/validation.md, "Footprints cut by their cells"): each doubling at a
  // cap that grows costs twice the one before on every row.
  int sun_max_cells = ocean::kReferenceHeldSunCells;
  // Scattered: add the cells' shares with the float atomics of GL_NV_shader_atomic_float where
  // the driver has them (NVIDIA's, Mesa's llvmpipe), else by compare-and-swap on their bits. The
  // same sums to float rounding in either order; under contention, one atomic against a retry
  // loop (the H200 took 6-30 s per sun term with the loop alone, stop 26).
  bool sun_float_atomics = true;
  // Scattered: the most invocations per batch of the lattice's cells' pass (one per segment of a
  // row of a footprint's cells; whole footprints per batch, one alone where it has more), in
  // [1, 2^31]. The image does not depend on it (OceanMethods.ScatteredSunDoesNotDependOnItsBatches
  // draws many small batches); by default they are as large as the shader's 32-bit index allows.
  std::uint64_t sun_batch_invocations = ocean::kReferenceMaxSunBatch;
  // Scattered: the cells of a row each invocation of the lattice's cells' pass takes, in [0,
  // 16384]; 0 (the default): the most llvmpipe's loop limit allows there, 64 on other renderers
  // (OceanNodeOptions::reference_sun_segment). The image does not depend on it but for float
  // rounding (OceanMethods.ScatteredSunDoesNotDependOnItsSegments); its time does.
  int sun_segment = 0;
  // Scattered: the rows of cells each invocation of the lattice's cells' pass takes, in [0, 8];
  // 0 (the default): 4, held on llvmpipe to what its loop limit allows (OceanNodeOptions::
  // reference_sun_block_rows). Like sun_segment, the image does not depend on it but for float
  // rounding; its time does.
  int sun_block_rows = 0;
  // Scattered: the places of the queue that takes the lattice's refined cells to a pass of their
  // own, in [-1, 4194240]; -1 (the default): 4,194,240, the most; 0: each refined where its
  // invocation meets it, as before stop 42 (OceanNodeOptions::reference_sun_refined_queue). Like
  // sun_segment, the image does not depend on it but for float rounding; its time does. A queue
  // of a few places (for tests) runs the cells' pass in that many more dispatches.
  std::int64_t sun_refined_queue = -1;
  // Scattered: where this render's lattice is kept, and where a lattice another render scattered
  // for the same view, time, sea and first sample is taken from instead of scattering it again,
  // when this render asks for that lattice without measuring it (ocean/scattered_sun_cache.hpp;
  // RenderStats::sun_lattice_reused). validate keeps one per reference, so that its term `all`
  // draws the lattice its sun term converged to. Null: every render scatters its own.
  std::shared_ptr<ocean::ScatteredSunCache> sun_cache;
  // For tests (OceanNodeOptions::reference_sun_test_faults): this many of the first lattices
  // scattered or drawn from sun_cache are overwritten (text, then zeros, in turn) before they
  // are checked, and scattered (or sent) again.
  int sun_test_faults = 0;
};

// The sky provider kept from one Renderer to the next (RendererOptions::sky_cache), so that
// Renderers drawing the same sky one after another (a flight's frames, the renders of a
// validation case) upload its tables once, build its sun-zenith array once (the view from 10 km
// up: 2.3 s on llvmpipe at 512^2 x 32), and build its sky map again only when the sun moves.
// It holds one provider: that of the last scene whose sky (sky.exr, or the atmosphere for the
// planet's radius), table cache folder and GL context differ from the one before is made anew
// (a sky.exr is read once: a file rewritten under the same path is not read again while the
// cache holds its provider).
// Give one cache only to Renderers used one after another, or on one thread; its textures live
// in the context that made them, which must outlive the cache (the cache keys on the context's
// address, so a later context at that address would not be told apart).
class SkyProviderCache;
std::shared_ptr<SkyProviderCache> make_sky_provider_cache();

struct RendererOptions {
  std::vector<std::string> shader_roots;  // searched before the default shader folders
  LightTerms terms;
  // The ocean's shading method. Methods other than `full` draw the projected grid's sea only:
  // the camera must be below kSpaceModeHeight (SceneError otherwise).
  ocean::OceanMethod method = ocean::OceanMethod::full;
  ReferenceSampling reference;
  // Folder of the atmosphere's table cache (empty: $THALASSA_CACHE_DIR, else
  // $XDG_CACHE_HOME/thalassa, else ~/.cache/thalassa).
  std::string cache_dir;
  // Origin of the waves' chart (planet/nadir_frame.hpp); by default the lattice point nearest
  // the camera's nadir. A flight gives all its frames one anchor, so that its waves never jump.
  std::optional<Geodetic> wave_anchor;
  // Where the sky provider is kept between Renderers (make_sky_provider_cache); none: each
  // Renderer makes its own. The images are the same either way.
  std::shared_ptr<SkyProviderCache> sky_cache;
};

// Throws SceneError for a valid scene that cannot be drawn as it stands, rather than drawing
// something else silently: a sky.exr that is not an existing file. `source` names where the
// offending key came from (a file, "--set"; SceneBuilder::source_of). The Renderer checks it
// too (and throws SceneError for a sky.exr that is not a usable equirectangular HDR image); a
// program calls it first to refuse before any GL work.
void check_drawable(const Scene& scene, const std::string& source = "scene");

class Renderer;

// What is not finite in a frame `renderer` drew (`image`, its image()), "" when every pixel is:
// nonfinite_pixels(image), and for the reference method how many of its samples were not finite
// and where, and, with its sun scattered, the sun's sums at the first pixel that is not
// (Renderer::reference_sun_sums): enough to tell a pixel's shared sun from one sample's shading.
std::string nonfinite_report(const Image& image, const Renderer& renderer);

class Renderer {
 public:
  // `context` must be current and stay alive as long as the Renderer. Throws SceneError for a
  // scene that cannot be drawn (a missing or unusable sky.exr), GlError or ShaderError otherwise.
  Renderer(GlContext& context, const Scene& scene, RendererOptions options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws one frame into the HDR target. Every GL state it changes is restored afterwards (the
  // framebuffer bindings, viewport, program, vertex array, depth state, clip control, uniform
  // buffer binding 0, texture unit 0), so a host's context is left as it was.
  void render();
  // Makes `scene` the one render() draws: the camera, the sun and the clock of a host's or a
  // flight's next frame, or any other key. What it shares with the last scene is kept rather
  // than made again:
  // - the compiled shader programs (a frame that compiles new ones, after a switch between
  //   `surface` and `space` mode say, is drawn twice by render(), so that no time includes
  //   compiling);
  // - the HDR target, its texture and framebuffer names with it, while the image's size stays;
  // - the sky provider while the sky does (sky.exr, the planet's radius; its sea's sky map is
  //   drawn again only when the sun moves at the camera's nadir);
  // - each node of the scene graph (the sky, the sea from space, the sea's projected grid) whose
  //   options are the same: the ocean's waves, settings and light terms, and the wakes and calm
  //   areas in view; a scene with ships under way places them anew each time and makes its sea
  //   again (RenderStats::kept_nodes).
  // The waves keep their chart (planet/nadir_frame.hpp) while the camera stays below
  // kSpaceModeHeight within kWaveAnchorKeepDistance of its anchor, so that they stay where they
  // are on the planet as the camera moves; RendererOptions::wave_anchor fixes it for good. The
  // image is then the one a new Renderer with that anchor draws (tests/gpu/set_scene_test.cpp).
  // The statistics start again: stats() describes this scene's frames. Throws like the
  // constructor (SceneError for a scene that cannot be drawn); the Renderer then keeps the
  // last scene, and draws it as before. The context must be current.
  void set_scene(const Scene& scene);
  // Forgets the frames' times measured so far (RenderStats::frames, frame_ms, passes,
  // timing_fallback_frames), so that the next ones are timed alone: after warm-up frames, while
  // a GPU's clocks rise from idle (validate's timing of the methods).
  void reset_timings();
  // The last frame: linear radiance, rows top first.
  Image image() const;
  // The reference method (after render()): each pixel's sea alone, the weighted mean of its
  // samples that saw the sea (the sky's left out), with alpha the fraction of its samples that
  // did; black with alpha 0 where none did. A pixel the horizon crosses is sky and sea in
  // image(), as a photograph's is; the other methods shade the one at its centre, and the
  // validation compares their sea with this (validation::reference_for_comparison). An empty
  // image (0 x 0) for the other methods.
  Image reference_sea_image() const;
  // The reference method with its sun scattered (after render()): the lattice's per-pixel sums
  // the lighting read (shaders/ocean/reference_sun_scatter.comp, Output), rows top first: R sum
  // omega sun (sr; a pixel's sun factor is R / G), G sum omega (sr: the solid angle of the visible
  // sea whose cells' centres the pixel sees), B the part of G from footprints over the cell cap
  // (sr: the pixel is unresolved where B > G / 2), A the solid angle of the cells hidden behind
  // the grid's crests (sr). For researchers checking the reference, and for finding where a pixel
  // went wrong. An empty image (0 x 0) otherwise.
  Image reference_sun_sums() const;
  // GL names of the HDR colour texture (RGBA32F) and its framebuffer, for host applications.
  unsigned hdr_texture() const;
  unsigned hdr_framebuffer() const;
  // Draws the last frame tone-mapped like the PNG (exposure of the scene) into `framebuffer`
  // (0: the context's default framebuffer) over a viewport of width x height pixels; restores
  // the GL state like render().
  void present(unsigned framebuffer, int width, int height);

  RenderStats stats() const;
  const Scene& scene() const;
  // The sea this renderer draws, for queries on the CPU (planet/sea_state.hpp): the current
  // scene in the chart of its waves' anchor (RenderStats::wave_anchor), which set_scene keeps
  // while the camera stays near it. Builds the scene's wave set, wakes and calm areas (below a
  // millisecond for the default scene); keep it while the scene stays.
  SeaState sea_state() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace thalassa
