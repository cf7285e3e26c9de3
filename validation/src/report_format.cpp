// The validation report's text formatting and lookups in its results (report_detail.hpp).
#include "report_detail.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace thalassa::validation {

namespace detail {

std::string number(double x, const char* nan_text) {
  if (std::isnan(x)) return nan_text;
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

namespace {

// A CSV field (RFC 4180): quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

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

std::vector<std::string> case_terms(const CaseResult& c) {
  std::vector<std::string> terms;
  for (const MethodResult& m : c.methods)
    for (const TermResult& t : m.terms)
      if (std::find(terms.begin(), terms.end(), t.term) == terms.end()) terms.push_back(t.term);
  return terms;
}

bool measured(const TermResult& t) { return !t.metrics.row_totals.empty(); }

double cost_ms(const MethodResult& m, const TermResult& t) {
  return m.timing_ms.value_or(t.frame_ms);
}

std::string timing_text(const TimingSettings& timing) {
  return timing.enabled() ? std::to_string(timing.width) + "x" + std::to_string(timing.height)
                          : std::string("the image size");
}

double median_of(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double max_of(const std::vector<double>& values) {
  double worst = kNaN;
  for (double v : values)
    if (std::isfinite(v) && !(v <= worst)) worst = v;
  return worst;
}

}  // namespace detail

}  // namespace thalassa::validation
