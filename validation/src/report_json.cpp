// results.json of the validation report: written and read back (thalassa/validation/report.hpp).
#include "thalassa/validation/report.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "report_detail.hpp"
#include "thalassa/ocean/method.hpp"

namespace thalassa::validation {

using ojson = nlohmann::ordered_json;
using namespace detail;

namespace detail {

namespace {

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

}  // namespace

}  // namespace detail

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
      jm["supersample"] = m.supersample;
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
    report.reference.sun_max_cells_per_wavelength =                   // nor double (before stop 25)
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
      m.supersample = jm.value("supersample", 1);
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

}  // namespace thalassa::validation
