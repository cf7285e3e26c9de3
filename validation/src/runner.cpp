// The cases of a validation suite rendered, written and measured (runner.hpp).
#include "thalassa/validation/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "thalassa/engine/image.hpp"
#include "thalassa/ocean/method.hpp"
#include "thalassa/ocean/scattered_sun_cache.hpp"
#include "thalassa/planet/renderer.hpp"
#include "thalassa/validation/metrics.hpp"

namespace thalassa::validation {
namespace {

namespace fs = std::filesystem;

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
  // frames with each sea pixel's sea alone (reference_for_comparison), or for a supersampled
  // method its sea pixels' sea alone (supersampled_for_comparison).
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
  CaseRunner(const Suite& suite, GlContext& context, const CaseRunOptions& options)
      : suite_(suite),
        context_(context),
        options_(options),
        sky_cache_(options.sky_cache ? options.sky_cache : make_sky_provider_cache()) {}

  CaseResult run(const SuiteCase& c) {
    CaseResult result;
    result.name = c.name;
    result.description = c.description;
    result.set = c.set;
    result.expected_exit = c.expected_exit;
    result.expected_error = c.expected_error;
    Scene scene;
    try {
      scene = case_scene(suite_, c);
      check_drawable(scene, "case " + c.name);
    } catch (const SceneError& error) {
      result.exit_status = kCaseInvalidInput;
      result.message = error.what();
      skipped(c.name, "refused: " + result.message);
      return result;
    }
    result.camera_height = scene.camera.height;
    const auto start = std::chrono::steady_clock::now();
    try {
      render_case(c, scene, result);
      time_methods(c, result);
    } catch (const SceneError& error) {
      result.exit_status = kCaseInvalidInput;
      result.message = error.what();
    } catch (const std::exception& error) {
      result.exit_status = kCaseRuntimeFailure;
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
      result.exit_status = kCaseRuntimeFailure;
      result.message = std::string("timing: ") + error.what();
    }
  }

 private:
  // Each method of the case other than the references, timed apart (Suite::timing): its scene
  // at the timing size with every light term, `frames` frames, the median frame time.
  void time_methods(const SuiteCase& c, CaseResult& result) {
    if (!suite_.timing.enabled()) return;
    const LightTerms every;  // every term, the default
    for (MethodResult& m : result.methods) {
      if (m.method == "reference") continue;
      const SuiteMethod* method = suite_.find_method(m.name);
      if (!method) continue;
      Scene scene = case_scene(suite_, c, method);
      // A supersampled method is timed at its own multiple of the timing size: its cost is its
      // pixels'.
      scene.image.width = suite_.timing.width * method->supersample;
      scene.image.height = suite_.timing.height * method->supersample;
      RendererOptions options;
      options.sky_cache = sky_cache_;
      options.method = *ocean::parse_method(method->method);
      options.terms = every;
      const auto start = std::chrono::steady_clock::now();
      Renderer renderer(context_, scene, options);
      // Warm-up frames, untimed, for at least kTimingWarmup: a GPU's clocks rise from idle over
      // tens to hundreds of ms, longer than five frames of a few ms (on the H200 the first
      // method timed in stop 26, basic, read 36.8 ms, and 6.4 on the next case). On llvmpipe
      // one frame.
      const auto warm_start = std::chrono::steady_clock::now();
      for (int k = 0;
           k < kTimingWarmupFrames && std::chrono::steady_clock::now() - warm_start < kTimingWarmup;
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
      done(c.name, detail, seconds);
    }
    result.timing = suite_.timing;
  }

  void render_case(const SuiteCase& c, const Scene& base_scene, CaseResult& result) {
    const ViewGeometry view(base_scene);
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
      const Scene scene = case_scene(suite_, c, method);
      // A supersampled method's view at its own size, whose sea pixels are those compared at
      // the sea pixels of the case's (supersampled_for_comparison).
      std::optional<ViewGeometry> supersampled_view;
      if (method->supersample > 1) supersampled_view.emplace(scene);
      MethodResult m;
      m.name = method->name;
      m.method = method->method;
      m.plain = method->plain();
      m.supersample = method->supersample;
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
        if (const std::string problem = parse_light_terms(terms_option(term), terms);
            !problem.empty())
          throw SceneError(suite_.source + ": terms: " + term + ": " + problem);
        const bool measure_lattice = job.is_reference && terms.sun && !lattice_measured;
        Rendered rendered =
            render_term(c, *method, scene, term, terms, measure_lattice, lattice, sun_cache);
        if (supersampled_view)
          for (Image& compared : rendered.compared)
            compared = supersampled_for_comparison(compared, method->supersample,
                                                   supersampled_view->sea_mask(), view.sea_mask());
        if (job.is_reference)
          for (std::size_t k = 0; k < rendered.compared.size(); ++k)
            rendered.compared[k] =
                reference_for_comparison(rendered.frames[k], rendered.compared[k], view.sea_mask());
        for (std::size_t k = 0; k < rendered.frames.size(); ++k)
          if (const std::string& problem = rendered.problems[k];
              !problem.empty() && result.exit_status != kCaseRuntimeFailure) {
            result.exit_status = kCaseRuntimeFailure;
            result.message =
                method->name + ", " + term + ", frame " + std::to_string(k) + ": " + problem;
          }
        TermResult t;
        t.term = term;
        t.frame_ms = rendered.stats.frame_ms;
        t.samples = rendered.stats.samples;
        const std::string stem = "images/" + c.name + "_" + method->name + "_" + term;
        t.png = stem + ".png";
        if (options_.write_exr) {
          t.exr = stem + ".exr";
          write_exr((fs::path(options_.dir) / t.exr).string(), rendered.frames.front(),
                    ExrPixelType::Float,
                    {{"thalassa:case", c.name},
                     {"thalassa:method", method->method},
                     {"thalassa:terms", terms_option(term)}});
        }
        write_png((fs::path(options_.dir) / t.png).string(), rendered.frames.front(),
                  scene.image.exposure);
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
          const std::vector<double> u = reference_row_uncertainty(
              suite_.reference.check_convergence ? rendered.stats.sample_row_changes : no_test,
              terms.sun ? lattice_rows : no_test, view.height());
          m.row_uncertainty.emplace_back(term, u);  // all NaN: neither test measured a row
          // The rows of the sea its sun resolves (a row of sky alone counts as resolved in
          // RenderStats::resolved_rows, and is never compared).
          const std::vector<double>& rows = rendered.stats.resolved_rows;
          if (!rows.empty()) {
            const PixelMask resolved =
                resolved_rows_mask(view.sea_mask(), rows, kResolvedRowFraction);
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
          const PixelMask compared = resolved_rows_mask(
              view.sea_mask(), ref->second.stats.resolved_rows, kResolvedRowFraction);
          const std::vector<Image>& against = ref->second.compared;
          t.metrics =
              compare_images(rendered.compared.front(), against.front(), view, suite_.horizon,
                             &compared, png_black_level(scene.image.exposure));
          if (rendered.frames.size() >= 2) {
            t.flicker = flicker(rendered.frames, view.sea_mask());
            // Relative to the reference's changes: undefined where the reference is black.
            if (against.size() == rendered.frames.size())
              t.temporal_error = t.metrics.reference_black
                                     ? std::numeric_limits<double>::quiet_NaN()
                                     : temporal_error(rendered.compared, against, compared);
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
    options.sky_cache = sky_cache_;
    options.reference.sun_cache = sun_cache;
    options.method = *ocean::parse_method(method.method);
    options.terms = terms;
    const ReferenceSettings& reference = suite_.reference;
    const int most = reference.max_samples(options.terms.sun);
    options.reference.max_samples = most;
    options.reference.min_samples = std::min(options.reference.min_samples, most);
    options.reference.sun_cells = reference.sun_cells();
    options.reference.sun_cells_per_wavelength = reference.sun_cells_per_wavelength;
    options.reference.sun = *parse_reference_sun(reference.sun);  // the suite's parser checked
    options.reference.sun_refine = reference.sun_refine;
    options.reference.grid_cell = reference.grid_cell;
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
      rendered.problems.push_back(nonfinite_report(renderer.image(), renderer));
      // A supersampled method's pixels averaged to the reference's (its scene is drawn at
      // supersample times the case's size: case_scene_builder).
      rendered.frames.push_back(method.supersample > 1
                                    ? box_filter(renderer.image(), method.supersample)
                                    : renderer.image());
      // The reference's sea alone (its pixels merged with image()'s by render_case); a
      // supersampled method's image at its own size (render_case averages it); other methods
      // compare as drawn.
      rendered.compared.push_back(options.method == ocean::OceanMethod::reference
                                      ? renderer.reference_sea_image()
                                  : method.supersample > 1 ? renderer.image()
                                                           : rendered.frames.back());
      if (k == 0) rendered.stats = renderer.stats();
      const double seconds = seconds_since(start);
      char detail[160];
      std::snprintf(detail, sizeof detail, "%s, %s, frame %d: %.0f ms (%d samples%s)",
                    method.name.c_str(), term.c_str(), k, renderer.stats().frame_ms,
                    renderer.stats().samples,
                    renderer.stats().sun_lattice_reused ? ", its sun's lattice kept" : "");
      done(c.name, detail, seconds);
      // What the render worked around (a lattice scattered again, and why), a line of its own.
      for (const std::string& warning : renderer.stats().warnings)
        note(c.name + ": " + method.name + ", " + term + ", frame " + std::to_string(k) +
             ": warning: " + warning);
    }
    return rendered;
  }

  void done(const std::string& case_name, const std::string& detail, double seconds) const {
    if (options_.progress.done) options_.progress.done(case_name, detail, seconds);
  }
  void skipped(const std::string& case_name, const std::string& why) const {
    if (options_.progress.skipped) options_.progress.skipped(case_name, why);
  }
  void note(const std::string& message) const {
    if (options_.progress.note) options_.progress.note(message);
  }

  const Suite& suite_;
  GlContext& context_;
  const CaseRunOptions& options_;
  // The sky provider the case's renders keep between them (its tables uploaded once, its sky map
  // built again only when the sun moves): the caller's, or the case's own.
  std::shared_ptr<SkyProviderCache> sky_cache_;
};

}  // namespace

CaseResult run_case(const Suite& suite, GlContext& context, const SuiteCase& c,
                    const CaseRunOptions& options) {
  return CaseRunner(suite, context, options).run(c);
}

void retime_case(const Suite& suite, GlContext& context, const SuiteCase& c, CaseResult& result,
                 const CaseRunOptions& options) {
  CaseRunner(suite, context, options).retime(c, result);
}

// Per method (and own reference), per term, one frame or the flicker frames; one (skipped) step
// for a case expected to be refused; and each method timed apart.
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

int retime_count(const Suite& suite, const CaseResult& kept) {
  if (!suite.timing.enabled() || kept.methods.empty() || kept.timing == suite.timing) return 0;
  int n = 0;
  for (const MethodResult& m : kept.methods) n += m.method != "reference";
  return n;
}

}  // namespace thalassa::validation
