// The validation report (thalassa/validation/report.hpp; the files are listed in
// docs/validation.md).
#include "thalassa/validation/report.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "thalassa/engine/file_io.hpp"
#include "thalassa/engine/program.hpp"
#include "thalassa/ocean/method.hpp"

namespace thalassa::validation {
namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Text

// A number that reads back to the same double (%.17g); NaN (undefined) as `nan_text`.
std::string number(double x, const char* nan_text = "") {
  if (std::isnan(x)) return nan_text;
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// A CSV field (RFC 4180): quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + csv_field(fields[i]);
  return line + "\n";
}

std::string html(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// A number for people: 4 significant digits, "–" when undefined.
std::string short_number(double x) {
  if (std::isnan(x)) return "&ndash;";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

std::string overrides_text(const std::vector<SceneOverride>& set) {
  std::string s;
  for (const SceneOverride& o : set) s += (s.empty() ? "" : " ") + o.assignment();
  return s;
}

const MethodResult* method_named(const CaseResult& c, const std::string& name) {
  for (const MethodResult& m : c.methods)
    if (m.name == name) return &m;
  return nullptr;
}

const MethodResult* reference_of(const CaseResult& c) {
  for (const MethodResult& m : c.methods)
    if (m.method == "reference" && m.plain) return &m;
  return nullptr;
}

// The reference `m` was measured against: its own (MethodResult::reference) or the case's.
const MethodResult* measured_against(const CaseResult& c, const MethodResult& m) {
  if (!m.reference.empty())
    if (const MethodResult* own = method_named(c, m.reference)) return own;
  return reference_of(c);
}

const TermResult* term_of(const MethodResult& m, const std::string& term) {
  for (const TermResult& t : m.terms)
    if (t.term == term) return &t;
  return nullptr;
}

// The terms of a case in first-seen order.
std::vector<std::string> case_terms(const CaseResult& c) {
  std::vector<std::string> terms;
  for (const MethodResult& m : c.methods)
    for (const TermResult& t : m.terms)
      if (std::find(terms.begin(), terms.end(), t.term) == terms.end()) terms.push_back(t.term);
  return terms;
}

// ---------------------------------------------------------------------------------------------
// JSON

ojson channels_json(const ChannelValues& v) {
  ojson j;
  j["l"] = v.l;
  j["r"] = v.r;
  j["g"] = v.g;
  j["b"] = v.b;
  return j;
}

ojson rows_json(const std::vector<ChannelValues>& rows) {
  ojson a = ojson::array();
  for (const ChannelValues& v : rows) a.push_back({v.l, v.r, v.g, v.b});
  return a;
}

double get_number(const ojson& j) { return j.is_null() ? kNaN : j.get<double>(); }

ChannelValues channels_from(const ojson& j) {
  return {get_number(j.at("l")), get_number(j.at("r")), get_number(j.at("g")),
          get_number(j.at("b"))};
}

std::vector<ChannelValues> rows_from(const ojson& a) {
  std::vector<ChannelValues> rows;
  for (const ojson& v : a)
    rows.push_back(
        {get_number(v.at(0)), get_number(v.at(1)), get_number(v.at(2)), get_number(v.at(3))});
  return rows;
}

std::optional<double> optional_from(const ojson& j, const char* key) {
  if (!j.contains(key)) return std::nullopt;
  return get_number(j.at(key));
}

// ---------------------------------------------------------------------------------------------
// gnuplot

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

// Whether the term was measured against a reference (compare_images ran on it).
bool measured(const TermResult& t) { return !t.metrics.row_totals.empty(); }

// What a method's term costs, ms: the method's frame timed apart (TimingSettings), else the
// term's image's own frame time.
double cost_ms(const MethodResult& m, const TermResult& t) {
  return m.timing_ms.value_or(t.frame_ms);
}

// "1280x720" or the case's images' size when the methods were not timed apart.
std::string timing_text(const TimingSettings& timing) {
  return timing.enabled() ? std::to_string(timing.width) + "x" + std::to_string(timing.height)
                          : std::string("the image size");
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

// Fig. 10's right column: each plain method's row totals (luminance over the sea) and their
// ratio to the reference's, row 0 at the top of the image.
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

// Fig. 10's right column over the seas of a case (summarize_seas): for each method measured
// against the case's reference on `term`, its rows summed over the seas beside the reference's
// (the first such method's reference rows: every one of them is the case's reference, on the
// rows that method counts), and their ratio. `lines` are the case's lines for the term.
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

// Every method and variant: its relative L1 error over the sea (left) and its row error (right,
// TermMetrics::row_error) against its frame time (timed apart at the case's TimingSettings when
// it has them, every term in one frame). A colour per method, a point shape per term; the
// reference's time (at the images' size) as a dashed line per term.
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
  script += "set multiplot layout 1,2 title \"" + c.name +
            ": error over the sea against frame time" +
            (c.timing.enabled() ? "\\n(methods timed at " + timing_text(c.timing) +
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

// Paper 004, fig. 5: the azimuth-averaged mean and standard deviation of the luminance
// difference to the reference, against the angle below the horizon, one curve per named band;
// `name` the plot's file stem, `title` its heading.
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

// The case's methods on `term` (horizon_bands_plot).
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

// The median of the finite values (NaN when there is none).
double median_of(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The largest of the finite values (NaN when there is none).
double max_of(const std::vector<double>& values) {
  double worst = kNaN;
  for (double v : values)
    if (std::isfinite(v) && !(v <= worst)) worst = v;
  return worst;
}

// Over the cases: each plain method's row error (TermMetrics::row_error) against the camera's
// height, the median over the cases at each height (fig. 10 across distances).
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

// ---------------------------------------------------------------------------------------------
// CSV

std::string metrics_csv(const Report& report) {
  std::string csv = csv_line({"case",
                              "method",
                              "kind",
                              "term",
                              "frame_ms",
                              "timing_ms",
                              "samples",
                              "sea_pixels",
                              "rel_l1_l",
                              "rel_l1_r",
                              "rel_l1_g",
                              "rel_l1_b",
                              "rel_rms_l",
                              "rel_rms_r",
                              "rel_rms_g",
                              "rel_rms_b",
                              "mean_abs_l",
                              "reference_mean_l",
                              "reference_black",
                              "max_row_deviation",
                              "mean_row_deviation",
                              "row_error",
                              "horizon_mean",
                              "horizon_std",
                              "horizon_reference_mean",
                              "horizon_pixels",
                              "flicker",
                              "reference_flicker",
                              "temporal_error",
                              "seconds",
                              "exr",
                              "png",
                              "reference"});
  for (const CaseResult& c : report.cases) {
    for (const MethodResult& m : c.methods) {
      const MethodResult* ref = measured_against(c, m);
      for (const TermResult& t : m.terms) {
        const ErrorStats& e = t.metrics.error;
        const HorizonBand& h = t.metrics.horizon;
        const TermResult* rt = ref ? term_of(*ref, t.term) : nullptr;
        csv += csv_line({c.name,
                         m.name,
                         m.method,
                         t.term,
                         number(t.frame_ms),
                         number(m.timing_ms.value_or(kNaN)),
                         std::to_string(t.samples),
                         std::to_string(e.pixels),
                         number(e.relative_l1.l),
                         number(e.relative_l1.r),
                         number(e.relative_l1.g),
                         number(e.relative_l1.b),
                         number(e.relative_rms.l),
                         number(e.relative_rms.r),
                         number(e.relative_rms.g),
                         number(e.relative_rms.b),
                         number(e.mean_abs.l),
                         number(e.reference_mean.l),
                         t.metrics.reference_black ? "1" : "0",
                         number(t.metrics.max_row_deviation),
                         number(t.metrics.mean_row_deviation),
                         number(t.metrics.row_error),
                         number(h.mean),
                         number(h.std),
                         number(h.reference_mean),
                         std::to_string(h.pixels),
                         number(t.flicker.value_or(kNaN)),
                         number(rt && rt->flicker ? *rt->flicker : kNaN),
                         number(t.temporal_error.value_or(kNaN)),
                         number(t.seconds.value_or(kNaN)),
                         t.exr,
                         t.png,
                         ref ? ref->name : std::string()});
      }
    }
  }
  return csv;
}

std::string rows_csv(const Report& report) {
  std::string csv =
      csv_line({"case", "method", "term", "row", "total_l", "total_r", "total_g", "total_b",
                "ratio_l", "ratio_r", "ratio_g", "ratio_b", "reference_uncertainty"});
  for (const CaseResult& c : report.cases)
    for (const MethodResult& m : c.methods)
      for (const TermResult& t : m.terms) {
        const auto& tot = t.metrics.row_totals;
        const auto& rat = t.metrics.row_ratios;
        const std::vector<double> u =
            reference_rows_uncertainty(measured_against(c, m), t.term, tot.size());
        for (std::size_t y = 0; y < tot.size(); ++y) {
          const ChannelValues r = y < rat.size() ? rat[y] : ChannelValues{kNaN, kNaN, kNaN, kNaN};
          csv += csv_line({c.name, m.name, t.term, std::to_string(y), number(tot[y].l),
                           number(tot[y].r), number(tot[y].g), number(tot[y].b), number(r.l),
                           number(r.r), number(r.g), number(r.b),
                           number(std::isfinite(r.l) ? u[y] : kNaN)});
        }
      }
  return csv;
}

std::string horizon_csv(const Report& report) {
  std::string csv = csv_line({"case", "method", "term", "beta_lo_deg", "beta_hi_deg", "pixels",
                              "weight_rad2", "mean", "std", "reference_mean"});
  for (const CaseResult& c : report.cases)
    for (const MethodResult& m : c.methods)
      for (const TermResult& t : m.terms)
        for (const HorizonBin& b : t.metrics.horizon.bins)
          csv += csv_line({c.name, m.name, t.term, number(b.beta_lo_deg), number(b.beta_hi_deg),
                           std::to_string(b.pixels), number(b.weight), number(b.mean),
                           number(b.std), number(b.reference_mean)});
  return csv;
}

std::string cases_csv(const Report& report) {
  std::string csv = csv_line({"case", "camera_height_m", "set", "expected_exit", "expected_error",
                              "exit_status", "message", "passed", "seconds"});
  for (const CaseResult& c : report.cases)
    csv += csv_line({c.name, number(c.camera_height), overrides_text(c.set),
                     std::to_string(c.expected_exit), c.expected_error,
                     std::to_string(c.exit_status), c.message, c.passed() ? "1" : "0",
                     number(c.seconds.value_or(kNaN))});
  return csv;
}

std::string summary_csv(const Report& report) {
  std::string csv = csv_line({"method", "term", "cases", "median_rel_l1_l", "worst_rel_l1_l",
                              "median_row_error", "worst_row_error", "median_frame_ms"});
  for (const SummaryLine& s : summarize(report))
    csv += csv_line({s.method, s.term, std::to_string(s.cases), number(s.median_relative_l1),
                     number(s.worst_relative_l1), number(s.median_row_error),
                     number(s.worst_row_error), number(s.median_frame_ms)});
  return csv;
}

std::string convergence_csv(const Report& report) {
  std::string csv =
      csv_line({"case", "reference", "term", "samples", "sample_change", "lattice_change",
                "lattice_cells_per_wavelength", "converged"});
  for (const ConvergenceLine& l : reference_convergence(report))
    csv += csv_line({l.case_name, l.reference, l.term, std::to_string(l.samples),
                     number(l.sample_change), number(l.lattice_change),
                     number(l.lattice_cells_per_wavelength), l.converged()});
  return csv;
}

std::string seas_csv(const std::vector<SeaLine>& seas) {
  std::string csv = csv_line({"case", "method", "term", "seas", "rows", "row_error",
                              "basic_row_error", "closer_alone", "horizon_mean", "horizon_std",
                              "horizon_reference_mean", "horizon_pixels"});
  for (const SeaLine& l : seas)
    csv += csv_line({l.case_name, l.method, l.term, std::to_string(l.seas), std::to_string(l.rows),
                     number(l.row_error), number(l.basic_row_error),
                     l.closer_alone < 0 ? "" : std::to_string(l.closer_alone),
                     number(l.horizon.mean), number(l.horizon.std),
                     number(l.horizon.reference_mean), std::to_string(l.horizon.pixels)});
  return csv;
}

// horizon.csv's columns for the bands pooled over the seas.
std::string seas_horizon_csv(const std::vector<SeaLine>& seas) {
  std::string csv = csv_line({"case", "method", "term", "seas", "beta_lo_deg", "beta_hi_deg",
                              "pixels", "weight_rad2", "mean", "std", "reference_mean"});
  for (const SeaLine& l : seas)
    for (const HorizonBin& b : l.horizon.bins)
      csv += csv_line({l.case_name, l.method, l.term, std::to_string(l.seas), number(b.beta_lo_deg),
                       number(b.beta_hi_deg), std::to_string(b.pixels), number(b.weight),
                       number(b.mean), number(b.std), number(b.reference_mean)});
  return csv;
}

std::string claim_csv(const Report& report) {
  std::string csv = csv_line({"case", "camera_height_m", "term", "full_row_error",
                              "basic_row_error", "reference_uncertainty", "verdict"});
  for (const ClaimLine& l : fig10_claim(report))
    csv += csv_line({l.case_name, number(l.camera_height), l.term, number(l.full), number(l.basic),
                     number(l.uncertainty), l.verdict()});
  return csv;
}

// ---------------------------------------------------------------------------------------------
// index.html

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
  std::string h = "<h2>The references' convergence</h2>\n<p>Issue 6 asks that doubling the "
                  "reference's samples, and its sun's lattice, change no image row's total by " +
                  percent + " % or more (<a href=\"convergence.csv\">convergence.csv</a>). Of " +
                  std::to_string(lines.size()) + " references and terms: " +
                  std::to_string(yes) + " within it, <span" + (no ? " class=\"fail\"" : "") +
                  ">" + std::to_string(no) + " not</span>, " + std::to_string(undefined) +
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
         "</a></td><td class=\"t\">" + html(l.reference) + "</td><td class=\"t\">" +
         html(l.term) + "</td><td>" + std::to_string(l.samples) + "</td>" +
         cell(l.sample_change) + (l.with_sun ? cell(l.lattice_change) : "<td></td>") + "<td>" +
         short_number(l.lattice_cells_per_wavelength) + "</td></tr>\n";
  }
  return h + "</table>\n";
}

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

}  // namespace

bool CaseResult::passed() const {
  if (exit_status != expected_exit) return false;
  return expected_error.empty() || message.find(expected_error) != std::string::npos;
}

std::vector<SummaryLine> summarize(const Report& report) {
  struct Values {
    std::vector<double> l1, rows, ms;
  };
  std::vector<std::pair<std::string, std::string>> keys;  // (method, term), first seen first
  std::vector<Values> values;
  for (const CaseResult& c : report.cases)
    for (const MethodResult& m : c.methods) {
      if (m.method == "reference") continue;
      for (const TermResult& t : m.terms) {
        if (!measured(t)) continue;
        const std::pair<std::string, std::string> key{m.name, t.term};
        auto found = std::find(keys.begin(), keys.end(), key);
        if (found == keys.end()) {
          keys.push_back(key);
          values.emplace_back();
          found = keys.end() - 1;
        }
        Values& v = values[std::size_t(found - keys.begin())];
        v.l1.push_back(t.metrics.error.relative_l1.l);
        v.rows.push_back(t.metrics.row_error);
        v.ms.push_back(cost_ms(m, t));
      }
    }
  std::vector<SummaryLine> lines;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const Values& v = values[i];
    lines.push_back({.method = keys[i].first,
                     .term = keys[i].second,
                     .cases = static_cast<int>(v.l1.size()),
                     .median_relative_l1 = median_of(v.l1),
                     .worst_relative_l1 = max_of(v.l1),
                     .median_row_error = median_of(v.rows),
                     .worst_row_error = max_of(v.rows),
                     .median_frame_ms = median_of(v.ms)});
  }
  return lines;
}

namespace {
// A method's row totals (luminance) and its reference's, summed over seas, and which rows every
// sea compares (ratios: 1 there, NaN elsewhere, as row_error reads them). A row counts where
// each sea compares it (its totals defined), whether or not the reference has light there in
// that sea: a row without a glint in one sea and with some in another is what the sum is for
// (its ratio, and so its part of that sea's TermMetrics::row_error, is undefined where the
// reference's total is 0).
struct SummedRows {
  std::vector<ChannelValues> method, reference, ratios;
  int seas = 0;
  // Each sea's own row error over the rows it compares, in the seas' order (NaN: none lit).
  std::vector<double> own_row_errors;
  // Each sea's near-horizon band whose bins are the first such band's (pool_horizon_bands).
  std::vector<HorizonBand> bands;
};

// Over the cases of `seas` that measured `method`'s `term` against its reference (the case's, or
// the variant's own: measured_against).
SummedRows summed_rows(const std::vector<const CaseResult*>& seas, const std::string& method,
                       const std::string& term) {
  SummedRows sums;
  for (const CaseResult* c : seas) {
    const MethodResult* m = method_named(*c, method);
    if (!m) continue;
    const MethodResult* reference = measured_against(*c, *m);
    const TermResult* t = term_of(*m, term);
    const TermResult* r = reference ? term_of(*reference, term) : nullptr;
    if (!t || !r || !measured(*t) || !measured(*r)) continue;
    const std::vector<ChannelValues>& mt = t->metrics.row_totals;
    const std::vector<ChannelValues>& rt = r->metrics.row_totals;
    if (rt.size() != mt.size()) continue;
    if (sums.seas == 0) {
      sums.method.assign(mt.size(), ChannelValues{});
      sums.reference.assign(mt.size(), ChannelValues{});
      sums.ratios.assign(mt.size(), ChannelValues{1.0, 1.0, 1.0, 1.0});
    } else if (sums.ratios.size() != mt.size()) {
      continue;  // another image size: not the same view
    }
    double error = 0.0, total = 0.0;
    for (std::size_t y = 0; y < mt.size(); ++y) {
      if (!std::isfinite(mt[y].l) || !std::isfinite(rt[y].l)) {
        sums.ratios[y].l = kNaN;
        continue;
      }
      error += std::abs(mt[y].l - rt[y].l);
      total += rt[y].l;
      sums.method[y].l += mt[y].l;
      sums.reference[y].l += rt[y].l;
    }
    sums.own_row_errors.push_back(total > 0.0 ? error / total : kNaN);
    ++sums.seas;
    const HorizonBand& band = t->metrics.horizon;
    if (!band.bins.empty() && (sums.bands.empty() || same_horizon_bins(band, sums.bands.front())))
      sums.bands.push_back(band);
  }
  return sums;
}
}  // namespace

std::vector<SeaLine> summarize_seas(const Report& report) {
  std::vector<std::string> groups;  // the cases the seas are of, first seen first
  for (const CaseResult& c : report.cases)
    if (!c.sea_of.empty() && std::find(groups.begin(), groups.end(), c.sea_of) == groups.end())
      groups.push_back(c.sea_of);
  std::vector<SeaLine> lines;
  for (const std::string& group : groups) {
    std::vector<const CaseResult*> seas;
    for (const CaseResult& c : report.cases)
      if (c.sea_of == group && c.passed() && !c.methods.empty()) seas.push_back(&c);
    std::vector<std::pair<std::string, std::string>> keys;  // (method, term), first seen first
    for (const CaseResult* c : seas)
      for (const MethodResult& m : c->methods) {
        if (m.method == "reference") continue;
        for (const TermResult& t : m.terms) {
          const std::pair<std::string, std::string> key{m.name, t.term};
          if (measured(t) && std::find(keys.begin(), keys.end(), key) == keys.end())
            keys.push_back(key);
        }
      }
    for (const auto& [method, term] : keys) {
      SummedRows sums = summed_rows(seas, method, term);
      if (sums.seas == 0) continue;
      SeaLine line{.case_name = group, .method = method, .term = term, .seas = sums.seas};
      // The basic method beside it, on the seas and rows both have, where both are measured
      // against the case's reference (a variant with its own reference is another sea).
      const MethodResult* first = method_named(*seas.front(), method);
      const bool own_reference = first && !first->reference.empty();
      if (method != "basic" && !own_reference) {
        const SummedRows basic = summed_rows(seas, "basic", term);
        if (basic.seas == sums.seas && basic.ratios.size() == sums.ratios.size()) {
          for (std::size_t y = 0; y < sums.ratios.size(); ++y)
            if (!std::isfinite(basic.ratios[y].l)) sums.ratios[y].l = kNaN;
          line.basic_row_error = row_error(basic.method, basic.reference, sums.ratios);
          line.closer_alone = 0;
          for (std::size_t k = 0; k < sums.own_row_errors.size(); ++k)
            line.closer_alone += sums.own_row_errors[k] < basic.own_row_errors[k] ? 1 : 0;
        }
      }
      line.row_error = row_error(sums.method, sums.reference, sums.ratios);
      line.horizon = pool_horizon_bands(sums.bands);
      for (std::size_t y = 0; y < sums.ratios.size(); ++y) {
        const bool counts = std::isfinite(sums.ratios[y].l);
        line.rows += counts ? 1 : 0;
        line.method_rows.push_back(counts ? sums.method[y].l : kNaN);
        line.reference_rows.push_back(counts ? sums.reference[y].l : kNaN);
      }
      lines.push_back(line);
    }
  }
  return lines;
}

std::string ClaimLine::verdict() const {
  if (!std::isfinite(full) || !std::isfinite(basic)) return "undefined";
  if (same()) return "same";
  if (indistinct()) return "indistinct";
  return full < basic ? "closer" : "farther";
}

namespace {
// The largest change of a reference's convergence tests for `term` (the samples' and, with the
// sun, the lattice's); NaN: not measured.
double largest_change(const MethodResult& reference, const std::string& term) {
  double u = kNaN;
  const auto take = [&](double v) {
    if (std::isfinite(v)) u = std::isfinite(u) ? std::max(u, v) : v;
  };
  for (const auto& [t, change] : reference.convergence)
    if (t == term) take(change);
  // One lattice for every term with the sun (measured on the first of them).
  if (term == "sun" || term == "all")
    for (const auto& [t, change] : reference.lattice_convergence) take(change);
  return u;
}
}  // namespace

std::vector<double> reference_rows_uncertainty(const MethodResult* reference,
                                               const std::string& term, std::size_t rows) {
  if (!reference) return std::vector<double>(rows, kNaN);
  for (const auto& [t, u] : reference->row_uncertainty)
    if (t == term) return u.size() == rows ? u : std::vector<double>(rows, kNaN);
  return std::vector<double>(rows, largest_change(*reference, term));
}

std::string ConvergenceLine::converged() const {
  const bool lattice_unknown = with_sun && !std::isfinite(lattice_change);
  if (std::isfinite(sample_change) && sample_change >= kConvergenceTolerance) return "no";
  if (with_sun && std::isfinite(lattice_change) && lattice_change >= kConvergenceTolerance)
    return "no";
  if (!std::isfinite(sample_change) || lattice_unknown) return "undefined";
  return "yes";
}

std::vector<ConvergenceLine> reference_convergence(const Report& report) {
  std::vector<ConvergenceLine> lines;
  for (const CaseResult& c : report.cases)
    for (const MethodResult& m : c.methods) {
      if (m.method != "reference") continue;
      for (const TermResult& t : m.terms) {
        ConvergenceLine line{.case_name = c.name, .reference = m.name, .term = t.term};
        line.samples = t.samples;
        for (const auto& [term, change] : m.convergence)
          if (term == t.term) line.sample_change = change;
        line.with_sun = t.term == "sun" || t.term == "all";
        if (line.with_sun) {
          // One lattice per reference (its largest change, should a report hold more).
          for (const auto& [term, change] : m.lattice_convergence)
            if (std::isfinite(change))
              line.lattice_change = std::isfinite(line.lattice_change)
                                        ? std::max(line.lattice_change, change)
                                        : change;
          for (const auto& [term, cells] : m.lattice_cells_per_wavelength)
            line.lattice_cells_per_wavelength = cells;
        }
        lines.push_back(line);
      }
    }
  return lines;
}

std::vector<ClaimLine> fig10_claim(const Report& report) {
  std::vector<ClaimLine> lines;
  for (const CaseResult& c : report.cases) {
    if (!(c.camera_height >= kClaimMinHeight)) continue;
    const MethodResult* full = method_named(c, "full");
    const MethodResult* basic = method_named(c, "basic");
    if (!full || !basic) continue;
    const MethodResult* reference = measured_against(c, *full);
    for (const TermResult& f : full->terms) {
      const TermResult* b = term_of(*basic, f.term);
      const TermResult* r = reference ? term_of(*reference, f.term) : nullptr;
      if (!measured(f) || !b || !measured(*b)) continue;
      ClaimLine line{.case_name = c.name,
                     .camera_height = c.camera_height,
                     .term = f.term,
                     .full = f.metrics.row_error,
                     .basic = b->metrics.row_error};
      // A black reference defines no row (compare_images), so its convergence, a ratio of
      // invisible tails (2e5 in stop 22's wind10_8km_high_sun), gives no uncertainty either.
      const std::size_t rows = f.metrics.row_ratios.size();
      if (r && r->metrics.row_totals.size() == rows && b->metrics.row_totals.size() == rows &&
          f.metrics.row_totals.size() == rows)
        line.uncertainty = row_error_difference_bound(
            f.metrics.row_totals, b->metrics.row_totals, r->metrics.row_totals,
            f.metrics.row_ratios, reference_rows_uncertainty(reference, f.term, rows));
      lines.push_back(std::move(line));
    }
  }
  return lines;
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

std::string report_json(const Report& report) {
  ojson j;
  j["suite"] = report.suite;
  j["description"] = report.description;
  j["source"] = report.source;
  j["version"] = report.version;
  j["backend"] = report.backend;
  j["renderer"] = report.renderer;
  j["gl_version"] = report.gl_version;
  j["context"] = report.context;
  j["horizon"] = {{"depth_deg", report.horizon.depth_deg}, {"bin_deg", report.horizon.bin_deg}};
  j["timing"] = {{"width", report.timing.width},
                 {"height", report.timing.height},
                 {"frames", report.timing.frames}};
  j["reference"] = {{"pixel_samples", report.reference.pixel_samples},
                    {"pixel_samples_without_sun", report.reference.pixel_samples_without_sun},
                    {"sun_normal_samples", report.reference.sun_normal_samples},
                    {"sun_cells_per_wavelength", report.reference.sun_cells_per_wavelength},
                    {"sun_max_cells_per_wavelength", report.reference.sun_max_cells_per_wavelength},
                    {"sun", report.reference.sun},
                    {"sun_refine", report.reference.sun_refine},
                    {"grid_cell", report.reference.grid_cell},
                    {"check_convergence", report.reference.check_convergence}};
  j["suite_cases"] = std::max(report.suite_cases, static_cast<int>(report.cases.size()));
  j["cases"] = ojson::array();
  for (const CaseResult& c : report.cases) {
    ojson jc;
    jc["name"] = c.name;
    jc["description"] = c.description;
    jc["set"] = ojson::object();
    for (const SceneOverride& o : c.set) jc["set"][o.key] = ojson::parse(o.value_json);
    jc["expected_exit"] = c.expected_exit;
    jc["expected_error"] = c.expected_error;
    jc["exit_status"] = c.exit_status;
    jc["message"] = c.message;
    jc["passed"] = c.passed();
    jc["camera_height"] = c.camera_height;
    if (!c.fingerprint.empty()) jc["fingerprint"] = c.fingerprint;
    if (c.seconds) jc["seconds"] = *c.seconds;
    if (!c.sea_of.empty()) {
      jc["sea_of"] = c.sea_of;
      jc["sea"] = c.sea;
    }
    if (!c.gl_version.empty()) jc["gl_version"] = c.gl_version;
    if (c.timing.enabled())
      jc["timing"] = {
          {"width", c.timing.width}, {"height", c.timing.height}, {"frames", c.timing.frames}};
    jc["methods"] = ojson::array();
    for (const MethodResult& m : c.methods) {
      ojson jm;
      jm["name"] = m.name;
      jm["method"] = m.method;
      jm["plain"] = m.plain;
      jm["reference"] = m.reference;
      if (m.timing_ms) jm["timing_ms"] = *m.timing_ms;
      jm["convergence"] = ojson::object();
      for (const auto& [term, change] : m.convergence) jm["convergence"][term] = change;
      if (!m.lattice_cells_per_wavelength.empty()) {
        jm["lattice_cells_per_wavelength"] = ojson::object();
        for (const auto& [term, cells] : m.lattice_cells_per_wavelength)
          jm["lattice_cells_per_wavelength"][term] = cells;
      }
      if (!m.lattice_convergence.empty()) {
        jm["lattice_convergence"] = ojson::object();
        for (const auto& [term, change] : m.lattice_convergence)
          jm["lattice_convergence"][term] = change;
      }
      jm["resolved_rows"] = ojson::object();
      for (const auto& [term, rows] : m.resolved_rows) jm["resolved_rows"][term] = rows;
      if (!m.row_uncertainty.empty()) {
        jm["row_uncertainty"] = ojson::object();
        for (const auto& [term, rows] : m.row_uncertainty) jm["row_uncertainty"][term] = rows;
      }
      jm["terms"] = ojson::array();
      for (const TermResult& t : m.terms) {
        const ErrorStats& e = t.metrics.error;
        const HorizonBand& h = t.metrics.horizon;
        ojson jt;
        jt["term"] = t.term;
        jt["frame_ms"] = t.frame_ms;
        jt["samples"] = t.samples;
        jt["exr"] = t.exr;
        jt["png"] = t.png;
        if (t.flicker) jt["flicker"] = *t.flicker;
        if (t.temporal_error) jt["temporal_error"] = *t.temporal_error;
        if (t.seconds) jt["seconds"] = *t.seconds;
        jt["reference_black"] = t.metrics.reference_black;
        jt["max_row_deviation"] = t.metrics.max_row_deviation;
        jt["mean_row_deviation"] = t.metrics.mean_row_deviation;
        jt["row_error"] = t.metrics.row_error;
        jt["error"] = {{"pixels", e.pixels},
                       {"relative_l1", channels_json(e.relative_l1)},
                       {"relative_rms", channels_json(e.relative_rms)},
                       {"mean_abs", channels_json(e.mean_abs)},
                       {"reference_mean", channels_json(e.reference_mean)}};
        ojson bins = ojson::array();
        for (const HorizonBin& b : h.bins)
          bins.push_back({{"beta_lo_deg", b.beta_lo_deg},
                          {"beta_hi_deg", b.beta_hi_deg},
                          {"pixels", b.pixels},
                          {"weight", b.weight},
                          {"mean", b.mean},
                          {"std", b.std},
                          {"reference_mean", b.reference_mean}});
        jt["horizon"] = {{"mean", h.mean},
                         {"std", h.std},
                         {"reference_mean", h.reference_mean},
                         {"pixels", h.pixels},
                         {"bins", bins}};
        jt["rows"] = {{"columns", {"l", "r", "g", "b"}},
                      {"total", rows_json(t.metrics.row_totals)},
                      {"ratio", rows_json(t.metrics.row_ratios)}};
        jm["terms"].push_back(std::move(jt));
      }
      jc["methods"].push_back(std::move(jm));
    }
    j["cases"].push_back(std::move(jc));
  }
  // NaN (an undefined ratio or error) is written as null.
  return j.dump(1) + "\n";
}

Report report_from_json(const std::string& json_text) {
  const ojson j = ojson::parse(json_text);
  Report report;
  report.suite = j.at("suite");
  report.description = j.at("description");
  report.source = j.at("source");
  report.version = j.at("version");
  report.backend = j.at("backend");
  report.renderer = j.at("renderer");
  report.gl_version = j.value("gl_version", std::string());
  report.context = j.value("context", std::string());
  report.horizon = {get_number(j.at("horizon").at("depth_deg")),
                    get_number(j.at("horizon").at("bin_deg"))};
  report.suite_cases = j.value("suite_cases", 0);
  const auto timing_from = [](const ojson& t) {
    return TimingSettings{t.at("width").get<int>(), t.at("height").get<int>(),
                          t.at("frames").get<int>()};
  };
  if (j.contains("timing")) report.timing = timing_from(j.at("timing"));
  if (j.contains("reference")) {
    const ojson& jr = j.at("reference");
    report.reference.pixel_samples = jr.at("pixel_samples");
    report.reference.pixel_samples_without_sun = jr.value("pixel_samples_without_sun", 0);
    report.reference.sun_normal_samples = jr.at("sun_normal_samples");
    report.reference.sun_cells_per_wavelength = get_number(jr.at("sun_cells_per_wavelength"));
    report.reference.sun = jr.value("sun", std::string("gathered"));  // older reports gathered
    report.reference.sun_refine = jr.value("sun_refine", 1);          // and did not refine
    report.reference.sun_max_cells_per_wavelength =  // nor double (before stop 25)
        jr.contains("sun_max_cells_per_wavelength")
            ? get_number(jr.at("sun_max_cells_per_wavelength"))
            : 0.0;
    // One vertex per pixel before stop 44.
    report.reference.grid_cell =
        jr.contains("grid_cell") ? get_number(jr.at("grid_cell")) : ocean::kReferenceGridCell;
    report.reference.check_convergence = jr.at("check_convergence");
  }
  for (const ojson& jc : j.at("cases")) {
    CaseResult c;
    c.name = jc.at("name");
    c.description = jc.at("description");
    for (const auto& [key, value] : jc.at("set").items()) c.set.push_back({key, value.dump()});
    c.expected_exit = jc.at("expected_exit");
    c.expected_error = jc.at("expected_error");
    c.exit_status = jc.at("exit_status");
    c.message = jc.at("message");
    c.camera_height = get_number(jc.at("camera_height"));
    c.fingerprint = jc.value("fingerprint", std::string());
    c.seconds = optional_from(jc, "seconds");
    c.sea_of = jc.value("sea_of", std::string());
    c.sea = jc.value("sea", 0);
    c.gl_version = jc.value("gl_version", std::string());
    std::vector<std::pair<std::size_t, std::size_t>> without_row_error;  // (method, term)
    if (jc.contains("timing")) c.timing = timing_from(jc.at("timing"));
    for (const ojson& jm : jc.at("methods")) {
      MethodResult m;
      m.name = jm.at("name");
      m.method = jm.at("method");
      m.plain = jm.at("plain");
      m.reference = jm.value("reference", std::string());
      m.timing_ms = optional_from(jm, "timing_ms");
      for (const auto& [term, change] : jm.at("convergence").items())
        m.convergence.push_back({term, get_number(change)});
      if (jm.contains("lattice_convergence"))
        for (const auto& [term, change] : jm.at("lattice_convergence").items())
          m.lattice_convergence.push_back({term, get_number(change)});
      if (jm.contains("lattice_cells_per_wavelength"))
        for (const auto& [term, cells] : jm.at("lattice_cells_per_wavelength").items())
          m.lattice_cells_per_wavelength.push_back({term, get_number(cells)});
      if (jm.contains("resolved_rows"))
        for (const auto& [term, rows] : jm.at("resolved_rows").items())
          m.resolved_rows.push_back({term, rows.get<int>()});
      if (jm.contains("row_uncertainty"))  // since stop 23
        for (const auto& [term, rows] : jm.at("row_uncertainty").items()) {
          std::vector<double> u;
          for (const ojson& v : rows) u.push_back(get_number(v));
          m.row_uncertainty.push_back({term, std::move(u)});
        }
      for (const ojson& jt : jm.at("terms")) {
        TermResult t;
        t.term = jt.at("term");
        t.frame_ms = get_number(jt.at("frame_ms"));
        t.samples = jt.value("samples", 0);
        t.exr = jt.at("exr");
        t.png = jt.at("png");
        t.flicker = optional_from(jt, "flicker");
        t.temporal_error = optional_from(jt, "temporal_error");
        t.seconds = optional_from(jt, "seconds");
        t.metrics.max_row_deviation = get_number(jt.at("max_row_deviation"));
        const ojson& je = jt.at("error");
        t.metrics.error.pixels = je.at("pixels");
        t.metrics.error.relative_l1 = channels_from(je.at("relative_l1"));
        t.metrics.error.relative_rms = channels_from(je.at("relative_rms"));
        t.metrics.error.mean_abs = channels_from(je.at("mean_abs"));
        t.metrics.error.reference_mean = channels_from(je.at("reference_mean"));
        // Since stop 23; a term that compared no pixel is not black (the first reports of stop
        // 23 called it so).
        t.metrics.reference_black =
            jt.value("reference_black", false) && t.metrics.error.pixels > 0;
        const ojson& jh = jt.at("horizon");
        HorizonBand& h = t.metrics.horizon;
        h.mean = get_number(jh.at("mean"));
        h.std = get_number(jh.at("std"));
        h.reference_mean = get_number(jh.at("reference_mean"));
        h.pixels = jh.at("pixels");
        for (const ojson& jb : jh.at("bins"))
          h.bins.push_back({get_number(jb.at("beta_lo_deg")), get_number(jb.at("beta_hi_deg")),
                            jb.at("pixels").get<int>(), get_number(jb.at("weight")),
                            get_number(jb.at("mean")), get_number(jb.at("std")),
                            get_number(jb.at("reference_mean"))});
        t.metrics.row_totals = rows_from(jt.at("rows").at("total"));
        t.metrics.row_ratios = rows_from(jt.at("rows").at("ratio"));
        // A report written before stop 22 has no mean: it is its rows' (metrics.hpp).
        t.metrics.mean_row_deviation = jt.contains("mean_row_deviation")
                                           ? get_number(jt.at("mean_row_deviation"))
                                           : mean_row_deviation(t.metrics.row_ratios);
        if (jt.contains("row_error"))
          t.metrics.row_error = get_number(jt.at("row_error"));
        else
          without_row_error.push_back({c.methods.size(), m.terms.size()});
        m.terms.push_back(std::move(t));
      }
      c.methods.push_back(std::move(m));
    }
    // A report written before stop 22 has no row error: it is the rows' against those of the
    // reference each method was measured against, which the report holds.
    for (const auto& [mi, ti] : without_row_error) {
      const MethodResult& m = c.methods[mi];
      TermMetrics& metrics = c.methods[mi].terms[ti].metrics;
      const MethodResult* against = measured_against(c, m);
      const TermResult* reference = against ? term_of(*against, m.terms[ti].term) : nullptr;
      metrics.row_error =
          reference && reference->metrics.row_totals.size() == metrics.row_totals.size()
              ? row_error(metrics.row_totals, reference->metrics.row_totals, metrics.row_ratios)
              : kNaN;
    }
    report.cases.push_back(std::move(c));
  }
  return report;
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
