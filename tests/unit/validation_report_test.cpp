// The validation report (validation/include/thalassa/validation/report.hpp): every file is
// written, the plots are real PNGs drawn by gnuplot (installed by scripts/setup), and the CSV
// and JSON read back to the same numbers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "thalassa/engine/image.hpp"
#include "thalassa/validation/report.hpp"

namespace thalassa::validation {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// RFC 4180 lines (no line breaks inside fields in our files).
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quoted) {
        if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
          fields.back() += '"';
          ++i;
        } else if (c == '"') {
          quoted = false;
        } else {
          fields.back() += c;
        }
      } else if (c == '"') {
        quoted = true;
      } else if (c == ',') {
        fields.emplace_back();
      } else {
        fields.back() += c;
      }
    }
    rows.push_back(std::move(fields));
  }
  return rows;
}

// A CSV number: empty is undefined (NaN).
double csv_number(const std::string& s) { return s.empty() ? NAN : std::stod(s); }

// Equal as the report promises: the same double, or both undefined.
void expect_same(double got, double want, const std::string& what) {
  if (std::isnan(want))
    EXPECT_TRUE(std::isnan(got)) << what << ": " << got;
  else
    EXPECT_EQ(got, want) << what;
}

// Metrics with awkward numbers (not short decimals), undefined ratios, and an empty bin.
TermMetrics synthetic_metrics(double seed, int rows) {
  TermMetrics m;
  for (int y = 0; y < rows; ++y) {
    const double t = seed * (y + 1) / 3.0;
    m.row_totals.push_back({t, t * 1.1, t / 7.0, std::sqrt(t)});
    m.row_ratios.push_back(y < 3 ? ChannelValues{NAN, NAN, NAN, NAN}
                                 : ChannelValues{1.0 + t / 100, 1.0 - t / 300, 1.0 / 3.0, 0.9});
  }
  m.reference_black = seed > 2.5;  // some terms of the report, not all
  m.max_row_deviation = seed / 100.0 + 1.0 / 3.0;
  m.mean_row_deviation = seed / 300.0 + 1.0 / 7.0;
  m.row_error = seed / 500.0 + 1.0 / 9.0;
  m.error.pixels = 1234;
  m.error.relative_l1 = {seed / 10 + 1e-17, 0.1 / 3, 0.2 / 3, 0.3 / 7};
  m.error.relative_rms = {seed / 9, 0.11, 0.12, NAN};
  m.error.mean_abs = {0.001 / 3, 0.002, 0.003, 0.004};
  m.error.reference_mean = {0.25, 0.3, 0.2, 0.1};
  for (int k = 0; k < 10; ++k) {
    HorizonBin b{0.5 * k,
                 0.5 * (k + 1),
                 100 + k,
                 1e-4 * (k + 1) / 3.0,
                 seed * 0.01 * k,
                 seed * 0.002 * (k + 1) / 7.0,
                 0.3};
    if (k == 9) b = {4.5, 5.0, 0, 0.0, NAN, NAN, NAN};  // an empty bin
    m.horizon.bins.push_back(b);
  }
  m.horizon.mean = seed * 0.04;
  m.horizon.std = seed * 0.0011 / 3.0;
  m.horizon.reference_mean = 0.3;
  m.horizon.pixels = 945;
  return m;
}

Report synthetic_report() {
  Report report;
  report.suite = "unit";
  report.description = "a report with <markup> & \"quotes\", to escape";
  report.source = "unit.json";
  report.backend = "osmesa";
  report.renderer = "llvmpipe (LLVM 15.0.6, 256 bits)";
  report.gl_version = "4.5 (Core Profile) Mesa 22.3.6";
  report.context = "EGL 1.5 device platform (Mesa Project), told of GPU resets";
  report.reference.pixel_samples = 64;
  report.reference.pixel_samples_without_sun = 512;
  report.reference.sun_normal_samples = 4096;
  report.reference.sun_cells_per_wavelength = 12.5;
  report.reference.sun = "gathered";  // not the default: read back as written
  report.reference.sun_refine = 4;
  report.reference.grid_cell = 0.25;
  report.reference.sun_max_cells_per_wavelength = 25.0;
  report.version = "0.1.0";
  CaseResult c;
  c.name = "wind10_100m_low_sun";
  c.description = "10 m/s, 100 m, low sun, with a comma";
  c.set = {{"ocean.wind_speed", "10"}, {"camera.height", "100"}, {"ocean.spectrum", "\"omega-2\""}};
  c.camera_height = 100.0;
  c.timing = {1280, 720, 5};
  report.timing = c.timing;
  const struct {
    const char* name;
    const char* method;
    bool plain;
    double ms;
  } methods[] = {{"reference", "reference", true, 5123.25},
                 {"basic", "basic", true, 40.5},
                 {"full", "full", true, 61.0 / 3.0},
                 {"full_cell4", "full", false, 90.125}};
  double seed = 1.0;
  for (const auto& m : methods) {
    MethodResult r{m.name, m.method, m.plain, {}, {}};
    if (r.name == "full_cell4") r.supersample = 3;  // read back as written (stop 53)
    for (const char* term : {"sun", "all"}) {
      TermResult t;
      t.term = term;
      t.frame_ms = m.ms * (term == std::string("all") ? 1.5 : 1.0);
      t.samples = m.method == std::string("reference") ? 64 : 1;
      t.exr = std::string("images/") + c.name + "_" + m.name + "_" + term + ".exr";
      t.png = std::string("images/") + c.name + "_" + m.name + "_" + term + ".png";
      t.metrics = synthetic_metrics(seed += 0.7, 40);
      if (term == std::string("all")) {
        t.flicker = 0.05 * seed;
        t.temporal_error = 0.1 / seed;
      }
      // What the term cost validate; unknown (a report before stop 28) for full_cell4's.
      if (m.name != std::string("full_cell4")) t.seconds = m.ms * 0.0031 + seed / 7.0;
      r.terms.push_back(std::move(t));
    }
    if (r.method != "reference") r.timing_ms = m.ms * 7.0 / 3.0;  // timed apart
    if (r.method == "reference") {
      r.convergence = {{"sun", 0.004}, {"all", 0.0071}};
      r.lattice_convergence = {{"sun", 0.018}, {"all", 0.0175}};
      r.lattice_cells_per_wavelength = {{"sun", 17.677669529663689}};
      // Per row for the sun (some rows not measured); none for "all": its rows take the
      // largest change of its tests.
      std::vector<double> u(40);
      for (int y = 0; y < 40; ++y) u[y] = y % 9 == 0 ? NAN : 0.001 * y / 3.0;
      r.row_uncertainty = {{"sun", u}};
    }
    c.methods.push_back(std::move(r));
  }
  c.seconds = 123.0 / 7.0;
  c.gl_version = "4.5 (Core Profile) Mesa 22.3.5";  // kept from a run under an older driver
  report.cases.push_back(c);
  CaseResult bad;
  bad.name = "lat_out_of_range";
  bad.set = {{"camera.lat", "90.5"}};
  bad.expected_exit = 2;
  bad.expected_error = "camera.lat: expected";
  bad.exit_status = 2;
  bad.message =
      "v.json: cases[1].set: camera.lat: expected a number in [-90, 90] (degrees), got 90.5";
  report.cases.push_back(bad);
  return report;
}

class ValidationReport : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("thalassa_report_" + std::to_string(getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ValidationReport, WritesEveryFileWithPlotsDrawnByGnuplot) {
  const Report report = synthetic_report();
  ReportOptions options;
  options.plot_width = 640;
  options.plot_height = 400;
  const std::vector<std::string> written = write_report(report, dir_.string(), options);
  for (const char* name :
       {"results.json", "metrics.csv", "rows.csv", "horizon.csv", "cases.csv", "summary.csv",
        "claim.csv", "convergence.csv", "seas.csv", "seas_horizon.csv", "index.html"})
    EXPECT_TRUE(std::find(written.begin(), written.end(), name) != written.end()) << name;
  const std::string c = report.cases[0].name;
  // Per term: rows and horizon; per case: error against time. The case that did not render has
  // no plots.
  const std::vector<std::string> plots = {
      c + "_sun_rows",    c + "_all_rows",      c + "_error_time",   c + "_sun_horizon",
      c + "_all_horizon", "summary_sun_height", "summary_all_height"};
  for (const std::string& p : plots) {
    for (const char* ext : {".dat", ".gp", ".png"}) {
      const std::string rel = "plots/" + p + ext;
      EXPECT_TRUE(fs::is_regular_file(dir_ / rel)) << rel;
      EXPECT_TRUE(std::find(written.begin(), written.end(), rel) != written.end()) << rel;
    }
    const Image png = read_image((dir_ / "plots" / (p + ".png")).string());
    EXPECT_EQ(png.width, 640) << p;
    EXPECT_EQ(png.height, 400) << p;
  }
  for (const std::string& rel : written) EXPECT_TRUE(fs::is_regular_file(dir_ / rel)) << rel;
  EXPECT_EQ(written.size(), 11u + 3u * plots.size());
  // Nothing pending or temporary is left.
  for (const auto& entry : fs::recursive_directory_iterator(dir_))
    EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
  // index.html links every plot and image relatively, and escapes text.
  const std::string index = read_text(dir_ / "index.html");
  for (const std::string& p : plots)
    EXPECT_NE(index.find("src=\"plots/" + p + ".png\""), std::string::npos) << p;
  for (const TermResult& t : report.cases[0].methods[1].terms) {
    EXPECT_NE(index.find("src=\"" + t.png + "\""), std::string::npos) << t.png;
    EXPECT_NE(index.find("href=\"" + t.exr + "\""), std::string::npos) << t.exr;
  }
  EXPECT_NE(index.find("&lt;markup&gt; &amp; &quot;quotes&quot;"), std::string::npos);
  // The driver and the context of the run, and the case rendered under another driver.
  EXPECT_NE(index.find("OpenGL 4.5 (Core Profile) Mesa 22.3.6; context EGL 1.5 device platform "
                       "(Mesa Project), told of GPU resets."),
            std::string::npos);
  EXPECT_NE(index.find("Rendered under OpenGL 4.5 (Core Profile) Mesa 22.3.5: "
                       "wind10_100m_low_sun.</p>"),
            std::string::npos);
  EXPECT_EQ(index.find("lat_out_of_range.</p>"), std::string::npos);
  EXPECT_NE(index.find("Of 2 references and terms: 0 within it, <span class=\"fail\">2 not</span>"),
            std::string::npos);
  EXPECT_NE(index.find("its sun gathered in cells"), std::string::npos);
  EXPECT_NE(index.find("cut into 4 x 4 subcells"), std::string::npos);
  EXPECT_NE(index.find("half the cells): sun 1.8%; all 1.75%; its lattice 17.68 cells per "
                       "shortest wavelength (sun);"),
            std::string::npos);
  EXPECT_NE(index.find("doubles them (per wavelength times sqrt 2, per pixel times 2) up to 1/25 "
                       "of the shortest wavelength"),
            std::string::npos);
  EXPECT_EQ(index.find("<markup>"), std::string::npos);
  EXPECT_EQ(index.find("=\"/"), std::string::npos);  // no absolute link
  // The row plot has the plain methods' curves only; the error plot every method but the
  // reference, which is a line at its frame time.
  const std::string rows_gp = read_text(dir_ / "plots" / (c + "_sun_rows.gp"));
  EXPECT_NE(rows_gp.find("title 'basic'"), std::string::npos);
  EXPECT_EQ(rows_gp.find("full_cell4"), std::string::npos);
  const std::string error_dat = read_text(dir_ / "plots" / (c + "_error_time.dat"));
  EXPECT_NE(error_dat.find("full_cell4 "), std::string::npos);
  EXPECT_EQ(error_dat.find("\nreference "), std::string::npos);
  // Its terms' labels a quarter of the height apart: two terms often take the same time.
  const std::string error_gp = read_text(dir_ / "plots" / (c + "_error_time.gp"));
  EXPECT_NE(error_gp.find("'reference (sun)' at 5123.25, graph 0.980000 right"), std::string::npos)
      << error_gp;
  EXPECT_NE(error_gp.find("'reference (all)' at 7684.875, graph 0.740000 right"), std::string::npos)
      << error_gp;
}

// A suite without a reference (the stress suite) measures nothing: the report has its tables
// and images, and no plot (gnuplot refuses to plot no data; it must not be asked to).
TEST_F(ValidationReport, WithoutAReferenceThereIsNothingToPlot) {
  Report report = synthetic_report();
  for (CaseResult& c : report.cases)
    for (MethodResult& m : c.methods)
      for (TermResult& t : m.terms) t.metrics = TermMetrics{};
  const std::vector<std::string> written = write_report(report, dir_.string());
  EXPECT_TRUE(fs::is_regular_file(dir_ / "index.html"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "metrics.csv"));
  for (const std::string& rel : written)
    EXPECT_EQ(rel.rfind("plots/", 0), std::string::npos) << rel;
}

TEST_F(ValidationReport, CsvAndJsonReadBackToTheSameNumbers) {
  const Report report = synthetic_report();
  write_report(report, dir_.string());
  const CaseResult& c = report.cases[0];
  std::map<std::pair<std::string, std::string>, const TermResult*> terms;
  for (const MethodResult& m : c.methods)
    for (const TermResult& t : m.terms) terms[{m.name, t.term}] = &t;

  // metrics.csv: one line per method and term, by column name.
  const auto metrics = parse_csv(read_text(dir_ / "metrics.csv"));
  ASSERT_EQ(metrics.size(), 1u + terms.size());
  std::map<std::string, std::size_t> col;
  for (std::size_t i = 0; i < metrics[0].size(); ++i) col[metrics[0][i]] = i;
  for (std::size_t i = 1; i < metrics.size(); ++i) {
    const auto& f = metrics[i];
    ASSERT_EQ(f.size(), metrics[0].size());
    EXPECT_EQ(f[col["case"]], c.name);
    const TermResult& t = *terms.at({f[col["method"]], f[col["term"]]});
    const std::string what = f[col["method"]] + "/" + f[col["term"]];
    expect_same(csv_number(f[col["frame_ms"]]), t.frame_ms, what + " frame_ms");
    const MethodResult* method = nullptr;
    for (const MethodResult& m : c.methods)
      if (m.name == f[col["method"]]) method = &m;
    ASSERT_NE(method, nullptr);
    expect_same(csv_number(f[col["timing_ms"]]), method->timing_ms.value_or(NAN),
                what + " timing_ms");
    EXPECT_EQ(f[col["samples"]], std::to_string(t.samples)) << what;
    expect_same(csv_number(f[col["rel_l1_l"]]), t.metrics.error.relative_l1.l, what + " l1");
    expect_same(csv_number(f[col["rel_l1_b"]]), t.metrics.error.relative_l1.b, what + " l1 b");
    expect_same(csv_number(f[col["rel_rms_b"]]), t.metrics.error.relative_rms.b, what + " rms b");
    EXPECT_EQ(f[col["reference_black"]], t.metrics.reference_black ? "1" : "0") << what;
    expect_same(csv_number(f[col["max_row_deviation"]]), t.metrics.max_row_deviation, what);
    expect_same(csv_number(f[col["mean_row_deviation"]]), t.metrics.mean_row_deviation, what);
    expect_same(csv_number(f[col["row_error"]]), t.metrics.row_error, what);
    expect_same(csv_number(f[col["horizon_std"]]), t.metrics.horizon.std, what + " std");
    expect_same(csv_number(f[col["flicker"]]), t.flicker.value_or(NAN), what + " flicker");
    expect_same(csv_number(f[col["reference_flicker"]]),
                terms.at({"reference", t.term})->flicker.value_or(NAN), what + " ref flicker");
    EXPECT_EQ(f[col["png"]], t.png);
    expect_same(csv_number(f[col["seconds"]]), t.seconds.value_or(NAN), what + " seconds");
  }
  // rows.csv: every row total and ratio.
  const auto rows = parse_csv(read_text(dir_ / "rows.csv"));
  ASSERT_EQ(rows.size(), 1u + terms.size() * 40u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& f = rows[i];
    const TermResult& t = *terms.at({f[1], f[2]});
    const std::size_t y = std::stoul(f[3]);
    expect_same(csv_number(f[4]), t.metrics.row_totals[y].l, "total");
    expect_same(csv_number(f[7]), t.metrics.row_totals[y].b, "total b");
    expect_same(csv_number(f[8]), t.metrics.row_ratios[y].l, "ratio");
    // The reference's uncertainty of the row where the ratio is defined: per row for the sun;
    // for "all" the largest change of its tests (the lattices', one for every term with the
    // sun: 0.018).
    const double u = !std::isfinite(t.metrics.row_ratios[y].l) ? NAN
                     : f[2] == "sun" ? (y % 9 == 0 ? NAN : 0.001 * y / 3.0)
                                     : 0.018;
    expect_same(csv_number(f[12]), u, "reference_uncertainty");
  }
  // horizon.csv: every bin.
  const auto horizon = parse_csv(read_text(dir_ / "horizon.csv"));
  ASSERT_EQ(horizon.size(), 1u + terms.size() * 10u);
  for (std::size_t i = 1; i < horizon.size(); ++i) {
    const auto& f = horizon[i];
    const TermResult& t = *terms.at({f[1], f[2]});
    const HorizonBin& b = t.metrics.horizon.bins[(i - 1) % 10];
    expect_same(csv_number(f[3]), b.beta_lo_deg, "lo");
    expect_same(csv_number(f[6]), b.weight, "weight");
    expect_same(csv_number(f[7]), b.mean, "mean");
    expect_same(csv_number(f[8]), b.std, "std");
  }
  // convergence.csv: the reference's two terms, each above 1 % by its sun's lattice (one per
  // reference: the larger of its two entries, 1.8 %).
  const auto convergence = parse_csv(read_text(dir_ / "convergence.csv"));
  ASSERT_EQ(convergence.size(), 3u);
  EXPECT_EQ(convergence[0],
            (std::vector<std::string>{"case", "reference", "term", "samples", "sample_change",
                                      "lattice_change", "lattice_cells_per_wavelength",
                                      "converged"}));
  EXPECT_EQ(convergence[1][2], "sun");
  EXPECT_EQ(convergence[1][3], "64");
  EXPECT_DOUBLE_EQ(std::stod(convergence[1][4]), 0.004);
  EXPECT_DOUBLE_EQ(std::stod(convergence[1][5]), 0.018);
  EXPECT_NEAR(std::stod(convergence[1][6]), 17.6777, 1e-4);
  EXPECT_EQ(convergence[1][7], "no");
  EXPECT_EQ(convergence[2][2], "all");
  EXPECT_DOUBLE_EQ(std::stod(convergence[2][5]), 0.018);
  EXPECT_EQ(convergence[2][7], "no");
  // cases.csv: the quoted description-free fields and the pass/fail.
  const auto cases = parse_csv(read_text(dir_ / "cases.csv"));
  ASSERT_EQ(cases.size(), 3u);
  EXPECT_EQ(cases[2][0], "lat_out_of_range");
  EXPECT_EQ(cases[2][6], report.cases[1].message);  // quoted: it holds commas
  EXPECT_EQ(cases[2][7], "1");
  // The run's seconds: the rendered case's, none for the refused one.
  EXPECT_EQ(cases[0][8], "seconds");
  expect_same(csv_number(cases[1][8]), *c.seconds, "case seconds");
  EXPECT_EQ(cases[2][8], "");

  // results.json: the whole report, read back.
  const Report back = report_from_json(read_text(dir_ / "results.json"));
  EXPECT_EQ(back.renderer, report.renderer);
  EXPECT_EQ(back.gl_version, report.gl_version);
  EXPECT_EQ(back.context, report.context);
  EXPECT_EQ(back.reference.pixel_samples, report.reference.pixel_samples);
  EXPECT_EQ(back.reference.pixel_samples_without_sun, report.reference.pixel_samples_without_sun);
  EXPECT_EQ(back.reference.sun_normal_samples, report.reference.sun_normal_samples);
  EXPECT_EQ(back.reference.sun_cells_per_wavelength, report.reference.sun_cells_per_wavelength);
  EXPECT_EQ(back.reference.sun, report.reference.sun);
  EXPECT_EQ(back.reference.sun_refine, report.reference.sun_refine);
  EXPECT_EQ(back.reference.grid_cell, report.reference.grid_cell);
  EXPECT_EQ(back.reference.sun_max_cells_per_wavelength,
            report.reference.sun_max_cells_per_wavelength);
  EXPECT_EQ(back.timing, report.timing);
  EXPECT_EQ(back.cases[0].timing, c.timing);
  EXPECT_EQ(back.cases[0].seconds, c.seconds);
  EXPECT_FALSE(back.cases[1].seconds.has_value());
  ASSERT_EQ(back.cases.size(), 2u);
  EXPECT_EQ(back.cases[0].gl_version, c.gl_version);
  EXPECT_EQ(back.cases[1].gl_version, "");
  EXPECT_EQ(back.cases[1].message, report.cases[1].message);
  EXPECT_TRUE(back.cases[1].passed());
  ASSERT_EQ(back.cases[0].set.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.cases[0].set[i].key, c.set[i].key);
    EXPECT_EQ(back.cases[0].set[i].value_json, c.set[i].value_json);
  }
  ASSERT_EQ(back.cases[0].methods.size(), c.methods.size());
  for (std::size_t mi = 0; mi < c.methods.size(); ++mi) {
    const MethodResult &a = back.cases[0].methods[mi], &b = c.methods[mi];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.plain, b.plain);
    EXPECT_EQ(a.supersample, b.supersample);
    EXPECT_EQ(a.convergence, b.convergence);
    EXPECT_EQ(a.lattice_convergence, b.lattice_convergence);
    EXPECT_EQ(a.lattice_cells_per_wavelength, b.lattice_cells_per_wavelength);
    ASSERT_EQ(a.row_uncertainty.size(), b.row_uncertainty.size());
    for (std::size_t k = 0; k < b.row_uncertainty.size(); ++k) {
      EXPECT_EQ(a.row_uncertainty[k].first, b.row_uncertainty[k].first);
      ASSERT_EQ(a.row_uncertainty[k].second.size(), b.row_uncertainty[k].second.size());
      for (std::size_t y = 0; y < b.row_uncertainty[k].second.size(); ++y)
        expect_same(a.row_uncertainty[k].second[y], b.row_uncertainty[k].second[y], "u");
    }
    EXPECT_EQ(a.timing_ms, b.timing_ms);
    ASSERT_EQ(a.terms.size(), b.terms.size());
    for (std::size_t ti = 0; ti < a.terms.size(); ++ti) {
      const TermResult &x = a.terms[ti], &w = b.terms[ti];
      const std::string what = b.name + "/" + w.term;
      expect_same(x.frame_ms, w.frame_ms, what);
      EXPECT_EQ(x.samples, w.samples) << what;
      EXPECT_EQ(x.flicker.has_value(), w.flicker.has_value()) << what;
      expect_same(x.flicker.value_or(NAN), w.flicker.value_or(NAN), what);
      expect_same(x.temporal_error.value_or(NAN), w.temporal_error.value_or(NAN), what);
      EXPECT_EQ(x.seconds, w.seconds) << what;
      expect_same(x.metrics.error.relative_l1.l, w.metrics.error.relative_l1.l, what);
      EXPECT_EQ(x.metrics.reference_black, w.metrics.reference_black) << what;
      expect_same(x.metrics.mean_row_deviation, w.metrics.mean_row_deviation, what);
      expect_same(x.metrics.row_error, w.metrics.row_error, what);
      expect_same(x.metrics.error.relative_rms.b, w.metrics.error.relative_rms.b, what);
      expect_same(x.metrics.error.mean_abs.l, w.metrics.error.mean_abs.l, what);
      EXPECT_EQ(x.metrics.error.pixels, w.metrics.error.pixels);
      ASSERT_EQ(x.metrics.row_totals.size(), w.metrics.row_totals.size());
      for (std::size_t y = 0; y < w.metrics.row_totals.size(); ++y) {
        expect_same(x.metrics.row_totals[y].g, w.metrics.row_totals[y].g, what);
        expect_same(x.metrics.row_ratios[y].l, w.metrics.row_ratios[y].l, what);
      }
      ASSERT_EQ(x.metrics.horizon.bins.size(), w.metrics.horizon.bins.size());
      for (std::size_t k = 0; k < w.metrics.horizon.bins.size(); ++k) {
        expect_same(x.metrics.horizon.bins[k].std, w.metrics.horizon.bins[k].std, what);
        EXPECT_EQ(x.metrics.horizon.bins[k].pixels, w.metrics.horizon.bins[k].pixels);
      }
      expect_same(x.metrics.horizon.mean, w.metrics.horizon.mean, what);
    }
  }
  // Undefined numbers are null in the JSON, never NaN text.
  EXPECT_EQ(read_text(dir_ / "results.json").find("NaN"), std::string::npos);
  EXPECT_EQ(report_json(back), report_json(report));
}

// The claim's uncertainty from the reference's per-row uncertainty (MethodResult::row_uncertainty):
// over two rows, full 10 % above and 5 % below the reference, basic 20 % and 10 % below, the
// rows uncertain by 2 % and 20 %. The reference within those bounds moves full's lead of 0.075
// by at most (0.04 + 0.1) / 2 = 0.07 (row_error_difference_bound), so full is closer; with the
// largest change, 20 %, in every row (a report without per-row uncertainty) it could move it by
// 0.25, and the two are indistinct.
TEST_F(ValidationReport, Fig10ClaimTakesTheReferencesPerRowUncertainty) {
  const auto make = [](bool per_row) {
    CaseResult c;
    c.name = "rows";
    c.camera_height = 1000.0;
    const double totals[3][2] = {{1.0, 1.0}, {0.8, 0.9}, {1.1, 0.95}};  // reference, basic, full
    const char* names[3] = {"reference", "basic", "full"};
    for (int k = 0; k < 3; ++k) {
      MethodResult m{names[k], names[k], true, {}, {}};
      TermResult t;
      t.term = "sun";
      for (double total : totals[k]) {
        t.metrics.row_totals.push_back({total, total, total, total});
        t.metrics.row_ratios.push_back({total, total, total, total});  // reference's rows are 1
      }
      t.metrics.row_error = (std::abs(totals[k][0] - 1.0) + std::abs(totals[k][1] - 1.0)) / 2.0;
      m.terms.push_back(t);
      c.methods.push_back(m);
    }
    c.methods[0].lattice_convergence = {{"sun", 0.2}};
    if (per_row) c.methods[0].row_uncertainty = {{"sun", {0.02, 0.2}}};
    Report report;
    report.cases.push_back(c);
    return fig10_claim(report);
  };
  const std::vector<ClaimLine> rows = make(true);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0].full, 0.075, 1e-15);
  EXPECT_NEAR(rows[0].basic, 0.15, 1e-15);
  EXPECT_NEAR(rows[0].uncertainty, 0.07, 1e-15);
  EXPECT_EQ(rows[0].verdict(), "closer");
  const std::vector<ClaimLine> largest = make(false);
  EXPECT_NEAR(largest[0].uncertainty, 0.25, 1e-15);
  EXPECT_EQ(largest[0].verdict(), "indistinct");
}

// A report of stop 22 or before has no mean_row_deviation nor row_error: they are read back as
// its rows' mean, and its rows' error against the rows of the reference each method was
// measured against; nor a supersample (stop 53), read back as 1.
TEST_F(ValidationReport, AnOlderReportGetsItsRowMetricsFromItsRows) {
  const Report report = synthetic_report();
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(report_json(report));
  for (auto& jm : j["cases"][0]["methods"]) {
    jm.erase("supersample");  // before stop 53: every method at the reference's pixels
    for (auto& jt : jm["terms"]) {
      jt.erase("mean_row_deviation");
      jt.erase("row_error");
    }
  }
  const Report back = report_from_json(j.dump());
  const CaseResult& c = back.cases[0];
  ASSERT_EQ(c.methods[0].name, "reference");
  for (const MethodResult& m : c.methods) {
    EXPECT_EQ(m.supersample, 1) << m.name;
    for (std::size_t ti = 0; ti < m.terms.size(); ++ti) {
      const TermMetrics& t = m.terms[ti].metrics;
      EXPECT_EQ(t.mean_row_deviation, mean_row_deviation(t.row_ratios)) << m.name;
      const double want =
          row_error(t.row_totals, c.methods[0].terms[ti].metrics.row_totals, t.row_ratios);
      ASSERT_TRUE(std::isfinite(want));
      EXPECT_EQ(t.row_error, want) << m.name;
    }
  }
}

// Over the cases: per method and term the median and the largest of each case's errors, the
// reference left out; fig. 10's claim only for the cases at 100 m or higher, by the row error,
// not holding where either method's is undefined.
TEST_F(ValidationReport, SummaryAndFig10ClaimOverTheCases) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Report report;
  const auto add_case = [&](const std::string& name, double height, double full_l1,
                            double full_rows, double basic_rows) {
    CaseResult c;
    c.name = name;
    c.camera_height = height;
    for (const char* method : {"reference", "basic", "full"}) {
      MethodResult m{method, method, true, {}, {}};
      TermResult t;
      t.term = "sky";
      t.frame_ms = method == std::string("full") ? height : 1.0;
      t.metrics.error.relative_l1.l = method == std::string("full") ? full_l1 : 0.5;
      t.metrics.row_error = method == std::string("full")    ? full_rows
                            : method == std::string("basic") ? basic_rows
                                                             : 0.0;
      // One row, the reference's total 1: full's above it, basic's below, by their row errors.
      const double total =
          method == std::string("basic") ? 1.0 - basic_rows : 1.0 + t.metrics.row_error;
      t.metrics.row_totals = {{total, total, total, total}};
      t.metrics.row_ratios = {{total, total, total, total}};
      m.terms.push_back(t);
      c.methods.push_back(m);
    }
    report.cases.push_back(c);
  };
  add_case("near", 4.0, 0.3, 0.9, 0.1);  // below 100 m: not in the claim
  add_case("mid", 100.0, 0.1, 0.05, 0.2);
  add_case("far", 8000.0, 0.2, 0.3, 0.25);
  add_case("dark", 1000.0, nan, nan, 0.4);
  add_case("same", 1000.0, 0.2, 0.125, 0.125);
  // The reference's own rows moved by up to 2 % at its last doubling: full's 0.01 lead is not
  // resolved (full 10 % above it, basic 11 % below: a reference 2 % lower takes 0.04 of the lead,
  // row_error_difference_bound). Its lattice counts for the terms with the sun only.
  add_case("close", 1000.0, 0.2, 0.1, 0.11);
  report.cases.back().methods[0].convergence = {{"sky", 0.02}};
  report.cases.back().methods[0].lattice_convergence = {{"sun", 0.5}};
  // A black reference (compare_images: its totals kept, no row ratio or row error defined): its
  // own convergence, a ratio of invisible tails, is no uncertainty.
  add_case("black", 8000.0, nan, nan, nan);
  report.cases.back().methods[0].convergence = {{"sky", 2e5}};
  for (MethodResult& m : report.cases.back().methods) {
    TermMetrics& t = m.terms[0].metrics;
    t.reference_black = true;
    t.row_totals = {{1e-20, 1e-20, 1e-20, 1e-20}};
    t.row_ratios = {{nan, nan, nan, nan}};
  }
  const std::vector<SummaryLine> lines = summarize(report);
  ASSERT_EQ(lines.size(), 2u);  // basic and full, sky; no line for the reference
  EXPECT_EQ(lines[0].method, "basic");
  const SummaryLine& full = lines[1];
  EXPECT_EQ(full.method, "full");
  EXPECT_EQ(full.term, "sky");
  EXPECT_EQ(full.cases, 7);
  EXPECT_DOUBLE_EQ(full.median_relative_l1, 0.2);  // of 0.3, 0.1, 0.2, 0.2, 0.2 (undefined out)
  EXPECT_DOUBLE_EQ(full.worst_relative_l1, 0.3);
  EXPECT_DOUBLE_EQ(full.median_row_error, 0.125);  // of 0.9, 0.05, 0.3, 0.125, 0.1
  EXPECT_DOUBLE_EQ(full.worst_row_error, 0.9);
  EXPECT_DOUBLE_EQ(full.median_frame_ms, 1000.0);  // of 4, 100, 1000, 1000, 1000, 8000, 8000
  EXPECT_DOUBLE_EQ(lines[0].median_relative_l1, 0.5);
  const std::vector<ClaimLine> claim = fig10_claim(report);
  ASSERT_EQ(claim.size(), 6u);
  EXPECT_EQ(claim[0].case_name, "mid");
  EXPECT_TRUE(claim[0].holds());
  EXPECT_EQ(claim[0].verdict(), "closer");
  EXPECT_EQ(claim[1].case_name, "far");
  EXPECT_FALSE(claim[1].holds());
  EXPECT_EQ(claim[1].verdict(), "farther");
  EXPECT_EQ(claim[2].case_name, "dark");
  EXPECT_FALSE(claim[2].holds());
  EXPECT_EQ(claim[2].verdict(), "undefined");
  EXPECT_TRUE(claim[3].same());
  EXPECT_FALSE(claim[3].holds());
  EXPECT_EQ(claim[3].verdict(), "same");
  EXPECT_NEAR(claim[4].uncertainty, 0.04, 1e-15);
  EXPECT_TRUE(claim[4].indistinct());
  EXPECT_FALSE(claim[4].holds());
  EXPECT_EQ(claim[4].verdict(), "indistinct");
  EXPECT_TRUE(std::isnan(claim[0].uncertainty));  // not measured: the row errors decide alone
  EXPECT_EQ(claim[5].case_name, "black");
  EXPECT_TRUE(std::isnan(claim[5].uncertainty));
  EXPECT_EQ(claim[5].verdict(), "undefined");
  write_report(report, dir_.string());
  const auto csv = parse_csv(read_text(dir_ / "claim.csv"));
  ASSERT_EQ(csv.size(), 7u);
  EXPECT_EQ(csv[0][5], "reference_uncertainty");
  EXPECT_EQ(csv[1][6], "closer");
  EXPECT_EQ(csv[2][6], "farther");
  EXPECT_EQ(csv[3][3], "");  // undefined: empty
  EXPECT_EQ(csv[4][6], "same");
  EXPECT_EQ(csv[5][6], "indistinct");
  EXPECT_NEAR(std::stod(csv[5][5]), 0.04, 1e-15);
  const std::string index = read_text(dir_ / "index.html");
  EXPECT_NE(index.find("it holds in 1 of 6 cases and terms; in 1 the two"), std::string::npos);
  EXPECT_EQ(csv[6][5], "");  // the black reference's uncertainty: not measured
  EXPECT_NE(index.find("in 1 they differ by no more than the reference's own uncertainty"),
            std::string::npos);
  const std::string heights = read_text(dir_ / "plots" / "summary_sky_height.dat");
  EXPECT_NE(heights.find("\n4 0.10000000000000001 0.90000000000000002\n"), std::string::npos)
      << heights;
  // Each method keeps the colour the rows plots give it, where the reference is line type 1.
  const std::string script = read_text(dir_ / "plots" / "summary_sky_height.gp");
  EXPECT_NE(script.find("lt 2 title 'basic'"), std::string::npos) << script;
  EXPECT_NE(script.find("lt 3 title 'full'"), std::string::npos) << script;
}

// No row compared anywhere (the reference's sun resolved none): gnuplot refuses a plot of no
// point, so the row plot says so, there is no summary plot, and the report is still written.
TEST_F(ValidationReport, NoRowComparedDrawsALabelAndNoSummaryPlot) {
  Report report = synthetic_report();
  for (MethodResult& m : report.cases[0].methods)
    for (TermResult& t : m.terms) {
      t.metrics.mean_row_deviation = NAN;
      t.metrics.row_error = NAN;
      for (ChannelValues& v : t.metrics.row_totals) v = {NAN, NAN, NAN, NAN};
      for (ChannelValues& v : t.metrics.row_ratios) v = {NAN, NAN, NAN, NAN};
    }
  const std::vector<std::string> written = write_report(report, dir_.string());
  EXPECT_TRUE(fs::is_regular_file(dir_ / "index.html"));
  EXPECT_FALSE(fs::exists(dir_ / "plots" / "summary_sun_height.png"));
  const std::string c = report.cases[0].name;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "plots" / (c + "_sun_rows.png")));
  EXPECT_NE(read_text(dir_ / "plots" / (c + "_sun_rows.gp")).find("no row compared"),
            std::string::npos);
}

TEST_F(ValidationReport, MissingGnuplotIsARunTimeErrorBeforeAnyFileIsWritten) {
  ReportOptions options;
  options.gnuplot = "/nonexistent/bin/gnuplot";
  try {
    write_report(synthetic_report(), dir_.string(), options);
    FAIL() << "wrote a report without gnuplot";
  } catch (const ReportError& e) {
    EXPECT_NE(std::string(e.what()).find("apt-get install gnuplot-nox"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_));
  EXPECT_THROW(find_gnuplot(options), ReportError);
  EXPECT_FALSE(find_gnuplot().empty());  // scripts/setup installs it
}

// A gnuplot that fails: the message names the plot and carries gnuplot's own output.
TEST_F(ValidationReport, FailingGnuplotIsReportedWithItsOutput) {
  fs::create_directories(dir_);
  const fs::path fake = dir_ / "fake-gnuplot";
  std::ofstream(fake) << "#!/bin/sh\necho 'no pngcairo here' >&2\nexit 3\n";
  fs::permissions(fake, fs::perms::owner_all);
  ReportOptions options;
  options.gnuplot = fake.string();
  try {
    write_report(synthetic_report(), (dir_ / "out").string(), options);
    FAIL();
  } catch (const ReportError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gnuplot failed (status 3): no pngcairo here"), std::string::npos) << what;
    EXPECT_NE(what.find("_rows.png"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / "index.html"));
}

// Issue 6, point 1's verdict per reference and term: every test it has below 1 %; a sun term
// needs its lattice measured; one test at or above 1 % fails it whatever the other says.
// thalassa validate --seas: the seas of a case sum their rows before the row error, on the rows
// every sea compares (a row the reference does not light in one sea among them), beside the
// basic method's over the same rows and the count of seas alone where the method is the closer,
// and pool their horizon bands bin by bin; a case that is no sea adds no line; sea_of and sea
// read back.
TEST_F(ValidationReport, SeasAreSummedRowByRowOnTheRowsEverySeaCompares) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Per sea: the reference's, full's and basic's row totals (luminance) of 5 rows (NaN: not
  // compared in that sea).
  struct Sea {
    std::vector<double> reference, full, basic;
  };
  const Sea seas[] = {{{10, 20, nan, 40, 0}, {12, 18, nan, 40, 3}, {5, 30, nan, 20, 1}},
                      {{30, 10, 5, nan, 6}, {27, 11, 5, nan, 4}, {31, 10, 6, nan, 6}}};
  Report report = synthetic_report();  // its first case is no sea
  for (int k = 0; k < 2; ++k) {
    const Sea& sea = seas[k];
    CaseResult c;
    c.name = "view_sea" + std::to_string(k + 1);
    c.sea_of = "view";
    c.sea = k + 1;
    c.camera_height = 1000.0;
    const auto method = [&](const char* name, const std::vector<double>& totals) {
      MethodResult m{name, name, true, {}, {}};
      TermResult t;
      t.term = "sun";
      for (std::size_t y = 0; y < totals.size(); ++y) {
        t.metrics.row_totals.push_back({totals[y], totals[y], totals[y], totals[y]});
        const double ratio = sea.reference[y] > 0.0 ? totals[y] / sea.reference[y] : nan;
        t.metrics.row_ratios.push_back({ratio, ratio, ratio, ratio});
      }
      t.metrics.row_error = 0.25;  // not what the seas' line reads
      t.frame_ms = 2.5;            // what the error-against-time plot needs
      t.metrics.error.relative_l1 = {0.1, 0.1, 0.1, 0.1};
      // Two bins of the band: the first with mean 1 (sea 1) and 3 (sea 2), standard deviation
      // 0.5 and weight 2 in each; the second lit in sea 1 alone. basic's means are 1 higher.
      const double offset = std::string(name) == "basic" ? 1.0 : 0.0;
      HorizonBand& band = t.metrics.horizon;
      band.bins.push_back(
          {0.0, 0.5, 10, 2.0, (k == 0 ? 1.0 : 3.0) + offset, 0.5, k == 0 ? 4.0 : 6.0});
      band.bins.push_back(k == 0 ? HorizonBin{0.5, 1.0, 4, 1.0, -1.0 + offset, 0.0, 2.0}
                                 : HorizonBin{0.5, 1.0, 0, 0.0, nan, nan, nan});
      band.pixels = k == 0 ? 14 : 10;
      m.terms.push_back(t);
      return m;
    };
    c.methods.push_back(method("reference", sea.reference));
    c.methods.push_back(method("basic", sea.basic));
    c.methods.push_back(method("full", sea.full));
    report.cases.push_back(c);
  }
  // Rows 0, 1 and 4 are compared in both seas (row 4 unlit by sea 1's reference): the
  // reference's sums 40, 30 and 6, full's 39, 29 and 7, basic's 36, 40 and 7. Alone, full's row
  // errors are 7 / 30 and 6 / 46, basic's 16 / 30 and 1 / 46.
  const std::vector<SeaLine> lines = summarize_seas(report);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].case_name, "view");
  EXPECT_EQ(lines[0].method, "basic");
  EXPECT_EQ(lines[0].term, "sun");
  EXPECT_EQ(lines[0].seas, 2);
  EXPECT_EQ(lines[0].rows, 3);
  EXPECT_DOUBLE_EQ(lines[0].row_error, 15.0 / 76.0);
  EXPECT_TRUE(std::isnan(lines[0].basic_row_error));
  EXPECT_EQ(lines[0].closer_alone, -1);
  EXPECT_EQ(lines[1].method, "full");
  EXPECT_EQ(lines[1].rows, 3);
  EXPECT_DOUBLE_EQ(lines[1].row_error, 3.0 / 76.0);
  EXPECT_DOUBLE_EQ(lines[1].basic_row_error, 15.0 / 76.0);
  EXPECT_EQ(lines[1].closer_alone, 1);
  // The rows summed, NaN where not every sea compares them.
  ASSERT_EQ(lines[1].method_rows.size(), 5u);
  ASSERT_EQ(lines[1].reference_rows.size(), 5u);
  EXPECT_DOUBLE_EQ(lines[1].method_rows[0], 39.0);
  EXPECT_DOUBLE_EQ(lines[1].method_rows[1], 29.0);
  EXPECT_TRUE(std::isnan(lines[1].method_rows[2]));
  EXPECT_TRUE(std::isnan(lines[1].method_rows[3]));
  EXPECT_DOUBLE_EQ(lines[1].method_rows[4], 7.0);
  EXPECT_DOUBLE_EQ(lines[1].reference_rows[0], 40.0);
  EXPECT_DOUBLE_EQ(lines[1].reference_rows[4], 6.0);
  EXPECT_TRUE(std::isnan(lines[1].reference_rows[3]));
  EXPECT_DOUBLE_EQ(lines[0].method_rows[1], 40.0);
  // full's bands pooled: the first bin's weight 4, mean (2 x 1 + 2 x 3) / 4 = 2, variance
  // (2 (0.25 + 1) + 2 (0.25 + 1)) / 4 = 1.25 (the spread within each sea and between them),
  // reference mean 5; the second bin sea 1's alone; the band's summary each bin once.
  const HorizonBand& pooled = lines[1].horizon;
  ASSERT_EQ(pooled.bins.size(), 2u);
  EXPECT_EQ(pooled.bins[0].pixels, 20);
  EXPECT_DOUBLE_EQ(pooled.bins[0].weight, 4.0);
  EXPECT_DOUBLE_EQ(pooled.bins[0].mean, 2.0);
  EXPECT_DOUBLE_EQ(pooled.bins[0].std, std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(pooled.bins[0].reference_mean, 5.0);
  EXPECT_EQ(pooled.bins[1].pixels, 4);
  EXPECT_DOUBLE_EQ(pooled.bins[1].mean, -1.0);
  EXPECT_DOUBLE_EQ(pooled.bins[1].std, 0.0);
  EXPECT_EQ(pooled.pixels, 24);
  EXPECT_DOUBLE_EQ(pooled.mean, 0.5);
  EXPECT_DOUBLE_EQ(pooled.std, 0.5 * std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(pooled.reference_mean, 3.5);
  EXPECT_DOUBLE_EQ(lines[0].horizon.bins[0].mean, 3.0);  // basic's
  // The files: seas.csv holds the lines, index.html their table and the plots of the summed rows
  // and of the pooled bands, seas_horizon.csv the bands' bins, results.json the seas.
  const std::vector<std::string> written = write_report(report, dir_.string());
  EXPECT_NE(std::find(written.begin(), written.end(), "plots/view_seas_sun_rows.png"),
            written.end());
  EXPECT_TRUE(fs::is_regular_file(dir_ / "plots" / "view_seas_sun_rows.png"));
  // Its data's row 0: the reference's sum, then basic's and full's sums and ratios.
  std::istringstream dat(read_text(dir_ / "plots" / "view_seas_sun_rows.dat"));
  std::string line;
  while (std::getline(dat, line) && line.rfind("0 ", 0) != 0) {
  }
  std::istringstream row(line);
  double y = -1, reference = 0, basic = 0, basic_ratio = 0, full = 0, full_ratio = 0;
  row >> y >> reference >> basic >> basic_ratio >> full >> full_ratio;
  EXPECT_EQ(y, 0.0) << line;
  EXPECT_DOUBLE_EQ(reference, 40.0);
  EXPECT_DOUBLE_EQ(basic, 36.0);
  EXPECT_DOUBLE_EQ(basic_ratio, 0.9);
  EXPECT_DOUBLE_EQ(full, 39.0);
  EXPECT_DOUBLE_EQ(full_ratio, 39.0 / 40.0);
  EXPECT_NE(read_text(dir_ / "index.html").find("plots/view_seas_sun_rows.png"), std::string::npos);
  const auto csv = parse_csv(read_text(dir_ / "seas.csv"));
  ASSERT_EQ(csv.size(), 3u);
  EXPECT_EQ(csv[0],
            (std::vector<std::string>{"case", "method", "term", "seas", "rows", "row_error",
                                      "basic_row_error", "closer_alone", "horizon_mean",
                                      "horizon_std", "horizon_reference_mean", "horizon_pixels"}));
  EXPECT_EQ(csv[2][0], "view");
  EXPECT_EQ(csv[2][1], "full");
  EXPECT_EQ(csv_number(csv[2][5]), 3.0 / 76.0);
  EXPECT_EQ(csv[2][7], "1");
  EXPECT_EQ(csv[1][7], "");
  EXPECT_DOUBLE_EQ(csv_number(csv[2][8]), 0.5);
  EXPECT_DOUBLE_EQ(csv_number(csv[2][9]), 0.5 * std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(csv_number(csv[2][10]), 3.5);
  EXPECT_EQ(csv[2][11], "24");
  const auto bins = parse_csv(read_text(dir_ / "seas_horizon.csv"));
  ASSERT_EQ(bins.size(), 5u);  // the header, two methods of two bins
  EXPECT_EQ(bins[0], (std::vector<std::string>{"case", "method", "term", "seas", "beta_lo_deg",
                                               "beta_hi_deg", "pixels", "weight_rad2", "mean",
                                               "std", "reference_mean"}));
  EXPECT_EQ(bins[3][1], "full");
  EXPECT_EQ(bins[3][3], "2");
  EXPECT_EQ(bins[3][6], "20");
  EXPECT_DOUBLE_EQ(csv_number(bins[3][8]), 2.0);
  EXPECT_DOUBLE_EQ(csv_number(bins[3][9]), std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(csv_number(bins[4][8]), -1.0);
  EXPECT_TRUE(fs::is_regular_file(dir_ / "plots" / "view_seas_sun_horizon.png"));
  EXPECT_NE(std::find(written.begin(), written.end(), "plots/view_seas_sun_horizon.png"),
            written.end());
  EXPECT_NE(read_text(dir_ / "index.html").find("plots/view_seas_sun_horizon.png"),
            std::string::npos);
  EXPECT_NE(read_text(dir_ / "index.html").find("<h2>Over the seas</h2>"), std::string::npos);
  const Report back = report_from_json(read_text(dir_ / "results.json"));
  ASSERT_EQ(back.cases.size(), report.cases.size());
  EXPECT_EQ(back.cases[0].sea_of, "");
  EXPECT_EQ(back.cases[0].sea, 0);
  EXPECT_EQ(back.cases.back().sea_of, "view");
  EXPECT_EQ(back.cases.back().sea, 2);
  // Without seas: no line, the header alone, no table.
  fs::remove_all(dir_);
  write_report(synthetic_report(), dir_.string());
  EXPECT_TRUE(summarize_seas(synthetic_report()).empty());
  EXPECT_EQ(parse_csv(read_text(dir_ / "seas.csv")).size(), 1u);
  EXPECT_EQ(parse_csv(read_text(dir_ / "seas_horizon.csv")).size(), 1u);
  EXPECT_EQ(read_text(dir_ / "index.html").find("Over the seas"), std::string::npos);
}

TEST(ValidationConvergence, EveryTestBelowOnePercentAndTheSunsLatticeMeasured) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto verdict = [](double samples, double lattice, bool sun) {
    ConvergenceLine l;
    l.sample_change = samples;
    l.lattice_change = lattice;
    l.with_sun = sun;
    return l.converged();
  };
  EXPECT_EQ(verdict(0.009, nan, false), "yes");
  EXPECT_EQ(verdict(0.01, nan, false), "no");  // "less than 1 %"
  EXPECT_EQ(verdict(nan, nan, false), "undefined");
  EXPECT_EQ(verdict(0.0, 0.0099, true), "yes");
  EXPECT_EQ(verdict(0.0, 0.43, true), "no");
  EXPECT_EQ(verdict(0.0, nan, true), "undefined");  // a black sun: no row measured
  EXPECT_EQ(verdict(0.02, nan, true), "no");
  EXPECT_EQ(verdict(nan, 0.02, true), "no");
  EXPECT_EQ(verdict(0.0, 0.43, false), "yes");  // a term without the sun has no lattice
  // The lines: one per reference (the variants' own too) and term, the lattice on sun and all.
  Report report;
  CaseResult c;
  c.name = "a";
  MethodResult reference{"reference", "reference", true, {}, {}};
  MethodResult own{"reference_full_waves30", "reference", false, "reference_full_waves30", {}};
  MethodResult full{"full", "full", true, {}, {}};
  for (MethodResult* m : {&reference, &own, &full})
    for (const char* term : {"sun", "sky", "all"}) {
      TermResult t;
      t.term = term;
      t.samples = m == &full ? 1 : 512;
      m->terms.push_back(t);
    }
  reference.convergence = {{"sun", 0.0}, {"sky", 0.008}, {"all", 0.02}};
  reference.lattice_convergence = {{"sun", 0.005}};
  reference.lattice_cells_per_wavelength = {{"sun", 22.6}};
  own.convergence = {{"sun", 0.0}, {"sky", 0.001}, {"all", 0.001}};
  own.lattice_convergence = {{"sun", nan}};
  c.methods = {reference, own, full};
  report.cases = {c};
  const std::vector<ConvergenceLine> lines = reference_convergence(report);
  ASSERT_EQ(lines.size(), 6u);
  std::vector<std::string> verdicts;
  for (const ConvergenceLine& l : lines) verdicts.push_back(l.reference + "/" + l.term + " " +
                                                            l.converged());
  EXPECT_EQ(verdicts, (std::vector<std::string>{
                          "reference/sun yes", "reference/sky yes", "reference/all no",
                          "reference_full_waves30/sun undefined",
                          "reference_full_waves30/sky yes",
                          "reference_full_waves30/all undefined"}));
  EXPECT_EQ(lines[0].lattice_cells_per_wavelength, 22.6);
  EXPECT_TRUE(std::isnan(lines[1].lattice_cells_per_wavelength));
  EXPECT_EQ(lines[2].samples, 512);
}
}  // namespace
}  // namespace thalassa::validation
