// Error metrics against a reference image (thalassa/validation/metrics.hpp, docs/validation.md).
#include "thalassa/validation/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "thalassa/planet/geodesy.hpp"
#include "thalassa/planet/nadir_frame.hpp"

namespace thalassa::validation {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;  // radians per degree

void check_same_size(const Image& a, const Image& b, const char* what) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument(std::string(what) + ": images of different sizes (" +
                                std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                                std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
}

void check_mask(const Image& image, const PixelMask& mask, const char* what) {
  if (mask.width != image.width || mask.height != image.height ||
      mask.inside.size() != static_cast<std::size_t>(mask.width) * mask.height)
    throw std::invalid_argument(std::string(what) + ": a mask of " + std::to_string(mask.width) +
                                "x" + std::to_string(mask.height) + " for an image of " +
                                std::to_string(image.width) + "x" + std::to_string(image.height));
}

// The four channels of a pixel: luminance, then R, G, B.
ChannelValues values_of(const float* p) { return {luminance(p), p[0], p[1], p[2]}; }

// Applies f to the four channels of each argument, member by member.
template <class F>
ChannelValues each(F f, const ChannelValues& a, const ChannelValues& b) {
  return {f(a.l, b.l), f(a.r, b.r), f(a.g, b.g), f(a.b, b.b)};
}

// num / den for a relative error: 0 / 0 is 0 (nothing to get wrong), x / 0 is NaN (undefined).
double relative(double num, double den) {
  if (den > 0.0) return num / den;
  return num == 0.0 ? 0.0 : kNaN;
}

// Wraps an angle difference (rad) into (-pi, pi].
double wrap_pi(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

void check_factor(const Image& image, int factor, const char* what) {
  if (factor < 1 || image.width % factor != 0 || image.height % factor != 0)
    throw std::invalid_argument(std::string(what) + ": a factor of " + std::to_string(factor) +
                                " for an image of " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) +
                                " (expected one of at least 1 that divides both sides)");
}

// The mean, in double, of the pixels of block (x, y) (factor x factor of them) for which
// `counts(i, j)` holds (the pixel's image coordinates); all of them where none does.
template <class Counts>
void block_mean(const Image& image, int factor, int x, int y, Counts counts, float* out) {
  for (const bool selective : {true, false}) {
    double sum[4] = {0.0, 0.0, 0.0, 0.0};
    int n = 0;
    for (int j = factor * y; j < factor * (y + 1); ++j)
      for (int i = factor * x; i < factor * (x + 1); ++i) {
        if (selective && !counts(i, j)) continue;
        const float* p = image.pixel(i, j);
        for (int k = 0; k < 4; ++k) sum[k] += p[k];
        ++n;
      }
    if (n == 0) continue;
    for (int k = 0; k < 4; ++k) out[k] = static_cast<float>(sum[k] / n);
    return;
  }
}

}  // namespace

Image box_filter(const Image& image, int factor) {
  check_factor(image, factor, "box_filter");
  Image out{image.width / factor, image.height / factor, {}};
  out.rgba.assign(static_cast<std::size_t>(out.width) * out.height * 4, 0.0f);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      block_mean(
          image, factor, x, y, [](int, int) { return true; }, out.pixel(x, y));
  return out;
}

Image supersampled_for_comparison(const Image& image, int factor, const PixelMask& image_sea,
                                  const PixelMask& sea_mask) {
  check_factor(image, factor, "supersampled_for_comparison");
  check_mask(image, image_sea, "supersampled_for_comparison");
  Image out{image.width / factor, image.height / factor, {}};
  check_mask(out, sea_mask, "supersampled_for_comparison");
  out.rgba.assign(static_cast<std::size_t>(out.width) * out.height * 4, 0.0f);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const bool sea = sea_mask(x, y);
      block_mean(
          image, factor, x, y, [&](int i, int j) { return !sea || image_sea(i, j); },
          out.pixel(x, y));
    }
  return out;
}

double luminance(const float* rgb) {
  return kLuminanceR * rgb[0] + kLuminanceG * rgb[1] + kLuminanceB * rgb[2];
}

int PixelMask::count() const {
  return static_cast<int>(std::count_if(inside.begin(), inside.end(), [](auto v) { return v; }));
}

PixelMask PixelMask::all(int width, int height) {
  return {width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height, 1)};
}

// ---------------------------------------------------------------------------------------------
// ViewGeometry

ViewGeometry::ViewGeometry(const Scene& scene)
    : width_(scene.image.width),
      height_(scene.image.height),
      basis_(camera_basis(scene.camera.heading, scene.camera.pitch, scene.camera.roll)),
      tan_half_fov_y_(std::tan(0.5 * scene.camera.fov_y * kDegree)),
      aspect_(static_cast<double>(scene.image.width) / scene.image.height),
      surface_(make_nadir_frame(Planet(scene.planet), scene.camera).sea_surface),
      camera_height_(scene.camera.height) {
  const std::size_t n = static_cast<std::size_t>(width_) * height_;
  sea_ = {width_, height_, std::vector<std::uint8_t>(n, 0)};
  beta_.assign(n, 0.0);
  weight_.assign(n, 0.0);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = index(x, y);
      sea_.inside[i] =
          ocean::sea_surface_distance(surface_, camera_height_, ray(x, y)).has_value() ? 1 : 0;
      beta_[i] = azimuth_and_beta(x, y).y;
      // Central differences over one pixel; the azimuth's wrapped, so a pixel that straddles
      // north is not 2 pi wide.
      const glm::dvec2 left = azimuth_and_beta(x - 0.5, y), right = azimuth_and_beta(x + 0.5, y);
      const glm::dvec2 top = azimuth_and_beta(x, y - 0.5), bottom = azimuth_and_beta(x, y + 0.5);
      const double da_dx = wrap_pi(right.x - left.x), db_dx = right.y - left.y;
      const double da_dy = wrap_pi(bottom.x - top.x), db_dy = bottom.y - top.y;
      weight_[i] = std::abs(da_dx * db_dy - da_dy * db_dx);
    }
  }
}

glm::dvec3 ViewGeometry::ray(double x, double y) const {
  const double u = 2.0 * (x + 0.5) / width_ - 1.0;
  const double v = 1.0 - 2.0 * (y + 0.5) / height_;
  return glm::normalize(view_ray(basis_, tan_half_fov_y_, aspect_, u, v));
}

glm::dvec2 ViewGeometry::azimuth_and_beta(double x, double y) const {
  const glm::dvec3 d = ray(x, y);
  const double horizontal = std::hypot(d.x, d.y);
  // Straight up or down the azimuth is undefined; any will do there (90 degrees from the
  // horizon, far outside any band near it).
  const glm::dvec2 azimuth =
      horizontal > 0.0 ? glm::dvec2(d.x, d.y) / horizontal : glm::dvec2(0, 1);
  const double ray_dip = std::atan2(-d.z, horizontal);  // rad below the horizontal
  const double horizon_dip =
      std::atan(ocean::sea_surface_horizon_dip(surface_, camera_height_, azimuth));
  return {std::atan2(azimuth.x, azimuth.y), ray_dip - horizon_dip};
}

// ---------------------------------------------------------------------------------------------
// Rows

std::vector<ChannelValues> row_totals(const Image& image, const PixelMask* mask) {
  if (mask) check_mask(image, *mask, "row_totals");
  std::vector<ChannelValues> rows(image.height);
  for (int y = 0; y < image.height; ++y) {
    ChannelValues sum;
    int pixels = 0;
    for (int x = 0; x < image.width; ++x) {
      if (mask && !(*mask)(x, y)) continue;
      sum = each(std::plus<>(), sum, values_of(image.pixel(x, y)));
      ++pixels;
    }
    rows[y] = pixels > 0 ? sum : ChannelValues{kNaN, kNaN, kNaN, kNaN};
  }
  return rows;
}

std::vector<ChannelValues> row_ratios(const std::vector<ChannelValues>& method,
                                      const std::vector<ChannelValues>& reference) {
  if (method.size() != reference.size())
    throw std::invalid_argument("row_ratios: " + std::to_string(method.size()) + " rows against " +
                                std::to_string(reference.size()));
  double brightest = 0.0;
  for (const ChannelValues& r : reference)
    if (std::isfinite(r.l)) brightest = std::max(brightest, r.l);
  const double floor = kSignificantRowFraction * brightest;
  std::vector<ChannelValues> ratios(method.size());
  const auto ratio = [](double m, double r) { return r > 0.0 ? m / r : kNaN; };
  for (std::size_t y = 0; y < method.size(); ++y) {
    if (reference[y].l > 0.0 && reference[y].l >= floor)
      ratios[y] = each(ratio, method[y], reference[y]);
    else
      ratios[y] = {kNaN, kNaN, kNaN, kNaN};
  }
  return ratios;
}

double max_row_deviation(const std::vector<ChannelValues>& ratios) {
  double worst = -1.0;  // none yet
  for (const ChannelValues& r : ratios)
    if (std::isfinite(r.l)) worst = std::max(worst, std::abs(r.l - 1.0));
  return worst >= 0.0 ? worst : kNaN;
}

double mean_row_deviation(const std::vector<ChannelValues>& ratios) {
  double sum = 0.0;
  int rows = 0;
  for (const ChannelValues& r : ratios)
    if (std::isfinite(r.l)) {
      sum += std::abs(r.l - 1.0);
      ++rows;
    }
  return rows > 0 ? sum / rows : kNaN;
}

double row_error(const std::vector<ChannelValues>& method_totals,
                 const std::vector<ChannelValues>& reference_totals,
                 const std::vector<ChannelValues>& ratios) {
  if (method_totals.size() != reference_totals.size() || ratios.size() != method_totals.size())
    throw std::invalid_argument("row_error: " + std::to_string(method_totals.size()) + ", " +
                                std::to_string(reference_totals.size()) + " and " +
                                std::to_string(ratios.size()) + " rows");
  double error = 0.0, total = 0.0;
  for (std::size_t y = 0; y < ratios.size(); ++y) {
    if (!std::isfinite(ratios[y].l)) continue;
    error += std::abs(method_totals[y].l - reference_totals[y].l);
    total += reference_totals[y].l;
  }
  return total > 0.0 ? error / total : kNaN;
}

std::vector<double> reference_row_uncertainty(std::span<const double> sample_row_changes,
                                              std::span<const double> lattice_row_changes,
                                              int rows) {
  std::vector<double> u(static_cast<std::size_t>(std::max(rows, 0)), kNaN);
  for (const std::span<const double> test : {sample_row_changes, lattice_row_changes}) {
    if (!test.empty() && static_cast<int>(test.size()) != rows)
      throw std::invalid_argument("reference_row_uncertainty: " + std::to_string(test.size()) +
                                  " rows of a test for " + std::to_string(rows));
    double largest = -1.0;  // none measured
    for (double change : test)
      if (std::isfinite(change)) largest = std::max(largest, change);
    if (largest < 0.0) continue;
    for (std::size_t y = 0; y < u.size(); ++y) {
      const double change = std::isfinite(test[y]) ? test[y] : largest;
      u[y] = std::isnan(u[y]) ? change : std::max(u[y], change);
    }
  }
  return u;
}

double row_error_difference_bound(const std::vector<ChannelValues>& a,
                                  const std::vector<ChannelValues>& b,
                                  const std::vector<ChannelValues>& reference,
                                  const std::vector<ChannelValues>& ratios,
                                  std::span<const double> uncertainty) {
  const std::size_t n = ratios.size();
  if (a.size() != n || b.size() != n || reference.size() != n || uncertainty.size() != n)
    throw std::invalid_argument("row_error_difference_bound: rows of " + std::to_string(a.size()) +
                                ", " + std::to_string(b.size()) + ", " +
                                std::to_string(reference.size()) + ", " + std::to_string(n) +
                                " and " + std::to_string(uncertainty.size()));
  double rise = 0.0, fall = 0.0, order = 0.0, total = 0.0;
  bool any_uncertainty = false;
  for (std::size_t y = 0; y < n; ++y) {
    if (!std::isfinite(ratios[y].l)) continue;
    const double r = reference[y].l;
    const double da = a[y].l - r, db = b[y].l - r;
    const auto g = [&](double shift) { return std::abs(da - shift) - std::abs(db - shift); };
    total += r;
    order += g(0.0);
    if (!std::isfinite(uncertainty[y])) continue;
    any_uncertainty = true;
    const double d = uncertainty[y] * std::abs(r);
    double high = std::max(g(d), g(-d)), low = std::min(g(d), g(-d));
    for (double kink : {da, db})
      if (std::abs(kink) <= d) {
        high = std::max(high, g(kink));
        low = std::min(low, g(kink));
      }
    rise += std::max(high - g(0.0), 0.0);
    fall += std::max(g(0.0) - low, 0.0);
  }
  if (!(total > 0.0) || !any_uncertainty) return kNaN;
  const double bound = order < 0.0 ? rise : order > 0.0 ? fall : std::max(rise, fall);
  return bound / total;
}

// ---------------------------------------------------------------------------------------------
// Errors over the sea

ErrorStats relative_errors(const Image& method, const Image& reference, const PixelMask& mask) {
  check_same_size(method, reference, "relative_errors");
  check_mask(method, mask, "relative_errors");
  ChannelValues abs_diff, abs_ref, sq_diff, sq_ref, sum_ref;
  ErrorStats stats;
  for (int y = 0; y < method.height; ++y) {
    for (int x = 0; x < method.width; ++x) {
      if (!mask(x, y)) continue;
      ++stats.pixels;
      const ChannelValues m = values_of(method.pixel(x, y)), r = values_of(reference.pixel(x, y));
      const ChannelValues d = each(std::minus<>(), m, r);
      abs_diff = each([](double s, double v) { return s + std::abs(v); }, abs_diff, d);
      sq_diff = each([](double s, double v) { return s + v * v; }, sq_diff, d);
      abs_ref = each([](double s, double v) { return s + std::abs(v); }, abs_ref, r);
      sq_ref = each([](double s, double v) { return s + v * v; }, sq_ref, r);
      sum_ref = each(std::plus<>(), sum_ref, r);
    }
  }
  // Over no pixel, undefined: relative(0, 0) is 0, which would read as a perfect match.
  const ChannelValues none{kNaN, kNaN, kNaN, kNaN};
  stats.relative_l1 = stats.pixels > 0 ? each(relative, abs_diff, abs_ref) : none;
  stats.relative_rms =
      stats.pixels > 0
          ? each([](double n, double d) { return std::sqrt(relative(n, d)); }, sq_diff, sq_ref)
          : none;
  const double n = stats.pixels > 0 ? stats.pixels : kNaN;
  const auto per_pixel = [n](double s, double) { return s / n; };
  stats.mean_abs = each(per_pixel, abs_diff, abs_diff);
  stats.reference_mean = each(per_pixel, sum_ref, sum_ref);
  return stats;
}

// ---------------------------------------------------------------------------------------------
// Near the horizon
//
// Paper 004 renders 360-degree equirectangular images: a row is one elevation, its pixels are
// equally spaced in azimuth, and the metric is the mean and standard deviation over a row of
// the luminance difference between a render and the baseline, plotted from the horizon to 5
// degrees below it (figs. 5, 7, 9, 11, 13), then averaged over those angles (fig. 14). Our
// images are perspective and may be rolled, so rows are not elevations. Choices, to keep the
// same quantity:
// - the angle is measured below the horizon in the pixel's own azimuth (the horizon dips with
//   height and, on the ellipsoid, slightly with azimuth), not below the horizontal;
// - pixels are gathered in bins of that angle (HorizonBandOptions::bin_deg; paper 004 has one
//   bin per image row), each pixel by its centre;
// - each pixel is weighted by its area in the (azimuth, angle) plane, so that a bin's mean is
//   the average over azimuth (uniform, as an equirectangular row) and over the angles within the
//   bin; the standard deviation is the population one (divided by the weight sum, not n - 1);
// - the difference is method minus reference (positive: the method is brighter);
// - the band's summary averages the non-empty bins' values with equal weight per bin.

namespace {
// The band's pixels and its summary from its bins: the non-empty bins' values averaged with
// equal weight per bin; NaN when every bin is empty.
void summarize_bins(HorizonBand& band) {
  double mean_sum = 0.0, std_sum = 0.0, ref_sum = 0.0;
  int filled = 0;
  band.pixels = 0;
  for (const HorizonBin& b : band.bins) {
    band.pixels += b.pixels;
    if (b.pixels > 0 && b.weight > 0.0) {
      mean_sum += b.mean;
      std_sum += b.std;
      ref_sum += b.reference_mean;
      ++filled;
    }
  }
  band.mean = filled ? mean_sum / filled : kNaN;
  band.std = filled ? std_sum / filled : kNaN;
  band.reference_mean = filled ? ref_sum / filled : kNaN;
}
}  // namespace

HorizonBand horizon_band(const Image& method, const Image& reference, const ViewGeometry& view,
                         const HorizonBandOptions& options, const PixelMask* compared) {
  check_same_size(method, reference, "horizon_band");
  if (method.width != view.width() || method.height != view.height())
    throw std::invalid_argument("horizon_band: images of " + std::to_string(method.width) + "x" +
                                std::to_string(method.height) + " for a view of " +
                                std::to_string(view.width()) + "x" + std::to_string(view.height()));
  if (!(options.depth_deg > 0.0) || !(options.bin_deg > 0.0))
    throw std::invalid_argument("horizon_band: depth_deg and bin_deg must be positive");
  const int bins = static_cast<int>(std::ceil(options.depth_deg / options.bin_deg - 1e-9));
  struct Sums {
    int n = 0;
    double w = 0.0, wd = 0.0, wr = 0.0, wdd = 0.0;  // wdd: sum w (d - mean)^2, second pass
  };
  std::vector<Sums> sums(bins);
  const double depth = options.depth_deg * kDegree, bin = options.bin_deg * kDegree;
  // Two passes over the band (means, then squared deviations from them): no cancellation in
  // the variance, so a constant difference has a standard deviation of exactly 0.
  for (int pass = 0; pass < 2; ++pass) {
    for (int y = 0; y < method.height; ++y) {
      for (int x = 0; x < method.width; ++x) {
        const double beta = view.below_horizon(x, y);
        if (!(beta >= 0.0 && beta < depth)) continue;
        if (compared && !(*compared)(x, y)) continue;
        const int k = std::min(bins - 1, static_cast<int>(beta / bin));
        const double w = view.azimuth_weight(x, y);
        const double r = luminance(reference.pixel(x, y));
        const double d = luminance(method.pixel(x, y)) - r;
        Sums& s = sums[k];
        if (pass == 0) {
          ++s.n;
          s.w += w;
          s.wd += w * d;
          s.wr += w * r;
        } else {
          const double deviation = d - s.wd / s.w;
          s.wdd += w * deviation * deviation;
        }
      }
    }
  }
  HorizonBand band;
  for (int k = 0; k < bins; ++k) {
    const Sums& s = sums[k];
    HorizonBin b;
    b.beta_lo_deg = k * options.bin_deg;
    b.beta_hi_deg = std::min(options.depth_deg, (k + 1) * options.bin_deg);
    b.pixels = s.n;
    b.weight = s.w;
    if (s.n > 0 && s.w > 0.0) {
      b.mean = s.wd / s.w;
      b.std = std::sqrt(s.wdd / s.w);
      b.reference_mean = s.wr / s.w;
    } else {
      b.mean = b.std = b.reference_mean = kNaN;
    }
    band.bins.push_back(b);
  }
  summarize_bins(band);
  return band;
}

bool same_horizon_bins(const HorizonBand& a, const HorizonBand& b) {
  if (a.bins.size() != b.bins.size()) return false;
  for (std::size_t k = 0; k < a.bins.size(); ++k)
    if (a.bins[k].beta_lo_deg != b.bins[k].beta_lo_deg ||
        a.bins[k].beta_hi_deg != b.bins[k].beta_hi_deg)
      return false;
  return true;
}

// Per bin, the pixels of every band as one set: with W_i, m_i, s_i and r_i band i's weight,
// mean, standard deviation and reference mean there, the set's weight is W = sum W_i, its mean
// m = sum W_i m_i / W, its variance sum W_i (s_i^2 + (m_i - m)^2) / W (each band's spread about
// its own mean plus its mean's about the set's: the parallel-axis form, no cancellation, so that
// bands of one constant difference pool to a standard deviation of exactly 0), its reference
// mean sum W_i r_i / W. A bin empty in a band (no pixel or no weight) adds nothing to it.
HorizonBand pool_horizon_bands(std::span<const HorizonBand> bands) {
  HorizonBand pooled;
  if (bands.empty()) {
    pooled.mean = pooled.std = pooled.reference_mean = kNaN;
    return pooled;
  }
  const std::vector<HorizonBin>& first = bands.front().bins;
  for (const HorizonBand& band : bands) {
    if (!same_horizon_bins(band, bands.front()))
      throw std::invalid_argument(
          "pool_horizon_bands: expected bands of the same bins (depth and bin width), got " +
          std::to_string(first.size()) + " and " + std::to_string(band.bins.size()) + " bins");
  }
  const auto filled = [](const HorizonBin& b) {
    return b.pixels > 0 && b.weight > 0.0 && std::isfinite(b.mean) && std::isfinite(b.std) &&
           std::isfinite(b.reference_mean);
  };
  for (std::size_t k = 0; k < first.size(); ++k) {
    HorizonBin p;
    p.beta_lo_deg = first[k].beta_lo_deg;
    p.beta_hi_deg = first[k].beta_hi_deg;
    double wd = 0.0, wr = 0.0;
    for (const HorizonBand& band : bands) {
      const HorizonBin& b = band.bins[k];
      if (!filled(b)) continue;
      p.pixels += b.pixels;
      p.weight += b.weight;
      wd += b.weight * b.mean;
      wr += b.weight * b.reference_mean;
    }
    if (p.weight > 0.0) {
      p.mean = wd / p.weight;
      p.reference_mean = wr / p.weight;
      double spread = 0.0;
      for (const HorizonBand& band : bands) {
        const HorizonBin& b = band.bins[k];
        if (!filled(b)) continue;
        const double offset = b.mean - p.mean;
        spread += b.weight * (b.std * b.std + offset * offset);
      }
      p.std = std::sqrt(spread / p.weight);
    } else {
      p.mean = p.std = p.reference_mean = kNaN;
    }
    pooled.bins.push_back(p);
  }
  summarize_bins(pooled);
  return pooled;
}

// ---------------------------------------------------------------------------------------------
// Temporal

double flicker(std::span<const Image> frames, const PixelMask& mask) {
  if (frames.size() < 2) return kNaN;
  double total = 0.0;
  for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
    const Image &a = frames[k], &b = frames[k + 1];
    check_same_size(a, b, "flicker");
    check_mask(a, mask, "flicker");
    double change = 0.0, level = 0.0;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x) {
        if (!mask(x, y)) continue;
        const double la = luminance(a.pixel(x, y)), lb = luminance(b.pixel(x, y));
        change += std::abs(lb - la);
        level += 0.5 * (la + lb);
      }
    total += relative(change, level);
  }
  return total / static_cast<double>(frames.size() - 1);
}

double temporal_error(std::span<const Image> method, std::span<const Image> reference,
                      const PixelMask& mask) {
  if (method.size() != reference.size())
    throw std::invalid_argument("temporal_error: " + std::to_string(method.size()) +
                                " frames against " + std::to_string(reference.size()));
  if (method.size() < 2) return kNaN;
  double error = 0.0, change = 0.0;
  for (std::size_t k = 0; k + 1 < method.size(); ++k) {
    for (const Image* image : {&method[k], &method[k + 1], &reference[k + 1]}) {
      check_same_size(*image, reference[k], "temporal_error");
      check_mask(*image, mask, "temporal_error");
    }
    for (int y = 0; y < mask.height; ++y)
      for (int x = 0; x < mask.width; ++x) {
        if (!mask(x, y)) continue;
        const double dm = luminance(method[k + 1].pixel(x, y)) - luminance(method[k].pixel(x, y));
        const double dr =
            luminance(reference[k + 1].pixel(x, y)) - luminance(reference[k].pixel(x, y));
        error += std::abs(dm - dr);
        change += std::abs(dr);
      }
  }
  return relative(error, change);
}

// ---------------------------------------------------------------------------------------------

TermMetrics compare_images(const Image& method, const Image& reference, const ViewGeometry& view,
                           const HorizonBandOptions& options, const PixelMask* compared,
                           double black_level) {
  check_same_size(method, reference, "compare_images");
  const PixelMask& mask = compared ? *compared : view.sea_mask();
  if (mask.width != method.width || mask.height != method.height)
    throw std::invalid_argument("compare_images: a mask of " + std::to_string(mask.width) + "x" +
                                std::to_string(mask.height) + " for images of " +
                                std::to_string(method.width) + "x" + std::to_string(method.height));
  TermMetrics m;
  m.row_totals = row_totals(method, &mask);
  const std::vector<ChannelValues> reference_totals = row_totals(reference, &mask);
  m.row_ratios = row_ratios(m.row_totals, reference_totals);
  m.max_row_deviation = max_row_deviation(m.row_ratios);
  m.mean_row_deviation = mean_row_deviation(m.row_ratios);
  m.row_error = row_error(m.row_totals, reference_totals, m.row_ratios);
  m.error = relative_errors(method, reference, mask);
  m.horizon = horizon_band(method, reference, view, options, compared);
  const auto black = [&](const Image& image) {
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        if (!mask(x, y)) continue;
        const float* p = image.pixel(x, y);
        if (!(std::max({p[0], p[1], p[2]}) < black_level)) return false;
      }
    return true;
  };
  m.reference_black = black_level > 0.0 && m.error.pixels > 0 && black(reference);
  if (m.reference_black) {
    for (ChannelValues& r : m.row_ratios) r = {kNaN, kNaN, kNaN, kNaN};
    m.max_row_deviation = max_row_deviation(m.row_ratios);
    m.mean_row_deviation = kNaN;
    m.row_error = kNaN;
    const double relative = black(method) ? 0.0 : kNaN;
    m.error.relative_l1 = m.error.relative_rms = {relative, relative, relative, relative};
  }
  return m;
}

PixelMask resolved_rows_mask(const PixelMask& mask, const std::vector<double>& resolved_rows,
                             double min_fraction) {
  if (resolved_rows.empty()) return mask;
  if (static_cast<int>(resolved_rows.size()) != mask.height)
    throw std::invalid_argument("resolved_rows_mask: " + std::to_string(resolved_rows.size()) +
                                " rows for a mask of " + std::to_string(mask.height));
  PixelMask out = mask;
  for (int y = 0; y < out.height; ++y)
    if (!(resolved_rows[y] >= min_fraction))
      for (int x = 0; x < out.width; ++x)
        out.inside[static_cast<std::size_t>(y) * out.width + x] = 0;
  return out;
}

Image reference_for_comparison(const Image& reference, const Image& sea,
                               const PixelMask& sea_mask) {
  if (sea.width == 0 && sea.height == 0) return reference;
  check_same_size(sea, reference, "reference_for_comparison");
  check_mask(reference, sea_mask, "reference_for_comparison");
  Image out = reference;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * out.width + x) * 4;
      if (!sea_mask(x, y) || !(sea.rgba[i + 3] > 0.0f)) continue;
      for (int c = 0; c < 3; ++c) out.rgba[i + c] = sea.rgba[i + c];
    }
  return out;
}

}  // namespace thalassa::validation
