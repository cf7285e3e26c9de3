// thalassa — the environment-map sky provider: loading, sun extraction, irradiance, the
// below-horizon radiance and the maps for the GPU. Contracts, conventions and the sun-extraction
// rule are in the header (thalassa/atmosphere/environment_map.hpp); this file says how, and why
// where it is not obvious.

#include "thalassa/atmosphere/environment_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "gauss_legendre.hpp"

namespace thalassa::atmosphere {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

// The smallest photograph accepted, pixels: below this one texel spans more than 45 deg and
// nothing a sky provider returns would mean much.
constexpr int kMinWidth = 8;
constexpr int kMinHeight = 4;

// Texel luminance for ranking texels in the sun search (Rec. 709 / sRGB weights; see header).
constexpr Rgb kLuminanceWeights = {0.2126, 0.7152, 0.0722};
// The sun-search constants (reasons in the header, "Sun extraction", points 2-4).
constexpr double kSunPercentile = 0.99;
constexpr double kSunThresholdFactor = 20.0;
constexpr double kSunMaxAngularRadius = 5.0 * kDegree;
constexpr int kSunRingWidth = 2;  // texels

// Points of the Gauss-Legendre rule for the mean Fresnel reflectance: F(mu) is analytic on
// [0, 1] (cos theta_t >= sqrt(1 - 1 / n^2) > 0 keeps the denominators away from 0), and 64
// points agree with 32 to rounding for n = 1.333.
constexpr int kFresnelQuadraturePoints = 64;

// Sample grid per texel of the stereographic map (see the header).
constexpr int kMinSamplesPerAxis = 4;
constexpr int kMaxSamplesPerAxis = 16;

double luminance(const Rgb& c) {
  return kLuminanceWeights[0] * c[0] + kLuminanceWeights[1] * c[1] + kLuminanceWeights[2] * c[2];
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, pattern, a, b, c);
  return buffer;
}

// The unit vector along d; throws std::invalid_argument (naming `function`) when d is zero or
// not finite.
Vec3 normalized(const Vec3& d, const char* function) {
  const double length = std::hypot(d[0], d[1], d[2]);
  if (!std::isfinite(length) || length == 0.0)
    throw std::invalid_argument(std::string("thalassa::atmosphere::") + function +
                                ": the direction must be finite and non-zero");
  return {d[0] / length, d[1] / length, d[2] / length};
}

// Zenith angle theta in [0, pi] and azimuth clockwise from north of a unit ENU direction.
std::pair<double, double> zenith_and_azimuth(const Vec3& d) {
  return {std::atan2(std::hypot(d[0], d[1]), d[2]), std::atan2(d[0], d[1])};
}

Vec3 direction_of(double theta, double alpha) {
  const double s = std::sin(theta);
  return {s * std::sin(alpha), s * std::cos(alpha), std::cos(theta)};
}

}  // namespace

// ---- Free functions ----------------------------------------------------------------------

Vec2 stereographic_coordinates(const Vec3& direction) {
  const Vec3 r = normalized(direction, "stereographic_coordinates");
  const double d = 1.0 + r[2];
  if (d >= 2.0 / (kSkyMapMaxRadius * kSkyMapMaxRadius)) return {r[0] / d, r[1] / d};
  const double r_xy = std::hypot(r[0], r[1]);
  if (r_xy > 0.0) return {r[0] * (kSkyMapMaxRadius / r_xy), r[1] * (kSkyMapMaxRadius / r_xy)};
  return {kSkyMapMaxRadius, 0.0};
}

Vec3 stereographic_direction(const Vec2& u) {
  if (!std::isfinite(u[0]) || !std::isfinite(u[1]))
    throw std::invalid_argument("thalassa::atmosphere::stereographic_direction: u must be finite");
  const double radius = std::hypot(u[0], u[1]);
  if (radius <= 1.0) {
    const double s = radius * radius;
    return {2.0 * u[0] / (1.0 + s), 2.0 * u[1] / (1.0 + s), (1.0 - s) / (1.0 + s)};
  }
  // Outside the unit circle, through the inverted point v = u / |u|^2 (|v| < 1), which maps to
  // the mirror image in z: r = (2 v_x, 2 v_y, |v|^2 - 1) / (1 + |v|^2). No |u|^2 to overflow.
  const Vec2 v = {u[0] / radius / radius, u[1] / radius / radius};
  const double s = 1.0 / radius / radius;
  return {2.0 * v[0] / (1.0 + s), 2.0 * v[1] / (1.0 + s), (s - 1.0) / (1.0 + s)};
}

double equirect_texel_solid_angle(int width, int height, int y) {
  if (width < 1 || height < 1 || y < 0 || y >= height)
    throw std::invalid_argument(
        "thalassa::atmosphere::equirect_texel_solid_angle: need width, height >= 1 and "
        "0 <= y < height");
  const double middle = kPi * (2.0 * y + 1.0) / (2.0 * height);
  return (2.0 * kPi / width) * 2.0 * std::sin(middle) * std::sin(kPi / (2.0 * height));
}

double fresnel_reflectance(double mu, double n) {
  mu = std::clamp(mu, 0.0, 1.0);
  const double sin_t2 = (1.0 - mu * mu) / (n * n);
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double r_s = (mu - n * cos_t) / (mu + n * cos_t);
  const double r_p = (n * mu - cos_t) / (n * mu + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

double mean_fresnel_reflectance(double n) {
  if (!std::isfinite(n) || !(n > 1.0))
    throw std::invalid_argument(
        "thalassa::atmosphere::mean_fresnel_reflectance: the refractive index must be finite "
        "and > 1");
  // Over mu in [0, 1]: the rule on [-1, 1] moved there, mu = (x + 1) / 2 with half the weight.
  std::vector<double> nodes, weights;
  detail::gauss_legendre(kFresnelQuadraturePoints, nodes, weights);
  double sum = 0.0;
  for (int i = 0; i < kFresnelQuadraturePoints; ++i) {
    const double mu = 0.5 * (nodes[i] + 1.0);
    sum += 0.5 * weights[i] * fresnel_reflectance(mu, n) * mu;
  }
  return 2.0 * sum;
}

double mean_water_fresnel() {
  static const double value = mean_fresnel_reflectance(kWaterRefractiveIndex);
  return value;
}

// ---- EnvironmentMap ---------------------------------------------------------------------

EnvironmentMap::EnvironmentMap(const std::string& path, const EnvironmentMapOptions& options)
    : options_(options) {
  Image image;
  try {
    image = read_image(path);
  } catch (const ImageError& error) {
    // read_image's message already starts with the path.
    throw EnvironmentMapError(std::string(error.what()));
  }
  load(image, path);
}

EnvironmentMap::EnvironmentMap(const Image& image, const EnvironmentMapOptions& options,
                               std::string_view name)
    : options_(options) {
  load(image, name);
}

void EnvironmentMap::load(const Image& image, std::string_view name) {
  const std::string source(name);
  if (!std::isfinite(options_.north_offset))
    throw EnvironmentMapError(source + ": north_offset must be finite (radians)");
  if (!std::isfinite(options_.scale) || !(options_.scale > 0.0))
    throw EnvironmentMapError(source + ": scale must be finite and > 0, got " +
                              format("%g", options_.scale));
  const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height);
  if (image.width < kMinWidth || image.height < kMinHeight)
    throw EnvironmentMapError(source + ": the image is " + size +
                              " pixels; an environment map needs at least 8x4");
  if (image.width != 2 * image.height)
    throw EnvironmentMapError(source + ": the image is " + size +
                              " pixels; an equirectangular environment map must be exactly twice "
                              "as wide as it is tall (2:1)");
  const std::size_t texels = static_cast<std::size_t>(image.width) * image.height;
  if (image.rgba.size() != texels * 4)
    throw EnvironmentMapError(source + ": the image holds " + std::to_string(image.rgba.size()) +
                              " values, not " + size + " RGBA pixels");

  // Every value must be a radiance: finite and >= 0, and still a finite float once scaled (the
  // maps for the GPU are float; this also keeps every sum below far from double's range).
  std::size_t non_finite = 0, negative = 0;
  std::size_t first_non_finite = 0, first_negative = 0;
  for (std::size_t i = 0; i < texels; ++i)
    for (int c = 0; c < 3; ++c) {
      const double value = static_cast<double>(image.rgba[i * 4 + c]) * options_.scale;
      if (!(std::abs(value) <= std::numeric_limits<float>::max())) {
        if (non_finite++ == 0) first_non_finite = i * 4 + c;
      } else if (value < 0.0) {
        if (negative++ == 0) first_negative = i * 4 + c;
      }
    }
  const auto describe = [&](std::size_t count, std::size_t first, const char* what) {
    const std::size_t pixel = first / 4;
    const char channel = "RGB"[first % 4];
    return source + ": " + std::to_string(count) + " pixel value" +
           (count == 1 ? " is " : "s are ") + what + "; the first at pixel (x " +
           std::to_string(pixel % image.width) + ", y " + std::to_string(pixel / image.width) +
           ") channel " + std::string(1, channel) + " = " + format("%g", image.rgba[first]) +
           (options_.scale != 1.0 ? format(" (times scale %g)", options_.scale) : std::string()) +
           "; radiance must be finite and >= 0";
  };
  if (non_finite > 0)
    throw EnvironmentMapError(
        describe(non_finite, first_non_finite, "not finite (or beyond float range once scaled)"));
  if (negative > 0) throw EnvironmentMapError(describe(negative, first_negative, "negative"));

  width_ = image.width;
  height_ = image.height;
  rgb_.resize(texels * 3);
  for (std::size_t i = 0; i < texels; ++i)
    for (int c = 0; c < 3; ++c) rgb_[i * 3 + c] = image.rgba[i * 4 + c];
  solid_angle_.resize(height_);
  for (int y = 0; y < height_; ++y)
    solid_angle_[y] = equirect_texel_solid_angle(width_, height_, y);

  if (options_.extract_sun)
    extract_sun(name);
  else
    sun_search_ = "no sun search (extract_sun is off)";

  // The sky irradiance, texel by texel: a texel of radiance L over zenith angles
  // [theta_t, theta_b] (theta_b cut at the horizon) gives L (2 pi / W) ∫ cos θ sin θ dθ
  // = L (2 pi / W) (cos^2 theta_t - cos^2 theta_b) / 2. Row edges are at pi (y / H) so that the
  // horizon of an even height is exactly pi / 2; its cosine is taken as exactly 0.
  Rgb sum{};
  for (int y = 0; 2 * y < height_; ++y) {
    const double cos_top = std::cos(kPi * (static_cast<double>(y) / height_));
    const double cos_bottom =
        2 * (y + 1) >= height_ ? 0.0 : std::cos(kPi * (static_cast<double>(y + 1) / height_));
    const double weight =
        (2.0 * kPi / width_) * 0.5 * (cos_top - cos_bottom) * (cos_top + cos_bottom);
    Rgb row{};
    for (int x = 0; x < width_; ++x) {
      const float* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
      for (int c = 0; c < 3; ++c) row[c] += p[c];
    }
    for (int c = 0; c < 3; ++c) sum[c] += row[c] * weight;
  }
  const double fresnel = mean_water_fresnel();
  for (int c = 0; c < 3; ++c) {
    sky_irradiance_[c] = sum[c] * options_.scale;
    below_horizon_radiance_[c] = fresnel * sky_irradiance_[c] / kPi;
  }
}

void EnvironmentMap::extract_sun(std::string_view name) {
  const std::size_t texels = static_cast<std::size_t>(width_) * height_;
  const auto index = [&](int x, int y) { return static_cast<std::size_t>(y) * width_ + x; };
  const auto rgb_at = [&](std::size_t i) -> Rgb {
    return {rgb_[i * 3], rgb_[i * 3 + 1], rgb_[i * 3 + 2]};
  };
  std::vector<float> lum(texels);
  for (std::size_t i = 0; i < texels; ++i) lum[i] = static_cast<float>(luminance(rgb_at(i)));

  // The solid-angle-weighted percentile: sort (luminance, row) and walk up to the weight.
  std::vector<std::pair<float, int>> ranked(texels);
  for (std::size_t i = 0; i < texels; ++i)
    ranked[i] = {lum[i], static_cast<int>(i / static_cast<std::size_t>(width_))};
  std::sort(ranked.begin(), ranked.end());
  const double total = 4.0 * kPi;
  double cumulative = 0.0;
  double percentile = ranked.back().first;
  for (const auto& [value, row] : ranked) {
    cumulative += solid_angle_[row];
    if (cumulative >= kSunPercentile * total) {
      percentile = value;
      break;
    }
  }
  ranked = {};
  const double threshold = kSunThresholdFactor * percentile;
  const double brightest = *std::max_element(lum.begin(), lum.end());
  const double max_solid_angle = 2.0 * kPi * (1.0 - std::cos(kSunMaxAngularRadius));
  const std::string unit_note =
      format(" (P99 luminance %g, threshold %g, brightest %g, in the photo's units)", percentile,
             threshold, brightest);

  // 8-neighbours, wrapping in azimuth and over the poles (see the header).
  const auto for_each_neighbour = [&](std::size_t i, auto&& visit) {
    const int x = static_cast<int>(i % width_), y = static_cast<int>(i / width_);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        int nx = x + dx, ny = y + dy;
        if (ny < 0 || ny >= height_) {
          ny = ny < 0 ? 0 : height_ - 1;
          nx += width_ / 2;
        }
        nx = ((nx % width_) + width_) % width_;
        visit(index(nx, ny));
      }
  };

  // Connected regions above the threshold; keep the one of most luminance x solid angle among
  // those reaching above the horizon.
  std::vector<char> above(texels), seen(texels, 0);
  for (std::size_t i = 0; i < texels; ++i) above[i] = lum[i] > threshold;
  std::vector<std::size_t> best, region, stack;
  double best_power = -1.0, best_solid_angle = 0.0;
  int regions = 0;
  for (std::size_t start = 0; start < texels; ++start) {
    if (!above[start] || seen[start]) continue;
    region.clear();
    stack.assign(1, start);
    seen[start] = 1;
    double power = 0.0, solid_angle = 0.0;
    bool reaches_sky = false;
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      region.push_back(i);
      const int y = static_cast<int>(i / width_);
      power += lum[i] * solid_angle_[y];
      solid_angle += solid_angle_[y];
      reaches_sky = reaches_sky || 2 * y < height_;  // the texel's top edge is above the horizon
      for_each_neighbour(i, [&](std::size_t j) {
        if (above[j] && !seen[j]) {
          seen[j] = 1;
          stack.push_back(j);
        }
      });
    }
    if (!reaches_sky) continue;
    ++regions;
    if (power > best_power) {
      best_power = power;
      best_solid_angle = solid_angle;
      best.swap(region);
    }
  }
  if (regions == 0) {
    sun_search_ = "no sun found: no texel above the horizon is brighter than " +
                  format("%g", kSunThresholdFactor) + " times the 99th-percentile luminance" +
                  unit_note;
    return;
  }
  if (best_solid_angle > max_solid_angle) {
    sun_search_ = "no sun found: the brightest region above the threshold spans " +
                  format("%.4g sr, more than the %.4g sr of a disc of %g deg radius",
                         best_solid_angle, max_solid_angle, kSunMaxAngularRadius / kDegree) +
                  unit_note;
    return;
  }

  // The ring: texels within kSunRingWidth steps of the region, outside it.
  std::vector<char> in_region(texels, 0);
  for (std::size_t i : best) in_region[i] = 1;
  std::vector<char> visited = in_region;
  std::vector<std::size_t> frontier = best, next;
  Rgb ring_sum{};
  double ring_weight = 0.0;
  for (int step = 0; step < kSunRingWidth; ++step) {
    next.clear();
    for (std::size_t i : frontier)
      for_each_neighbour(i, [&](std::size_t j) {
        if (visited[j]) return;
        visited[j] = 1;
        next.push_back(j);
        const double w = solid_angle_[j / width_];
        const Rgb c = rgb_at(j);
        for (int k = 0; k < 3; ++k) ring_sum[k] += c[k] * w;
        ring_weight += w;
      });
    frontier.swap(next);
  }
  Rgb fill{};
  for (int k = 0; k < 3; ++k) fill[k] = ring_weight > 0.0 ? ring_sum[k] / ring_weight : 0.0;

  // Fill the region and collect what was removed.
  ExtractedSun sun;
  Vec3 centroid{};
  double weight_sum = 0.0, peak = 0.0;
  for (std::size_t i : best) {
    const double w_texel = solid_angle_[i / width_];
    Rgb excess{};
    for (int k = 0; k < 3; ++k) {
      float& value = rgb_[i * 3 + k];
      // min(value, fill) rounded to float never exceeds the float `value`: excess >= 0.
      const float filled = static_cast<float>(std::min(static_cast<double>(value), fill[k]));
      excess[k] = static_cast<double>(value) - static_cast<double>(filled);
      value = filled;
      sun.irradiance[k] += excess[k] * w_texel * options_.scale;
    }
    const double excess_luminance = luminance(excess);
    const double w = excess_luminance * w_texel;
    const int x = static_cast<int>(i % width_), y = static_cast<int>(i / width_);
    const Vec3 d = direction_of(kPi * (y + 0.5) / height_,
                                options_.north_offset + 2.0 * kPi * (x + 0.5) / width_);
    for (int k = 0; k < 3; ++k) centroid[k] += w * d[k];
    weight_sum += w;
    peak = std::max(peak, excess_luminance);
  }
  const double centroid_length = std::hypot(centroid[0], centroid[1], centroid[2]);
  if (!(weight_sum > 0.0) || !(centroid_length > 0.0)) {
    sun_search_ =
        "no sun found: the brightest region is no brighter than the sky around it" + unit_note;
    return;
  }
  for (int k = 0; k < 3; ++k) sun.direction[k] = centroid[k] / centroid_length;
  sun.solid_angle = weight_sum / peak;
  sun.angular_radius = 2.0 * std::asin(std::min(1.0, std::sqrt(sun.solid_angle / (4.0 * kPi))));
  sun.texel_count = static_cast<int>(best.size());
  sun_ = sun;

  const auto [theta, alpha] = zenith_and_azimuth(sun.direction);
  double azimuth = alpha / kDegree;
  if (azimuth < 0.0) azimuth += 360.0;
  sun_search_ = "sun found in " + std::string(name) + ": " + std::to_string(sun.texel_count) +
                " texels, " +
                format("azimuth %.3f deg, elevation %.3f deg, radius %.3f deg", azimuth,
                       90.0 - theta / kDegree, sun.angular_radius / kDegree) +
                format(", irradiance (%g, %g, %g) W m^-2 nm^-1", sun.irradiance[0],
                       sun.irradiance[1], sun.irradiance[2]);
}

std::optional<Vec3> EnvironmentMap::sun_direction() const {
  if (!sun_) return std::nullopt;
  return sun_->direction;
}

Rgb EnvironmentMap::sun_irradiance() const { return sun_ ? sun_->irradiance : Rgb{}; }

Rgb EnvironmentMap::texel(int x, int y) const {
  const float* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
  return {p[0] * options_.scale, p[1] * options_.scale, p[2] * options_.scale};
}

Rgb EnvironmentMap::lookup(double theta, double alpha, int last_row) const {
  // Texel centres are at theta = pi (y + 1/2) / H and alpha = north_offset + 2 pi (x + 1/2) / W.
  const double fy = std::clamp(theta / kPi * height_ - 0.5, 0.0, static_cast<double>(last_row));
  const int y0 = std::min(static_cast<int>(fy), last_row - 1);
  const double ty = fy - y0;
  double fx = (alpha - options_.north_offset) / (2.0 * kPi) * width_ - 0.5;
  fx -= width_ * std::floor(fx / width_);  // [0, W]
  int x0 = static_cast<int>(fx);
  const double tx = fx - x0;
  x0 %= width_;
  const int x1 = (x0 + 1) % width_;
  const Rgb a = texel(x0, y0), b = texel(x1, y0), c = texel(x0, y0 + 1), d = texel(x1, y0 + 1);
  Rgb out;
  for (int k = 0; k < 3; ++k)
    out[k] = (1.0 - ty) * ((1.0 - tx) * a[k] + tx * b[k]) + ty * ((1.0 - tx) * c[k] + tx * d[k]);
  return out;
}

Rgb EnvironmentMap::sky_radiance(const Vec3& direction) const {
  const auto [theta, alpha] =
      zenith_and_azimuth(normalized(direction, "EnvironmentMap::sky_radiance"));
  return lookup(theta, alpha, height_ - 1);
}

Rgb EnvironmentMap::radiance(const Vec3& direction) const {
  const Vec3 d = normalized(direction, "EnvironmentMap::radiance");
  if (d[2] < 0.0) return below_horizon_radiance_;
  const auto [theta, alpha] = zenith_and_azimuth(d);
  return lookup(theta, alpha, last_sky_row());
}

Image EnvironmentMap::stereographic_map(int size, double extent, double north_azimuth) const {
  if (size < 1 || !std::isfinite(extent) || !(extent > 0.0) || !std::isfinite(north_azimuth))
    throw std::invalid_argument(
        "thalassa::atmosphere::EnvironmentMap::stereographic_map: need size >= 1, a finite "
        "extent > 0 and a finite north_azimuth");
  const double texel_u = 2.0 * extent / size;
  // One u unit spans at most 2 rad (at the zenith: theta = 2 atan |u|); a photograph row spans
  // pi / H.
  const double wanted = std::ceil(2.0 * texel_u / (kPi / height_));
  const int n = static_cast<int>(std::clamp(wanted, static_cast<double>(kMinSamplesPerAxis),
                                            static_cast<double>(kMaxSamplesPerAxis)));
  Image image{size, size, std::vector<float>(static_cast<std::size_t>(size) * size * 4)};
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      Rgb sum{};
      for (int sj = 0; sj < n; ++sj)
        for (int si = 0; si < n; ++si) {
          const double ux = -extent + texel_u * (i + (si + 0.5) / n);
          const double uy = extent - texel_u * (j + (sj + 0.5) / n);
          const double radius = std::hypot(ux, uy);
          // |u| <= 1 is r_z >= 0 (radiance()'s sky side); theta = 2 atan |u| and the azimuth
          // of (r_x, r_y), parallel to u, give the direction without normalising.
          const Rgb value = radius <= 1.0
                                ? lookup(2.0 * std::atan(radius),
                                         std::atan2(ux, uy) + north_azimuth, last_sky_row())
                                : below_horizon_radiance_;
          for (int k = 0; k < 3; ++k) sum[k] += value[k];
        }
      float* p = image.pixel(i, j);
      for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(sum[k] / (n * n));
      p[3] = 1.0f;
    }
  return image;
}

Image EnvironmentMap::panorama(int width, double north_offset) const {
  if (width < 2 || width % 2 != 0 || !std::isfinite(north_offset))
    throw std::invalid_argument(
        "thalassa::atmosphere::EnvironmentMap::panorama: need an even width >= 2 and a finite "
        "north_offset");
  const int height = width / 2;
  const int n = std::clamp((width_ + width - 1) / width, 1, kMaxSamplesPerAxis);
  Image image{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 4)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Rgb sum{};
      double weight = 0.0;
      for (int sy = 0; sy < n; ++sy) {
        const double theta = kPi * (y + (sy + 0.5) / n) / height;
        const double w = std::sin(theta);  // the area element, so that the texel is an average
        for (int sx = 0; sx < n; ++sx) {
          const Rgb value =
              lookup(theta, north_offset + 2.0 * kPi * (x + (sx + 0.5) / n) / width, height_ - 1);
          for (int k = 0; k < 3; ++k) sum[k] += w * value[k];
          weight += w;
        }
      }
      float* p = image.pixel(x, y);
      for (int k = 0; k < 3; ++k) p[k] = static_cast<float>(sum[k] / weight);
      p[3] = 1.0f;
    }
  return image;
}

}  // namespace thalassa::atmosphere
