#include "thalassa/planet/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <variant>

#include "elapsed_ms.hpp"
#include "reference_accumulator.hpp"
#include "sky_provider_factory.hpp"
#include "space_ocean_node.hpp"
#include "thalassa/atmosphere/gl/sky_node.hpp"
#include "thalassa/atmosphere/gl/sky_provider.hpp"
#include "thalassa/engine/gl/gpu_timer.hpp"
#include "thalassa/engine/gl/hdr_target.hpp"
#include "thalassa/engine/gl/scene_graph.hpp"
#include "thalassa/engine/gl/shader_library.hpp"
#include "thalassa/engine/gl/state_guard.hpp"
#include "thalassa/engine/gl_info.hpp"
#include "thalassa/ocean/gl/ocean_node.hpp"
#include "thalassa/ocean/projected_grid.hpp"
#include "thalassa/ocean/sea_surface.hpp"
#include "thalassa/planet/camera_frame.hpp"
#include "thalassa/planet/local_features.hpp"
#include "thalassa/planet/nadir_frame.hpp"

namespace thalassa {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

gl::FrameInputs frame_inputs(const Scene& scene, const NadirFrame& frame) {
  gl::FrameInputs inputs;
  inputs.width = scene.image.width;
  inputs.height = scene.image.height;
  const CameraBasis basis =
      camera_basis(scene.camera.heading, scene.camera.pitch, scene.camera.roll);
  inputs.camera_right = basis.right;
  inputs.camera_up = basis.up;
  inputs.camera_forward = basis.forward;
  inputs.tan_half_fov_y = std::tan(0.5 * scene.camera.fov_y * kDegree);
  // A camera exactly on the sea is above it (the scene allows height 0): kSurfaceCameraHeight.
  inputs.camera_height = scene.camera.height >= 0.0
                             ? std::max(scene.camera.height, kSurfaceCameraHeight)
                             : scene.camera.height;
  inputs.sun_direction = sun_direction(scene.sun.zenith, scene.sun.azimuth);
  inputs.time = scene.time;
  inputs.sea_curvature = frame.sea_surface.curvature;
  inputs.wave_origin = frame.wave_origin;
  inputs.wave_axes = frame.wave_axes;
  return inputs;
}

// Which of the sky and the sea the image sees: the image's rays against the sea at rest (the
// planet's quadric), decided exactly by the projected grid's tests (projected_grid.hpp).
void horizon_visibility(const gl::FrameInputs& inputs, bool& sky_visible, bool& sea_visible) {
  // Below the surface the sea fills the whole image with deep-water light.
  if (inputs.camera_height < 0.0) {
    sea_visible = true;
    sky_visible = false;
    return;
  }
  const ocean::GridCamera camera = ocean::make_grid_camera(
      inputs.camera_right, inputs.camera_up, inputs.camera_forward, inputs.tan_half_fov_y,
      inputs.camera_height, inputs.width, inputs.height, ocean::SeaSurface{inputs.sea_curvature});
  const glm::dvec2 lo(-1.0), hi(1.0);  // the whole image
  sea_visible = ocean::image_sees_sea(camera, lo, hi);
  sky_visible = ocean::image_sees_sky(camera, lo, hi);
}

// s: the reference cuts each pixel into s x s strata, s^2 <= its first sample count
// (ReferenceSampling).
int reference_strata(const ReferenceSampling& r) {
  const int least = std::min(r.min_samples, r.max_samples);
  int strata = 1;
  while ((strata + 1) * (strata + 1) <= least) ++strata;
  return strata;
}

// The most cells of the reference's sun per side of what one ocean-node pass integrates: with
// the scatter, sun_cells (sun_cells^2 per pixel's footprint, in whatever shape); gathered,
// sun_cells per pixel side shared among the s strata of a side, at most 64 (the shader's row
// buffer).
int reference_sun_cells(const ReferenceSampling& r) {
  if (r.sun == ReferenceSun::scattered) return r.sun_cells;
  const int strata = reference_strata(r);
  return std::clamp((r.sun_cells + strata - 1) / strata, 1, 64);
}

// The options a node of the graph was made with, to tell whether the next scene can keep it
// (Renderer::set_scene): each node's options compare whole, the sky provider and the wakes and
// calm areas placed in view by the objects they point to.
using NodeOptions =
    std::variant<atmosphere::SkyNodeOptions, SpaceOceanNodeOptions, ocean::OceanNodeOptions>;
struct NodeRecipe {
  NodeOptions options;
  const atmosphere::SkyProvider* provider = nullptr;  // the sky node's (the others hold theirs)
  bool operator==(const NodeRecipe&) const = default;
};

std::unique_ptr<gl::Node> make_node(const NodeRecipe& recipe,
                                    const std::shared_ptr<atmosphere::SkyProvider>& provider) {
  if (const auto* sky = std::get_if<atmosphere::SkyNodeOptions>(&recipe.options))
    return atmosphere::make_sky_node(*sky, provider);
  if (const auto* space = std::get_if<SpaceOceanNodeOptions>(&recipe.options))
    return make_space_ocean_node(*space);
  return ocean::make_ocean_node(std::get<ocean::OceanNodeOptions>(recipe.options));
}

// The features a recipe's node draws; null for the sky.
std::shared_ptr<const ocean::LocalFeatures>* recipe_features(NodeRecipe& recipe) {
  if (auto* space = std::get_if<SpaceOceanNodeOptions>(&recipe.options)) return &space->features;
  if (auto* surface = std::get_if<ocean::OceanNodeOptions>(&recipe.options))
    return &surface->features;
  return nullptr;
}

// Throws std::invalid_argument for reference settings out of their ranges (ReferenceSampling).
void check_reference_sampling(const ReferenceSampling& r) {
  if (r.min_samples >= 1 && r.max_samples >= r.min_samples && r.row_tolerance > 0.0 &&
      r.sun_cells >= 1 && r.sun_cells <= ocean::kReferenceMaxSunCells && r.sun_max_cells >= 1 &&
      r.sun_max_cells <= ocean::kReferenceMaxSunCells && r.sun_batch_invocations >= 1 &&
      r.sun_batch_invocations <= ocean::kReferenceMaxSunBatch && r.sun_segment >= 0 &&
      r.sun_segment <= ocean::kReferenceMaxSunCells && r.sun_block_rows >= 0 &&
      r.sun_block_rows <= ocean::kReferenceMaxSunBlockRows && r.sun_refined_queue >= -1 &&
      r.sun_refined_queue <= ocean::kReferenceMaxSunRefinedQueue &&
      r.grid_cell >= ocean::kReferenceMinGridCell && r.grid_cell <= ocean::kReferenceGridCell &&
      r.sun_cells_per_wavelength >= 1.0 &&
      r.sun_cells_per_wavelength <= ocean::kReferenceMaxCellsPerWavelength &&
      (r.sun_max_cells_per_wavelength == 0.0 ||
       (r.sun_max_cells_per_wavelength >= r.sun_cells_per_wavelength &&
        r.sun_max_cells_per_wavelength <= ocean::kReferenceMaxCellsPerWavelength)))
    return;
  throw std::invalid_argument(
      "ReferenceSampling: expected 1 <= min_samples <= max_samples, row_tolerance > 0, "
      "sun_cells in [1, " +
      std::to_string(ocean::kReferenceMaxSunCells) + "], sun_max_cells in [1, " +
      std::to_string(ocean::kReferenceMaxSunCells) + "], sun_cells_per_wavelength in [1, " +
      std::to_string(int(ocean::kReferenceMaxCellsPerWavelength)) +
      "], sun_max_cells_per_wavelength 0 or in [sun_cells_per_wavelength, " +
      std::to_string(int(ocean::kReferenceMaxCellsPerWavelength)) +
      "], grid_cell in [0.125, 1], sun_batch_invocations in [1, 2^31], sun_segment in [0, " +
      std::to_string(ocean::kReferenceMaxSunCells) + "], sun_block_rows in [0, " +
      std::to_string(ocean::kReferenceMaxSunBlockRows) + "] and sun_refined_queue in [-1, " +
      std::to_string(ocean::kReferenceMaxSunRefinedQueue) + "]");
}

// Everything that follows from one scene, made before any of it replaces the last scene's, so
// that a scene that cannot be drawn leaves the Renderer as it was (Renderer::set_scene).
struct StagedScene {
  Scene scene;
  NadirFrame nadir;
  gl::FrameInputs inputs;
  std::shared_ptr<atmosphere::SkyProvider> provider;
  bool provider_kept = false;
  double provider_ms = 0.0;
  int sky_map_builds_before = 0;
  bool sky_map_array_before = false;
  double features_ms = -1.0;
  std::shared_ptr<const ocean::LocalFeatures> features;  // placed for this scene; null: none
  bool calm_chart_kept = false;
  // Made only where the image's size changed (the accumulator: for the reference method).
  std::optional<gl::HdrTarget> target;
  std::optional<ReferenceAccumulator> accumulator;
  // The graph, in drawing order: each node's recipe, and the node made for it, or null where
  // the last scene's node of the same recipe (kept[i], its index there) is kept.
  std::vector<NodeRecipe> recipes;
  std::vector<std::unique_ptr<gl::Node>> made;
  std::vector<int> kept;
};

}  // namespace

std::optional<ReferenceSun> parse_reference_sun(std::string_view name) {
  if (name == "scattered") return ReferenceSun::scattered;
  if (name == "gathered") return ReferenceSun::gathered;
  return std::nullopt;
}

const char* reference_sun_name(ReferenceSun sun) {
  return sun == ReferenceSun::scattered ? "scattered" : "gathered";
}

void check_drawable(const Scene& scene, const std::string& source) {
  std::error_code error;
  if (!scene.sky.exr.empty() && !std::filesystem::is_regular_file(scene.sky.exr, error))
    throw SceneError(source + ": sky.exr: expected an HDR image file, got \"" + scene.sky.exr +
                     "\" (no such file)");
}

struct Renderer::Impl {
  GlContext& context;
  RendererOptions renderer_options;
  gl::ShaderLibrary shaders;
  GlInfo info;
  gl::GpuTimer timer;
  std::shared_ptr<SkyProviderCache> sky_cache;  // the options', or the Renderer's own
  // The scene drawn, and what follows from it (StagedScene).
  Scene scene;
  NadirFrame nadir;
  gl::FrameInputs inputs;
  gl::HdrTarget target;
  gl::SceneGraph graph;
  std::vector<NodeRecipe> recipes;      // graph.nodes()[i] was made from recipes[i]
  std::vector<std::string> kept_nodes;  // RenderStats::kept_nodes
  std::vector<double> frame_ms;
  std::map<std::string, std::vector<double>> pass_ms;
  std::vector<std::string> pass_order;
  gl::VertexArray present_vao;
  int timer_fallbacks_before = 0;  // the compiling frame's, not counted in the statistics
  std::shared_ptr<atmosphere::SkyProvider> provider;
  double provider_ms = 0.0;   // creating the provider: tables computed or loaded, uploaded
  // The provider came from the sky cache, made for an earlier Renderer or scene: what it had
  // built by then (its sky map's builds, its array) was not this scene's cost.
  bool provider_kept = false;
  int sky_map_builds_before = 0;
  bool sky_map_array_before = false;
  double features_ms = -1.0;  // placing the wakes and calm areas (CPU); < 0: the scene has none
  // The wakes and calm areas placed for the scene (null: none), and whether its calm areas'
  // chart was the last scene's (RenderStats::calm_chart_kept).
  std::shared_ptr<const ocean::LocalFeatures> placed_features;
  bool calm_chart_kept = false;
  double set_scene_ms = -1.0;      // set_scene's own time; < 0: the constructor's scene
  double compile_ms_before = 0.0;  // the shader library's compile time when the scene was set

  Impl(GlContext& context_, const Scene& scene_, const RendererOptions& options)
      : context(context_),
        renderer_options(options),
        shaders([&] {
          std::vector<std::filesystem::path> roots(options.shader_roots.begin(),
                                                   options.shader_roots.end());
          return roots;
        }()),
        info(query_gl_info()),
        timer(gl::GpuTimer::source_for_renderer(info.renderer)),
        sky_cache(options.sky_cache ? options.sky_cache : make_sky_provider_cache()),
        target(scene_.image.width, scene_.image.height) {
    if (!info.missing.empty()) {
      std::string missing;
      for (const auto& name : info.missing) missing += (missing.empty() ? "" : ", ") + name;
      throw gl::GlError("this OpenGL context lacks what thalassa needs: " + missing);
    }
    if (options.method == ocean::OceanMethod::reference)
      check_reference_sampling(options.reference);
    StagedScene staged = stage(scene_, false);
    commit(std::move(staged));
  }

  // The waves' chart for `scene`'s camera (planet/nadir_frame.hpp): the options' anchor where
  // they give one; else, after the first scene, the last scene's anchor while the camera stays
  // below kSpaceModeHeight within kWaveAnchorKeepDistance of it (so that the waves do not jump
  // as the camera moves), and the lattice point nearest the camera otherwise (from space no
  // wave is resolved, and a new anchor shows nothing).
  std::optional<Geodetic> wave_anchor(const Scene& next, bool has_scene) const {
    if (renderer_options.wave_anchor) return renderer_options.wave_anchor;
    if (!has_scene || next.camera.height >= kSpaceModeHeight) return std::nullopt;
    return kept_wave_anchor(Planet(next.planet), nadir.wave_anchor, next.camera.lat,
                            next.camera.lon);
  }

  // Makes what `next` needs that the current scene does not hold; changes nothing of the
  // Renderer's but its caches (the sky cache, the shader library). `has_scene`: false for the
  // constructor's scene.
  StagedScene stage(const Scene& next, bool has_scene) {
    check_drawable(next);
    const auto& options = renderer_options;
    StagedScene s;
    s.scene = next;
    s.nadir = make_nadir_frame(Planet(next.planet), next.camera, wave_anchor(next, has_scene));
    s.inputs = frame_inputs(next, s.nadir);
    // Creating the provider uploads tables and images: from client memory, tightly packed,
    // whatever unpack state a host's context has, which is given back after.
    const gl::StateGuard guard;
    gl::set_pass_state();
    if (has_scene && (next.image.width != target.width() || next.image.height != target.height())) {
      s.target.emplace(next.image.width, next.image.height);
      if (options.method == ocean::OceanMethod::reference)
        s.accumulator.emplace(next.image.width, next.image.height, shaders);
    }
    const auto provider_start = std::chrono::steady_clock::now();
    s.provider = sky_cache->provider(context, next, options, {}, s.provider_kept);
    s.sky_map_builds_before = s.provider->sky_map_builds();
    s.sky_map_array_before = s.provider->sky_map_array_ms() > 0.0;
    s.provider_ms = elapsed_ms(provider_start);
    // A photograph's sun is where the photograph has it.
    if (const auto sun = s.provider->sun_direction()) s.inputs.sun_direction = *sun;
    bool sky_visible = false, sea_visible = false;
    horizon_visibility(s.inputs, sky_visible, sea_visible);
    // The sun's disc and glint while any of the disc is above the horizon (the provider fades
    // them as it sets).
    const bool sun_up = s.inputs.sun_direction.z > -std::sin(s.provider->sun_angular_radius());
    if (sky_visible)
      s.recipes.push_back({.options = atmosphere::SkyNodeOptions{.sun_disc = sun_up},
                           .provider = s.provider.get()});
    const bool space = next.camera.height >= kSpaceModeHeight;
    // Wakes and calm areas in view (issue 9), placed in the nadir frame; none for most scenes.
    // The calm areas' chart follows from the frame, what the image sees, the planet and the
    // areas, not from the clock: where only those are the last scene's (a viewer at rest, its
    // ships and waves moving), the last chart is kept and the wakes alone placed anew.
    std::shared_ptr<const ocean::LocalFeatures> features;
    if (sea_visible && (!next.wakes.empty() || !next.calm_areas.empty())) {
      const auto start = std::chrono::steady_clock::now();
      const bool keep_calm =
          has_scene && placed_features && placed_features->calm && next.camera == scene.camera &&
          next.planet == scene.planet && next.image.width == scene.image.width &&
          next.image.height == scene.image.height && next.calm_areas == scene.calm_areas;
      if (keep_calm) {
        Scene wakes_only = next;
        wakes_only.calm_areas.clear();
        ocean::LocalFeatures placed =
            place_local_features(Planet(next.planet), wakes_only, s.nadir);
        placed.calm = placed_features->calm;
        features = std::make_shared<const ocean::LocalFeatures>(std::move(placed));
      } else {
        features = std::make_shared<const ocean::LocalFeatures>(
            place_local_features(Planet(next.planet), next, s.nadir));
      }
      s.calm_chart_kept = keep_calm;
      s.features_ms = elapsed_ms(start);
    }
    s.features = features;
    if (sea_visible && space)
      s.recipes.push_back(
          {.options = SpaceOceanNodeOptions{.settings = next.ocean,
                                            .sun_glint = sun_up && options.terms.sun,
                                            .sky = options.terms.sky,
                                            .sea = options.terms.sea,
                                            .air = options.terms.air,
                                            .provider = s.provider,
                                            .features = features}});
    if (space && options.method != ocean::OceanMethod::full)
      throw SceneError("--method " + std::string(ocean::method_name(options.method)) +
                       ": expected a camera below " + std::to_string(int(kSpaceModeHeight)) +
                       " m (the method draws the projected grid's sea), got camera.height " +
                       std::to_string(next.camera.height));
    if (sea_visible && !space)
      s.recipes.push_back(
          {.options = ocean::OceanNodeOptions{
               .settings = next.ocean,
               .sun_glint = sun_up && options.terms.sun,
               .sky = options.terms.sky,
               .sea = options.terms.sea,
               .air = options.terms.air,
               .sky_nine_samples = next.ocean.sky_filter == "nine_samples",
               .sky_shrm = next.ocean.sky_filter == "shrm",
               .provider = s.provider,
               .method = options.method,
               .reference_sun_cells = reference_sun_cells(options.reference),
               .reference_cells_per_wavelength = options.reference.sun_cells_per_wavelength,
               .reference_sun_refine = options.reference.sun_refine,
               .reference_grid_cell = options.reference.grid_cell,
               .reference_sun_scatter = options.reference.sun == ReferenceSun::scattered,
               .reference_measure_lattice = options.reference.measure_lattice,
               .reference_max_cells_per_wavelength = options.reference.sun_max_cells_per_wavelength,
               .reference_max_sun_cells = options.reference.sun_max_cells,
               .reference_lattice_tolerance = options.reference.row_tolerance,
               .reference_float_atomics = options.reference.sun_float_atomics,
               .reference_sun_segment = options.reference.sun_segment,
               .reference_sun_block_rows = options.reference.sun_block_rows,
               .reference_sun_refined_queue = options.reference.sun_refined_queue,
               .reference_sun_batch = options.reference.sun_batch_invocations,
               .reference_sun_cache = options.reference.sun_cache,
               .reference_sun_test_faults = options.reference.sun_test_faults,
               .features = features}});
    // Keep each node of the last scene whose recipe is the new one's: the same wakes and calm
    // areas in view count as the same (they are placed anew for every scene).
    for (NodeRecipe& recipe : s.recipes) {
      int keep = -1;
      for (std::size_t i = 0; i < recipes.size() && keep < 0; ++i) {
        if (recipes[i].options.index() != recipe.options.index()) continue;
        auto* mine = recipe_features(recipe);
        const auto* theirs = recipe_features(recipes[i]);
        if (mine && *mine && *theirs && **mine == **theirs) *mine = *theirs;
        if (recipes[i] == recipe) keep = static_cast<int>(i);
      }
      s.kept.push_back(keep);
      s.made.push_back(keep >= 0 ? std::unique_ptr<gl::Node>() : make_node(recipe, s.provider));
    }
    return s;
  }

  // Renderer::reset_timings.
  void reset_timings();
  // Forgets the last scene's frames: their times (reset_timings), the order of their passes and
  // the reference's results.
  void forget_frames();

  // Puts a staged scene in place; nothing here throws but an allocation.
  void commit(StagedScene s) {
    scene = std::move(s.scene);
    nadir = s.nadir;
    inputs = s.inputs;
    if (s.target) target = std::move(*s.target);
    if (s.accumulator) accumulator = std::move(s.accumulator);
    std::vector<std::unique_ptr<gl::Node>> old = graph.set_nodes({});
    std::vector<std::unique_ptr<gl::Node>> nodes;
    kept_nodes.clear();
    for (std::size_t i = 0; i < s.recipes.size(); ++i) {
      if (s.kept[i] >= 0) {
        nodes.push_back(std::move(old[std::size_t(s.kept[i])]));
        kept_nodes.push_back(nodes.back()->name());
      } else {
        nodes.push_back(std::move(s.made[i]));
      }
    }
    graph.set_nodes(std::move(nodes));
    recipes = std::move(s.recipes);
    provider = std::move(s.provider);
    provider_kept = s.provider_kept;
    provider_ms = s.provider_ms;
    sky_map_builds_before = s.sky_map_builds_before;
    sky_map_array_before = s.sky_map_array_before;
    features_ms = s.features_ms;
    placed_features = std::move(s.features);
    calm_chart_kept = s.calm_chart_kept;
    shaders.start_use_record();
    compile_ms_before = shaders.compile_ms();
  }

  // One frame at the inputs' pixel offset, drawn and its timer queries read: its time and its
  // passes', which record_frame adds to the statistics.
  struct DrawnFrame {
    gl::PassTime frame;
    std::vector<gl::PassTime> passes;
  };
  DrawnFrame draw_frame() {
    DrawnFrame drawn;
    {
      const gl::StateGuard guard;  // a host's context gets its state back
      graph.render(inputs, target, shaders, timer);
    }
    drawn.passes = timer.resolve(drawn.frame);
    return drawn;
  }

  // A resolved frame's passes into pass_ms and pass_order; its GPU (or wall) time in ms.
  double record_frame(const gl::PassTime& frame, const std::vector<gl::PassTime>& passes) {
    const bool wall = timer.source() == gl::TimingSource::FinishWallClock;
    pass_order.clear();
    for (const auto& pass : passes) {
      pass_order.push_back(pass.name);
      pass_ms[pass.name].push_back(wall ? pass.wall_ms : pass.query_ms);
    }
    return wall ? frame.wall_ms : frame.query_ms;
  }

  // The reference: frames at stratified pixel offsets averaged in double, the sample count
  // doubled until the rows' totals settle (ReferenceSampling); the average goes back into the
  // HDR target, so that image(), present() and the host's texture all show it. Returns the
  // summed time of its frames (ms), each with its pass adding it to the sums.
  //
  // The sums stay on the GPU (ReferenceAccumulator, reference_accumulate.comp) and the frames'
  // timer queries are read 64 frames at a time, so that the samples follow each other without
  // the host waiting for each; the host reads the sums once per doubling. Until stop 32 it read
  // every sample back and added it itself: 0.76 ms of the host's per sample on an H200.
  //
  // Each pixel is cut into s x s strata, s = floor(sqrt(min_samples)) (at most max_samples):
  // sample k stands for stratum k mod s^2, at the point of it given by the Halton (2, 3) point
  // of round k / s^2, and the sample counts are whole rounds (multiples of s^2), so that every
  // stratum has as many samples and the average is a box filter over the pixel. The reference's
  // sun, scattered (the default), is the same for every sample of a pixel
  // (shaders/ocean/reference_sun_scatter.comp, computed once per image by the ocean node: its
  // time is added once); gathered, it integrates over the sample's stratum
  // (shaders/ocean/reference_sun.glsl).
  //
  // A pixel's samples of the sky count as they fall (its coverage); its samples of the sea are
  // averaged with their visible-area weights (shaders/ocean/visible_area_weight.glsl), which the
  // sea's alpha carries (ocean_lighting.frag): pixel = (sum of sky samples + n_sea x
  // sum(w L) / sum(w)) / samples.
  double draw_reference(int max_samples) {
    const int width = target.width(), height = target.height();
    accumulator->clear();
    std::vector<ReferencePixelSums> sums;
    // Each row's total luminance of the sea: its pixels' sea share, n_sea sea_mean / count. The
    // sky's samples do not count: the reference is the sea's, the sky is every method's, and
    // its supersampled sun disc alone held every reference at the most samples (a row of the
    // low sun's disc still moved by 0.84 % at 1,024; docs/validation.md, stop 22).
    auto row_totals = [&](int count) {
      std::vector<double> totals(height, 0.0);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const ReferencePixelSums& sum = sums[std::size_t(y) * width + x];
          const glm::dvec3 p = double(sum.sea) * sum.sea_mean() / double(count);
          totals[y] += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
        }
      return totals;
    };
    double ms = 0.0;
    const auto collect_frames = [&] {
      for (const auto& frame : timer.resolve_deferred())
        ms += record_frame(frame.frame, frame.passes);
    };
    int count = 0;
    std::vector<double> half_totals;
    samples = 0;
    sample_row_change = 0.0;
    sample_row_changes.clear();
    const ReferenceSampling& reference = renderer_options.reference;
    const int least = std::min(reference.min_samples, max_samples);
    // The strata the ocean node's per-stratum cell cap was set for (reference_sun_cells).
    const int strata = reference_strata(reference);
    const int round = strata * strata;
    max_samples = std::max(round, max_samples / round * round);
    for (int goal = std::max(round, least / round * round);; goal *= 2) {
      goal = std::min(goal, max_samples);
      for (; count < goal; ++count) {
        const int q = count % round, r = count / round;
        // In [0, 1 - 1e-3]: a point on a stratum's upper edge would be read back by the shader
        // (float) as the next stratum's lower edge. Halton points of the few rounds used stay
        // far below it.
        const auto inside = [](double h) { return std::min(h, 1.0 - 1e-3); };
        inputs.pixel_offset = {(q % strata + inside(radical_inverse(2, r + 1))) / strata - 0.5,
                               (q / strata + inside(radical_inverse(3, r + 1))) / strata - 0.5};
        inputs.pixel_stratum = 1.0 / strata;
        {
          const gl::StateGuard guard;  // a host's context gets its state back
          graph.render(inputs, target, shaders, timer);
          accumulator->add(target.color_texture());
          timer.end_pass("reference.accumulate");
        }
        // Nothing waits for the GPU here: the frame's timer queries are read a batch at a time,
        // and the flush hands the frame to the GPU while the host queues the next.
        timer.defer_frame();
        glFlush();
        if (timer.deferred_frames() >= kDeferredFrames) collect_frames();
      }
      collect_frames();
      sums = accumulator->read();
      const std::vector<double> totals = row_totals(count);
      if (!half_totals.empty()) {
        sample_row_change = 0.0;
        sample_row_changes.assign(height, std::numeric_limits<double>::quiet_NaN());
        const double brightest = *std::max_element(totals.begin(), totals.end());
        for (int y = 0; y < height; ++y)
          if (totals[y] > kNegligibleRow * brightest) {
            sample_row_changes[y] = std::abs(totals[y] - half_totals[y]) / totals[y];
            sample_row_change = std::max(sample_row_change, sample_row_changes[y]);
          }
        if (!reference.fixed_samples && sample_row_change < reference.row_tolerance) break;
      }
      if (count >= max_samples) break;
      half_totals = totals;
    }
    inputs.pixel_offset = glm::dvec2(0.0);
    inputs.pixel_stratum = 1.0;
    samples = count;
    ms += node_measurement("reference_sun.ms");
    std::vector<float> average(sums.size() * 4);
    for (std::size_t i = 0; i < sums.size(); ++i) {
      const glm::dvec3 p = sums[i].mean(count);
      average[4 * i + 0] = float(p.r);
      average[4 * i + 1] = float(p.g);
      average[4 * i + 2] = float(p.b);
      average[4 * i + 3] = 1.0f;  // like every other image's
    }
    nonfinite_samples = 0;
    nonfinite_pixels = 0;
    first_nonfinite_x = first_nonfinite_y = -1;
    first_nonfinite_samples = 0;
    for (std::size_t i = 0; i < sums.size(); ++i) {
      if (sums[i].nonfinite == 0) continue;
      nonfinite_samples += sums[i].nonfinite;
      if (nonfinite_pixels++ == 0) {
        first_nonfinite_x = int(i % std::size_t(width));
        first_nonfinite_y = int(i / std::size_t(width));  // read_rgba_top_down: from the top
        first_nonfinite_samples = sums[i].nonfinite;
      }
    }
    // With the reference's sun, each row's fraction of samples whose sun resolved every wave.
    resolved_rows.clear();
    if (renderer_options.terms.sun) {
      resolved_rows.assign(height, 0.0);
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x)
          resolved_rows[y] += double(sums[std::size_t(y) * width + x].resolved) / count;
        resolved_rows[y] /= width;
      }
    }
    target.write_rgba_top_down(average);
    sea_rgba.assign(sums.size() * 4, 0.0f);
    for (std::size_t i = 0; i < sums.size(); ++i) {
      const ReferencePixelSums& p = sums[i];
      if (p.sea == 0) continue;
      const glm::dvec3 sea = p.sea_mean();
      sea_rgba[4 * i + 0] = float(sea.r);
      sea_rgba[4 * i + 1] = float(sea.g);
      sea_rgba[4 * i + 2] = float(sea.b);
      sea_rgba[4 * i + 3] = float(double(p.sea) / count);
    }
    return ms;
  }

  // A node's measurement (gl::Node::measurements) by name; 0 when no node has it.
  double node_measurement(const std::string& name) const {
    for (const auto& node : graph.nodes())
      for (const auto& [key, value] : node->measurements())
        if (key == name) return value;
    return 0.0;
  }

  // A node's per-row measurement (gl::Node::row_measurements) by name; empty when no node has it.
  std::vector<double> node_row_measurement(const std::string& name) const {
    for (const auto& node : graph.nodes())
      for (const auto& [key, rows] : node->row_measurements())
        if (key == name) return rows;
    return {};
  }

  // A node's per-pixel measurement (gl::Node::pixel_measurements) by name; empty when no node
  // has it. The context must be current.
  Image node_pixel_measurement(const std::string& name) const {
    for (const auto& node : graph.nodes())
      for (auto& [key, image] : node->pixel_measurements())
        if (key == name) return std::move(image);
    return {};
  }

  // The reference's samples whose timer queries may wait unread (gl::GpuTimer::defer_frame):
  // enough that the GPU never idles for the host, few enough to hold a few hundred queries.
  static constexpr std::size_t kDeferredFrames = 64;

  // Rows whose total is below this fraction of the brightest row's do not count in the
  // reference's convergence test: a row the sun's glint barely touches (1e-12 of the brightest
  // was seen) changes by 100 % between sample counts while adding nothing to the image.
  static constexpr double kNegligibleRow = 1e-3;

  // The Halton sequence's radical inverse of i in `base`, in [0, 1).
  static double radical_inverse(int base, int i) {
    double inverse = 0.0, scale = 1.0 / base;
    for (; i > 0; i /= base, scale /= base) inverse += (i % base) * scale;
    return inverse;
  }

  int samples = 1;
  double sample_row_change = 0.0;
  std::vector<double> sample_row_changes;  // RenderStats::sample_row_changes
  std::vector<double> resolved_rows;
  // RenderStats::reference_nonfinite_*, of the last draw_reference.
  long long nonfinite_samples = 0;
  int nonfinite_pixels = 0;
  int first_nonfinite_x = -1, first_nonfinite_y = -1, first_nonfinite_samples = 0;
  std::vector<float> sea_rgba;  // Renderer::reference_sea_image's pixels, top row first
  std::optional<ReferenceAccumulator> accumulator;  // the reference method's sums
};

Renderer::Renderer(GlContext& context, const Scene& scene, RendererOptions options)
    : impl_(std::make_unique<Impl>(context, scene, options)) {
  // A first frame compiles every shader, so that no timed frame includes compilation (one sample
  // of the reference is enough for that).
  impl_->context.make_current();
  if (options.method == ocean::OceanMethod::reference)
    impl_->accumulator.emplace(impl_->target.width(), impl_->target.height(), impl_->shaders);
  impl_->draw_frame();
  reset_timings();
}

void Renderer::set_scene(const Scene& scene) {
  Impl& m = *impl_;
  m.context.make_current();
  const auto start = std::chrono::steady_clock::now();
  m.commit(m.stage(scene, true));
  m.set_scene_ms = elapsed_ms(start);
  m.forget_frames();
  // The reference compiles before its samples are timed, as in the constructor; the other
  // methods draw a frame that compiled anything again (render()).
  if (m.renderer_options.method == ocean::OceanMethod::reference) {
    m.draw_frame();
    m.forget_frames();
  }
}

void Renderer::reset_timings() { impl_->reset_timings(); }

void Renderer::Impl::reset_timings() {
  frame_ms.clear();
  pass_ms.clear();
  timer_fallbacks_before = timer.fallback_frames();
}

void Renderer::Impl::forget_frames() {
  reset_timings();
  pass_order.clear();
  samples = 1;
  sample_row_change = 0.0;
  sample_row_changes.clear();
  resolved_rows.clear();
  nonfinite_samples = 0;
  nonfinite_pixels = 0;
  first_nonfinite_x = first_nonfinite_y = -1;
  first_nonfinite_samples = 0;
  sea_rgba.clear();
}

// GL objects are deleted in the renderer's own context (a no-op for a host's context, which
// the host must keep current).
Renderer::~Renderer() {
  try {
    if (impl_) impl_->context.make_current();
  } catch (const ContextError&) {
    // A context that cannot be made current any more has lost its objects with it.
  }
}

void Renderer::render() {
  Impl& m = *impl_;
  m.context.make_current();
  // The reference's frame is all its samples (its passes' times stay per sample).
  if (m.renderer_options.method == ocean::OceanMethod::reference) {
    m.frame_ms.push_back(m.draw_reference(m.renderer_options.reference.max_samples));
    return;
  }
  const std::size_t programs = m.shaders.program_count();
  const int fallbacks = m.timer.fallback_frames();
  Impl::DrawnFrame drawn = m.draw_frame();
  // A frame that compiled programs (the first after a set_scene that needs new ones) is not
  // timed: it is drawn again, and the second one's times are recorded.
  if (m.shaders.program_count() != programs) {
    m.timer_fallbacks_before += m.timer.fallback_frames() - fallbacks;
    drawn = m.draw_frame();
  }
  m.frame_ms.push_back(m.record_frame(drawn.frame, drawn.passes));
}

Image Renderer::image() const {
  impl_->context.make_current();
  Image image;
  image.width = impl_->target.width();
  image.height = impl_->target.height();
  image.rgba = impl_->target.read_rgba_top_down();
  return image;
}

Image Renderer::reference_sea_image() const {
  Image image;
  if (impl_->renderer_options.method != ocean::OceanMethod::reference || impl_->sea_rgba.empty())
    return image;
  image.width = impl_->target.width();
  image.height = impl_->target.height();
  image.rgba = impl_->sea_rgba;
  return image;
}

Image Renderer::reference_sun_sums() const {
  if (impl_->renderer_options.method != ocean::OceanMethod::reference) return {};
  impl_->context.make_current();
  return impl_->node_pixel_measurement("reference_sun.sums");
}

unsigned Renderer::hdr_texture() const { return impl_->target.color_texture(); }
unsigned Renderer::hdr_framebuffer() const { return impl_->target.framebuffer(); }

void Renderer::present(unsigned framebuffer, int width, int height) {
  Impl& m = *impl_;
  m.context.make_current();
  if (!m.present_vao) m.present_vao = gl::make_vertex_array();
  const GLuint program =
      m.shaders.program({.vertex = "engine/fullscreen.vert", .fragment = "engine/tonemap.frag"});
  const gl::StateGuard guard;
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  gl::set_pass_state();
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program);
  glBindTextureUnit(0, m.target.color_texture());
  glProgramUniform1f(program, glGetUniformLocation(program, "exposure"),
                     static_cast<float>(m.scene.image.exposure));
  glBindVertexArray(m.present_vao.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  gl::check_error("present");
}

RenderStats Renderer::stats() const {
  const Impl& m = *impl_;
  RenderStats stats;
  stats.backend = std::string(backend_name(m.context.backend()));
  stats.renderer = m.info.renderer;
  stats.gl_version = m.info.version;
  stats.context = m.context.description();
  stats.width = m.target.width();
  stats.height = m.target.height();
  stats.mode = m.scene.camera.height >= kSpaceModeHeight ? "space" : "surface";
  stats.frames = static_cast<int>(m.frame_ms.size());
  stats.frame_ms = median(m.frame_ms);
  stats.timing = m.timer.source() == gl::TimingSource::FinishWallClock ? "finish_wall_clock"
                                                                       : "gl_timestamp_query";
  stats.timing_fallback_frames = m.timer.fallback_frames() - m.timer_fallbacks_before;
  for (const auto& name : m.pass_order) {
    auto it = m.pass_ms.find(name);
    if (it != m.pass_ms.end()) stats.passes.emplace_back(name, median(it->second));
  }
  for (const auto& node : m.graph.nodes())
    stats.resolved_waves = std::max(stats.resolved_waves, node->resolved_waves());
  stats.built.push_back("engine.hdr_target.rgba32f+depth32f." + std::to_string(stats.width) + "x" +
                        std::to_string(stats.height));
  for (const auto& item : m.provider->built()) stats.built.push_back(item);
  for (const auto& node : m.graph.nodes())
    for (const auto& item : node->built()) stats.built.push_back(item);
  stats.sky_provider = m.provider->kind();
  stats.method = std::string(ocean::method_name(m.renderer_options.method));
  stats.samples = m.samples;
  stats.sample_row_change = m.sample_row_change;
  stats.sample_row_changes = m.sample_row_changes;
  if (m.renderer_options.method == ocean::OceanMethod::reference) {
    stats.reference_grid_cell = m.renderer_options.reference.grid_cell;
    if (m.renderer_options.terms.sun)
      stats.reference_sun = reference_sun_name(m.renderer_options.reference.sun);
  }
  stats.resolved_rows = m.resolved_rows;
  stats.reference_nonfinite_samples = m.nonfinite_samples;
  stats.reference_nonfinite_pixels = m.nonfinite_pixels;
  stats.reference_first_nonfinite_x = m.first_nonfinite_x;
  stats.reference_first_nonfinite_y = m.first_nonfinite_y;
  stats.reference_first_nonfinite_samples = m.first_nonfinite_samples;
  stats.sun_lattice_row_change = m.node_measurement("reference_sun.lattice_row_change");
  stats.sun_lattice_rows = static_cast<int>(m.node_measurement("reference_sun.lattice_rows"));
  stats.sun_lattice_ms = m.node_measurement("reference_sun.ms");
  stats.sun_lattice_hidden = m.node_measurement("reference_sun.hidden_fraction");
  stats.sun_lattice_margin = static_cast<int>(m.node_measurement("reference_sun.margin_px"));
  stats.sun_lattice_refine = static_cast<int>(m.node_measurement("reference_sun.refine"));
  stats.sun_lattice_segment = static_cast<int>(m.node_measurement("reference_sun.segment"));
  stats.sun_lattice_block_rows = static_cast<int>(m.node_measurement("reference_sun.block_rows"));
  stats.sun_lattice_refined_queue = m.node_measurement("reference_sun.refined_queue");
  stats.sun_lattice_scattered_cells = m.node_measurement("reference_sun.scattered_cells");
  stats.sun_lattice_refined_cells = m.node_measurement("reference_sun.refined_cells");
  stats.sun_lattice_refined_in_place = m.node_measurement("reference_sun.refined_in_place");
  stats.sun_lattice_row_changes = m.node_row_measurement("reference_sun.lattice_row_changes");
  stats.sun_lattice_cells_per_wavelength =
      m.node_measurement("reference_sun.cells_per_wavelength");
  stats.sun_lattice_cells = static_cast<int>(m.node_measurement("reference_sun.cells"));
  {
    const std::vector<double> x = m.node_row_measurement("reference_sun.row_cells_x");
    const std::vector<double> y = m.node_row_measurement("reference_sun.row_cells_y");
    stats.sun_lattice_row_cells.clear();
    for (std::size_t row = 0; row < std::min(x.size(), y.size()); ++row)
      stats.sun_lattice_row_cells.push_back({static_cast<int>(x[row]), static_cast<int>(y[row])});
  }
  stats.sun_lattice_doublings = static_cast<int>(m.node_measurement("reference_sun.doublings"));
  stats.sun_lattice_float_atomics = m.node_measurement("reference_sun.float_atomics") > 0.0;
  stats.sun_lattice_reused = m.node_measurement("reference_sun.reused") > 0.0;
  stats.sun_lattice_rescatters = static_cast<int>(m.node_measurement("reference_sun.rescatters"));
  for (const auto& node : m.graph.nodes())
    for (std::string& warning : node->warnings()) stats.warnings.push_back(std::move(warning));
  stats.sky_provider_kept = m.provider_kept;
  stats.kept_nodes = m.kept_nodes;
  stats.wave_anchor = m.nadir.wave_anchor;
  stats.calm_chart_kept = m.calm_chart_kept;
  if (m.set_scene_ms >= 0.0) stats.setup_ms.emplace_back("renderer.set_scene", m.set_scene_ms);
  if (const double compile = m.shaders.compile_ms() - m.compile_ms_before; compile > 0.0)
    stats.setup_ms.emplace_back("shaders.compile", compile);
  if (!m.provider_kept) stats.setup_ms.emplace_back("sky.provider", m.provider_ms);
  if (m.features_ms >= 0.0) stats.setup_ms.emplace_back("features.place", m.features_ms);
  if (!m.provider_kept)
    for (const auto& [name, ms] : m.provider->setup_ms()) stats.setup_ms.emplace_back(name, ms);
  // The maps this Renderer built (the last build's time; a kept provider's earlier builds are
  // another Renderer's).
  if (m.provider->sky_map_builds() > m.sky_map_builds_before)
    stats.setup_ms.emplace_back("sky.map", m.provider->sky_map_ms());
  if (m.provider->sky_map_array_ms() > 0.0 && !m.sky_map_array_before)
    stats.setup_ms.emplace_back("sky.map_array", m.provider->sky_map_array_ms());
  for (const auto& program : m.shaders.used_programs()) stats.built.push_back("shader:" + program);
  return stats;
}

const Scene& Renderer::scene() const { return impl_->scene; }

SeaState Renderer::sea_state() const { return SeaState(impl_->scene, impl_->nadir.wave_anchor); }

}  // namespace thalassa
