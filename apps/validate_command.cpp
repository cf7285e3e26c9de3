// thalassa validate [SUITE.json] -o DIR (issue 6, point 4): renders each case of a suite with
// each of its methods and light terms, measures them against the case's reference
// (validation/metrics.hpp) and writes the report (validation/report.hpp). Cases that expect
// exit status 2 are checked to be refused with their message; the others to render finite
// images. The command's own exit status: 0 when every case ended as it expected, 1 otherwise
// (or at run time), 2 for a bad suite or bad options.
#include <fnmatch.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"
#include "thalassa/thalassa.hpp"

namespace thalassa::cli {
namespace {

namespace fs = std::filesystem;
using validation::CaseResult;
using validation::MethodResult;
using validation::Suite;
using validation::SuiteCase;
using validation::SuiteMethod;
using validation::TermResult;

// The methods' timing (Suite::timing) first renders untimed frames for this long, at most
// kTimingWarmupFrames of them.
constexpr std::chrono::milliseconds kTimingWarmup{250};
constexpr int kTimingWarmupFrames = 100;

// Whether case `c` renders the suite's reference (then its metrics are computed).
bool renders_reference(const Suite& suite, const SuiteCase& c) {
  const SuiteMethod* reference = suite.reference_method();
  return reference &&
         std::find(c.methods.begin(), c.methods.end(), reference->name) != c.methods.end();
}

// The renders of one case: (method name, term) -> images over the flicker frames (frame 0
// first) and the frame time of frame 0.
struct Rendered {
  std::vector<Image> frames;
  // What the metrics compare, per frame: the frames themselves, or for the reference the
  // frames with each sea pixel's sea alone (validation::reference_for_comparison).
  std::vector<Image> compared;
  RenderStats stats;
  // Per frame: what in it is not finite (nonfinite_report), "" when nothing.
  std::vector<std::string> problems;
};

// The reference's sun lattice as drawn (RenderStats::sun_lattice_cells_per_wavelength and
// sun_lattice_cells), for the renders of a reference that draw the lattice another converged.
struct SunLattice {
  double cells_per_wavelength = 0.0;
  int cells = 0;
};

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class CaseRunner {
 public:
  // With write_exr false the images are written as PNG alone (--no-exr).
  CaseRunner(const Suite& suite, GlContext& context, const std::string& dir, ProgressBar& bar,
             bool write_exr)
      : suite_(suite), context_(context), dir_(dir), bar_(bar), write_exr_(write_exr) {}

  CaseResult run(const SuiteCase& c) {
    CaseResult result;
    result.name = c.name;
    result.description = c.description;
    result.set = c.set;
    result.expected_exit = c.expected_exit;
    result.expected_error = c.expected_error;
    Scene scene;
    try {
      scene = validation::case_scene(suite_, c);
      check_drawable(scene, "case " + c.name);
    } catch (const SceneError& error) {
      result.exit_status = kExitInvalidInput;
      result.message = error.what();
      bar_.skipped(c.name, "refused: " + result.message);
      return result;
    }
    result.camera_height = scene.camera.height;
    const auto start = std::chrono::steady_clock::now();
    try {
      render_case(c, scene, result);
      time_methods(c, result);
    } catch (const SceneError& error) {
      result.exit_status = kExitInvalidInput;
      result.message = error.what();
    } catch (const std::exception& error) {
      result.exit_status = kExitRuntimeFailure;
      result.message = error.what();
    }
    result.seconds = seconds_since(start);
    return result;
  }

  // A case kept from an earlier report (--resume) whose methods were timed at other settings
  // than the suite's: times them again, without rendering its images.
  void retime(const SuiteCase& c, CaseResult& result) {
    try {
      time_methods(c, result);
    } catch (const std::exception& error) {
      result.exit_status = kExitRuntimeFailure;
      result.message = std::string("timing: ") + error.what();
    }
  }

 private:
  // Each method of the case other than the references, timed apart (Suite::timing): its scene
  // at the timing size with every light term, `frames` frames, the median frame time.
  void time_methods(const SuiteCase& c, CaseResult& result) {
    if (!suite_.timing.enabled()) return;
    LightTerms every;
    parse_terms(validation::terms_option("all"), every);
    for (MethodResult& m : result.methods) {
      if (m.method == "reference") continue;
      const SuiteMethod* method = suite_.find_method(m.name);
      if (!method) continue;
      Scene scene = validation::case_scene(suite_, c, method);
      scene.image.width = suite_.timing.width;
      scene.image.height = suite_.timing.height;
      RendererOptions options;
      options.method = *ocean::parse_method(method->method);
      options.terms = every;
      const auto start = std::chrono::steady_clock::now();
      Renderer renderer(context_, scene, options);
      // Warm-up frames, untimed, for at least kTimingWarmup: a GPU's clocks rise from idle over
      // tens to hundreds of ms, longer than five frames of a few ms (on the H200 the first
      // method timed in stop 26, basic, read 36.8 ms, and 6.4 on the next case). On llvmpipe
      // one frame.
      const auto warm_start = std::chrono::steady_clock::now();
      for (int k = 0; k < kTimingWarmupFrames &&
                      std::chrono::steady_clock::now() - warm_start < kTimingWarmup;
           ++k)
        renderer.render();
      renderer.reset_timings();
      for (int k = 0; k < suite_.timing.frames; ++k) renderer.render();
      m.timing_ms = renderer.stats().frame_ms;
      const double seconds = seconds_since(start);
      char detail[160];
      std::snprintf(detail, sizeof detail, "%s, timed at %dx%d: %.1f ms (median of %d frames)",
                    m.name.c_str(), scene.image.width, scene.image.height, *m.timing_ms,
                    suite_.timing.frames);
      bar_.done(c.name, detail, seconds);
    }
    result.timing = suite_.timing;
  }

  void render_case(const SuiteCase& c, const Scene& base_scene, CaseResult& result) {
    const validation::ViewGeometry view(base_scene);
    const SuiteMethod* reference = suite_.reference_method();
    const bool has_reference = renders_reference(suite_, c);
    // What is rendered, in order: the case's reference first, then the own references of the
    // variants that change the sea (SuiteMethod::own_reference), then every other method, each
    // measured against the reference of its sea: key "" the case's, else the variant's name.
    struct Job {
      const SuiteMethod* method;
      std::string against;  // the key of its reference; "" the case's
      bool is_reference;    // its images are the reference of `against`
    };
    std::vector<Job> jobs;
    // The own references' methods (name, set); reserved, so that the jobs' pointers stay valid.
    std::vector<SuiteMethod> own_references;
    own_references.reserve(c.methods.size());
    if (has_reference) jobs.push_back({reference, "", true});
    for (const std::string& name : c.methods) {
      const SuiteMethod* m = suite_.find_method(name);
      if (!has_reference || !m->own_reference) continue;
      own_references.push_back({.name = "reference_" + m->name,
                                .method = reference->method,
                                .description = "the reference of " + m->name + "'s sea",
                                .set = m->set});
      jobs.push_back({&own_references.back(), m->name, true});
    }
    for (const std::string& name : c.methods) {
      const SuiteMethod* m = suite_.find_method(name);
      if (m == reference) continue;
      jobs.push_back({m, m->own_reference && has_reference ? m->name : "", false});
    }
    // (reference key, term) -> the reference's renders.
    std::map<std::pair<std::string, std::string>, Rendered> reference_images;
    for (const Job& job : jobs) {
      const SuiteMethod* method = job.method;
      const Scene scene = validation::case_scene(suite_, c, method);
      MethodResult m;
      m.name = method->name;
      m.method = method->method;
      m.plain = method->plain();
      // A variant's own reference is measured against itself, like the case's.
      if (!job.against.empty()) m.reference = "reference_" + job.against;
      // The sun's lattice converges once per reference, on its first term with the sun (the
      // others draw the same lattice of the same view: the coarser one, and the doublings,
      // would cost them a third more or several times for the same number). They draw the
      // lattice it ended with.
      bool lattice_measured = false;
      std::optional<SunLattice> lattice;
      std::vector<double> lattice_rows;  // its per-row changes (RenderStats), for every sun term
      // The lattice itself, kept: the term `all`'s frame 0 draws the sun term's lattice of the
      // same view and time, without scattering it again (about a quarter of a reference's time).
      const std::shared_ptr<ocean::ScatteredSunCache> sun_cache =
          job.is_reference ? ocean::make_scattered_sun_cache() : nullptr;
      for (const std::string& term : suite_.terms) {
        const auto term_start = std::chrono::steady_clock::now();
        LightTerms terms;
        if (const std::string problem = parse_terms(validation::terms_option(term), terms);
            !problem.empty())
          throw SceneError(suite_.source + ": " + problem);
        const bool measure_lattice = job.is_reference && terms.sun && !lattice_measured;
        Rendered rendered =
            render_term(c, *method, scene, term, terms, measure_lattice, lattice, sun_cache);
        if (job.is_reference)
          for (std::size_t k = 0; k < rendered.compared.size(); ++k)
            rendered.compared[k] = validation::reference_for_comparison(
                rendered.frames[k], rendered.compared[k], view.sea_mask());
        for (std::size_t k = 0; k < rendered.frames.size(); ++k)
          if (const std::string& problem = rendered.problems[k];
              !problem.empty() && result.exit_status != kExitRuntimeFailure) {
            result.exit_status = kExitRuntimeFailure;
            result.message =
                method->name + ", " + term + ", frame " + std::to_string(k) + ": " + problem;
          }
        TermResult t;
        t.term = term;
        t.frame_ms = rendered.stats.frame_ms;
        t.samples = rendered.stats.samples;
        const std::string stem = "images/" + c.name + "_" + method->name + "_" + term;
        t.png = stem + ".png";
        if (write_exr_) {
          t.exr = stem + ".exr";
          write_exr((fs::path(dir_) / t.exr).string(), rendered.frames.front(), ExrPixelType::Float,
                    {{"thalassa:case", c.name},
                     {"thalassa:method", method->method},
                     {"thalassa:terms", validation::terms_option(term)}});
        }
        write_png((fs::path(dir_) / t.png).string(), rendered.frames.front(), scene.image.exposure);
        if (job.is_reference) {
          reference_images[{job.against, term}] = rendered;
          if (suite_.reference.check_convergence)
            m.convergence.emplace_back(term, rendered.stats.sample_row_change);
          if (measure_lattice && rendered.stats.sun_lattice_ms > 0.0) {
            // No row measured (a sun black in the view, or no row resolved): undefined, not 0.
            m.lattice_convergence.emplace_back(term, rendered.stats.sun_lattice_rows > 0
                                                         ? rendered.stats.sun_lattice_row_change
                                                         : kUndefined);
            m.lattice_cells_per_wavelength.emplace_back(
                term, rendered.stats.sun_lattice_cells_per_wavelength);
            lattice = SunLattice{rendered.stats.sun_lattice_cells_per_wavelength,
                                 rendered.stats.sun_lattice_cells};
            lattice_rows = rendered.stats.sun_lattice_row_changes;
            lattice_measured = true;
          }
          const std::vector<double> no_test;
          const std::vector<double> u = validation::reference_row_uncertainty(
              suite_.reference.check_convergence ? rendered.stats.sample_row_changes : no_test,
              terms.sun ? lattice_rows : no_test, view.height());
          m.row_uncertainty.emplace_back(term, u);  // all NaN: neither test measured a row
          // The rows of the sea its sun resolves (a row of sky alone counts as resolved in
          // RenderStats::resolved_rows, and is never compared).
          const std::vector<double>& rows = rendered.stats.resolved_rows;
          if (!rows.empty()) {
            const validation::PixelMask resolved = validation::resolved_rows_mask(
                view.sea_mask(), rows, validation::kResolvedRowFraction);
            int sea_rows = 0;
            for (int y = 0; y < resolved.height; ++y) {
              bool any = false;
              for (int x = 0; x < resolved.width && !any; ++x) any = resolved(x, y);
              sea_rows += any ? 1 : 0;
            }
            m.resolved_rows.emplace_back(term, sea_rows);
          }
        }
        const auto ref = reference_images.find({job.against, term});
        if (ref != reference_images.end()) {
          // Only the rows where the reference's sun is resolved (all rows without the sun).
          const validation::PixelMask compared = validation::resolved_rows_mask(
              view.sea_mask(), ref->second.stats.resolved_rows, validation::kResolvedRowFraction);
          const std::vector<Image>& against = ref->second.compared;
          t.metrics = validation::compare_images(rendered.compared.front(), against.front(), view,
                                                 suite_.horizon, &compared,
                                                 png_black_level(scene.image.exposure));
          if (rendered.frames.size() >= 2) {
            t.flicker = validation::flicker(rendered.frames, view.sea_mask());
            // Relative to the reference's changes: undefined where the reference is black.
            if (against.size() == rendered.frames.size())
              t.temporal_error =
                  t.metrics.reference_black
                      ? std::numeric_limits<double>::quiet_NaN()
                      : validation::temporal_error(rendered.compared, against, compared);
          }
        }
        t.seconds = seconds_since(term_start);
        m.terms.push_back(std::move(t));
      }
      result.methods.push_back(std::move(m));
    }
  }

  // One method and term (`terms`, parsed from `term`) on the case: frame 0 at the scene's time,
  // then the flicker frames; the reference's sun measures its lattice's convergence on frame 0
  // with measure_lattice (doubling its cells as the suite allows), and the other frames draw the
  // lattice frame 0 ended with; with `lattice`, every frame draws that one. A reference's frames
  // keep their lattices in `sun_cache` and draw a kept one of the same view and time from it.
  Rendered render_term(const SuiteCase& c, const SuiteMethod& method, const Scene& scene,
                       const std::string& term, const LightTerms& terms, bool measure_lattice,
                       const std::optional<SunLattice>& lattice,
                       const std::shared_ptr<ocean::ScatteredSunCache>& sun_cache) {
    RendererOptions options;
    options.reference.sun_cache = sun_cache;
    options.method = *ocean::parse_method(method.method);
    options.terms = terms;
    const validation::ReferenceSettings& reference = suite_.reference;
    const int most = reference.max_samples(options.terms.sun);
    options.reference.max_samples = most;
    options.reference.min_samples = std::min(options.reference.min_samples, most);
    options.reference.sun_cells = reference.sun_cells();
    options.reference.sun_cells_per_wavelength = reference.sun_cells_per_wavelength;
    options.reference.sun = *parse_reference_sun(reference.sun);  // the suite's parser checked
    options.reference.sun_refine = reference.sun_refine;
    options.reference.sun_max_cells_per_wavelength = reference.sun_max_cells_per_wavelength;
    const auto draw = [&](const SunLattice& drawn) {
      options.reference.sun_cells_per_wavelength = drawn.cells_per_wavelength;
      options.reference.sun_cells = drawn.cells;
      options.reference.sun_max_cells_per_wavelength = 0.0;
    };
    if (lattice && lattice->cells > 0) draw(*lattice);
    const bool over_time = suite_.flicker.frames >= 2 &&
                           std::find(suite_.flicker.terms.begin(), suite_.flicker.terms.end(),
                                     term) != suite_.flicker.terms.end();
    const int frames = over_time ? suite_.flicker.frames : 1;
    Rendered rendered;
    for (int k = 0; k < frames; ++k) {
      const auto start = std::chrono::steady_clock::now();
      Scene s = scene;
      s.time += k * suite_.flicker.dt;
      options.reference.measure_lattice = measure_lattice && k == 0;
      if (k == 1 && options.method == ocean::OceanMethod::reference) {
        // The later frames take frame 0's samples, no more and no fewer (the same min_samples,
        // hence the same strata): the sample points and the sun's lattice do not depend on the
        // time, so the frames' difference is the sea's motion seen through the same samples.
        // Converged anew, each frame stopped at its own count (32 against 128 on
        // wind10_100m_low_sun, stop 23), and their difference held two estimates' noise on top
        // of the motion (there 0.307 against 0.303 through the same samples).
        options.reference.max_samples = rendered.stats.samples;
        options.reference.fixed_samples = true;
        if (rendered.stats.sun_lattice_cells > 0)
          draw({rendered.stats.sun_lattice_cells_per_wavelength, rendered.stats.sun_lattice_cells});
      }
      Renderer renderer(context_, s, options);
      renderer.render();
      rendered.frames.push_back(renderer.image());
      rendered.problems.push_back(nonfinite_report(rendered.frames.back(), renderer));
      // The reference's sea alone (its pixels merged with image()'s by render_case); other
      // methods compare as drawn.
      rendered.compared.push_back(options.method == ocean::OceanMethod::reference
                                      ? renderer.reference_sea_image()
                                      : rendered.frames.back());
      if (k == 0) rendered.stats = renderer.stats();
      const double seconds = seconds_since(start);
      char detail[160];
      std::snprintf(detail, sizeof detail, "%s, %s, frame %d: %.0f ms (%d samples%s)",
                    method.name.c_str(), term.c_str(), k, renderer.stats().frame_ms,
                    renderer.stats().samples,
                    renderer.stats().sun_lattice_reused ? ", its sun's lattice kept" : "");
      bar_.done(c.name, detail, seconds);
      // What the render worked around (a lattice scattered again, and why), a line of its own.
      for (const std::string& warning : renderer.stats().warnings)
        bar_.note(c.name + ": " + method.name + ", " + term + ", frame " + std::to_string(k) +
                  ": warning: " + warning);
    }
    return rendered;
  }

  const Suite& suite_;
  GlContext& context_;
  std::string dir_;
  ProgressBar& bar_;
  bool write_exr_ = true;
};

// The renders a case asks for, for the progress bar: per method (and own reference), per term,
// one frame or the flicker frames; one (skipped) step for a case expected to be refused.
int render_count(const Suite& suite, const SuiteCase& c) {
  if (c.expected_exit != 0) return 1;
  // Each method other than the reference timed apart (Suite::timing).
  const auto timed = [&] {
    int n = 0;
    if (suite.timing.enabled())
      for (const std::string& name : c.methods) n += suite.find_method(name)->method != "reference";
    return n;
  };
  const bool has_reference = renders_reference(suite, c);
  std::size_t renders = c.methods.size();
  for (const std::string& name : c.methods)
    renders += has_reference && suite.find_method(name)->own_reference ? 1 : 0;
  int count = 0;
  for (std::size_t m = 0; m < renders; ++m)
    for (const std::string& term : suite.terms) {
      const bool over_time = suite.flicker.frames >= 2 &&
                             std::find(suite.flicker.terms.begin(), suite.flicker.terms.end(),
                                       term) != suite.flicker.terms.end();
      count += over_time ? suite.flicker.frames : 1;
    }
  return count + timed();
}

// Whether a case kept from an earlier report must be timed again (Suite::timing changed, or
// it was not timed): the count of its timing renders, 0 when not.
int retime_count(const Suite& suite, const CaseResult& kept) {
  if (!suite.timing.enabled() || kept.methods.empty() || kept.timing == suite.timing) return 0;
  int n = 0;
  for (const MethodResult& m : kept.methods) n += m.method != "reference";
  return n;
}

// Whether every PNG image a case's report names is in `dir` (a resumed run keeps it only then).
// Its EXR images may be gone: the report shows the PNGs, and its numbers are in results.json
// (a GPU machine's report comes back without its EXRs where it would not fit: scripts/device).
bool images_present(const CaseResult& c, const std::string& dir) {
  std::error_code error;
  for (const MethodResult& m : c.methods)
    for (const TermResult& t : m.terms)
      if (!t.png.empty() && !fs::is_regular_file(fs::path(dir) / t.png, error)) return false;
  return true;
}

// A kept case without the EXR images of it that are gone from `dir` (their names dropped, so
// that the report names no file it does not have); how many were dropped.
int drop_missing_exrs(CaseResult& c, const std::string& dir) {
  std::error_code error;
  int dropped = 0;
  for (MethodResult& m : c.methods)
    for (TermResult& t : m.terms)
      if (!t.exr.empty() && !fs::is_regular_file(fs::path(dir) / t.exr, error)) {
        t.exr.clear();
        ++dropped;
      }
  return dropped;
}

}  // namespace

void add_validate_command(CLI::App& app, ValidateArgs& args) {
  CLI::App* validate = app.add_subcommand(
      "validate",
      "Render a suite of cases with each shading method against the reference and write the "
      "validation report (the default suite in data/suites/validation.json if none is given)");
  validate->add_option("suite", args.suite, "Suite file (JSON, see docs/validation.md)");
  validate->add_option("-o,--output", args.dir, "Folder of the report")->required();
  validate->add_option("--backend", args.backend, "egl or osmesa (default: egl, else osmesa)")
      ->check(CLI::IsMember({"egl", "osmesa"}));
  validate->add_option("--case", args.cases,
                       "Run only this case (a name or a shell pattern such as 'wind10_*'; may be "
                       "given more than once; default: every case)");
  validate->add_option("--method", args.methods,
                       "Render only this method or variant of the suite (its name; may be given "
                       "more than once; default: every one). The suite's reference is rendered "
                       "whatever this says: every metric compares with it");
  validate->add_option("--term", args.terms,
                       "Measure only this light term of the suite's terms (sun, sky, sea, air or "
                       "all; may be given more than once; default: every one)");
  validate
      ->add_option("--reference-samples", args.reference_samples,
                   "The reference's most samples per pixel, instead of the suite's "
                   "reference.pixel_samples (it doubles them from 16 while a row's total changes "
                   "by 1% or more; a machine with a GPU affords 1024 and more); the terms without "
                   "the sun keep reference.pixel_samples_without_sun where it is larger")
      ->check(CLI::Range(1, ocean::kReferenceMaxPixelSamples));
  validate
      ->add_option("--reference-sun-max-cells-per-wavelength", args.reference_sun_max_cells,
                   "The reference's sun: while its lattice moves a row's total by 1% or more "
                   "against half its cells, double them up to this many per shortest wavelength, "
                   "instead of the suite's reference.sun_max_cells_per_wavelength (at least its "
                   "reference.sun_cells_per_wavelength; each doubling about twice the sun's time)")
      ->check(CLI::Range(1.0, ocean::kReferenceMaxCellsPerWavelength));
  validate
      ->add_option("--reference-sun-cells", args.reference_sun_cells,
                   "The reference's sun: the square root of its first lattice's most cells per "
                   "pixel's footprint, instead of that of the suite's "
                   "reference.sun_normal_samples; the footprints that need more are not "
                   "compared (on the default suite's views 512 resolves the sea from 6 degrees "
                   "below the horizon, 2048, the default suite's, from 3 degrees, 16384 from "
                   "the row below the horizon's, at many times the cost)")
      ->check(CLI::Range(1, ocean::kReferenceMaxSunCells));
  validate
      ->add_option("--seas", args.seas,
                   "Draw each selected case over this many seas, its ocean.seed and the next "
                   "ones (cases NAME_sea1 to NAME_seaN), sum each row's totals over them and pool "
                   "their horizon bands (seas.csv, seas_horizon.csv, index.html): the reference "
                   "draws one sea's glints and the other methods the expected glint of their "
                   "BRDFs, so rows of few glints compare a sea's luck unless the seas are summed")
      ->check(CLI::Range(1, validation::kMaxSeas));
  validate->add_flag("--resume", args.resume,
                     "Keep the cases of the report already in the output folder that were run "
                     "with the same inputs (scene, methods, settings, program and renderer) and "
                     "whose PNG images are there (EXR images gone are left out of the report), "
                     "and render the rest; the report is rewritten after each case, so a run cut "
                     "short can be resumed, and runs of different --case can be joined");
  validate->add_flag("--no-exr", args.no_exr,
                     "Write the images as PNG only, no EXR (the PNGs, plots and numbers are the "
                     "whole report): for a report that must travel small, such as a lent GPU "
                     "machine's (scripts/device/run); --resume keeps its cases either way");
  validate
      ->add_option("--time-limit", args.time_limit,
                   "Seconds from the start after which no case is begun that the longest case "
                   "of this run says would end past them (the report holds the cases done, and "
                   "--resume goes on; a case under way is not stopped)")
      ->check(CLI::Validator(
          [](const std::string& text) -> std::string {
            double seconds = 0.0;
            try {
              seconds = std::stod(text);
            } catch (const std::exception&) {
            }
            return seconds > 0.0 && std::isfinite(seconds)
                       ? std::string()
                       : "expected seconds greater than 0, got " + text;
          },
          "SECONDS > 0"));
}

namespace {

// Which of the suite's cases `patterns` name (all when empty), one flag per case. A pattern that
// matches no case is bad input: a misspelt name would otherwise run nothing and pass.
std::vector<bool> select_cases(const Suite& suite, const std::vector<std::string>& patterns) {
  std::vector<bool> selected(suite.cases.size(), patterns.empty());
  for (const std::string& p : patterns) {
    bool any = false;
    for (std::size_t i = 0; i < suite.cases.size(); ++i)
      if (fnmatch(p.c_str(), suite.cases[i].name.c_str(), 0) == 0) selected[i] = any = true;
    if (!any) {
      std::string names;
      for (const SuiteCase& c : suite.cases) names += (names.empty() ? "" : ", ") + c.name;
      throw SceneError("--case: expected the name or pattern of a case of " + suite.source + " (" +
                       names + "), got \"" + p + "\"");
    }
  }
  return selected;
}

// The cases of the report in `dir` (--resume), by name; none when it has no report yet. A report
// that cannot be read, or one of another suite, is bad input (SceneError): resuming it would mix
// two runs.
std::map<std::string, CaseResult> earlier_cases(const std::string& dir, const Suite& suite) {
  const fs::path path = fs::path(dir) / "results.json";
  std::error_code error;
  if (!fs::exists(path, error)) return {};
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  validation::Report earlier;
  try {
    if (!in) throw std::runtime_error("cannot read it");
    earlier = validation::report_from_json(text.str());
  } catch (const std::exception& e) {
    throw SceneError("--resume: " + path.string() + ": expected the results.json of a report, " +
                     "got a file it cannot read (" + e.what() + ")");
  }
  if (earlier.suite != suite.name)
    throw SceneError("--resume: " + path.string() + ": expected a report of suite \"" + suite.name +
                     "\", got one of \"" + earlier.suite + "\" (write to another folder)");
  std::map<std::string, CaseResult> cases;
  for (CaseResult& c : earlier.cases) cases[c.name] = std::move(c);
  return cases;
}

}  // namespace

int run_validate(const ValidateArgs& args) {
  const auto run_start = std::chrono::steady_clock::now();
  // 1. The suite, the output folder and gnuplot, before any render.
  Suite suite;
  std::vector<bool> selected;
  try {
    suite =
        args.suite.empty() ? validation::default_suite() : validation::load_suite_file(args.suite);
    selected = select_cases(suite, args.cases);
    validation::narrow_suite(suite, args.methods, args.terms);
    if (args.seas > 1) {
      // The seas of each case, selected as the case was.
      const std::vector<std::size_t> origin = validation::expand_seas(suite, args.seas);
      std::vector<bool> seas_selected;
      for (std::size_t i : origin) seas_selected.push_back(selected[i]);
      selected = std::move(seas_selected);
    }
    if (args.reference_samples > 0) {
      // The terms with the sun take N; those without keep their own cap where it is larger.
      validation::ReferenceSettings& reference = suite.reference;
      if (reference.pixel_samples_without_sun > 0)
        reference.pixel_samples_without_sun =
            std::max(reference.pixel_samples_without_sun, args.reference_samples);
      reference.pixel_samples = args.reference_samples;
    }
    if (args.reference_sun_max_cells > 0.0) {
      if (args.reference_sun_max_cells < suite.reference.sun_cells_per_wavelength)
        throw SceneError("--reference-sun-max-cells-per-wavelength: expected at least the "
                         "suite's reference.sun_cells_per_wavelength (" +
                         format_number(suite.reference.sun_cells_per_wavelength) + "), got " +
                         format_number(args.reference_sun_max_cells));
      suite.reference.sun_max_cells_per_wavelength = args.reference_sun_max_cells;
    }
    if (args.reference_sun_cells > 0)
      suite.reference.sun_normal_samples = args.reference_sun_cells * args.reference_sun_cells;
  } catch (const SceneError& error) {
    print_error(error.what());
    return kExitInvalidInput;
  }
  std::error_code error;
  if (fs::exists(args.dir, error) && !fs::is_directory(args.dir, error)) {
    print_error("-o " + args.dir + ": expected a folder, got a file");
    return kExitInvalidInput;
  }
  std::map<std::string, CaseResult> earlier;
  if (args.resume) {
    try {
      earlier = earlier_cases(args.dir, suite);
    } catch (const SceneError& e) {
      print_error(e.what());
      return kExitInvalidInput;
    }
  }
  try {
    validation::find_gnuplot();
  } catch (const validation::ReportError& e) {
    print_error(e.what());
    return kExitRuntimeFailure;
  }
  fs::create_directories(fs::path(args.dir) / "images", error);
  if (error) {
    print_error("-o " + args.dir + ": cannot create the folder (" + error.message() + ")");
    return kExitInvalidInput;
  }

  // 2. Every case: run, or with --resume kept from the earlier report where it was run with the
  // same inputs (case_fingerprint), ended as it expected and its images are still there. The report
  // is rewritten after each case, so that a run cut short leaves the cases it finished (and
  // --resume goes on).
  std::unique_ptr<GlContext> context = open_context(args.backend);
  validation::Report report;
  report.suite = suite.name;
  report.description = suite.description;
  report.source = suite.source;
  report.backend = std::string(backend_name(context->backend()));
  const GlInfo gl_info = query_gl_info();
  report.renderer = gl_info.renderer;
  report.gl_version = gl_info.version;
  report.context = context->description();
  report.version = THALASSA_VERSION_STRING;
  report.horizon = suite.horizon;
  report.timing = suite.timing;
  report.reference = suite.reference;
  report.suite_cases = static_cast<int>(suite.cases.size());
  const std::string environment =
      "thalassa " + report.version + ", " + report.backend + ", " + report.renderer;
  // Per case: its fingerprint, and the earlier run kept (null: render it, or leave it out).
  std::vector<std::string> fingerprints;
  std::vector<const CaseResult*> kept;
  int steps = 0;
  for (std::size_t i = 0; i < suite.cases.size(); ++i) {
    const SuiteCase& c = suite.cases[i];
    fingerprints.push_back(validation::case_fingerprint(suite, c, environment));
    const auto found = earlier.find(c.name);
    // A case that did not end as it expected (a run-time failure: a shader that did not build,
    // a driver error) is rendered again: its inputs may be the same, its result is not one.
    const bool keep = found != earlier.end() && found->second.fingerprint == fingerprints.back() &&
                      found->second.passed() && images_present(found->second, args.dir);
    kept.push_back(keep ? &found->second : nullptr);
    if (selected[i])
      steps += keep ? 1 + retime_count(suite, found->second) : render_count(suite, c);
  }
  ProgressBar bar(steps, "renders");
  CaseRunner runner(suite, *context, args.dir, bar, !args.no_exr);
  // Per case, in the suite's order: its result once known. The kept ones are known from the
  // start, so that every report written holds them all: neither a run cut short nor one whose
  // --case comes earlier in the suite than the kept ones loses any (until stop 23 a report was
  // written with the cases up to the one just run, and the kept ones after it were dropped).
  std::vector<std::optional<CaseResult>> results(suite.cases.size());
  std::vector<int> exrs_gone(suite.cases.size(), 0);
  for (std::size_t i = 0; i < suite.cases.size(); ++i)
    if (kept[i]) {
      results[i] = *kept[i];
      exrs_gone[i] = drop_missing_exrs(*results[i], args.dir);
    }
  const auto write = [&]() {
    report.cases.clear();
    for (const std::optional<CaseResult>& r : results)
      if (r) report.cases.push_back(*r);
    validation::write_report(report, args.dir);
  };
  int failed = 0, run = 0;
  // --time-limit: the longest case rendered so far (s), and the first case not begun for it.
  double longest_case = 0.0;
  std::string stopped_before;
  for (std::size_t i = 0; i < suite.cases.size(); ++i) {
    const SuiteCase& c = suite.cases[i];
    if (!selected[i]) continue;
    if (!kept[i] && args.time_limit > 0.0 &&
        seconds_since(run_start) + longest_case > args.time_limit) {
      stopped_before = c.name;
      break;
    }
    const auto case_start = std::chrono::steady_clock::now();
    if (kept[i]) {
      bar.skipped(c.name, exrs_gone[i] > 0 ? "kept from the earlier run (--resume), without the " +
                                                 std::to_string(exrs_gone[i]) +
                                                 " EXR images gone from the folder"
                                           : std::string("kept from the earlier run (--resume)"));
      // One timed at other settings than the suite's is timed again (its images are kept).
      if (retime_count(suite, *kept[i]) == 0) continue;
      runner.retime(c, *results[i]);
    } else {
      results[i] = runner.run(c);
      results[i]->fingerprint = fingerprints[i];
      results[i]->sea_of = c.sea_of;
      results[i]->sea = c.sea;
      results[i]->gl_version = report.gl_version;
      longest_case = std::max(longest_case, seconds_since(case_start));
    }
    ++run;
    if (!results[i]->passed()) {
      ++failed;
      print_error("case " + c.name + ": expected exit status " + std::to_string(c.expected_exit) +
                  ", got " + std::to_string(results[i]->exit_status) +
                  (results[i]->message.empty() ? "" : " (" + results[i]->message + ")"));
    }
    // 3. The report, so far.
    try {
      write();
    } catch (const validation::ReportError& e) {
      bar.finish();
      print_error(e.what());
      return kExitRuntimeFailure;
    }
  }
  bar.finish();
  if (run == 0) {
    // Nothing rendered (every selected case kept): the report is still written, so that it
    // holds what this run selected.
    try {
      write();
    } catch (const validation::ReportError& e) {
      print_error(e.what());
      return kExitRuntimeFailure;
    }
  }
  const auto chosen = std::count(selected.begin(), selected.end(), true);
  if (!stopped_before.empty())
    std::fprintf(stderr,
                 "thalassa: --time-limit %g s: stopped before case %s after %.0f s (the longest "
                 "case took %.0f s); --resume goes on from there\n",
                 args.time_limit, stopped_before.c_str(), seconds_since(run_start), longest_case);
  std::fprintf(stderr, "thalassa: %ld cases, %d not as expected; report in %s/index.html\n",
               static_cast<long>(chosen), failed, args.dir.c_str());
  return failed == 0 ? kExitOk : kExitRuntimeFailure;
}

}  // namespace thalassa::cli
