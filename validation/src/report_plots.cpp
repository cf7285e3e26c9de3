// The validation report's plots, drawn by gnuplot (report_detail.hpp).
#include "report_detail.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "thalassa/engine/file_io.hpp"
#include "thalassa/engine/program.hpp"

namespace thalassa::validation {

namespace fs = std::filesystem;
namespace detail {

namespace {

// A file's whole text; nullopt when it cannot be read (missing).
std::optional<std::string> read_text_if_exists(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Writes NAME.dat and NAME.gp into `plots` and runs gnuplot on the script, which must write
// its PNG to the file named by gnuplot variable `out` (a pending name, renamed into place when
// gnuplot succeeds); where both files already hold exactly that and the PNG exists, it is kept
// and gnuplot is not run. Returns the PNG's file name.
std::string draw(const std::string& gnuplot, const fs::path& plots, const std::string& name,
                 const std::string& data, const std::string& script, const ReportOptions& options) {
  const std::string png = name + ".png";
  const std::string pending = "." + png + ".tmp-" + std::to_string(getpid());
  const std::string header =
      "# Drawn by thalassa validate; redraw with: gnuplot " + name + ".gp (in this folder).\n" +
      "if (!exists(\"out\")) out = '" + png + "'\n" + "set terminal pngcairo size " +
      std::to_string(options.plot_width) + "," + std::to_string(options.plot_height) +
      " noenhanced font ',10'\n" + "set output out\nset datafile missing 'NaN'\n";
  // Already drawn from the same data and script (a report rewritten after each case of a run, or
  // resumed): the PNG is gnuplot's output of exactly these files, so it is kept.
  std::error_code ec;
  if (fs::is_regular_file(plots / png, ec) &&
      read_text_if_exists(plots / (name + ".dat")) == data &&
      read_text_if_exists(plots / (name + ".gp")) == header + script)
    return png;
  write_text_atomically((plots / (name + ".dat")).string(), data);
  write_text_atomically((plots / (name + ".gp")).string(), header + script);
  const std::string log = (plots / ("." + name + ".log")).string();
  const int status =
      run_program({gnuplot, "-e", "out='" + pending + "'", name + ".gp"}, log, plots.string());
  std::string output;
  {
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    output = text.str();
  }
  fs::remove(log, ec);
  if (status != 0 || !fs::is_regular_file(plots / pending, ec)) {
    fs::remove(plots / pending, ec);
    while (!output.empty() && (output.back() == '\n' || output.back() == '\r')) output.pop_back();
    std::replace(output.begin(), output.end(), '\n', ' ');
    throw ReportError((plots / png).string() + ": gnuplot failed (status " +
                      std::to_string(status) + ")" + (output.empty() ? "" : ": " + output));
  }
  fs::rename(plots / pending, plots / png, ec);
  if (ec) throw ReportError((plots / png).string() + ": cannot rename into place: " + ec.message());
  return png;
}

// The ratio panel of the per-row plots (rows_plot, seas_rows_plot): a log scale, so that half and
// twice the reference lie as far from 1, and clamp(r) holding a method black where the reference
// is lit (ratio 0) or 100 times too bright at the axis's ends.
constexpr const char* kRatioAxis =
    "set logscale y 2\nset ylabel \"ratio to the reference\\n(log scale, in [1/64, 64])\"\n"
    "clamp(r) = r < 1.0/64 ? 1.0/64 : (r > 64 ? 64 : r)\n";

// One method's clamped ratio, column `column` of NAME.dat, in line type index + 1 (the colour it
// has in the totals' panel above).
std::string ratio_curve(const std::string& name, std::size_t column, std::size_t index,
                        const std::string& title) {
  return "'" + name + ".dat' using 1:(clamp($" + std::to_string(column) + ")) with lines lw 2 lt " +
         std::to_string(index + 1) + " title '" + title + "'";
}

}  // namespace

std::string rows_plot(const std::string& gnuplot, const fs::path& plots, const CaseResult& c,
                      const std::string& term, const ReportOptions& options) {
  std::vector<std::pair<std::string, const TermResult*>> curves;
  for (const MethodResult& m : c.methods)
    if (m.plain)
      if (const TermResult* t = term_of(m, term); t && measured(*t)) curves.push_back({m.name, t});
  if (curves.empty()) return "";  // no reference in the suite: nothing was measured
  std::size_t rows = 0;
  for (const auto& [name, t] : curves) rows = std::max(rows, t->metrics.row_totals.size());
  // The reference's relative uncertainty per row, where the ratios are defined (the reference's
  // own ratio, 1, is defined exactly there).
  const MethodResult* reference = reference_of(c);
  const TermResult* reference_term = reference ? term_of(*reference, term) : nullptr;
  const std::vector<double> uncertainty = reference_rows_uncertainty(reference, term, rows);
  bool any_uncertainty = false;
  std::string data = "# row";
  for (const auto& [name, t] : curves) data += " total_" + name + " ratio_" + name;
  data +=
      " reference_uncertainty\n# totals: luminance summed over the row's sea pixels, "
      "W m^-2 sr^-1 nm^-1; the reference's uncertainty: relative, per row\n";
  for (std::size_t y = 0; y < rows; ++y) {
    data += std::to_string(y);
    for (const auto& [name, t] : curves) {
      const auto& tot = t->metrics.row_totals;
      const auto& rat = t->metrics.row_ratios;
      data += " " + number(y < tot.size() ? tot[y].l : kNaN, "NaN");
      data += " " + number(y < rat.size() ? rat[y].l : kNaN, "NaN");
    }
    const auto& own =
        reference_term ? reference_term->metrics.row_ratios : std::vector<ChannelValues>{};
    const double u = y < own.size() && std::isfinite(own[y].l) ? uncertainty[y] : kNaN;
    any_uncertainty = any_uncertainty || std::isfinite(u);
    data += " " + number(u, "NaN") + "\n";
  }
  const std::string name = c.name + "_" + term + "_rows";
  std::string script = "set multiplot layout 2,1 title '" + c.name + ", " + term +
                       ": total radiance per image row (fig. 10)'\n"
                       "set key outside right\nset grid\nset xlabel 'image row (0 = top)'\n"
                       // The same margins in both panels, so that their rows line up (the
                       // key, outside on the right, differs between them).
                       "set lmargin 15\nset rmargin 22\n"
                       // Half a row each side: an image of one row has a range too.
                       "set xrange [-0.5:" +
                       number(static_cast<double>(rows) - 0.5) +
                       "]\n"
                       "set ylabel \"row total luminance\\n(W m^-2 sr^-1 nm^-1)\"\n";
  // No row compared at all (the reference's sun resolved none): gnuplot refuses a plot whose
  // every point is undefined, so the panel says so.
  bool any_total = false;
  for (const auto& [name_, t] : curves)
    for (const ChannelValues& total : t->metrics.row_totals) any_total |= std::isfinite(total.l);
  if (any_total) {
    // Each method keeps its colour (line type i + 1) in both panels: the ratio panel's line of
    // 1 would otherwise take the first colour and shift the others by one.
    script += "plot ";
    for (std::size_t i = 0; i < curves.size(); ++i)
      script += std::string(i ? ", " : "") + "'" + name +
                ".dat' using 1:" + std::to_string(2 + 2 * i) + " with lines lw 2 lt " +
                std::to_string(i + 1) + " title '" + curves[i].first + "'";
    script += "\n";
  } else {
    script +=
        "set label 1 'no row compared (no row of the sea resolved by the reference)' at graph "
        "0.5, graph 0.5 center\nplot 0 with lines dt 2 lc 'grey' notitle\nunset label 1\n";
  }
  // No defined ratio at all (the reference's sun resolved no row, or the term is black): gnuplot
  // refuses a plot whose every point is undefined, so the panel says so over the line of 1.
  bool any_ratio = false;
  for (const auto& [name_, t] : curves)
    for (const ChannelValues& ratio : t->metrics.row_ratios) any_ratio |= std::isfinite(ratio.l);
  if (any_ratio) {
    script += std::string(kRatioAxis) + "plot ";
    // The band a method's ratio may lie in for being the truth's, given the reference's own
    // uncertainty u: 1 +- u (clamped to the axis).
    if (any_uncertainty) {
      const std::string u = "$" + std::to_string(2 + 2 * curves.size());
      script += "'" + name + ".dat' using 1:(clamp(1 - " + u + ")):(clamp(1 + " + u +
                ")) with filledcurves fc 'grey' fs transparent solid 0.5 noborder title "
                "'reference \xC2\xB1 u', ";  // UTF-8 plus-minus
    }
    script += "1 with lines dt 2 lc 'grey' notitle";
    for (std::size_t i = 0; i < curves.size(); ++i)
      script += ", " + ratio_curve(name, 3 + 2 * i, i, curves[i].first);
  } else {
    script +=
        "set label 1 'no row measured (no row resolved by the reference, or none lit)' at graph "
        "0.5, graph 0.5 center\nset ylabel 'ratio to the reference'\nplot 1 with lines dt 2 "
        "title 'ratio 1'\nunset label 1";
  }
  script += "\nunset multiplot\n";
  return draw(gnuplot, plots, name, data, script, options);
}

std::string seas_rows_plot(const std::string& gnuplot, const fs::path& plots,
                           const std::string& case_name, const std::string& term,
                           const std::vector<const SeaLine*>& lines, const ReportOptions& options) {
  if (lines.empty()) return "";
  std::size_t rows = 0;
  bool any = false;
  for (const SeaLine* l : lines) {
    rows = std::max(rows, l->method_rows.size());
    for (double v : l->reference_rows) any = any || std::isfinite(v);
  }
  if (!any) return "";  // no row counted in every sea: gnuplot refuses an empty plot
  std::string data = "# row reference";
  for (const SeaLine* l : lines) data += " total_" + l->method + " ratio_" + l->method;
  data += "\n# totals: luminance summed over the row's sea pixels and over " +
          std::to_string(lines.front()->seas) +
          " seas, W m^-2 sr^-1 nm^-1; NaN: a row not compared in every sea\n";
  const auto at = [](const std::vector<double>& v, std::size_t y) {
    return y < v.size() ? v[y] : kNaN;
  };
  for (std::size_t y = 0; y < rows; ++y) {
    data += std::to_string(y) + " " + number(at(lines.front()->reference_rows, y), "NaN");
    for (const SeaLine* l : lines) {
      const double m = at(l->method_rows, y), r = at(l->reference_rows, y);
      data += " " + number(m, "NaN") + " " + number(r > 0.0 ? m / r : kNaN, "NaN");
    }
    data += "\n";
  }
  const std::string name = case_name + "_seas_" + term + "_rows";
  std::string script =
      "set multiplot layout 2,1 title '" + case_name + ", " + term + ": total radiance per image " +
      "row summed over " + std::to_string(lines.front()->seas) +
      " seas (fig. 10)'\nset key outside right\nset grid\nset xlabel 'image row (0 = top)'\n"
      "set lmargin 15\nset rmargin 22\nset xrange [-0.5:" +
      number(static_cast<double>(rows) - 0.5) +
      "]\nset ylabel \"row total luminance\\nover the seas\"\nplot '" + name +
      ".dat' using 1:2 with lines lw 2 lc 'black' title 'reference'";
  for (std::size_t i = 0; i < lines.size(); ++i)
    script += ", '" + name + ".dat' using 1:" + std::to_string(3 + 2 * i) + " with lines lw 2 lt " +
              std::to_string(i + 1) + " title '" + lines[i]->method + "'";
  // The ratio as rows_plot draws it; where no method has a defined ratio (every summed reference
  // row 0) the panel says so.
  bool any_ratio = false;
  for (const SeaLine* l : lines)
    for (std::size_t y = 0; y < l->method_rows.size(); ++y)
      any_ratio = any_ratio || (at(l->reference_rows, y) > 0.0 && std::isfinite(l->method_rows[y]));
  if (any_ratio) {
    script += "\n" + std::string(kRatioAxis) + "plot 1 with lines dt 2 lc 'grey' notitle";
    for (std::size_t i = 0; i < lines.size(); ++i)
      script += ", " + ratio_curve(name, 4 + 2 * i, i, lines[i]->method);
  } else {
    script +=
        "\nset label 1 'no row lit in the summed reference' at graph 0.5, graph 0.5 center\n"
        "set ylabel 'ratio to the reference'\nplot 1 with lines dt 2 title 'ratio 1'\nunset label "
        "1";
  }
  script += "\nunset multiplot\n";
  return draw(gnuplot, plots, name, data, script, options);
}

std::string error_time_plot(const std::string& gnuplot, const fs::path& plots, const CaseResult& c,
                            const ReportOptions& options) {
  const std::vector<std::string> terms = case_terms(c);
  if (terms.empty()) return "";
  std::vector<const MethodResult*> methods;  // the case's as dashed lines; a variant's own: 0
  for (const MethodResult& m : c.methods)
    if (m.method != "reference") methods.push_back(&m);
  bool any = false;  // a suite without a reference measures nothing to plot
  for (const MethodResult* m : methods)
    for (const TermResult& t : m->terms) any = any || measured(t);
  if (!any) return "";
  // Filled circle, square, triangle up, diamond, triangle down (pngcairo's point types).
  static constexpr int kTermPoint[] = {7, 5, 9, 13, 11};
  // Colours that stay apart for a dozen methods (the default palette cycles after 8).
  static constexpr const char* kMethodColour[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                                  "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                                  "#bcbd22", "#17becf", "#000000", "#b8860b"};
  constexpr std::size_t kColours = std::size(kMethodColour);
  std::string data = "# method term frame_ms relative_l1 row_error method_index term_index\n";
  for (std::size_t mi = 0; mi < methods.size(); ++mi)
    for (std::size_t ti = 0; ti < terms.size(); ++ti) {
      const TermResult* t = term_of(*methods[mi], terms[ti]);
      if (!t || !measured(*t)) continue;
      data += methods[mi]->name + " " + terms[ti] + " " + number(cost_ms(*methods[mi], *t), "NaN") +
              " " + number(t->metrics.error.relative_l1.l, "NaN") + " " +
              number(t->metrics.row_error, "NaN") + " " + std::to_string(mi + 1) + " " +
              std::to_string(kTermPoint[ti % std::size(kTermPoint)]) + "\n";
    }
  const std::string name = c.name + "_error_time";
  std::string script;
  for (std::size_t i = 0; i < kColours; ++i)
    script += "set linetype " + std::to_string(i + 1) + " lc rgb '" + kMethodColour[i] + "'\n";
  script += "set linetype cycle " + std::to_string(kColours) + "\n";
  // A double-quoted gnuplot string (for its line break): the names hold no quote.
  const bool supersampled = std::any_of(c.methods.begin(), c.methods.end(),
                                        [](const MethodResult& m) { return m.supersample > 1; });
  script +=
      "set multiplot layout 1,2 title \"" + c.name + ": error over the sea against frame time" +
      (c.timing.enabled() ? "\\n(methods timed at " + timing_text(c.timing) +
                                (supersampled ? " (a supersampled one at its multiple)" : "") +
                                " with every term; the reference at the image size)"
                          : std::string()) +
      "\" font ',10' margins 0.08,0.78,0.12,0.88 spacing 0.09\n"
      "set grid\nset logscale x\nunset key\n"
      "set xlabel 'frame time (ms)'\n";
  // The x range covers every time, the reference's included (arrows do not widen it).
  double lo = HUGE_VAL, hi = 0.0;
  for (const MethodResult& m : c.methods)
    for (const TermResult& t : m.terms)
      if (const double ms = cost_ms(m, t); ms > 0.0 && std::isfinite(ms)) {
        lo = std::min(lo, ms);
        hi = std::max(hi, ms);
      }
  if (hi > 0.0) script += "set xrange [" + number(lo / 1.5) + ":" + number(hi * 1.5) + "]\n";
  if (const MethodResult* ref = reference_of(c)) {
    int i = 0;
    for (const std::string& term : terms) {
      const TermResult* t = term_of(*ref, term);
      if (!t || !(t->frame_ms > 0.0)) continue;
      script += "set arrow " + std::to_string(++i) + " from " + number(t->frame_ms) +
                ", graph 0 to " + number(t->frame_ms) + ", graph 1 nohead dt 2 lc rgb 'gray40'\n";
      // Along its line, from the top: beside the methods' points wherever they lie (on a GPU
      // the references take tens of ms, among the methods' times on llvmpipe). Each term's a
      // quarter of the height lower than the last (a label is about a fifth), since two terms'
      // references often take the same time (the sky's and the refracted light's: stop 30's
      // plots printed them over each other).
      const int top_percent = 98 - 24 * ((i - 1) % 4);
      script += "set label " + std::to_string(i) + " 'reference (" + term + ")' at " +
                number(t->frame_ms) + ", graph " + std::to_string(top_percent / 100.0) +
                " right rotate by 90 offset -0.6,0 font ',8'\n";
    }
  }
  // Whether a panel has a point: gnuplot refuses a plot whose every point is undefined (no row
  // compared: the row error is undefined for every method).
  const auto any_finite = [&](auto value) {
    for (const MethodResult* m : methods)
      for (const TermResult& t : m->terms)
        if (measured(t) && std::isfinite(value(t))) return true;
    return false;
  };
  const auto panel = [&](int column, const std::string& ylabel, bool has_points, bool key) {
    std::string p = "set ylabel '" + ylabel + "'\n";
    if (has_points) {
      p += "set yrange [0:*]\nplot '" + name + ".dat' using 3:" + std::to_string(column) +
           ":7:6 with points pt variable ps 1.3 lc variable notitle";
    } else {
      p += "set yrange [0:1]\nset label 20 'nothing compared' at graph 0.5, graph 0.5 center\n"
           "plot 0 with lines dt 2 lc rgb 'grey' notitle";
    }
    if (key) {
      // One entry per method (its colour) and per term (its shape), outside on the right.
      p = "set key at screen 0.99, screen 0.88 right top font ',8' spacing 1.1\n" + p;
      for (std::size_t mi = 0; mi < methods.size(); ++mi)
        p += ", NaN with points pt 7 lc " + std::to_string(mi % kColours + 1) + " title '" +
             methods[mi]->name + "'";
      for (std::size_t ti = 0; ti < terms.size(); ++ti)
        p += ", NaN with points pt " + std::to_string(kTermPoint[ti % std::size(kTermPoint)]) +
             " lc rgb 'black' title '" + terms[ti] + "'";
    }
    return p + "\nunset label 20\n";
  };
  script +=
      panel(4, "relative L1 error (per pixel)",
            any_finite([](const TermResult& t) { return t.metrics.error.relative_l1.l; }), false);
  script += panel(5, "row error (energy per row)",
                  any_finite([](const TermResult& t) { return t.metrics.row_error; }), true);
  script += "unset multiplot\n";
  return draw(gnuplot, plots, name, data, script, options);
}

std::string horizon_bands_plot(
    const std::string& gnuplot, const fs::path& plots, const std::string& name,
    const std::string& title, const std::vector<std::pair<std::string, const HorizonBand*>>& curves,
    const ReportOptions& options) {
  if (curves.empty()) return "";
  std::string data = "# beta_mid_deg";
  for (const auto& [method, band] : curves) data += " mean_" + method + " std_" + method;
  data += "\n# luminance difference method - reference, W m^-2 sr^-1 nm^-1\n";
  const std::vector<HorizonBin>& first = curves.front().second->bins;
  for (std::size_t k = 0; k < first.size(); ++k) {
    data += number(0.5 * (first[k].beta_lo_deg + first[k].beta_hi_deg));
    for (const auto& [method, band] : curves) {
      const auto& bs = band->bins;
      data += " " + number(k < bs.size() ? bs[k].mean : kNaN, "NaN") + " " +
              number(k < bs.size() ? bs[k].std : kNaN, "NaN");
    }
    data += "\n";
  }
  std::string script =
      "set multiplot layout 1,2 title '" + title +
      ": luminance difference to the reference near the horizon (Tessendorf et al. 2023)'\n"
      "set key outside bottom center horizontal font ',8'\nset grid\n"
      "set xlabel 'degrees below the horizon'\n"
      "set xrange [0:*]\n"
      "set ylabel 'azimuth-averaged mean (W m^-2 sr^-1 nm^-1)'\nplot ";
  for (std::size_t i = 0; i < curves.size(); ++i)
    script += std::string(i ? ", " : "") + "'" + name +
              ".dat' using 1:" + std::to_string(2 + 2 * i) + " with linespoints title '" +
              curves[i].first + "'";
  // The same key under both panels keeps their axes the same height.
  script += "\nset ylabel 'azimuth-averaged standard deviation'\nplot ";
  for (std::size_t i = 0; i < curves.size(); ++i)
    script += std::string(i ? ", " : "") + "'" + name +
              ".dat' using 1:" + std::to_string(3 + 2 * i) + " with linespoints title '" +
              curves[i].first + "'";
  script += "\nunset multiplot\n";
  return draw(gnuplot, plots, name, data, script, options);
}

std::string horizon_plot(const std::string& gnuplot, const fs::path& plots, const CaseResult& c,
                         const std::string& term, const ReportOptions& options) {
  std::vector<std::pair<std::string, const HorizonBand*>> curves;
  for (const MethodResult& m : c.methods) {
    if (m.method == "reference") continue;
    const TermResult* t = term_of(m, term);
    if (t && t->metrics.horizon.pixels > 0) curves.push_back({m.name, &t->metrics.horizon});
  }
  return horizon_bands_plot(gnuplot, plots, c.name + "_" + term + "_horizon", c.name + ", " + term,
                            curves, options);
}

std::string summary_height_plot(const std::string& gnuplot, const fs::path& plots,
                                const Report& report, const std::string& term,
                                const ReportOptions& options) {
  std::vector<std::string> methods;
  // Every plain method in the cases' order, the reference included: a method's line type is its
  // place here, as on the rows plots (rows_plot), so that it keeps its colour across the report.
  std::vector<std::string> order;
  std::vector<double> heights;
  for (const CaseResult& c : report.cases)
    for (const MethodResult& m : c.methods) {
      if (!m.plain) continue;
      if (std::find(order.begin(), order.end(), m.name) == order.end()) order.push_back(m.name);
      if (m.method == "reference") continue;
      const TermResult* t = term_of(m, term);
      if (!t || !measured(*t)) continue;
      if (std::find(methods.begin(), methods.end(), m.name) == methods.end())
        methods.push_back(m.name);
      if (std::find(heights.begin(), heights.end(), c.camera_height) == heights.end())
        heights.push_back(c.camera_height);
    }
  if (methods.empty()) return "";
  std::sort(heights.begin(), heights.end());
  bool any = false;  // gnuplot refuses a plot with no defined point: then there is no plot
  std::string data = "# camera_height_m";
  for (const std::string& m : methods) data += " " + m;
  data += "\n# the median over the cases at that height of the row error (luminance)\n";
  for (double height : heights) {
    data += number(height);
    for (const std::string& name : methods) {
      std::vector<double> values;
      for (const CaseResult& c : report.cases)
        if (c.camera_height == height)
          if (const MethodResult* m = method_named(c, name))
            if (const TermResult* t = term_of(*m, term); t && measured(*t))
              values.push_back(t->metrics.row_error);
      const double median = median_of(values);
      any = any || std::isfinite(median);
      data += " " + number(median, "NaN");
    }
    data += "\n";
  }
  if (!any) return "";
  const std::string name = "summary_" + term + "_height";
  std::string script = "set title '" + term +
                       ": relative L1 error of the row totals against the camera height "
                       "(median over the cases at each height)'\nset key outside right\nset grid\n"
                       "set xlabel 'camera height (m)'\nset ylabel 'row error'\n"
                       "set yrange [0:*]\n";
  // A log axis needs positive heights; a camera below the sea's rest level keeps it linear.
  if (heights.front() > 0.0)
    script += "set logscale x\nset xrange [" + number(heights.front() / 2) + ":" +
              number(heights.back() * 2) + "]\n";
  script += "plot ";
  for (std::size_t i = 0; i < methods.size(); ++i)
    script +=
        std::string(i ? ", " : "") + "'" + name + ".dat' using 1:" + std::to_string(2 + i) +
        " with linespoints lw 2 pt 7 lt " +
        std::to_string(std::find(order.begin(), order.end(), methods[i]) - order.begin() + 1) +
        " title '" + methods[i] + "'";
  script += "\n";
  return draw(gnuplot, plots, name, data, script, options);
}

}  // namespace detail

}  // namespace thalassa::validation
