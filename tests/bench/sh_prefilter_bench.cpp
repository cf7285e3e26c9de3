// Tables 4 and 5 of Ramamoorthi & Hanrahan 2002 (sec. 7.4) on this machine: angular-domain
// against frequency-space prefiltering of an environment map, with the measured error of each
// (issue 8, point 5). Timed, never asserted (DESIGN section 6). One thread throughout.
//
// Settings, as in the paper where it states them:
// * Input: the synthetic sky of tests/unit/synthetic_sky.hpp (gradient, ground, horizon, a bright
//   3-degree region and a glow), one channel, S_L x S_L = 128 x 128 lat-long (sec. 7.4: "the
//   resolution S_L and S_B of the inputs and final results were 128"). --input=S changes S_L.
// * Output: S_B x S_B = 128 x 128 lat-long reflection maps (over the reflection direction C).
// * Table 4, Phong s = 8 ... 512: the frequency route at the paper's F_B = 1 + sqrt(6 s) (its
//   conservative order for epsilon = 0.01; rounded up), with analytic BRDF coefficients: the
//   lighting's projection to F_B, the convolution and the reconstruction of the 128 x 128 map
//   (appendix C, radially symmetric case). The angular route integrates, per output texel, the
//   input texels within the Phong support of epsilon = 0.05 (the paper's "more aggressive"
//   setting, appendix D); the exact angular integral over the whole hemisphere about C is timed
//   as well and is the reference for every error.
// * Table 5, microfacet (eq. 11) sigma = 0.1 ... 0.5: F_B, P_B chosen for epsilon < 0.03 by
//   choose_orders (sec. 5.1 / appendix C) on a 128 x 32 x 32 table; "SHRM" = the lighting's
//   projection + the BRDF table's projection + the convolution + the 128 x 128 local SHRM;
//   "total" = SHRM + the T_B x T_B = 100 explicit reflection maps (local views on a 10 x 10
//   lat-long grid of omega_o). The angular route per image integrates within the BRDF's support
//   of epsilon = 0.05 about C (brdf_support); it is timed on --views=N views (default 4, spread
//   in theta_o) and its total is 100 times the mean time per image (extrapolated: 100 angular
//   images take tens of minutes here). The exact angular integral at the same views is the
//   reference for the errors, weighted by sin theta_o.
// * Errors (sec. 5.1, appendix B): epsilon_B = ∫ (B' - B)^2 / ∫ B^2, the fraction of the
//   reflected light's energy missed; "predicted" is the BRDF's energy fraction left out by the
//   orders used (the paper's conservative estimate).
//
// Run: build/tests/sh_prefilter_bench --table            (markdown table, as in the docs)
//      build/tests/sh_prefilter_bench --table=csv        (the same numbers as CSV)
//      [--only=4|5] (one table) [--input=S] (S_L) [--views=N] (table 5's angular views)
//      build/tests/sh_prefilter_bench [--benchmark_filter=...]   (Google Benchmark timings)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "../unit/synthetic_sky.hpp"
#include "thalassa/atmosphere/sh_brdf.hpp"
#include "thalassa/atmosphere/sh_prefilter.hpp"
#include "thalassa/atmosphere/spherical_harmonics.hpp"

namespace {

using namespace thalassa::sh;

constexpr double kPi = std::numbers::pi;
constexpr int kOutput = 128;                 // S_B
constexpr int kViewGrid = 10;                // T_B of table 5
constexpr double kPaperPhongEpsilon = 0.01;  // sec. 7.4, frequency domain
constexpr double kAngularEpsilon = 0.05;     // sec. 7.4, angular domain support
constexpr double kMicrofacetEpsilon = 0.03;  // table 5
constexpr int kFrequencyRepeats = 5;         // frequency timings: the median of this many
const std::vector<double> kPhongExponents = {8, 16, 32, 64, 128, 256, 512};
const std::vector<double> kSigmas = {0.1, 0.2, 0.3, 0.4, 0.5};
// The BRDF table of table 5 (theta_i x theta_o x phi nodes): resolves l < 128, p < 32.
constexpr BrdfGrid kMicrofacetGrid{128, 32, 32};

int g_input = 128;  // S_L
int g_views = 4;

const std::vector<double>& environment() {
  static const std::vector<double> map = thalassa::test::SyntheticSky{}.lat_long(g_input, g_input);
  return map;
}
LatLongLayout input_layout() { return LatLongLayout{g_input, g_input, 1, 0}; }

int paper_phong_order(double s) { return static_cast<int>(std::ceil(1.0 + std::sqrt(6.0 * s))); }

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <typename F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(seconds_since(start));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// ---- The two routes -----------------------------------------------------------------------

std::vector<double> phong_frequency(double s, int order) {
  const std::vector<double> lighting = project_lat_long(environment(), input_layout(), order);
  return radial_reflection_map(lighting, order, phong_coefficients(s, order), kOutput, kOutput);
}

std::vector<double> phong_angular(double s, double support) {
  return angular_prefilter(environment(), input_layout(), phong_radial_brdf(s),
                           AngularOptions{kOutput, kOutput, support});
}

struct Microfacet {
  double sigma;
  CosineWeightedBrdf brdf;
  ReparameterizedBrdf reparameterized;
  BrdfTable table;
  OrderChoice orders;
  explicit Microfacet(double s)
      : sigma(s),
        brdf(microfacet_brdf(s)),
        reparameterized(reparameterize_by_reflection(brdf)),
        table(tabulate(reparameterized, kMicrofacetGrid)),
        orders(choose_orders(table, kMicrofacetEpsilon)) {}
};

ShrmMap microfacet_shrm(const Microfacet& m) {
  const int f = m.orders.order_l, p = m.orders.order_p;
  const std::vector<double> lighting = project_lat_long(environment(), input_layout(), f);
  const BrdfCoefficients rho = project_brdf(m.table, f, p);
  return local_shrm_map(convolve(lighting, f, rho), kOutput, kOutput);
}

double view_theta(int j) { return (j + 0.5) * kPi / kViewGrid; }
double view_phi(int k) { return 2.0 * kPi * (k + 0.5) / kViewGrid; }

// The views on which the angular route is timed and errors measured: N rows of the T_B grid,
// spread in theta_o, each at a different azimuth column.
struct View {
  double theta_o, phi_o;
};
std::vector<View> sample_views() {
  std::vector<View> views;
  for (int v = 0; v < g_views; ++v) {
    const int row = std::min(kViewGrid - 1, static_cast<int>((v + 0.5) * kViewGrid / g_views));
    views.push_back({view_theta(row), view_phi((3 * v) % kViewGrid)});
  }
  return views;
}

// ---- Google Benchmark timings -------------------------------------------------------------

void PhongAngular(benchmark::State& state) {
  const double s = static_cast<double>(state.range(0));
  const double support = phong_support(s, kAngularEpsilon);
  for (auto _ : state) benchmark::DoNotOptimize(phong_angular(s, support));
}
void PhongAngularHemisphere(benchmark::State& state) {
  const double s = static_cast<double>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(phong_angular(s, kPi / 2.0));
}
void PhongFrequency(benchmark::State& state) {
  const double s = static_cast<double>(state.range(0));
  const int order = paper_phong_order(s);
  for (auto _ : state) benchmark::DoNotOptimize(phong_frequency(s, order));
  state.counters["F_B"] = order;
}
void MicrofacetAngularImage(benchmark::State& state) {
  const Microfacet m(state.range(0) / 10.0);
  const View v = sample_views().front();
  const double support = brdf_support(m.reparameterized, v.theta_o, kAngularEpsilon);
  for (auto _ : state) {
    benchmark::DoNotOptimize(angular_prefilter(environment(), input_layout(), m.brdf, v.theta_o,
                                               v.phi_o, AngularOptions{kOutput, kOutput, support}));
  }
}
void MicrofacetShrm(benchmark::State& state) {
  const Microfacet m(state.range(0) / 10.0);
  for (auto _ : state) benchmark::DoNotOptimize(microfacet_shrm(m));
  state.counters["F_B"] = m.orders.order_l;
  state.counters["P_B"] = m.orders.order_p;
}
void MicrofacetFrequencyTotal(benchmark::State& state) {
  const Microfacet m(state.range(0) / 10.0);
  for (auto _ : state) {
    const ShrmMap shrm = microfacet_shrm(m);
    for (int j = 0; j < kViewGrid; ++j) {
      for (int k = 0; k < kViewGrid; ++k) {
        benchmark::DoNotOptimize(local_reflection_map(shrm, view_theta(j), view_phi(k)));
      }
    }
  }
}

BENCHMARK(PhongAngular)
    ->RangeMultiplier(2)
    ->Range(8, 512)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(PhongAngularHemisphere)
    ->RangeMultiplier(2)
    ->Range(8, 512)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(PhongFrequency)->RangeMultiplier(2)->Range(8, 512)->Unit(benchmark::kMillisecond);
BENCHMARK(MicrofacetAngularImage)->DenseRange(1, 5)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(MicrofacetShrm)->DenseRange(1, 5)->Unit(benchmark::kMillisecond);
BENCHMARK(MicrofacetFrequencyTotal)->DenseRange(1, 5)->Unit(benchmark::kMillisecond);

// ---- The tables ----------------------------------------------------------------------------

struct Printer {
  bool csv;
  void header(const std::vector<std::string>& columns) const {
    std::string line;
    for (std::size_t i = 0; i < columns.size(); ++i) {
      line += csv ? (i ? "," : "") + columns[i] : "| " + columns[i] + " ";
    }
    std::printf("%s%s\n", line.c_str(), csv ? "" : "|");
    if (!csv) {
      std::string rule;
      for (std::size_t i = 0; i < columns.size(); ++i) rule += "|---";
      std::printf("%s|\n", rule.c_str());
    }
  }
  void row(const std::vector<std::string>& cells) const {
    std::string line;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      line += csv ? (i ? "," : "") + cells[i] : "| " + cells[i] + " ";
    }
    std::printf("%s%s\n", line.c_str(), csv ? "" : "|");
    std::fflush(stdout);
  }
};

std::string fmt(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

void table4(const Printer& out) {
  std::printf("\nTable 4 (Phong), S_L = %d, S_B = %d, one thread\n\n", g_input, kOutput);
  out.header({"s", "F_B (paper)", "F (eps=0.01)", "angular eps=0.05 (s)", "angular exact (s)",
              "frequency (s)", "ratio", "ratio exact", "predicted eps", "measured eps (freq)",
              "measured eps (angular 0.05)"});
  for (double s : kPhongExponents) {
    const int order = paper_phong_order(s);
    const double energy = phong_energy(s);
    const OrderChoice ours =
        choose_orders(phong_coefficients(s, 4 * order), energy, kPaperPhongEpsilon);
    const double predicted = 1.0 - brdf_energy(phong_coefficients(s, order), order, 0) / energy;
    const double support = phong_support(s, kAngularEpsilon);

    std::vector<double> truncated, exact, frequency;
    auto start = std::chrono::steady_clock::now();
    truncated = phong_angular(s, support);
    const double t_truncated = seconds_since(start);
    start = std::chrono::steady_clock::now();
    exact = phong_angular(s, kPi / 2.0);  // rho-hat = 0 beyond 90 degrees: exact
    const double t_exact = seconds_since(start);
    const double t_frequency =
        median_seconds(kFrequencyRepeats, [&] { frequency = phong_frequency(s, order); });

    EnergyError e_frequency, e_truncated;
    e_frequency.add(frequency, exact, kOutput, kOutput);
    e_truncated.add(truncated, exact, kOutput, kOutput);
    out.row({fmt("%.0f", s), fmt("%.0f", order), fmt("%.0f", ours.order_l),
             fmt("%.3f", t_truncated), fmt("%.3f", t_exact), fmt("%.4f", t_frequency),
             fmt("%.0f", t_truncated / t_frequency), fmt("%.0f", t_exact / t_frequency),
             fmt("%.1e", predicted), fmt("%.1e", e_frequency.relative()),
             fmt("%.1e", e_truncated.relative())});
  }
}

void table5(const Printer& out) {
  std::printf(
      "\nTable 5 (microfacet), S_L = %d, S_B = %d, T_B = %d, angular on %d views, one "
      "thread\n\n",
      g_input, kOutput, kViewGrid, g_views);
  out.header({"sigma", "F_B, P_B", "angular total (s, 100 x image)", "angular / image (s)",
              "exact / image (s)", "frequency total (s)", "SHRM (s)", "ratio (total)",
              "ratio (image / SHRM)", "predicted eps", "measured eps (freq)",
              "measured eps (angular 0.05)"});
  for (double sigma : kSigmas) {
    const Microfacet m(sigma);
    ShrmMap shrm;
    const double t_shrm = median_seconds(kFrequencyRepeats, [&] { shrm = microfacet_shrm(m); });
    const double t_total =
        t_shrm + median_seconds(3, [&] {
          for (int j = 0; j < kViewGrid; ++j) {
            for (int k = 0; k < kViewGrid; ++k) {
              benchmark::DoNotOptimize(local_reflection_map(shrm, view_theta(j), view_phi(k)));
            }
          }
        });
    EnergyError e_frequency, e_truncated;
    double t_angular = 0.0, t_exact = 0.0;
    const std::vector<View> views = sample_views();
    for (const View& v : views) {
      const double support = brdf_support(m.reparameterized, v.theta_o, kAngularEpsilon);
      auto start = std::chrono::steady_clock::now();
      const std::vector<double> truncated =
          angular_prefilter(environment(), input_layout(), m.brdf, v.theta_o, v.phi_o,
                            AngularOptions{kOutput, kOutput, support});
      t_angular += seconds_since(start);
      start = std::chrono::steady_clock::now();
      const std::vector<double> exact =
          angular_prefilter(environment(), input_layout(), m.brdf, v.theta_o, v.phi_o,
                            AngularOptions{kOutput, kOutput, 0.0});
      t_exact += seconds_since(start);
      const std::vector<double> frequency = local_reflection_map(shrm, v.theta_o, v.phi_o);
      const double weight = std::sin(v.theta_o);
      e_frequency.add(frequency, exact, kOutput, kOutput, weight);
      e_truncated.add(truncated, exact, kOutput, kOutput, weight);
    }
    const double per_image = t_angular / static_cast<double>(views.size());
    const double angular_total = per_image * kViewGrid * kViewGrid;
    out.row({fmt("%.1f", sigma),
             fmt("%.0f", m.orders.order_l) + ", " + fmt("%.0f", m.orders.order_p),
             fmt("%.1f", angular_total), fmt("%.2f", per_image),
             fmt("%.2f", t_exact / static_cast<double>(views.size())), fmt("%.3f", t_total),
             fmt("%.3f", t_shrm), fmt("%.0f", angular_total / t_total),
             fmt("%.1f", per_image / t_shrm), fmt("%.1e", m.orders.predicted_error),
             fmt("%.1e", e_frequency.relative()), fmt("%.1e", e_truncated.relative())});
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Our own flags first; the rest go to Google Benchmark.
  std::string table;
  int only = 0;  // 0: both tables
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--table") == 0) {
      table = "markdown";
    } else if (std::strncmp(argv[i], "--table=", 8) == 0) {
      table = argv[i] + 8;
    } else if (std::strncmp(argv[i], "--input=", 8) == 0) {
      g_input = std::atoi(argv[i] + 8);
    } else if (std::strncmp(argv[i], "--only=", 7) == 0) {
      only = std::atoi(argv[i] + 7);
    } else if (std::strncmp(argv[i], "--views=", 8) == 0) {
      g_views = std::atoi(argv[i] + 8);
    } else {
      rest.push_back(argv[i]);
    }
  }
  if (g_input < 8 || g_views < 1 || (!table.empty() && table != "markdown" && table != "csv") ||
      (only != 0 && only != 4 && only != 5)) {
    std::fprintf(stderr,
                 "usage: sh_prefilter_bench [--table[=markdown|csv]] [--only=4|5] [--input=S>=8] "
                 "[--views=N>=1] [benchmark flags]\n");
    return 2;
  }
  if (!table.empty()) {
    const Printer printer{table == "csv"};
    if (only != 5) table4(printer);
    if (only != 4) table5(printer);
    return 0;
  }
  int count = static_cast<int>(rest.size());
  benchmark::Initialize(&count, rest.data());
  if (benchmark::ReportUnrecognizedArguments(count, rest.data())) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
