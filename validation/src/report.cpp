// The validation report (thalassa/validation/report.hpp; the files are listed in
// docs/validation.md): write_report puts together the plots, the CSV files, results.json and
// index.html.
#include "thalassa/validation/report.hpp"

#include <algorithm>
#include <filesystem>

#include "report_detail.hpp"
#include "thalassa/engine/file_io.hpp"
#include "thalassa/engine/program.hpp"

namespace thalassa::validation {

namespace fs = std::filesystem;
using namespace detail;

bool CaseResult::passed() const {
  if (exit_status != expected_exit) return false;
  return expected_error.empty() || message.find(expected_error) != std::string::npos;
}

std::string find_gnuplot(const ReportOptions& options) {
  const std::string program = options.gnuplot.empty() ? "gnuplot" : options.gnuplot;
  const std::string found = find_program(program);
  if (found.empty())
    throw ReportError("gnuplot is not installed (\"" + program +
                      "\" not found on PATH), and the report's plots need it: on Debian, "
                      "apt-get install gnuplot-nox (scripts/setup installs it)");
  return found;
}

std::vector<std::string> write_report(const Report& report, const std::string& dir,
                                      const ReportOptions& options) {
  const std::string gnuplot = find_gnuplot(options);
  std::error_code ec;
  const fs::path root(dir), plots = root / "plots";
  fs::create_directories(plots, ec);
  if (ec) throw ReportError(plots.string() + ": cannot create the folder: " + ec.message());
  std::vector<std::string> written;
  const auto text = [&](const std::string& name, const std::string& content) {
    try {
      write_text_atomically((root / name).string(), content);
    } catch (const FileError& e) {
      throw ReportError(e.what());
    }
    written.push_back(name);
  };
  // Plots first: index.html links them, and is written last. A plot drawn (png not empty): its
  // three files written, and its link under `title`.
  const auto add_plot = [&](std::vector<std::pair<std::string, std::string>>& links,
                            const std::string& title, const std::string& png) {
    if (png.empty()) return;
    const std::string stem = png.substr(0, png.size() - 4);
    for (const char* ext : {".dat", ".gp", ".png"}) written.push_back("plots/" + stem + ext);
    links.push_back({title, "plots/" + png});
  };
  std::vector<std::vector<std::pair<std::string, std::string>>> plot_links;
  try {
    for (const CaseResult& c : report.cases) {
      auto& links = plot_links.emplace_back();
      const auto add = [&](const std::string& title, const std::string& png) {
        add_plot(links, title, png);
      };
      if (c.methods.empty()) continue;
      for (const std::string& term : case_terms(c))
        add(c.name + " " + term + ": per-row radiance",
            rows_plot(gnuplot, plots, c, term, options));
      add(c.name + ": error against frame time", error_time_plot(gnuplot, plots, c, options));
      for (const std::string& term : case_terms(c))
        add(c.name + " " + term + ": near the horizon",
            horizon_plot(gnuplot, plots, c, term, options));
    }
  } catch (const FileError& e) {
    throw ReportError(e.what());
  }
  std::vector<std::pair<std::string, std::string>> summary_links;
  try {
    std::vector<std::string> terms;
    for (const CaseResult& c : report.cases)
      for (const std::string& term : case_terms(c))
        if (std::find(terms.begin(), terms.end(), term) == terms.end()) terms.push_back(term);
    for (const std::string& term : terms) {
      add_plot(summary_links, term + ": mean row deviation against height",
               summary_height_plot(gnuplot, plots, report, term, options));
    }
  } catch (const FileError& e) {
    throw ReportError(e.what());
  }
  // Over the seas: per case and term, the rows of the methods measured against the case's
  // reference (a variant with its own reference sums another sea's rows) and every method's
  // pooled horizon band.
  const std::vector<SeaLine> seas = summarize_seas(report);
  try {
    const auto own_reference = [&](const SeaLine& l) {
      for (const CaseResult& c : report.cases)
        if (c.sea_of == l.case_name)
          if (const MethodResult* m = method_named(c, l.method)) return !m->reference.empty();
      return false;
    };
    std::vector<std::pair<std::string, std::string>> keys;  // (case, term), first seen first
    for (const SeaLine& l : seas)
      if (std::find(keys.begin(), keys.end(), std::pair{l.case_name, l.term}) == keys.end())
        keys.push_back({l.case_name, l.term});
    for (const auto& [case_name, term] : keys) {
      std::vector<const SeaLine*> lines;
      for (const SeaLine& l : seas)
        if (l.case_name == case_name && l.term == term && !own_reference(l)) lines.push_back(&l);
      const std::string png = seas_rows_plot(gnuplot, plots, case_name, term, lines, options);
      if (!png.empty())  // then lines holds a line
        add_plot(summary_links,
                 case_name + " " + term + ": per-row radiance summed over " +
                     std::to_string(lines.front()->seas) + " seas",
                 png);
      std::vector<std::pair<std::string, const HorizonBand*>> bands;
      int most_seas = 0;
      for (const SeaLine& l : seas)
        if (l.case_name == case_name && l.term == term && l.horizon.pixels > 0) {
          bands.push_back({l.method, &l.horizon});
          most_seas = std::max(most_seas, l.seas);
        }
      add_plot(
          summary_links,
          case_name + " " + term + ": near the horizon over " + std::to_string(most_seas) + " seas",
          horizon_bands_plot(
              gnuplot, plots, case_name + "_seas_" + term + "_horizon",
              case_name + ", " + term + ", " + std::to_string(most_seas) + " seas pooled", bands,
              options));
    }
  } catch (const FileError& e) {
    throw ReportError(e.what());
  }
  text("results.json", report_json(report));
  text("metrics.csv", metrics_csv(report));
  text("rows.csv", rows_csv(report));
  text("horizon.csv", horizon_csv(report));
  text("cases.csv", cases_csv(report));
  text("summary.csv", summary_csv(report));
  text("claim.csv", claim_csv(report));
  text("convergence.csv", convergence_csv(report));
  text("seas.csv", seas_csv(seas));
  text("seas_horizon.csv", seas_horizon_csv(seas));
  text("index.html", index_html(report, seas, plot_links, summary_links));
  return written;
}

}  // namespace thalassa::validation
