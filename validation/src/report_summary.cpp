// Summaries of the validation report: per method, over the seas, fig. 10's claim and the
// references' convergence (thalassa/validation/report.hpp).
#include "thalassa/validation/report.hpp"

#include <algorithm>
#include <cmath>

#include "report_detail.hpp"

namespace thalassa::validation {

using namespace detail;

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

namespace detail {

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

}  // namespace detail

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

namespace detail {

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

}  // namespace detail

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

}  // namespace thalassa::validation
