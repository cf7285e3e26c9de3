// The validation report's CSV files (report_detail.hpp; docs/validation.md lists them).
#include "report_detail.hpp"

#include <cmath>

namespace thalassa::validation {

namespace detail {

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
    csv +=
        csv_line({c.name, number(c.camera_height), overrides_text(c.set),
                  std::to_string(c.expected_exit), c.expected_error, std::to_string(c.exit_status),
                  c.message, c.passed() ? "1" : "0", number(c.seconds.value_or(kNaN))});
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
  std::string csv = csv_line({"case", "reference", "term", "samples", "sample_change",
                              "lattice_change", "lattice_cells_per_wavelength", "converged"});
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

}  // namespace detail

}  // namespace thalassa::validation
