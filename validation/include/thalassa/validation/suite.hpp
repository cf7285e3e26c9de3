// thalassa — suite files: the scenes `thalassa validate [SUITE.json] -o DIR` renders, the
// methods and variants it renders each with, and what it measures (issue 6, point 4; the format
// is in docs/validation.md). One format for every suite: the validation suite
// (data/suites/validation.json: methods against a reference) and stress suites (cases of
// overrides, each with the exit status it must end with).
//
// A case's scene is the embedded default scene, then the suite's `scene` file if given, then
// `base`'s overrides, then the case's own `set`, each applied as `--set key=value` with the
// value's JSON text. A method's (or variant's) `set` is laid over the case's scene for that
// method only: the reference of a case is its scene without them, and a variant with
// own_reference is measured against a reference rendered with its `set`.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "thalassa/engine/scene.hpp"
#include "thalassa/validation/metrics.hpp"

namespace thalassa::validation {

// A suite file that cannot be used. what() is one line, like SceneError's (and a SceneError, so
// that the command line maps it to exit status 2 as a bad scene):
//   "<source>: <key path in the file>: expected <what>, got <what was found>", e.g.
//   "suite.json: cases[3].set.camera.hieght: expected a scene key (docs/scene.md), got an
//   unknown key".
class SuiteError : public SceneError {
 public:
  using SceneError::SceneError;
};

// One scene-key override: the dotted key path and its value as JSON text ("0.01", "\"omega-2\"").
struct SceneOverride {
  std::string key;
  std::string value_json;
  // "key=value_json", the --set form (SceneBuilder::set reads the JSON text back exactly).
  std::string assignment() const { return key + "=" + value_json; }
};

// The ocean's shading methods (thalassa render --method).
inline constexpr std::string_view kMethods[] = {"reference", "basic", "full", "normals"};
// The most pixels per reference pixel a method may draw along each axis (SuiteMethod::supersample):
// 16 x 16 times the pixels of a suite's image, 2048 x 1152 for its usual 128 x 72.
inline constexpr int kMaxSupersample = 16;
// The light terms a suite measures: the renderer's --terms items and "all" (every term as the
// user sees it: --terms sun,sky,sea,air).
inline constexpr std::string_view kTerms[] = {"sun", "sky", "sea", "air", "all"};
// The --terms value that renders `term` ("all" -> "sun,sky,sea,air").
std::string terms_option(std::string_view term);

// One way of rendering each case: a method, and for a variant the scene keys it changes.
struct SuiteMethod {
  std::string name;    // [a-z0-9_]+, unique among the suite's methods; names files and curves
  std::string method;  // one of kMethods
  std::string description;
  std::vector<SceneOverride> set;  // laid over the case's scene for this method only
  // Whether `set` changes the sea itself (ocean.waves: 30 waves are another sea than 60), so
  // that the variant is measured against a reference of its own, the reference method rendered
  // with the same `set` ("reference_" + name in the report), rather than the case's. A variant
  // that changes how a sea is drawn (ocean.grid_cell, ocean.sky_filter) keeps the case's.
  bool own_reference = false;
  // Pixels per reference pixel along each axis: the method draws the case at supersample times
  // its width and height, and each block of supersample x supersample pixels is averaged into the
  // pixel of the reference's size (box_filter in metrics.hpp; for the metrics the block's sea
  // alone at a sea pixel, supersampled_for_comparison).
  // It measures the method at the resolution a user renders at (the suite's images are sized for
  // the reference's cost): which waves a pixel resolves, and the grid's cells (ocean.grid_cell is
  // in pixels), follow the pixel. Its frame time is the larger image's. 1 for the reference.
  int supersample = 1;
  // A plain method (no `set`, drawn at the reference's pixels): drawn on the per-row radiance
  // plots (fig. 10). Every method is on the error-against-time plot.
  bool plain() const { return set.empty() && supersample == 1; }
};

struct SuiteCase {
  std::string name;  // [a-z0-9_]+, unique within the suite; names output files
  int index = -1;    // its place in the file's "cases" array, which messages name ("cases[3]")
  std::string description;
  std::vector<SceneOverride> set;  // in file order
  int expected_exit = 0;           // 0 (renders, every pixel finite) or 2 (invalid input)
  std::string expected_error;      // with 2: a substring of the one-line error message
  // The names of the suite's methods this case is rendered with, in the suite's order (all of
  // them unless the case's `methods` lists some).
  std::vector<std::string> methods;
  // One of the seas of another case (expand_seas): that case's name, and which sea (1 to the
  // number of seas); "" and 0 for a case of the file.
  std::string sea_of;
  int sea = 0;
};

// Frames for the flicker metric: frame k of a case is its scene at time + k * dt.
struct FlickerSettings {
  int frames = 2;                            // [0, 100]; fewer than 2: no flicker measured
  double dt = 1.0 / 30;                      // s between frames, (0, 3600]
  std::vector<std::string> terms = {"all"};  // the terms measured over time (a subset of terms)
};

// The methods' frame times for the error-against-time plots, measured apart from the images:
// each method other than the reference is rendered again at width x height with every light
// term, `frames` times, and its time is the median (RenderStats::frame_ms). The suite's images
// are sized for the reference's cost, where a frame of every other method is a few ms of fixed
// overhead on any renderer and does not tell the methods' costs apart. Width and height both 0:
// the images' own frame times. Not part of a case's fingerprint: `thalassa validate --resume`
// times a kept case again, without rendering its images, when its timing differs.
struct TimingSettings {
  int width = 0;   // pixels, [1, 8192], or 0 with height 0
  int height = 0;  // pixels, [1, 8192], or 0 with width 0
  int frames = 5;  // [1, 100]
  bool enabled() const { return width > 0 && height > 0; }
  bool operator==(const TimingSettings&) const = default;
};

// What the reference renderer is asked for (issue 6, point 1); the validate command passes them
// on. check_convergence: also render the reference with twice the samples and report the
// largest change of a row's total (it must stay below 1%).
struct ReferenceSettings {
  int pixel_samples = 16;  // samples per pixel, [1, 16384]
  // The same for the terms without the sun (sky, sea, air), which cost a small fraction of the
  // sun's reference per sample and converge more slowly per sample than it costs to take more;
  // 0: pixel_samples.
  int pixel_samples_without_sun = 0;
  // Normal samples per pixel for the sun's disc, [1, 2048^2]: the reference's sun integrates
  // over up to round(sqrt(n))^2 cells of each pixel's footprint, in whatever shape it needs
  // (ReferenceSampling::sun_cells, shaders/ocean/reference_sun_scatter.comp), each at most the
  // shortest wavelength / sun_cells_per_wavelength ([1, 128]) wide. The footprints that need
  // more are not compared: on the default suite's 100 m views 256^2 (65536, the default here,
  // and the default suite's until stop 34, when it meant 256 per side: rows 47-71) resolves rows
  // 37-71 of the sea's 21-71, 512^2 rows 31-71 and 2048^2 (the default suite's) rows 25-71
  // (docs/validation.md, "Footprints cut by their cells").
  int sun_normal_samples = 65536;
  double sun_cells_per_wavelength = 16.0;
  // How the reference integrates the sun over its cells: "scattered" (once per image from a
  // lattice of the sea; its convergence, the lattice against one of half the cells, is always
  // reported as MethodResult::lattice_convergence) or "gathered" (per sample over its pixel
  // stratum). planet/renderer.hpp, ReferenceSun.
  std::string sun = "scattered";
  // Scattered: subcells per side of the cells whose slopes come near the mirror slope, [1, 8]
  // (1: none; ReferenceSampling::sun_refine).
  int sun_refine = 4;
  // The cell of the grid the reference rasterises every wave on, pixels, [1/8, 1]
  // (ReferenceSampling::grid_cell): where waves shorter than a pixel's footprint raise crests
  // inside it (near the horizon) a finer grid hides what they hide (docs/validation.md, stop 44).
  double grid_cell = 1.0;
  // Scattered: while the lattice moves a compared row by 1 % or more against half its cells, it
  // doubles its cells up to this many per wavelength, [sun_cells_per_wavelength, 128]; 0: never
  // (ReferenceSampling::sun_max_cells_per_wavelength).
  double sun_max_cells_per_wavelength = 0.0;
  bool check_convergence = false;

  // The most samples per pixel of a term with the sun or without it.
  int max_samples(bool with_sun) const {
    return with_sun || pixel_samples_without_sun <= 0 ? pixel_samples : pixel_samples_without_sun;
  }
  // The square root of the sun's most cells per pixel's footprint: round(sqrt(sun_normal_samples)),
  // at least 1 (ReferenceSampling::sun_cells).
  int sun_cells() const {
    return std::max(1, static_cast<int>(std::lround(std::sqrt(double(sun_normal_samples)))));
  }
};

struct Suite {
  std::string name;  // [a-z0-9_]+
  std::string description;
  std::string source;      // the file it was read from (or "default suite"), for messages
  std::string scene_file;  // the base scene file, resolved against the suite's folder; "" none
  std::vector<SceneOverride> base;   // laid under every case's overrides
  std::vector<SuiteMethod> methods;  // in file order; default: one plain "full"
  std::vector<std::string> terms;    // light terms measured, in file order; default {"all"}
  FlickerSettings flicker;
  TimingSettings timing;
  ReferenceSettings reference;
  HorizonBandOptions horizon;
  std::vector<SuiteCase> cases;  // in file order, at least one

  const SuiteMethod* find_method(std::string_view name) const;
  // The reference method, if the suite has one (method "reference" with no `set`): metrics are
  // computed only then.
  const SuiteMethod* reference_method() const;
};

// Parses a suite; `source` names it in messages; a `scene` path is resolved against `base_dir`
// (the suite file's folder; empty: the working directory). Checks the file's shape, names,
// that every override names a scene key, and, for the base, the methods' sets and every case
// expecting exit status 0, the values themselves with the scene's checks (the case's whole scene
// is built, so a constraint between keys is checked too). A case expecting 2 holds an invalid
// value on purpose: only its keys are checked. Throws SuiteError.
Suite load_suite_text(std::string_view json_text, std::string_view source,
                      const std::string& base_dir = "");
// Reads and parses a suite file; a missing or unreadable file is a SuiteError.
Suite load_suite_file(const std::string& path);
// The suite `thalassa validate` runs with no file (data/suites/validation.json, embedded at
// build time).
Suite default_suite();
std::string_view default_suite_json();

// Narrows `suite` to some of its methods and terms, as `thalassa validate --method` and
// `--term` ask: `methods` names methods (or variants) of the suite, `terms` terms of its
// `terms`; an empty list keeps them all. The reference method, which every metric compares with,
// is kept whether named or not (and a kept variant with own_reference still gets its own), the
// cases' method lists keep the kept methods in the suite's order, and flicker keeps the kept
// terms it measured (none left: no flicker). A name or term the suite does not have is a
// SuiteError naming the option: a misspelt name would otherwise run less than asked and pass.
void narrow_suite(Suite& suite, const std::vector<std::string>& methods,
                  const std::vector<std::string>& terms);

// The most seas `thalassa validate --seas` draws of a case.
inline constexpr int kMaxSeas = 64;

// Replaces each case that is expected to render (expected_exit 0) with `seas` cases, its seas, as
// `thalassa validate --seas N` asks: the k-th (k = 1 to seas) is named NAME_seaK, sets
// ocean.seed to the case's own seed + k - 1 after the case's overrides (another realization of
// the same spectrum: the waves' directions and phases), and records sea_of = NAME, sea = k. The
// reference draws one sea's glints and the other methods the expected glint of their BRDFs, so
// rows that hold few glints compare a realization's luck unless the seas are summed
// (summarize_seas in report.hpp; docs/validation.md, "One sea's glints and the BRDF's expected
// glint"). A case expected to fail stays as it is, and seas = 1 leaves the suite unchanged.
// Returns, for each case of the new list, the index of the case it came from in the old one.
// Throws SuiteError (naming --seas) for seas outside [1, kMaxSeas], a seed past 2^32 - 1, or a
// new name that another case already has.
std::vector<std::size_t> expand_seas(Suite& suite, int seas);

// The --set assignments of a case rendered with `method` (null: the case's own scene): the
// suite's base, the case's set, then the method's set.
std::vector<std::string> case_assignments(const Suite& suite, const SuiteCase& c,
                                          const SuiteMethod* method = nullptr);
// The SceneBuilder of that scene (defaults, the suite's scene file, then case_assignments), so
// that the caller can add its own overrides (time, image.exr_type) before build(). Throws
// SceneError where the scene is invalid (as a case expecting 2 requires).
SceneBuilder case_scene_builder(const Suite& suite, const SuiteCase& c,
                                const SuiteMethod* method = nullptr);
Scene case_scene(const Suite& suite, const SuiteCase& c, const SuiteMethod* method = nullptr);
// Why that scene is invalid input: the one-line message of the SceneError case_scene() throws
// (the message a run of the case prints with exit status 2, which must contain a case's
// expected_error); nullopt where the scene builds.
std::optional<std::string> case_scene_error(const Suite& suite, const SuiteCase& c,
                                            const SuiteMethod* method = nullptr);

// A digest of everything that decides what `thalassa validate` renders and measures for case `c`
// (16 hex digits, FNV-1a 64 of a canonical JSON text): the scene of each of its methods as built
// (defaults, the suite's scene file, base, case and method overrides; or the message that
// refuses it), the methods' names and kinds, the suite's terms, flicker, reference and horizon
// settings, the case's expected ending, and `environment` (the caller's program version and
// renderer, whose frame times the report holds). Two runs of a case with the same fingerprint
// measure the same thing: `thalassa validate --resume` keeps a case of an earlier report only
// when its fingerprint is the one the suite gives now.
std::string case_fingerprint(const Suite& suite, const SuiteCase& c, std::string_view environment);

}  // namespace thalassa::validation
