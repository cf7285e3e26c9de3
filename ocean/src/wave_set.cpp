// The wave set of the Bruneton et al. 2010 ocean: see ocean/include/thalassa/ocean/wave_set.hpp
// for the derivations, frames and units.

#include "thalassa/ocean/wave_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "trochoids_reference.hpp"

namespace thalassa::ocean {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;  // the double nearest 2 pi (rounded down)
// 2 pi - kTwoPi, rounded to double: 2 pi = kTwoPi + kTwoPiTail + O(6e-33). (2 pi =
// 6.283185307179586476925286766559..., kTwoPi = 6.283185307179586231995926937088...)
constexpr double kTwoPiTail = 2.4492935982947064e-16;
constexpr double kDegree = std::numbers::pi / 180.0;

// Largest number of waves (the scene's range of ocean.waves).
constexpr int kMaxWaves = 4096;

// Hasselmann, Dunckel & Ewing (1980), spreading exponent s(omega / omega_p) (see wave_set.hpp):
// s = kLowScale (omega / omega_p)^kLowExponent below kSplit omega_p, s = kHighScale
// (omega / omega_p)^mu above, mu = kHighExponent - kHighSlope (V / c_p - kHighReference).
constexpr double kHasselmannSplit = 1.05;
constexpr double kHasselmannLowScale = 6.97;
constexpr double kHasselmannLowExponent = 4.06;
constexpr double kHasselmannHighScale = 9.77;
constexpr double kHasselmannHighExponent = -2.33;
constexpr double kHasselmannHighSlope = 1.45;
constexpr double kHasselmannHighReference = 1.17;

// Intervals of the tabulated CDF of cos^(2s)(u) on u = |theta| / 2 in [0, pi / 2] (Simpson's
// rule per interval, quadratic inversion inside it): the CDF is right to ~1e-7 (the test
// measures it), far below the sampling noise of a few thousand waves; 2048 exp per wave (8M for
// the largest set) cost ~50 ms.
constexpr int kSpreadingTableIntervals = 1024;

// 2^-53: u = (bits >> 11) * 2^-53 maps 64 random bits to a double in [0, 1), every value a
// multiple of 2^-53 (exact).
constexpr double kTwoToMinus53 = 1.0 / 9007199254740992.0;

double uniform(std::mt19937_64& generator) {
  return static_cast<double>(generator() >> 11) * kTwoToMinus53;
}

// (4 beta / 5)^(1/4): omega_p / omega_0 = V / c_p for the PM spectrum (wave_set.hpp).
double pm_peak_ratio() { return std::pow(4.0 * kPiersonMoskowitzBeta / 5.0, 0.25); }

// x mod 2 pi for a double x, in about [-pi, pi] (|x| < 2^53 2 pi): n = nearest integer to
// x / 2 pi; x - n 2 pi = (x - n kTwoPi) - n kTwoPiTail, each with one FMA: the products are exact
// inside the FMA and the results small, so each step rounds once at ~4e-16 rad. The neglected
// term n 6e-33 is < 1e-18 rad for n < 1.6e14 (|x| < 1e15).
double reduce_two_pi(double x) {
  const double n = std::nearbyint(x / kTwoPi);
  const double r = std::fma(-n, kTwoPi, x);
  return std::fma(-n, kTwoPiTail, r);
}

// (a b) mod 2 pi, with the rounding error of the product a b (exact by FMA) added back.
double reduce_product(double a, double b) {
  const double product = a * b;
  const double error = std::fma(a, b, -product);
  return reduce_two_pi(product) + error;
}

// Midpoint-rule band width in ln(omega) of each wave (wave_set.hpp): half the progression's
// step in ln(lambda), at least half of ln(2) / n.
double log_omega_band(int n, double lambda_min, double lambda_max) {
  const double octave_share = std::log(2.0) / n;
  if (n < 2) return 0.5 * octave_share;
  return 0.5 * std::max(std::log(lambda_max / lambda_min) / (n - 1), octave_share);
}

// Counts the leading indices i of [0, n) for which `in_range(i)` holds, given that it holds for
// a prefix only, from the estimate `estimate` (any real; from logarithms): the estimate is
// clamped to [0, n], then moved by the exact test of the boundary waves (one step or two, since
// the logarithms are accurate to a few ulps).
template <typename Predicate>
int count_prefix(double estimate, int n, Predicate in_range) {
  int count = 0;
  if (std::isnan(estimate)) {
    count = 0;
  } else if (estimate >= n) {
    count = n;
  } else if (estimate > 0.0) {
    count = static_cast<int>(std::ceil(estimate));
  }
  while (count < n && in_range(count)) ++count;
  while (count > 0 && !in_range(count - 1)) --count;
  return count;
}

}  // namespace

double pierson_moskowitz_spectrum(double omega, double wind_speed) {
  if (!(wind_speed > 0.0) || !(omega > 0.0)) return 0.0;
  const double omega0 = kGravity / wind_speed;
  const double ratio = omega0 / omega;
  const double ratio2 = ratio * ratio;
  // For tiny winds ratio^4 overflows to +inf and exp(-inf) = 0: still no NaN.
  return kPiersonMoskowitzAlpha * kGravity * kGravity / std::pow(omega, 5.0) *
         std::exp(-kPiersonMoskowitzBeta * ratio2 * ratio2);
}

double pierson_moskowitz_peak_angular_frequency(double wind_speed) {
  if (!(wind_speed > 0.0)) return std::numeric_limits<double>::infinity();
  return pm_peak_ratio() * kGravity / wind_speed;
}

double hasselmann_spreading_exponent(double omega, double peak_omega) {
  if (!(omega > 0.0) || !(peak_omega > 0.0)) return 0.0;
  const double ratio = omega / peak_omega;  // 0 for a calm sea (peak_omega = +inf)
  if (ratio < kHasselmannSplit) {
    return kHasselmannLowScale * std::pow(ratio, kHasselmannLowExponent);
  }
  // V / c_p = V omega_p / g = (4 beta / 5)^(1/4) for the fully developed PM sea, whatever V.
  const double mu =
      kHasselmannHighExponent - kHasselmannHighSlope * (pm_peak_ratio() - kHasselmannHighReference);
  return kHasselmannHighScale * std::pow(ratio, mu);
}

double hasselmann_spreading(double theta, double s) {
  const double c = std::abs(std::cos(0.5 * theta));
  // N(s) = 2^(2s - 1) Gamma(s + 1)^2 / (pi Gamma(2s + 1)), in logarithms (no overflow).
  const double log_norm = (2.0 * s - 1.0) * std::log(2.0) + 2.0 * std::lgamma(s + 1.0) -
                          std::lgamma(2.0 * s + 1.0) - std::log(kPi);
  if (c == 0.0) return s > 0.0 ? 0.0 : std::exp(log_norm);
  return std::exp(log_norm + 2.0 * s * std::log(c));
}

double sample_hasselmann_angle(double u, double s) {
  // D is symmetric: v = 2u - 1 in [-1, 1] (exact for u = m 2^-53), sign(v) picks the side and
  // |v| the cumulative probability G(a) = integral_0^a cos^(2s) / integral_0^(pi/2) cos^(2s) of
  // a = |theta| / 2 in [0, pi / 2].
  const double v = 2.0 * std::clamp(u, 0.0, 1.0) - 1.0;
  const double target_fraction = std::abs(v);
  constexpr int kN = kSpreadingTableIntervals;
  constexpr double h = 0.5 * kPi / kN;
  // ln cos(m h / 2) for m = 0 .. 2 kN - 1 (the interval ends and midpoints), the same for
  // every s: computed once (thread-safe static initialisation).
  static const std::array<double, 2 * kN> log_cos = [] {
    std::array<double, 2 * kN> table;
    for (int m = 0; m < 2 * kN; ++m) table[m] = std::log(std::cos(0.5 * m * h));
    return table;
  }();
  // cos^(2s) at a = m h / 2.
  const auto density = [s](int m) { return s == 0.0 ? 1.0 : std::exp(2.0 * s * log_cos[m]); };
  // cumulative[j] = integral_0^(j h) cos^(2s), by Simpson's rule on each interval (error
  // O(h^4 s^2)); edge[j] = cos^(2s)(j h).
  std::array<double, kN + 1> cumulative;
  std::array<double, kN + 1> edge;
  cumulative[0] = 0.0;
  edge[0] = 1.0;
  for (int j = 1; j < kN; ++j) {
    edge[j] = density(2 * j);
    cumulative[j] =
        cumulative[j - 1] + h / 6.0 * (edge[j - 1] + 4.0 * density(2 * j - 1) + edge[j]);
  }
  // The last interval, [pi/2 - h, pi/2], where cos^(2s)(pi/2 - t) = sin^(2s) t ~ t^(2s) has an
  // infinite derivative at t = 0 for s < 1/2 (Simpson would be ~1e-4 off for s ~ 0):
  // integral_0^h t^(2s) dt = h^(2s + 1) / (2s + 1), relative error O(s h^2).
  edge[kN] = s == 0.0 ? 1.0 : 0.0;
  cumulative[kN] = cumulative[kN - 1] + std::pow(h, 2.0 * s + 1.0) / (2.0 * s + 1.0);
  const double target = target_fraction * cumulative[kN];
  // First j with cumulative[j] >= target: the interval [j - 1, j].
  const auto it = std::lower_bound(cumulative.begin() + 1, cumulative.end(), target);
  const int j = it == cumulative.end() ? kN : static_cast<int>(it - cumulative.begin());
  const double mass = cumulative[j] - cumulative[j - 1];
  const double fraction =
      mass > 0.0 ? std::clamp((target - cumulative[j - 1]) / mass, 0.0, 1.0) : 0.0;
  // Inside the interval, invert the CDF of the density linear between its ends f0, f1
  // (normalised to the interval's mass): (f1 - f0) / 2 tau^2 + f0 tau = fraction (f0 + f1) / 2,
  // tau in [0, 1], in the stable form tau = 2c / (f0 + sqrt(f0^2 + 4 a c)), which equals
  // 2c / (f0 + sqrt(f0^2 + fraction (f1^2 - f0^2))) (the root is an interpolation: >= 0).
  const double f0 = edge[j - 1];
  const double f1 = edge[j];
  const double c = fraction * 0.5 * (f0 + f1);
  const double denominator = f0 + std::sqrt(f0 * f0 + fraction * (f1 * f1 - f0 * f0));
  const double tau = denominator > 0.0 ? std::clamp(2.0 * c / denominator, 0.0, 1.0) : fraction;
  const double a = (j - 1 + tau) * h;
  return std::copysign(2.0 * a, v);
}

WaveSet make_wave_set(const OceanSettings& settings, double max_steepness) {
  const int n = settings.waves;
  if (n < 1 || n > kMaxWaves) {
    throw std::invalid_argument("ocean.waves: expected an integer in [1, 4096], got " +
                                std::to_string(n));
  }
  if (!(settings.lambda_min > 0.0) || !std::isfinite(settings.lambda_max) ||
      !(settings.lambda_min <= settings.lambda_max)) {
    throw std::invalid_argument(
        "ocean.lambda_min, ocean.lambda_max: expected finite 0 < lambda_min <= lambda_max");
  }
  if (!(max_steepness > 0.0 && max_steepness < 1.0)) {
    throw std::invalid_argument("max_steepness: expected a number in (0, 1)");
  }

  WaveSet set;
  set.lambda_min = settings.lambda_min;
  set.lambda_max = settings.lambda_max;
  set.spectrum = settings.spectrum;
  set.wind_speed = std::max(settings.wind_speed, 0.0);
  set.max_steepness = max_steepness;

  // Downwind: the wind blows FROM the azimuth a (clockwise from north), so TOWARD a + 180 deg;
  // the unit vector of an azimuth b is (sin b, cos b) in (east, north).
  const double from = settings.wind_direction * kDegree;
  set.downwind = glm::dvec2(-std::sin(from), -std::cos(from));
  set.crosswind = glm::dvec2(-set.downwind.y, set.downwind.x);

  const double peak_omega = pierson_moskowitz_peak_angular_frequency(set.wind_speed);
  set.peak_wavelength =
      set.wind_speed > 0.0 ? 2.0 * kPi * kGravity / (peak_omega * peak_omega) : 0.0;

  // Geometric progression, i = 0 the longest: ln(lambda_i) = ln(lambda_max) - i step.
  const double log_span = std::log(set.lambda_max / set.lambda_min);
  const double log_step = n > 1 ? log_span / (n - 1) : 0.0;
  set.wavelength_ratio = std::exp(log_step);
  set.log_omega_band = log_omega_band(n, set.lambda_min, set.lambda_max);

  std::mt19937_64 generator(settings.seed);
  set.waves.resize(n);
  for (int i = 0; i < n; ++i) {
    Wave& wave = set.waves[i];
    // The last wave is lambda_min exactly (no rounding of the exponential at the end).
    wave.wavelength = i == 0       ? set.lambda_max
                      : i == n - 1 ? set.lambda_min
                                   : set.lambda_max * std::exp(-i * log_step);
    wave.wavenumber = 2.0 * kPi / wave.wavelength;
    wave.angular_frequency = std::sqrt(kGravity * wave.wavenumber);
    // Draws, in this order: the angle, then the phase.
    const double u_angle = uniform(generator);
    const double u_phase = uniform(generator);
    const double s = hasselmann_spreading_exponent(wave.angular_frequency, peak_omega);
    wave.angle = sample_hasselmann_angle(u_angle, s);
    const double c = std::cos(wave.angle);
    const double sn = std::sin(wave.angle);
    wave.direction = c * set.downwind + sn * set.crosswind;
    wave.wave_vector = wave.wavenumber * wave.direction;
    wave.phase = kTwoPi * u_phase;  // in [0, 2 pi): u < 1 and kTwoPi < 2 pi
    // PM amplitude of the wave's band: h = sqrt(2 S(omega) omega Delta).
    wave.amplitude =
        std::sqrt(2.0 * pierson_moskowitz_spectrum(wave.angular_frequency, set.wind_speed) *
                  wave.angular_frequency * set.log_omega_band);
  }

  const auto clamp_all = [&set, max_steepness]() {
    set.clamped_count = 0;
    for (Wave& wave : set.waves) {
      const double max_amplitude = max_steepness / wave.wavenumber;
      wave.clamped = wave.amplitude > max_amplitude;
      if (wave.clamped) {
        wave.amplitude = max_amplitude;
        ++set.clamped_count;
      }
    }
  };
  clamp_all();

  if (settings.spectrum == WaveSpectrum::OmegaMinus2) {
    // Constant steepness c with n (1 - sqrt(1 - c^2)) = the PM set's total slope variance:
    // with v = sigma_PM^2 / n, c^2 = 1 - (1 - v)^2 = v (2 - v). v <= the clamp's variance, so
    // c <= max_steepness up to rounding (std::min: rounding is not a clamp).
    double pm_variance = 0.0;
    for (const Wave& wave : set.waves) {
      pm_variance += glsl::TrochoidSlopeVariance(wave.wavenumber * wave.amplitude);
    }
    const double v = pm_variance / n;
    const double steepness = std::min(std::sqrt(v * (2.0 - v)), max_steepness);
    for (Wave& wave : set.waves) wave.amplitude = steepness / wave.wavenumber;
    clamp_all();
  }

  // Slope variances of the suffixes, summed from the short end (no cancellation: every term is
  // >= 0).
  set.tail_variance.assign(n + 1, SlopeVariance{});
  for (int i = n - 1; i >= 0; --i) {
    const SlopeVariance term = trochoid_slope_variance(set.waves[i]);
    set.tail_variance[i].along = set.tail_variance[i + 1].along + term.along;
    set.tail_variance[i].across = set.tail_variance[i + 1].across + term.across;
  }
  return set;
}

SlopeVariance trochoid_slope_variance(const Wave& wave, double weight) {
  const double variance = glsl::TrochoidSlopeVariance(wave.wavenumber * weight * wave.amplitude);
  const double c = std::cos(wave.angle);
  const double s = std::sin(wave.angle);
  return {c * c * variance, s * s * variance};
}

SlopeVariance tail_slope_variance(const WaveSet& wave_set, int first) {
  if (wave_set.tail_variance.empty()) return {};
  const int n = static_cast<int>(wave_set.tail_variance.size()) - 1;
  return wave_set.tail_variance[std::clamp(first, 0, n)];
}

SlopeVariance total_slope_variance(const WaveSet& wave_set) {
  return tail_slope_variance(wave_set, 0);
}

double wave_filter_weight(double n_min, double n_max, double ratio) {
  return glsl::WaveFilterWeight(n_min, n_max, ratio);
}

ResolvedRange resolved_wave_range(const WaveSet& wave_set, double length, double n_min,
                                  double n_max) {
  if (!(length >= 0.0)) {
    throw std::invalid_argument("resolved_wave_range: expected a length >= 0 (m)");
  }
  if (!(n_max > n_min) || !(n_min > 0.0) || !std::isfinite(n_max)) {
    throw std::invalid_argument("resolved_wave_range: expected 0 < n_min < n_max");
  }
  const int n = static_cast<int>(wave_set.waves.size());
  // The exact tests, as in WaveFilterWeight: xbar = (lambda_i / L - n_min) / (n_max - n_min),
  // w > 0 iff xbar > 0, w = 1 iff xbar >= 1 (L = 0 gives ratio +inf: resolved).
  const auto xbar = [&](int i) {
    return (wave_set.waves[i].wavelength / length - n_min) / (n_max - n_min);
  };
  const auto positive = [&](int i) { return xbar(i) > 0.0; };
  const auto full = [&](int i) { return xbar(i) >= 1.0; };
  // lambda_i = lambda_max r^-i > N L  <=>  i < y = ln(lambda_max / (N L)) / ln(r), r > 1: the
  // count of such i >= 0 is ceil(y) (and the count of i <= y, for w = 1, is floor(y) + 1, which
  // differs from ceil(y) only when y is an integer: the boundary test of count_prefix settles
  // it, as it settles the rounding of the logarithms). When all waves share one wavelength
  // (r = 1) the count is n or 0, from the first wave's test.
  const double log_ratio = std::log(wave_set.wavelength_ratio);
  const auto estimate = [&](double factor, bool first_in_range) {
    if (!(log_ratio > 0.0)) return first_in_range ? double(n) : 0.0;
    return std::log(wave_set.lambda_max / (factor * length)) / log_ratio;
  };
  ResolvedRange range;
  if (n == 0) return range;
  range.positive = count_prefix(estimate(n_min, positive(0)), n, positive);
  range.full = count_prefix(estimate(n_max, full(0)), n, full);
  return range;
}

SlopeVariance unresolved_slope_variance(const WaveSet& wave_set, double pixel_size, double n_min,
                                        double n_max) {
  const ResolvedRange range = resolved_wave_range(wave_set, pixel_size, n_min, n_max);
  SlopeVariance variance = tail_slope_variance(wave_set, range.positive);
  // Waves [range.full, range.positive) have 0 < w_n < 1; waves [0, range.full) have w_n = 1,
  // w_r = 0 and contribute nothing.
  for (int i = range.full; i < range.positive; ++i) {
    const Wave& wave = wave_set.waves[i];
    const double w_n = wave_filter_weight(n_min, n_max, wave.wavelength / pixel_size);
    const SlopeVariance term = trochoid_slope_variance(wave, 1.0 - w_n);
    variance.along += term.along;
    variance.across += term.across;
  }
  return variance;
}

double wrapped_phase(const Wave& wave, double time, glm::dvec2 origin) {
  // omega t - k_x x0_x - k_y x0_y + phi, each product reduced modulo 2 pi (with its rounding
  // error added back): a sum of terms in about [-pi, pi] (the errors are < 1e-5 rad), then one
  // final reduction to [0, 2 pi).
  const double sum = reduce_product(wave.angular_frequency, time) -
                     reduce_product(wave.wave_vector.x, origin.x) -
                     reduce_product(wave.wave_vector.y, origin.y) + wave.phase;
  // Already in [0, 2 pi) (e.g. at t = 0 at the origin, where it is phi exactly): kept as is.
  if (sum >= 0.0 && sum < kTwoPi) return sum;
  double phase = reduce_two_pi(sum);  // in about [-pi, pi]
  if (phase < 0.0) phase = (phase + kTwoPi) + kTwoPiTail;
  if (phase >= kTwoPi) phase -= kTwoPi;  // only when the addition rounded up to kTwoPi
  if (!(phase >= 0.0)) phase = 0.0;      // a non-finite input
  return phase;
}

std::vector<double> wrapped_phases(const WaveSet& wave_set, double time, glm::dvec2 origin) {
  std::vector<double> phases;
  phases.reserve(wave_set.waves.size());
  for (const Wave& wave : wave_set.waves) phases.push_back(wrapped_phase(wave, time, origin));
  return phases;
}

}  // namespace thalassa::ocean
