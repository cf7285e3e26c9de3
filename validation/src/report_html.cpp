// The validation report's index.html (report_detail.hpp).
#include "report_detail.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace thalassa::validation {

namespace detail {

namespace {

// The summary over the cases (summarize), fig. 10's claim (fig10_claim), the lines over the seas
// (summarize_seas) and the plots of the mean row deviation against height.
std::string summary_html(const Report& report, const std::vector<SeaLine>& seas,
                         const std::vector<std::pair<std::string, std::string>>& plots) {
  const std::vector<SummaryLine> lines = summarize(report);
  if (lines.empty()) return "";
  std::string h = "<h2>Over the cases</h2>\n<p>Per method and term, over the " +
                  std::to_string(report.cases.size()) +
                  " cases of this report (<a href=\"summary.csv\">summary.csv</a>): the median "
                  "and the largest relative L1 error of the luminance over the sea, and of its "
                  "row totals (the row error: fig. 10's energy per distance), and the median frame "
                  "time (timed apart where the cases "
                  "were).</p>\n<table><tr><th>method</th><th>term</th><th>cases</th><th>rel. L1, "
                  "median</th><th>rel. L1, largest</th><th>row error, median</th>"
                  "<th>row error, largest</th><th>frame (ms), median</th></tr>\n";
  for (const SummaryLine& s : lines)
    h += "<tr><td class=\"t\">" + html(s.method) + "</td><td class=\"t\">" + html(s.term) +
         "</td><td>" + std::to_string(s.cases) + "</td><td>" + short_number(s.median_relative_l1) +
         "</td><td>" + short_number(s.worst_relative_l1) + "</td><td>" +
         short_number(s.median_row_error) + "</td><td>" + short_number(s.worst_row_error) +
         "</td><td>" + short_number(s.median_frame_ms) + "</td></tr>\n";
  h += "</table>\n";
  const std::vector<ClaimLine> claim = fig10_claim(report);
  if (!claim.empty()) {
    int holds = 0, same = 0, indistinct = 0;
    for (const ClaimLine& l : claim) {
      holds += l.holds() ? 1 : 0;
      same += l.same() ? 1 : 0;
      indistinct += l.indistinct() ? 1 : 0;
    }
    h += "<p>Fig. 10's claim, the full method closer to the reference than the basic one with "
         "the camera at " +
         short_number(kClaimMinHeight) +
         " m or higher, by the row error (<a href=\"claim.csv\">claim.csv</a>): it "
         "holds in " +
         std::to_string(holds) + " of " + std::to_string(claim.size()) + " cases and terms; in " +
         std::to_string(same) +
         " the two drew the same rows (the foreground resolves no wave: basic's one variance is "
         "full's everywhere), in " +
         std::to_string(indistinct) +
         " they differ by no more than the reference's own uncertainty (the most its rows, each "
         "uncertain by the change its convergence tests measured there, could move the "
         "difference toward the other order).</p>\n"
         "<table><tr><th>case</th><th>camera height (m)</th><th>term</th><th>full</th>"
         "<th>basic</th><th>reference's uncertainty</th><th>full</th></tr>\n";
    for (const ClaimLine& l : claim)
      h += "<tr><td class=\"t\"><a href=\"#" + html(l.case_name) + "\">" + html(l.case_name) +
           "</a></td><td>" + short_number(l.camera_height) + "</td><td class=\"t\">" +
           html(l.term) + "</td><td>" + short_number(l.full) + "</td><td>" + short_number(l.basic) +
           "</td><td>" + short_number(l.uncertainty) + "</td><td" +
           (l.verdict() == "farther" ? " class=\"fail\">" : ">") + l.verdict() + "</td></tr>\n";
    h += "</table>\n";
  }
  if (!seas.empty()) {
    h += "<h2>Over the seas</h2>\n<p>Per case drawn over several seas (<code>thalassa validate "
         "--seas</code>; <a href=\"seas.csv\">seas.csv</a>), method and term: each row's total "
         "summed over the seas, the method's and its reference's, on the rows every sea "
         "compares, and the row error of the sums; beside it the basic method's over the same "
         "seas and rows, and in how many seas alone the method's own row error is the smaller. "
         "The reference draws one sea's glints, the methods the expected glint of their BRDFs: "
         "where a row holds few glints, one sea is its luck, and the sum over seas measures the "
         "method. The horizon band (paper 004's metric) pools the seas' pixels, bin by bin "
         "(<a href=\"seas_horizon.csv\">seas_horizon.csv</a>): its mean is the method's bias "
         "over the seas, its standard deviation the spread within and between them.</p>\n"
         "<table><tr><th>case</th><th>method</th><th>term</th><th>seas</th>"
         "<th>rows</th><th>row error</th><th>basic's</th><th>closer alone</th><th>horizon "
         "mean</th><th>horizon std</th></tr>\n";
    for (const SeaLine& l : seas)
      h += "<tr><td class=\"t\">" + html(l.case_name) + "</td><td class=\"t\">" + html(l.method) +
           "</td><td class=\"t\">" + html(l.term) + "</td><td>" + std::to_string(l.seas) +
           "</td><td>" + std::to_string(l.rows) + "</td><td>" + short_number(l.row_error) +
           "</td><td>" + short_number(l.basic_row_error) + "</td><td>" +
           (l.closer_alone < 0 ? std::string()
                               : std::to_string(l.closer_alone) + " of " + std::to_string(l.seas)) +
           "</td><td>" + short_number(l.horizon.mean) + "</td><td>" + short_number(l.horizon.std) +
           "</td></tr>\n";
    h += "</table>\n";
  }
  h += "<p>";
  for (const auto& [title, png] : plots)
    h += "<a href=\"" + html(png) + "\"><img class=\"plot\" src=\"" + html(png) + "\" alt=\"" +
         html(title) + "\" title=\"" + html(title) + "\"></a>\n";
  h += "</p>\n";
  return h;
}

// How many references met issue 6's convergence criterion (reference_convergence), and the ones
// that did not.
std::string convergence_html(const Report& report) {
  const std::vector<ConvergenceLine> lines = reference_convergence(report);
  if (lines.empty()) return {};
  int yes = 0, no = 0, undefined = 0;
  for (const ConvergenceLine& l : lines) {
    const std::string v = l.converged();
    (v == "yes" ? yes : v == "no" ? no : undefined) += 1;
  }
  const std::string percent = short_number(100.0 * kConvergenceTolerance);
  std::string h =
      "<h2>The references' convergence</h2>\n<p>Issue 6 asks that doubling the "
      "reference's samples, and its sun's lattice, change no image row's total by " +
      percent + " % or more (<a href=\"convergence.csv\">convergence.csv</a>). Of " +
      std::to_string(lines.size()) + " references and terms: " + std::to_string(yes) +
      " within it, <span" + (no ? " class=\"fail\"" : "") + ">" + std::to_string(no) +
      " not</span>, " + std::to_string(undefined) +
      " undefined (not checked, or a sun with no row lit and resolved).</p>\n";
  if (no == 0) return h;
  h += "<table><tr><th>case</th><th>reference</th><th>term</th><th>samples</th><th>last "
       "doubling of the samples (%)</th><th>sun's lattice against half its cells (%)</th>"
       "<th>its cells per shortest wavelength</th></tr>\n";
  const auto cell = [&](double change) {
    return std::string(std::isfinite(change) && change >= kConvergenceTolerance
                           ? "<td class=\"fail\">"
                           : "<td>") +
           short_number(100.0 * change) + "</td>";
  };
  for (const ConvergenceLine& l : lines) {
    if (l.converged() != "no") continue;
    h += "<tr><td class=\"t\"><a href=\"#" + html(l.case_name) + "\">" + html(l.case_name) +
         "</a></td><td class=\"t\">" + html(l.reference) + "</td><td class=\"t\">" + html(l.term) +
         "</td><td>" + std::to_string(l.samples) + "</td>" + cell(l.sample_change) +
         (l.with_sun ? cell(l.lattice_change) : "<td></td>") + "<td>" +
         short_number(l.lattice_cells_per_wavelength) + "</td></tr>\n";
  }
  return h + "</table>\n";
}

}  // namespace

std::string index_html(const Report& report, const std::vector<SeaLine>& seas,
                       const std::vector<std::vector<std::pair<std::string, std::string>>>& plots,
                       const std::vector<std::pair<std::string, std::string>>& summary_plots) {
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>thalassa "
      "validate: " +
      html(report.suite) +
      "</title>\n<style>body{font-family:sans-serif;margin:1em 2em}table{border-collapse:"
      "collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 6px;text-align:right}"
      "th{background:#eee}td.t{text-align:left}img.thumb{width:240px}img.plot{max-width:"
      "48%}.fail{color:#b00;font-weight:bold}</style>\n</head><body>\n";
  h += "<h1>Suite " + html(report.suite) + "</h1>\n<p>" + html(report.description) + "</p>\n";
  h += "<p>Suite file: " + html(report.source) + "; thalassa " + html(report.version) +
       "; backend " + html(report.backend) + "; renderer " + html(report.renderer) +
       (report.gl_version.empty() ? std::string() : ", OpenGL " + html(report.gl_version)) +
       (report.context.empty() ? std::string() : "; context " + html(report.context)) + ".</p>\n";
  // Cases kept (--resume) from a run under another driver: their frame times are that driver's.
  std::map<std::string, std::vector<std::string>> other_drivers;
  for (const CaseResult& c : report.cases)
    if (!c.gl_version.empty() && c.gl_version != report.gl_version)
      other_drivers[c.gl_version].push_back(c.name);
  for (const auto& [version, names] : other_drivers) {
    h += "<p>Rendered under OpenGL " + html(version) + ":";
    for (const std::string& name : names) h += " " + html(name);
    h += ".</p>\n";
  }
  h += "<p>Frame times: " +
       (report.timing.enabled()
            ? "each method other than the reference timed apart at " + timing_text(report.timing) +
                  " with every term, the median of " + std::to_string(report.timing.frames) +
                  " frames (the error against time plots use it); the reference's at the "
                  "images' size"
            : std::string("the images' own (the suite times nothing apart)")) +
       ".</p>\n";
  const int without_sun = report.reference.pixel_samples_without_sun;
  h += "<p>Reference: up to " + std::to_string(report.reference.pixel_samples) +
       " samples per pixel" +
       (without_sun > 0 ? " (" + std::to_string(without_sun) + " for the terms without the sun)"
                        : std::string()) +
       ", doubling from 16 while a row's total over the sea changes by 1 % or more; its sun " +
       html(report.reference.sun) + " in cells of at most 1/" +
       short_number(report.reference.sun_cells_per_wavelength) +
       " of the shortest wavelength, at most " + std::to_string(report.reference.sun_cells()) +
       "<sup>2</sup> per pixel" +
       (report.reference.sun_refine > 1
            ? ", those whose slopes come near the mirror slope cut into " +
                  std::to_string(report.reference.sun_refine) + " x " +
                  std::to_string(report.reference.sun_refine) + " subcells"
            : std::string()) +
       (report.reference.sun_max_cells_per_wavelength > report.reference.sun_cells_per_wavelength
            ? "; while its lattice moves a row by 1 % or more against half its cells, it doubles "
              "them (per wavelength times sqrt 2, per pixel times 2) up to 1/" +
                  short_number(report.reference.sun_max_cells_per_wavelength) +
                  " of the shortest wavelength"
            : std::string()) +
       "; every wave rasterised on a grid of " + short_number(report.reference.grid_cell) +
       "-pixel cells.</p>\n";
  if (report.suite_cases > static_cast<int>(report.cases.size()))
    h += "<p class=\"fail\">A part of the suite: " + std::to_string(report.cases.size()) +
         " of its " + std::to_string(report.suite_cases) +
         " cases were run (thalassa validate --case).</p>\n";
  h += "<p>Every number: <a href=\"results.json\">results.json</a>, <a "
       "href=\"metrics.csv\">metrics.csv</a>, <a href=\"rows.csv\">rows.csv</a>, <a "
       "href=\"horizon.csv\">horizon.csv</a>, <a href=\"cases.csv\">cases.csv</a>, <a "
       "href=\"summary.csv\">summary.csv</a>, <a href=\"claim.csv\">claim.csv</a>. Definitions: "
       "docs/validation.md. Errors are over the pixels that see the sea; the horizon band is 0 "
       "to " +
       short_number(report.horizon.depth_deg) + " degrees below the horizon in bins of " +
       short_number(report.horizon.bin_deg) + " degrees.</p>\n";
  // Summary.
  h += "<h2>Cases</h2>\n<table><tr><th>case</th><th>camera height (m)</th><th>overrides</th>"
       "<th>expected</th><th>status</th><th>passed</th><th>run (s)</th></tr>\n";
  for (const CaseResult& c : report.cases)
    h += "<tr><td class=\"t\"><a href=\"#" + html(c.name) + "\">" + html(c.name) + "</a></td><td>" +
         short_number(c.camera_height) + "</td><td class=\"t\">" + html(overrides_text(c.set)) +
         "</td><td>" + std::to_string(c.expected_exit) + "</td><td>" +
         std::to_string(c.exit_status) + "</td><td" + (c.passed() ? ">yes" : " class=\"fail\">no") +
         "</td><td>" + short_number(c.seconds.value_or(kNaN)) + "</td></tr>\n";
  h += "</table>\n";
  h += convergence_html(report);
  h += summary_html(report, seas, summary_plots);
  for (std::size_t ci = 0; ci < report.cases.size(); ++ci) {
    const CaseResult& c = report.cases[ci];
    const MethodResult* ref = reference_of(c);
    h += "<h2 id=\"" + html(c.name) + "\">" + html(c.name) + "</h2>\n<p>" + html(c.description) +
         "</p>\n<p>Overrides: <code>" + html(overrides_text(c.set)) + "</code></p>\n";
    if (!c.message.empty())
      h += "<p" + std::string(c.passed() ? "" : " class=\"fail\"") + ">Exit status " +
           std::to_string(c.exit_status) + ": " + html(c.message) + "</p>\n";
    if (c.methods.empty()) continue;
    const std::vector<std::string> terms = case_terms(c);
    // Images: a row per method, a column per term.
    h += "<table><tr><th>method</th>";
    for (const std::string& t : terms) h += "<th>" + html(t) + "</th>";
    h += "</tr>\n";
    for (const MethodResult& m : c.methods) {
      h += "<tr><td class=\"t\">" + html(m.name) + "</td>";
      for (const std::string& term : terms) {
        const TermResult* t = term_of(m, term);
        h += "<td>";
        if (t && !t->png.empty()) {
          const std::string img = "<img class=\"thumb\" src=\"" + html(t->png) + "\" alt=\"" +
                                  html(m.name + " " + term) + "\">";
          h += t->exr.empty() ? img : "<a href=\"" + html(t->exr) + "\">" + img + "</a>";
        }
        h += "</td>";
      }
      h += "</tr>\n";
    }
    h += "</table>\n";
    // Numbers.
    h += "<table><tr><th>method</th><th>term</th><th>frame (ms)</th><th>timed frame (ms), " +
         html(timing_text(c.timing)) +
         "</th><th>samples</th><th>rel. "
         "L1</th><th>rel. "
         "RMS</th><th>max |row ratio - 1|</th><th>mean |row ratio - 1|</th><th>row "
         "error</th><th>horizon "
         "mean</th><th>horizon std</th>"
         "<th>flicker</th><th>reference flicker</th><th>temporal error</th><th>run (s)</th></tr>\n";
    for (const MethodResult& m : c.methods)
      for (const TermResult& t : m.terms) {
        const MethodResult* against = measured_against(c, m);
        const TermResult* rt = against ? term_of(*against, t.term) : nullptr;
        const std::string name = against && against != ref && against != &m
                                     ? m.name + " (against " + against->name + ")"
                                     : m.name;
        h += "<tr><td class=\"t\">" + html(name) + "</td><td class=\"t\">" + html(t.term) +
             (t.metrics.reference_black ? " (the reference is black)" : "") + "</td><td>" +
             short_number(t.frame_ms) + "</td><td>" + short_number(m.timing_ms.value_or(kNaN)) +
             "</td><td>" + (t.samples > 0 ? std::to_string(t.samples) : std::string("-")) +
             "</td><td>" + short_number(t.metrics.error.relative_l1.l) + "</td><td>" +
             short_number(t.metrics.error.relative_rms.l) + "</td><td>" +
             short_number(t.metrics.max_row_deviation) + "</td><td>" +
             short_number(t.metrics.mean_row_deviation) + "</td><td>" +
             short_number(t.metrics.row_error) + "</td><td>" +
             short_number(t.metrics.horizon.mean) + "</td><td>" +
             short_number(t.metrics.horizon.std) + "</td><td>" +
             short_number(t.flicker.value_or(kNaN)) + "</td><td>" +
             short_number(rt && rt->flicker ? *rt->flicker : kNaN) + "</td><td>" +
             short_number(t.temporal_error.value_or(kNaN)) + "</td><td>" +
             short_number(t.seconds.value_or(kNaN)) + "</td></tr>\n";
      }
    h += "</table>\n";
    // The case's reference, then the variants' own references.
    for (const MethodResult& r : c.methods) {
      if (r.method != "reference") continue;
      const std::string which = &r == ref ? "Reference" : "Reference " + r.name;
      if (!r.convergence.empty()) {
        h += "<p>" + html(which) + " convergence (largest row change at twice the samples):";
        for (const auto& [term, change] : r.convergence)
          h += " " + html(term) + " " + short_number(100.0 * change) + "%;";
        h += "</p>\n";
      }
      if (!r.lattice_convergence.empty()) {
        h += "<p>" + html(which) +
             " sun's convergence (largest row change from a lattice of half the cells):";
        for (const auto& [term, change] : r.lattice_convergence)
          h += " " + html(term) + " " +
               (std::isfinite(change) ? short_number(100.0 * change) + "%"
                                      : std::string("not measured (no row lit and resolved)")) +
               ";";
        for (const auto& [term, cells] : r.lattice_cells_per_wavelength)
          h += " its lattice " + short_number(cells) + " cells per shortest wavelength (" +
               html(term) + ");";
        h += "</p>\n";
      }
      if (!r.resolved_rows.empty()) {
        h += "<p>" + html(which) +
             ": image rows of the sea where its sun resolves every wave (the only rows "
             "compared for that term):";
        for (const auto& [term, rows] : r.resolved_rows)
          h += " " + html(term) + " " + std::to_string(rows) + ";";
        h += "</p>\n";
      }
    }
    h += "<p>";
    for (const auto& [title, png] : plots[ci])
      h += "<a href=\"" + html(png) + "\"><img class=\"plot\" src=\"" + html(png) + "\" alt=\"" +
           html(title) + "\" title=\"" + html(title) + "\"></a>\n";
    h += "</p>\n";
  }
  h += "</body></html>\n";
  return h;
}

}  // namespace detail

}  // namespace thalassa::validation
