// thalassa — the validation report (issue 6, point 4): every number of a suite's run as CSV and
// JSON, per-row radiance plots like fig. 10 of Bruneton et al. 2010, an error-against-frame-time
// plot per case, the near-horizon curves of Tessendorf et al. 2023, and an index.html that shows
// the images, plots and tables together (relative links). docs/validation.md lists the files.
//
// Plots are PNGs drawn by gnuplot (Debian: gnuplot-nox, pngcairo terminal), run as a
// subprocess on a data file and a script written beside each plot (so that a plot can be
// redrawn by hand: cd DIR/plots && gnuplot NAME.gp). A missing gnuplot is a ReportError
// (exit status 1), never a silent skip.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "thalassa/validation/metrics.hpp"
#include "thalassa/validation/suite.hpp"

namespace thalassa::validation {

// Writing the report failed at run time (gnuplot missing or failing, a file not writable).
class ReportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One light term of one method on one case.
struct TermResult {
  std::string term;       // one of kTerms ("sun", "sky", "sea", "air", "all")
  double frame_ms = 0.0;  // the frame's time, ms (RenderStats::frame_ms: median GPU time)
  // Samples per pixel of the frame (RenderStats::samples): the reference's after its doublings,
  // 1 for the other methods; 0 when not known (a report written before stop 16).
  int samples = 0;
  std::string exr;      // the image, relative to the report's folder ("" when not written)
  std::string png;      // its tone-mapped PNG, relative to the report's folder
  TermMetrics metrics;  // against the case's reference (compare_images)
  // Over the suite's flicker frames, when this term is one of FlickerSettings::terms.
  std::optional<double> flicker;         // validation::flicker of this method's frames
  std::optional<double> temporal_error;  // validation::temporal_error against the reference's
  // What the term cost `thalassa validate`, wall-clock s: its renders' set-up (tables loaded, sky
  // map drawn), every frame with the host's waits and read-backs between them (a reference's
  // samples one at a time), writing its images and comparing them; frame_ms is the frames' GPU
  // time alone. None in a report written before stop 28.
  std::optional<double> seconds;
};

// One method (or variant) on one case.
struct MethodResult {
  std::string name;    // SuiteMethod::name
  std::string method;  // SuiteMethod::method
  bool plain = true;   // SuiteMethod::plain(): on the per-row plots
  // The reference its terms are measured against: "" the case's, else the name of the variant's
  // own reference ("reference_" + name, SuiteMethod::own_reference), itself a method of the case
  // (whose own `reference` is its name: it is measured against itself).
  std::string reference;
  std::vector<TermResult> terms;  // in the suite's term order
  // Its frame time (ms) at the case's TimingSettings (every light term, the median of its
  // frames); none for the references, or when the suite times the images themselves.
  std::optional<double> timing_ms;
  // The reference only, with ReferenceSettings::check_convergence: per term, the largest
  // |row total at twice the samples / row total - 1| (max_row_deviation).
  std::vector<std::pair<std::string, double>> convergence;
  // The reference only, per term with the scattered sun (ReferenceSettings::sun): the largest
  // change of a row's total sun from a lattice of half the cells
  // (RenderStats::sun_lattice_row_change), the sun's own convergence test.
  std::vector<std::pair<std::string, double>> lattice_convergence;
  // With it: the cells per shortest wavelength its lattice was drawn with, after its doublings
  // (RenderStats::sun_lattice_cells_per_wavelength; ReferenceSettings::
  // sun_max_cells_per_wavelength). Empty in reports before stop 25.
  std::vector<std::pair<std::string, double>> lattice_cells_per_wavelength;
  // The reference only, per term: the relative uncertainty of each image row's total (top row
  // first), from both tests (reference_row_uncertainty: a row a test did not count, a row of sky
  // among them, takes that test's largest change; the report reads the rows it compares).
  // Fig. 10's claim and the per-row plots use it; a report written before stop 23 has none,
  // and its rows take the largest changes above instead.
  std::vector<std::pair<std::string, std::vector<double>>> row_uncertainty;
  // The reference only, per term with the sun: the image rows of the sea (rows with a pixel of
  // the sea mask) where its sun resolved every wave (RenderStats::resolved_rows >=
  // kResolvedRowFraction); the other methods are compared with it on those rows only, for that
  // term. Before stop 22 the rows of sky alone were counted too.
  std::vector<std::pair<std::string, int>> resolved_rows;
  // SuiteMethod::supersample: drawn at this many pixels per reference pixel along each axis, and
  // timed at this multiple of the case's TimingSettings (1 in reports before stop 53).
  int supersample = 1;
};

// A row counts as resolved by the reference's sun when at least this fraction of it is.
inline constexpr double kResolvedRowFraction = 0.99;

struct CaseResult {
  std::string name;
  std::string description;
  std::vector<SceneOverride> set;  // the case's overrides (for the table)
  int expected_exit = 0;
  std::string expected_error;
  // What the case ended with: exit status and its one-line message ("" when it rendered).
  int exit_status = 0;
  std::string message;
  double camera_height = 0.0;         // m, for the tables
  std::vector<MethodResult> methods;  // empty for a case that was not rendered
  // What its methods' timing_ms were measured at (disabled: not timed apart).
  TimingSettings timing;
  // case_fingerprint of the inputs it was run with ("" in a report written before stop 22):
  // what `thalassa validate --resume` compares to keep it.
  std::string fingerprint;
  // The case's run, wall-clock s: its terms (TermResult::seconds) and its methods' timing. None
  // for a case refused before rendering, or in a report written before stop 28.
  std::optional<double> seconds;
  // One of the seas of a case of the suite (SuiteCase::sea_of, sea; thalassa validate --seas):
  // that case's name and which sea; "" and 0 otherwise.
  std::string sea_of;
  int sea = 0;
  // GL_VERSION (with the driver's version) of the run that rendered it: a case kept by --resume
  // keeps its own, which may differ from the report's ("" in a report written before stop 43).
  std::string gl_version;
  // The case passed: it ended as expected (expected_exit, and expected_error in the message).
  bool passed() const;
};

struct Report {
  std::string suite;        // Suite::name
  std::string description;  // Suite::description
  std::string source;       // the suite file
  std::string backend;      // RenderStats::backend
  std::string renderer;     // RenderStats::renderer (GL_RENDERER)
  std::string gl_version;   // RenderStats::gl_version of this run ("" before stop 43)
  std::string context;      // RenderStats::context of this run ("" before stop 43)
  std::string version;      // thalassa's version
  HorizonBandOptions horizon;
  TimingSettings timing;        // Suite::timing, as run
  ReferenceSettings reference;  // Suite::reference, as run (thalassa validate --reference-samples)
  std::vector<CaseResult> cases;
  // The cases in the suite file: more than cases.size() when `thalassa validate --case` ran
  // some of them (0: not known, taken as cases.size()).
  int suite_cases = 0;
};

// Over the cases of a report, one line per method (or variant) and term, in the order of the
// cases' methods and terms: how the method does across the suite. The reference itself and the
// variants' own references have no line (they are what is measured against).
struct SummaryLine {
  std::string method;  // MethodResult::name
  std::string term;
  int cases = 0;  // cases where the term was measured against a reference
  // Over those cases (NaN where none is defined): the median and the largest relative L1 error
  // of the luminance over the sea and of the row totals (TermMetrics::row_error), and the median
  // frame time (ms; timed apart where the case was, MethodResult::timing_ms).
  double median_relative_l1 = 0.0, worst_relative_l1 = 0.0;
  double median_row_error = 0.0, worst_row_error = 0.0;
  double median_frame_ms = 0.0;
};
std::vector<SummaryLine> summarize(const Report& report);

// Issue 6, point 1: the reference is converged when doubling its samples changes each image
// row's total by less than this (relative); for its scattered sun, doubling its lattice's cells.
inline constexpr double kConvergenceTolerance = 0.01;

// Whether each reference met it: one line per reference (the case's, and the variants' own) and
// term, in the order of the cases and terms. A term with the sun counts the lattice too (one per
// reference, measured on its first sun term, MethodResult::lattice_convergence).
struct ConvergenceLine {
  std::string case_name;
  std::string reference;  // MethodResult::name
  std::string term;
  int samples = 0;  // per pixel, as run
  // The last doubling of the samples (NaN: not checked, ReferenceSettings::check_convergence)
  // and, with the sun, the lattice against half its cells (NaN: not measured, or no row lit
  // and resolved) and its cells per shortest wavelength (NaN: not reported, before stop 25).
  double sample_change = std::numeric_limits<double>::quiet_NaN();
  double lattice_change = std::numeric_limits<double>::quiet_NaN();
  double lattice_cells_per_wavelength = std::numeric_limits<double>::quiet_NaN();
  bool with_sun = false;
  // "yes": every test it has is below kConvergenceTolerance; "no": one is not; "undefined":
  // the samples were not checked, or with the sun the lattice measured no row.
  std::string converged() const;
};
std::vector<ConvergenceLine> reference_convergence(const Report& report);

// Fig. 10's claim (Bruneton et al. 2010; issue 6, point 5): at every distance beyond
// kClaimMinHeight the full method is closer to the reference than the basic one. Per case with
// the camera at or above that height and per term: the row error (TermMetrics::row_error, the
// energy per distance) of `full` and of `basic`, and the reference's own uncertainty, against
// which their difference is judged. Cases without both methods measured are left out.
inline constexpr double kClaimMinHeight = 100.0;  // m, the "beyond 100 m"
struct ClaimLine {
  std::string case_name;
  double camera_height = 0.0;  // m
  std::string term;
  double full = 0.0, basic = 0.0;  // row errors (NaN: no row defined)
  // What the case's reference's own error can do to the difference of the two row errors: the
  // most it moves toward the other order over every reference whose rows are within their
  // measured uncertainty (row_error_difference_bound of the reference's row_uncertainty; for
  // a report before stop 23, every row within the largest change of its tests). A difference
  // within it is not resolved by the reference. NaN: not measured (taken as 0), or the
  // reference is black.
  double uncertainty = std::numeric_limits<double>::quiet_NaN();
  // The smaller difference the reference resolves: the uncertainty, 0 where not measured.
  double resolved() const { return std::isfinite(uncertainty) ? uncertainty : 0.0; }
  // full < basic by more than the reference's uncertainty; false where either is undefined.
  bool holds() const { return full < basic - resolved(); }
  // The two drew the same rows: where the foreground's pixels already leave every wave
  // unresolved, basic's one slope variance is full's everywhere and the images are the same.
  bool same() const { return full == basic; }
  // They differ, by no more than the reference's uncertainty.
  bool indistinct() const {
    return std::isfinite(full) && std::isfinite(basic) && !same() &&
           std::abs(full - basic) <= resolved();
  }
  // "closer", "indistinct", "same", "farther" or "undefined" (either is).
  std::string verdict() const;
};
std::vector<ClaimLine> fig10_claim(const Report& report);

// Over the seas of a case (thalassa validate --seas, CaseResult::sea_of), one line per method
// or variant measured against a reference and per term, in the order first seen: fig. 10's
// row totals summed over the seas, and the near-horizon band pooled over them. A row counts where
// every sea compares it (its row totals defined in each, whether the reference lit it or not: a row
// with no glint in one sea and some in another is what the sum is for); the row error
// (validation::row_error's sum |T_method - T_reference| / sum T_reference) is that of the method's
// sums against its reference's. The reference draws one sea's glints and the methods the expected
// glint of their BRDFs: a row of few glints is a realization's luck in one sea, and the sum over
// seas is what measures the method there (docs/validation.md, "One sea's glints and the BRDF's
// expected glint").
struct SeaLine {
  std::string case_name;  // the case the seas are of (CaseResult::sea_of)
  std::string method;     // MethodResult::name
  std::string term;
  int seas = 0;  // the seas where the method's term was measured
  int rows = 0;  // the rows every one of them compares
  double row_error = std::numeric_limits<double>::quiet_NaN();  // of the sums (NaN: no row)
  // The basic method's row error over the same seas and rows (NaN: the case has no basic, or
  // no row), and in how many of the seas alone this method's row error, by the same measure on
  // the rows that sea compares, is the smaller (-1: no basic, or this is the basic method).
  double basic_row_error = std::numeric_limits<double>::quiet_NaN();
  int closer_alone = -1;
  // Each image row's luminance total (W m^-2 sr^-1 nm^-1) summed over the seas, the method's and
  // its reference's, row 0 at the top; NaN on the rows that do not count (not compared by every
  // sea, or, beside the basic method, by basic's). Fig. 10's right column over the seas
  // (plots/<case>_seas_<term>_rows.png).
  std::vector<double> method_rows, reference_rows;
  // Paper 004's near-horizon metric over the same seas: their bands pooled, per bin the pixels
  // of every sea as one set (pool_horizon_bands; the seas whose band has the first sea's bins),
  // so that its mean is the method's bias against the reference averaged over the seas' luck and
  // its standard deviation holds the spread within and between seas
  // (plots/<case>_seas_<term>_horizon.png, seas_horizon.csv). No bins where no sea has a band.
  HorizonBand horizon;
};
std::vector<SeaLine> summarize_seas(const Report& report);

// A reference's relative uncertainty of each of its `rows` row totals for `term`: its
// MethodResult::row_uncertainty, or in a report without it (before stop 23) the largest change
// of its convergence tests for the term in every row; NaN where not measured (or no reference).
std::vector<double> reference_rows_uncertainty(const MethodResult* reference,
                                               const std::string& term, std::size_t rows);

struct ReportOptions {
  std::string gnuplot;                      // the gnuplot program; empty: "gnuplot" found on PATH
  int plot_width = 800, plot_height = 500;  // pixels of each plot
};

// The gnuplot program that write_report will run (options.gnuplot, or "gnuplot" on PATH); a
// ReportError saying how to install it when there is none. The validate command calls it before
// rendering anything, so that a missing gnuplot costs no render.
std::string find_gnuplot(const ReportOptions& options = {});

// Writes the report into `dir` (created if missing), every file atomically:
//   results.json, metrics.csv, rows.csv, horizon.csv, cases.csv, index.html,
//   plots/<case>_<term>_rows.{dat,gp,png}      row totals and ratios (fig. 10)
//   plots/<case>_error_time.{dat,gp,png}       relative L1 error against frame time
//   plots/<case>_<term>_horizon.{dat,gp,png}   near-horizon mean and std (paper 004, fig. 5)
//   summary.csv, claim.csv                     summarize and fig10_claim, over the cases
//   convergence.csv                            reference_convergence
//   seas.csv                                   summarize_seas (its header alone without seas)
//   seas_horizon.csv                           its pooled horizon bands, bin by bin
//   plots/<case>_seas_<term>_rows.{dat,gp,png} the rows summed over a case's seas (fig. 10)
//   plots/<case>_seas_<term>_horizon.{dat,gp,png}  the horizon band pooled over its seas
//   plots/summary_<term>_height.{dat,gp,png}   row error against camera height
// Returns the paths written, relative to `dir`. Throws ReportError.
std::vector<std::string> write_report(const Report& report, const std::string& dir,
                                      const ReportOptions& options = {});

// The JSON text of results.json (the report's every number; NaN, an undefined ratio or error,
// is null), and its reading back, for tools and tests.
std::string report_json(const Report& report);
Report report_from_json(const std::string& json_text);

}  // namespace thalassa::validation
