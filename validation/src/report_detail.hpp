// Internal to the validation report: the helpers its files share (report_format.cpp), the
// plots (report_plots.cpp), the CSV files (report_csv.cpp) and index.html (report_html.cpp),
// which write_report (report.cpp) puts together with results.json (report_json.cpp) and the
// summaries (report_summary.cpp). Not installed; the public surface is
// thalassa/validation/report.hpp.
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "thalassa/validation/report.hpp"

namespace thalassa::validation::detail {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Text and lookups (report_format.cpp).

// A number that reads back to the same double (%.17g); NaN (undefined) as `nan_text`.
std::string number(double x, const char* nan_text = "");

// One CSV line of the fields, each quoted where it needs to be (RFC 4180).
std::string csv_line(const std::vector<std::string>& fields);

// Text escaped for HTML.
std::string html(const std::string& s);

// A number for people: 4 significant digits, "–" when undefined.
std::string short_number(double x);

// A case's overrides as `key=value` pairs, space-separated.
std::string overrides_text(const std::vector<SceneOverride>& set);

// The case's method of that name; nullptr when there is none.
const MethodResult* method_named(const CaseResult& c, const std::string& name);

// The case's reference; nullptr when it has none.
const MethodResult* reference_of(const CaseResult& c);

// The reference `m` was measured against: its own (MethodResult::reference) or the case's.
const MethodResult* measured_against(const CaseResult& c, const MethodResult& m);

// The method's result for `term`; nullptr when it has none.
const TermResult* term_of(const MethodResult& m, const std::string& term);

// The terms of a case in first-seen order.
std::vector<std::string> case_terms(const CaseResult& c);

// Whether the term was measured against a reference (compare_images ran on it).
bool measured(const TermResult& t);

// What a method's term costs, ms: the method's frame timed apart (TimingSettings), else the
// term's image's own frame time.
double cost_ms(const MethodResult& m, const TermResult& t);

// "1280x720" or the case's images' size when the methods were not timed apart.
std::string timing_text(const TimingSettings& timing);

// The median of the finite values (NaN when there is none).
double median_of(std::vector<double> values);

// The largest of the finite values (NaN when there is none).
double max_of(const std::vector<double>& values);

// Plots, drawn by gnuplot into `plots` (report_plots.cpp): each returns its PNG's file name,
// or "" where there is nothing to draw.

// Fig. 10's right column: each plain method's row totals (luminance over the sea) and their
// ratio to the reference's, row 0 at the top of the image.
std::string rows_plot(const std::string& gnuplot, const std::filesystem::path& plots,
                      const CaseResult& c, const std::string& term, const ReportOptions& options);

// Fig. 10's right column over the seas of a case (summarize_seas): for each method measured
// against the case's reference on `term`, its rows summed over the seas beside the reference's
// (the first such method's reference rows: every one of them is the case's reference, on the
// rows that method counts), and their ratio. `lines` are the case's lines for the term.
std::string seas_rows_plot(const std::string& gnuplot, const std::filesystem::path& plots,
                           const std::string& case_name, const std::string& term,
                           const std::vector<const SeaLine*>& lines, const ReportOptions& options);

// Every method and variant: its relative L1 error over the sea (left) and its row error (right,
// TermMetrics::row_error) against its frame time (timed apart at the case's TimingSettings when
// it has them, every term in one frame). A colour per method, a point shape per term; the
// reference's time (at the images' size) as a dashed line per term.
std::string error_time_plot(const std::string& gnuplot, const std::filesystem::path& plots,
                            const CaseResult& c, const ReportOptions& options);

// Paper 004, fig. 5: the azimuth-averaged mean and standard deviation of the luminance
// difference to the reference, against the angle below the horizon, one curve per named band;
// `name` the plot's file stem, `title` its heading.
std::string horizon_bands_plot(
    const std::string& gnuplot, const std::filesystem::path& plots, const std::string& name,
    const std::string& title, const std::vector<std::pair<std::string, const HorizonBand*>>& curves,
    const ReportOptions& options);

// The case's methods on `term` (horizon_bands_plot).
std::string horizon_plot(const std::string& gnuplot, const std::filesystem::path& plots,
                         const CaseResult& c, const std::string& term,
                         const ReportOptions& options);

// Over the cases: each plain method's row error (TermMetrics::row_error) against the camera's
// height, the median over the cases at each height (fig. 10 across distances).
std::string summary_height_plot(const std::string& gnuplot, const std::filesystem::path& plots,
                                const Report& report, const std::string& term,
                                const ReportOptions& options);

// The CSV files (report_csv.cpp).

std::string metrics_csv(const Report& report);

std::string rows_csv(const Report& report);

std::string horizon_csv(const Report& report);

std::string cases_csv(const Report& report);

std::string summary_csv(const Report& report);

std::string convergence_csv(const Report& report);

std::string seas_csv(const std::vector<SeaLine>& seas);

// horizon.csv's columns for the bands pooled over the seas.
std::string seas_horizon_csv(const std::vector<SeaLine>& seas);

std::string claim_csv(const Report& report);

// index.html (report_html.cpp).

std::string index_html(const Report& report, const std::vector<SeaLine>& seas,
                       const std::vector<std::vector<std::pair<std::string, std::string>>>& plots,
                       const std::vector<std::pair<std::string, std::string>>& summary_plots);

}  // namespace thalassa::validation::detail
