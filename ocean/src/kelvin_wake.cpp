// thalassa — the Kelvin wake (kelvin_wake.hpp; derivations in docs/wakes.md).
#include "thalassa/ocean/kelvin_wake.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace thalassa::ocean {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kSqrt2 = std::numbers::sqrt2;
constexpr double kSqrt3 = std::numbers::sqrt3;

[[noreturn]] void fail(const char* name, double value, const char* expected) {
  std::ostringstream message;
  message.precision(17);
  message << "thalassa::ocean::kelvin_wake_at: " << name << ": expected " << expected << ", got "
          << value;
  throw std::invalid_argument(message.str());
}

void check(const KelvinWakeParams& p) {
  if (!std::isfinite(p.speed)) fail("speed (m/s)", p.speed, "a finite number");
  if (!std::isfinite(p.amplitude) || p.amplitude < 0.0)
    fail("amplitude (m)", p.amplitude, "a finite number >= 0");
  if (!std::isfinite(p.draft) || p.draft <= 0.0) fail("draft (m)", p.draft, "a finite number > 0");
  if (!std::isfinite(p.length) || p.length <= 0.0)
    fail("length (m)", p.length, "a finite number > 0");
}

// 3 x^2 - 2 x^3 of clamp((x - a) / (b - a), 0, 1): the paper's w(a, b, x), C1.
double smoothstep(double a, double b, double x) {
  const double u = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

double wrap(double x) {
  double r = std::fmod(x, kTwoPi);
  if (r < 0.0) r += kTwoPi;
  return r >= kTwoPi ? 0.0 : r;
}

// psi''' at the cusp, rad: (3 sqrt 3 / 2) k0 b (docs/wakes.md, "the cusp").
double cusp_third_derivative(double k0, double behind) { return 1.5 * kSqrt3 * k0 * behind; }

// R = 2 / (pi Ai_max^2) (psi''' / 2)^(2/3), rad: with it, sqrt(2 pi / R) is half of the Airy
// peak 2 pi Ai_max (2 / psi''')^(1/3) of the uniform solution at the cusp (two branches meet).
double cusp_regularisation(double k0, double behind) {
  const double third = cusp_third_derivative(k0, behind);
  return 2.0 / (kPi * kAiryMaximum * kAiryMaximum) * std::cbrt(0.25 * third * third);
}

// |psi''| with the cusp's regularisation: (psi''^4 + R^4)^(1/4). The 4-norm (rather than the
// 2-norm) leaves the amplitude away from the cusp within 0.2 % of the plain stationary-phase
// value once k0 b > 600 (R / |psi''| ~ (k0 b)^(-1/3) on the track).
double regularised(double psi2, double r) {
  const double m = std::max(std::abs(psi2), r);
  if (m == 0.0) return 0.0;
  const double u = psi2 / m, v = r / m;
  return m * std::sqrt(std::sqrt(u * u * u * u + v * v * v * v));
}

// The factor that makes the transverse amplitude on the track at b = lambda0 exactly a_ref:
// there k0 b = 2 pi, psi'' = -2 pi and R are pure numbers, so is the factor
// 1 / sqrt(2 pi / (psi''^4 + R^4)^(1/4)).
double reference_normalisation() {
  static const double factor = [] {
    const double k0 = 1.0, b = kTwoPi;
    return 1.0 / std::sqrt(kTwoPi / regularised(-k0 * b, cusp_regularisation(k0, b)));
  }();
  return factor;
}

// One branch at t = tan(theta) >= 0 (the lateral sign applied by the caller), before the fades.
// `airy` multiplies the amplitude (1 inside the wedge).
WakeWave branch(const KelvinWakeParams& p, double k0, double t, double behind, double lateral_abs,
                double sign, double offset, double regularisation, double airy) {
  WakeWave w;
  const double s = std::sqrt(1.0 + t * t);  // sec(theta)
  w.angle = sign * std::atan(t);
  w.wavenumber = k0 * s * s;
  w.wave_vector = {k0 * s, sign * k0 * s * t};  // k0 sec^2 (cos, sin) = k0 sec (1, t)
  w.wavelength = kTwoPi / w.wavenumber;
  w.angular_frequency = std::sqrt(kGravity * w.wavenumber);
  const double psi = -k0 * s * (behind - lateral_abs * t);
  const double psi2 = -k0 * (behind - 4.0 * lateral_abs * t) * s * s * s;
  const double density = p.amplitude * std::exp(-k0 * p.draft * t * t);
  w.amplitude = density * std::sqrt(kTwoPi / regularised(psi2, regularisation)) *
                reference_normalisation() * airy;
  w.argument = wrap(-(psi + offset));
  return w;
}

WakeWave empty_wave(double angle) {
  WakeWave w;
  w.angle = angle;
  return w;
}

}  // namespace

double kelvin_reference_normalisation() { return reference_normalisation(); }

double WakeWave::slope_variance(double weight) const {
  const double x = std::min(wavenumber * weight * amplitude, 1.0);
  const double x2 = x * x;
  return x2 / (1.0 + std::sqrt(1.0 - x2));  // 1 - sqrt(1 - x^2) without cancellation
}

SlopeVariance KelvinWakeSample::slope_variance(glm::dvec2 axis, double weight_transverse,
                                               double weight_divergent) const {
  SlopeVariance v;
  const double axis_length = std::hypot(axis.x, axis.y);
  const glm::dvec2 a = axis_length > 0.0 ? axis / axis_length : glm::dvec2(1.0, 0.0);
  const auto add = [&](const WakeWave& w, double weight) {
    const double variance = w.slope_variance(weight);
    if (variance == 0.0 || w.wavenumber == 0.0) return;
    const double c = glm::dot(w.wave_vector, a) / w.wavenumber;  // cos(angle to the axis)
    const double c2 = std::min(c * c, 1.0);
    v.along += variance * c2;
    v.across += variance * (1.0 - c2);
  };
  add(transverse, weight_transverse);
  add(divergent, weight_divergent);
  return v;
}

double KelvinWakeSample::linear_height() const {
  return transverse.amplitude * std::cos(transverse.argument) +
         divergent.amplitude * std::cos(divergent.argument);
}

double kelvin_transverse_wavenumber(double speed) {
  if (!(std::abs(speed) >= kMinimumWakeSpeed) || !std::isfinite(speed)) return 0.0;
  return kGravity / (speed * speed);
}

double kelvin_transverse_wavelength(double speed) {
  const double k0 = kelvin_transverse_wavenumber(speed);
  return k0 > 0.0 ? kTwoPi / k0 : 0.0;
}

double kelvin_wake_displacement_bound(double speed) {
  return 2.0 * kMaxTrochoidSteepness * speed * speed / kGravity;
}

KelvinRoots kelvin_stationary_roots(double tau) {
  KelvinRoots r;
  if (!(tau > 0.0)) {
    r.transverse = 0.0;
    r.divergent = std::numeric_limits<double>::infinity();
    return r;
  }
  if (tau >= kKelvinTanHalfAngle) {
    r.transverse = r.divergent = 1.0 / kSqrt2;
    return r;
  }
  const double s = std::sqrt(std::max(0.0, 1.0 - 8.0 * tau * tau));
  r.transverse = 2.0 * tau / (1.0 + s);
  r.divergent = (1.0 + s) / (4.0 * tau);
  return r;
}

double kelvin_phase(double k0, double theta, double behind, double lateral) {
  const double t = std::tan(theta);
  return -k0 * std::sqrt(1.0 + t * t) * (behind - lateral * t);
}

KelvinWakeSample kelvin_wake_at(const KelvinWakeParams& params, double behind, double lateral) {
  check(params);
  KelvinWakeSample out;
  const double sign = lateral < 0.0 ? -1.0 : 1.0;
  out.transverse = empty_wave(0.0);
  out.divergent = empty_wave(sign * kPi / 2.0);
  const double k0 = kelvin_transverse_wavenumber(params.speed);
  if (k0 == 0.0 || params.amplitude == 0.0) return out;
  if (!std::isfinite(behind) || !std::isfinite(lateral)) return out;
  if (!(behind > 0.0) || behind >= params.length) return out;

  const double lambda0 = kTwoPi / k0;
  const double y = std::abs(lateral);
  const double tau = y / behind;
  // Fades: in from the ship over one transverse wavelength (the far-field form is not valid
  // nearer), out over the last kWakeTailFraction of the length.
  const double fade =
      smoothstep(0.0, lambda0, behind) *
      (1.0 - smoothstep((1.0 - kWakeTailFraction) * params.length, params.length, behind));
  if (fade == 0.0) return out;  // also keeps b^(-1/2) from overflowing for a denormal b
  const double third = cusp_third_derivative(k0, behind);
  const double regularisation = cusp_regularisation(k0, behind);
  constexpr double kOffset = kPi / 4.0;  // stationary phase: sign(psi'') pi / 4

  if (tau <= kKelvinTanHalfAngle) {
    out.inside_wedge = true;
    const KelvinRoots roots = kelvin_stationary_roots(tau);
    out.transverse =
        branch(params, k0, roots.transverse, behind, y, sign, -kOffset, regularisation, fade);
    // Past t ~ 30 the source term exp(-k0 d t^2) is below 1e-300 for any wake worth drawing;
    // the root itself is +inf on the track.
    if (std::isfinite(roots.divergent) &&
        k0 * params.draft * roots.divergent * roots.divergent < 700.0) {
      out.divergent =
          branch(params, k0, roots.divergent, behind, y, sign, kOffset, regularisation, fade);
    }
  } else {
    // Beyond the cusp line: both branches stay at the cusp and decay as Ai's tail, z = delta
    // (psi''' / 2)^(-1/3), delta = d psi / d theta at the cusp = k0 b sqrt(3/2) (2 tau - 1/sqrt2).
    const double delta = k0 * behind * std::sqrt(1.5) * (2.0 * tau - 1.0 / kSqrt2);
    const double z = delta / std::cbrt(0.5 * third);
    const double airy = z >= kWakeAiryCutoff
                            ? 0.0
                            : std::exp(-2.0 / 3.0 * z * std::sqrt(z)) *
                                  (1.0 - smoothstep(kWakeAiryFadeStart, kWakeAiryCutoff, z));
    if (airy > 0.0) {
      const double tc = 1.0 / kSqrt2;
      out.transverse =
          branch(params, k0, tc, behind, y, sign, -kOffset, regularisation, fade * airy);
      out.divergent = branch(params, k0, tc, behind, y, sign, kOffset, regularisation, fade * airy);
    }
  }
  for (WakeWave* w : {&out.transverse, &out.divergent}) {
    if (w->wavenumber * w->amplitude > kMaxTrochoidSteepness) {
      w->amplitude = kMaxTrochoidSteepness / w->wavenumber;
      w->clamped = true;
    }
  }
  return out;
}

double kelvin_wake_half_width(const KelvinWakeParams& params) {
  check(params);
  const double k0 = kelvin_transverse_wavenumber(params.speed);
  if (k0 == 0.0 || params.amplitude == 0.0) return 0.0;
  const double b = params.length;
  // z = k0 b sqrt(3/2) 2 dtau / (psi'''/2)^(1/3) = kWakeAiryCutoff at the tail's end.
  const double dtau = kWakeAiryCutoff * std::cbrt(0.5 * cusp_third_derivative(k0, b)) /
                      (2.0 * std::sqrt(1.5) * k0 * b);
  return b * (kKelvinTanHalfAngle + dtau);
}

}  // namespace thalassa::ocean
