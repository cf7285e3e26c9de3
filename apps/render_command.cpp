#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "thalassa/thalassa.hpp"

namespace thalassa::cli {
namespace {

std::string stats_json(const RenderStats& stats) {
  nlohmann::ordered_json json;
  json["backend"] = stats.backend;
  json["renderer"] = stats.renderer;
  json["gl_version"] = stats.gl_version;
  json["context"] = stats.context;
  json["width"] = stats.width;
  json["height"] = stats.height;
  json["mode"] = stats.mode;
  json["frames"] = stats.frames;
  json["frame_ms"] = stats.frame_ms;
  json["timing"] = stats.timing;
  json["timing_fallback_frames"] = stats.timing_fallback_frames;
  json["passes"] = nlohmann::ordered_json::object();
  for (const auto& [name, ms] : stats.passes) json["passes"][name] = ms;
  json["resolved_waves"] = stats.resolved_waves;
  json["method"] = stats.method;
  json["samples"] = stats.samples;
  json["sample_row_change"] = stats.sample_row_change;
  // Per row (NaN, a row not counted, is written null).
  if (!stats.sample_row_changes.empty()) json["sample_row_changes"] = stats.sample_row_changes;
  if (!stats.reference_sun.empty()) json["reference_sun"] = stats.reference_sun;
  if (!stats.warnings.empty()) json["warnings"] = stats.warnings;
  if (stats.method == "reference" && stats.sun_lattice_ms > 0.0) {
    json["sun_lattice_row_change"] = stats.sun_lattice_row_change;
    json["sun_lattice_rows"] = stats.sun_lattice_rows;
    if (!stats.sun_lattice_row_changes.empty())
      json["sun_lattice_row_changes"] = stats.sun_lattice_row_changes;
    json["sun_lattice_ms"] = stats.sun_lattice_ms;
    json["sun_lattice_margin"] = stats.sun_lattice_margin;
    json["sun_lattice_refine"] = stats.sun_lattice_refine;
    json["sun_lattice_segment"] = stats.sun_lattice_segment;
    json["sun_lattice_block_rows"] = stats.sun_lattice_block_rows;
    json["sun_lattice_refined_queue"] = stats.sun_lattice_refined_queue;
    json["sun_lattice_scattered_cells"] = stats.sun_lattice_scattered_cells;
    json["sun_lattice_refined_cells"] = stats.sun_lattice_refined_cells;
    json["sun_lattice_refined_in_place"] = stats.sun_lattice_refined_in_place;
    json["sun_lattice_rescatters"] = stats.sun_lattice_rescatters;
    json["sun_lattice_hidden"] = stats.sun_lattice_hidden;
    json["sun_lattice_cells_per_wavelength"] = stats.sun_lattice_cells_per_wavelength;
    json["sun_lattice_cells"] = stats.sun_lattice_cells;
    if (!stats.sun_lattice_row_cells.empty())
      json["sun_lattice_row_cells"] = stats.sun_lattice_row_cells;
    json["sun_lattice_doublings"] = stats.sun_lattice_doublings;
    json["sun_lattice_float_atomics"] = stats.sun_lattice_float_atomics;
  }
  if (!stats.resolved_rows.empty()) json["resolved_rows"] = stats.resolved_rows;
  if (stats.method == "reference") {
    json["reference_grid_cell"] = stats.reference_grid_cell;
    json["reference_nonfinite_samples"] = stats.reference_nonfinite_samples;
    json["reference_nonfinite_pixels"] = stats.reference_nonfinite_pixels;
    if (stats.reference_first_nonfinite_x >= 0)
      json["reference_first_nonfinite"] = {{"x", stats.reference_first_nonfinite_x},
                                           {"y", stats.reference_first_nonfinite_y},
                                           {"samples", stats.reference_first_nonfinite_samples}};
  }
  json["sky_provider"] = stats.sky_provider;
  json["setup_ms"] = nlohmann::ordered_json::object();
  for (const auto& [name, ms] : stats.setup_ms) json["setup_ms"][name] = ms;
  json["built"] = stats.built;
  return json.dump(2) + "\n";
}

}  // namespace

void add_render_command(CLI::App& app, RenderArgs& args) {
  CLI::App* render = app.add_subcommand(
      "render", "Render a scene (the embedded default scene if none is given) to EXR and PNG");
  render->add_option("scene", args.scene, "Scene file (JSON, see docs/scene.md)");
  render->add_option("-o,--output", args.exr, "Linear HDR output (.exr)")->capture_default_str();
  render->add_option("--png", args.png, "Tone-mapped output (.png); default: the EXR's name");
  render->add_flag("--no-png", args.no_png, "Write no PNG");
  render->add_option("--set", args.sets, "Override a scene key: --set camera.height=100")
      ->allow_extra_args(false);
  render->add_option("--stats", args.stats, "Write frame statistics as JSON");
  render->add_option("--backend", args.backend, "egl, osmesa or glfw (default: egl, else osmesa)")
      ->check(CLI::IsMember({"egl", "osmesa", "glfw"}));
  render->add_option("--repeat", args.repeat, "Frames to render (statistics are medians)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  render->add_flag("--float", args.float_exr, "Write a 32-bit float EXR (default: half)");
  render
      ->add_option("--terms", args.terms,
                   "The ocean's light terms drawn, any of sun,sky,sea,air (comma-separated; air: "
                   "the light the atmosphere scatters between the camera and the sea)")
      ->capture_default_str();
  render
      ->add_option("--method", args.method,
                   "The ocean's shading method: full (the paper's), basic (fig. 10's constant "
                   "BRDF), normals (no BRDF) or reference (every wave as geometry, a mirror, "
                   "supersampled); other than full, the camera must be below 20000 m")
      ->check(CLI::IsMember({"full", "basic", "normals", "reference"}))
      ->capture_default_str();
  render
      ->add_option(
          "--samples", args.samples,
          "The reference's most samples per pixel (it doubles them from 16 until each "
          "image row's total over the sea changes by less than 1%; whole rounds of its s x s pixel "
          "strata)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  render->add_flag("--fixed-samples", args.fixed_samples,
                   "The reference draws exactly --samples samples per pixel, converged or not "
                   "(the same 4 x 4 strata and sample points): as validate draws a flicker "
                   "frame after the first, with the first frame's count");
  render
      ->add_option("--reference-sun", args.reference_sun,
                   "How the reference integrates the sun over cells of the sea: scattered (once "
                   "per image from a lattice of the sea, each cell's glint added to the pixel "
                   "that sees it: no noise between sample counts, and independent of the "
                   "resolution) or gathered (per sample over its pixel stratum; kept to compare "
                   "with, docs/validation.md)")
      ->check(CLI::IsMember({"scattered", "gathered"}))
      ->capture_default_str();
  render
      ->add_option("--sun-cells", args.sun_cells,
                   "The reference's sun: scattered, the square root of the most cells per "
                   "pixel's footprint, in whatever shape it needs (gathered: the most per side, "
                   "at most 64 per side of each of its s x s strata); rows that need more are "
                   "reported unresolved in --stats resolved_rows")
      ->check(CLI::Range(1, ocean::kReferenceMaxSunCells))
      ->capture_default_str();
  render
      ->add_option("--sun-cells-per-wavelength", args.sun_cells_per_wavelength,
                   "The reference's sun: cells per shortest wavelength (finer is more accurate "
                   "and costs the square; scattered, --stats sun_lattice_row_change measures it)")
      ->check(CLI::Range(1.0, ocean::kReferenceMaxCellsPerWavelength))
      ->capture_default_str();
  render
      ->add_option("--sun-max-cells-per-wavelength", args.sun_max_cells_per_wavelength,
                   "The reference's sun, scattered: while its lattice moves an image row's total "
                   "by 1% or more against half its cells, double its cells (per wavelength "
                   "times sqrt 2, --sun-cells times sqrt 2) up to this many per wavelength (at "
                   "least --sun-cells-per-wavelength; 0: no doubling); --stats "
                   "sun_lattice_cells_per_wavelength says where it stopped")
      ->check(CLI::Range(0.0, ocean::kReferenceMaxCellsPerWavelength))
      ->capture_default_str();
  render
      ->add_option("--sun-segment", args.sun_segment,
                   "The reference's sun, scattered: the cells of a row each invocation of its "
                   "scatter takes (0: the most llvmpipe's loop limit allows there, 64 on other "
                   "renderers; held to that most on llvmpipe); the same image to float rounding, "
                   "for timing (--stats sun_lattice_segment, sun_lattice_ms)")
      ->check(CLI::Range(0, ocean::kReferenceMaxSunCells))
      ->capture_default_str();
  render
      ->add_option("--sun-block-rows", args.sun_block_rows,
                   "The reference's sun, scattered: the rows of cells each invocation of its "
                   "scatter takes, a column of N + 1 corners serving N cells (0: 4, held on "
                   "llvmpipe to what its loop limit allows); the same image to float rounding, "
                   "for timing (--stats sun_lattice_block_rows, sun_lattice_ms)")
      ->check(CLI::Range(0, ocean::kReferenceMaxSunBlockRows))
      ->capture_default_str();
  render
      ->add_option(
          "--sun-refined-queue", args.sun_refined_queue,
          "The reference's sun, scattered: the places of the queue that takes its "
          "refined cells (those near the mirror slope, cut into subcells) to a pass of "
          "their own (-1: the most, 4194240; 0: none, each refined where its invocation meets it); "
          "the same image to float rounding, for timing (--stats "
          "sun_lattice_refined_queue, sun_lattice_refined_cells, "
          "sun_lattice_refined_in_place, sun_lattice_ms); each chunk of cells it serves is "
          "two dispatches, so a queue of a few places makes very many")
      ->check(CLI::Range(std::int64_t(-1), ocean::kReferenceMaxSunRefinedQueue))
      ->capture_default_str();
  render->add_flag("--sun-swap-atomics", args.sun_swap_atomics,
                   "The reference's sun, scattered: add its cells' shares by compare-and-swap "
                   "even where the driver has float atomics (GL_NV_shader_atomic_float); the "
                   "same image to float rounding, for timing the two (--stats "
                   "sun_lattice_ms, sun_lattice_float_atomics)");
  render->add_option(
      "--sun-sums", args.sun_sums,
      "The reference's sun, scattered: write its lattice's per-pixel sums as a float EXR (R sum "
      "of solid angle x sun, G sum of solid angle, sr: the pixel's sun factor is R / G; B the part "
      "of G over the cell cap; A the solid angle hidden behind crests, sr), also when the image "
      "is refused for not being finite");
  render
      ->add_option("--sun-refine", args.sun_refine,
                   "The reference's sun, scattered: cells whose slopes come near the mirror slope "
                   "(the few that reflect the sun) are cut into N x N subcells, as if the lattice "
                   "were N times finer where the glints are")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  render
      ->add_option("--reference-grid-cell", args.reference_grid_cell,
                   "The reference: the cell of the grid it rasterises every wave on, pixels (each "
                   "sample's normal is exact whatever the cell; the cell decides which facets a "
                   "crest hides inside a pixel: those behind waves of two cells and longer; "
                   "finer costs the square in vertices)")
      ->check(CLI::Range(ocean::kReferenceMinGridCell, ocean::kReferenceGridCell))
      ->capture_default_str();
}

int run_render(const RenderArgs& args) {
  // 1. Everything the user typed is checked before any GL work.
  LoadedScene loaded;
  try {
    loaded = load_scene(args.scene, args.sets,
                        args.float_exr ? std::vector<std::string>{"image.exr_type=float"}
                                       : std::vector<std::string>{});
  } catch (const SceneError& error) {
    print_error(error.what());
    return kExitInvalidInput;
  }
  const Scene& scene = loaded.scene;
  const std::string png = png_path(args.exr, args.png, args.no_png);
  RendererOptions renderer_options;
  renderer_options.method = *ocean::parse_method(args.method);  // CLI11 checked the word
  renderer_options.reference.max_samples = args.samples;
  renderer_options.reference.min_samples =
      std::min(renderer_options.reference.min_samples, args.samples);
  renderer_options.reference.fixed_samples = args.fixed_samples;
  renderer_options.reference.sun_cells = args.sun_cells;
  renderer_options.reference.sun_cells_per_wavelength = args.sun_cells_per_wavelength;
  renderer_options.reference.sun_refine = args.sun_refine;
  renderer_options.reference.grid_cell = args.reference_grid_cell;
  renderer_options.reference.sun_max_cells_per_wavelength = args.sun_max_cells_per_wavelength;
  renderer_options.reference.sun_float_atomics = !args.sun_swap_atomics;
  renderer_options.reference.sun_segment = args.sun_segment;
  renderer_options.reference.sun_block_rows = args.sun_block_rows;
  renderer_options.reference.sun_refined_queue = args.sun_refined_queue;
  renderer_options.reference.sun = *parse_reference_sun(args.reference_sun);  // CLI11 checked
  const std::vector<std::string> problems = {
      renderer_options.method != ocean::OceanMethod::full && scene.camera.height >= kSpaceModeHeight
          ? "--method " + args.method +
                ": expected a camera below 20000 m (the method draws the "
                "projected grid's sea), got camera.height " +
                format_number(scene.camera.height)
          : "",
      args.sun_max_cells_per_wavelength != 0.0 &&
              args.sun_max_cells_per_wavelength < args.sun_cells_per_wavelength
          ? "--sun-max-cells-per-wavelength: expected 0 or at least --sun-cells-per-wavelength (" +
                format_number(args.sun_cells_per_wavelength) + "), got " +
                format_number(args.sun_max_cells_per_wavelength)
          : "",
      parse_terms(args.terms, renderer_options.terms), check_output("-o", args.exr, ".exr"),
      png.empty() ? "" : check_output("--png", png, ".png"),
      args.stats.empty() ? "" : check_output("--stats", args.stats, ""),
      args.sun_sums.empty() ? "" : check_output("--sun-sums", args.sun_sums, ".exr"),
      args.sun_sums.empty() || (renderer_options.method == ocean::OceanMethod::reference &&
                                renderer_options.terms.sun &&
                                renderer_options.reference.sun == ReferenceSun::scattered)
          ? ""
          : "--sun-sums: expected --method reference with the term sun and --reference-sun "
            "scattered (the sums are its lattice's)",
      args.sun_sums.empty() ? "" : check_distinct("--sun-sums", args.sun_sums, {args.exr, png}),
      // The image outputs differ by extension; the statistics may name either of them.
      args.stats.empty() ? ""
                         : check_distinct("--stats", args.stats, {args.exr, png, args.sun_sums})};
  for (const std::string& problem : problems) {
    if (!problem.empty()) {
      print_error(problem);
      return kExitInvalidInput;
    }
  }

  // 2. A context, the renderer, the frames.
  ContextOptions options;
  options.width = scene.image.width;
  options.height = scene.image.height;
  std::unique_ptr<GlContext> context = open_context(args.backend, options);
  std::unique_ptr<Renderer> renderer_owner;
  try {
    renderer_owner = std::make_unique<Renderer>(*context, scene, renderer_options);
  } catch (const SceneError& error) {
    print_error(error.what());
    return kExitInvalidInput;
  }
  Renderer& renderer = *renderer_owner;
  for (int i = 0; i < args.repeat; ++i) {
    renderer.render();
    if (context->backend() == Backend::Glfw) {
      int width = 0, height = 0;
      context->default_framebuffer_size(width, height);
      renderer.present(0, width, height);
      context->present();
    }
  }
  const Image image = renderer.image();
  RenderStats stats = renderer.stats();
  {
    SeaCache sea;
    if (const double depth = camera_depth(sea, scene, stats.wave_anchor); depth > 0.0) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "the camera (%.3g m) is %.3g m under the water at its nadir: the image shows "
                    "the wave from inside (`thalassa sea` gives the sea's height)",
                    scene.camera.height, depth);
      stats.warnings.push_back(text);
    }
  }
  for (const std::string& warning : stats.warnings) print_error("warning: " + warning);
  const Image sun_sums = args.sun_sums.empty() ? Image{} : renderer.reference_sun_sums();
  if (!args.sun_sums.empty() && sun_sums.rgba.empty()) {
    print_error("--sun-sums: the render drew no scattered sun");  // checked above: not expected
    return kExitRuntimeFailure;
  }
  const Metadata sun_sums_metadata = {
      {"thalassa:channels",
       "R sum omega sun, G sum omega, B the part of G over the cell cap, A hidden solid angle "
       "(sr; shaders/ocean/reference_sun_scatter.comp)"}};
  // An image that is not finite is an error, not a file; the statistics and the sun's sums, when
  // asked for, are still written, since they say what the render did.
  if (const std::string problem = nonfinite_report(image, renderer); !problem.empty()) {
    PendingOutputs diagnostics;
    if (!args.stats.empty()) write_text_atomically(diagnostics.add(args.stats), stats_json(stats));
    if (!sun_sums.rgba.empty())
      write_exr(diagnostics.add(args.sun_sums), sun_sums, ExrPixelType::Float, sun_sums_metadata);
    diagnostics.commit();
    print_error("the rendered image: " + problem + "; no image written");
    return kExitRuntimeFailure;
  }

  // 3. Outputs, each written whole or not at all.
  const Metadata metadata = render_metadata(scene, loaded.merged_json, stats,
                                            {{"thalassa:terms", args.terms},
                                             {"thalassa:method", args.method},
                                             {"thalassa:samples", std::to_string(stats.samples)}});
  PendingOutputs outputs;
  write_exr(outputs.add(args.exr), image, scene.image.exr_type, metadata);
  if (!png.empty())
    write_png(outputs.add(png), image, scene.image.exposure, {{"Software", "thalassa"}});
  if (!args.stats.empty()) write_text_atomically(outputs.add(args.stats), stats_json(stats));
  if (!sun_sums.rgba.empty())
    write_exr(outputs.add(args.sun_sums), sun_sums, ExrPixelType::Float, sun_sums_metadata);
  outputs.commit();
  return kExitOk;
}

}  // namespace thalassa::cli
