// thalassa validate [SUITE.json] -o DIR (issue 6, point 4): renders each case of a suite with
// each of its methods and light terms and measures them against the case's reference
// (validation/runner.hpp), keeps the cases of an earlier run (--resume), and writes the report
// (validation/report.hpp). Cases that expect
// exit status 2 are checked to be refused with their message; the others to render finite
// images. The command's own exit status: 0 when every case ended as it expected, 1 otherwise
// (or at run time), 2 for a bad suite or bad options.
#include <fnmatch.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
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
using validation::TermResult;

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
      steps += keep ? 1 + validation::retime_count(suite, found->second)
                    : validation::render_count(suite, c);
  }
  ProgressBar bar(steps, "renders");
  validation::CaseRunOptions run_options;
  run_options.dir = args.dir;
  run_options.write_exr = !args.no_exr;
  // One sky provider for the whole run, in this context: the cases' sky is the same atmosphere.
  run_options.sky_cache = make_sky_provider_cache();
  run_options.progress.done = [&](const std::string& item, const std::string& detail,
                                  double seconds) { bar.done(item, detail, seconds); };
  run_options.progress.skipped = [&](const std::string& item, const std::string& why) {
    bar.skipped(item, why);
  };
  run_options.progress.note = [&](const std::string& message) { bar.note(message); };
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
      if (validation::retime_count(suite, *kept[i]) == 0) continue;
      validation::retime_case(suite, *context, c, *results[i], run_options);
    } else {
      results[i] = validation::run_case(suite, *context, c, run_options);
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
