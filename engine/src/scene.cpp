// thalassa — scene files: the key table, validation, overrides and the solar position.
//
// key_table() below is the single source of truth for every scene key: its type, range, unit,
// default, documentation and the Scene field it fills. Validation, the embedded default scene,
// scene_keys() and the defaults of SceneBuilder all come from it; the in-class initializers of
// the structs in scene.hpp must agree with it (tests/unit/scene_test.cpp checks that).
#include "thalassa/engine/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <type_traits>
#include <utility>

#include "scene_features.hpp"
#include "strict_json.hpp"

namespace thalassa {
namespace {

using json = nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Enumerations: the spelling of each value in files, in one place per type.

template <class E>
struct EnumNames;

template <>
struct EnumNames<ExrPixelType> {
  static constexpr std::array<std::pair<std::string_view, ExrPixelType>, 2> values{{
      {"half", ExrPixelType::Half},
      {"float", ExrPixelType::Float},
  }};
};

template <>
struct EnumNames<PlanetShape> {
  static constexpr std::array<std::pair<std::string_view, PlanetShape>, 2> values{{
      {"wgs84", PlanetShape::Wgs84},
      {"sphere", PlanetShape::Sphere},
  }};
};

template <>
struct EnumNames<WaveSpectrum> {
  static constexpr std::array<std::pair<std::string_view, WaveSpectrum>, 2> values{{
      {"pierson-moskowitz", WaveSpectrum::PiersonMoskowitz},
      {"omega-2", WaveSpectrum::OmegaMinus2},
  }};
};

// ---------------------------------------------------------------------------------------------
// Storing an already validated JSON value into a Scene field.

void assign(double& dst, const json& v) { dst = v.get<double>(); }
void assign(int& dst, const json& v) { dst = static_cast<int>(v.get<std::int64_t>()); }
void assign(std::uint32_t& dst, const json& v) {
  dst = static_cast<std::uint32_t>(v.get<std::int64_t>());
}
void assign(std::string& dst, const json& v) { dst = v.get<std::string>(); }
void assign(std::optional<std::string>& dst, const json& v) { dst = v.get<std::string>(); }

template <class E>
requires std::is_enum_v<E>
void assign(E& dst, const json& v) {
  const auto& name = v.get_ref<const std::string&>();
  for (const auto& [spelling, value] : EnumNames<E>::values) {
    if (spelling == name) dst = value;
  }
}

// The Scene field reached from a Scene by a chain of member pointers, e.g.
// field_of<&Scene::camera, &CameraSettings::height>.
template <auto... Members>
auto& field_of(Scene& s) {
  return (s.*....*Members);
}

template <auto... Members>
void store(Scene& s, const json& v) {
  assign(field_of<Members...>(s), v);
}

template <auto... Members>
using FieldType = std::remove_cvref_t<decltype(field_of<Members...>(std::declval<Scene&>()))>;

// ---------------------------------------------------------------------------------------------
// The key table.

enum class Kind { Number, Integer, String, Enum };

struct Range {
  double lo = 0.0;
  double hi = 0.0;
  bool lo_open = false;  // (lo, hi] instead of [lo, hi]
};

struct KeyDesc {
  std::string_view path;  // "camera.height"
  Kind kind = Kind::Number;
  Range range;                                  // Number and Integer only
  std::vector<std::string_view> allowed;        // Enum only
  std::string_view text_range;                  // String only: what is accepted, in words
  bool (*text_ok)(std::string_view) = nullptr;  // String only: an extra format check
  std::string_view unit;
  std::string_view default_json;  // JSON text; empty = no default (the key is absent)
  std::string_view doc;           // one sentence
  void (*store)(Scene&, const json&) = nullptr;
};

template <auto... M>
KeyDesc number(std::string_view path, Range r, std::string_view unit, std::string_view def,
               std::string_view doc) {
  static_assert(std::is_same_v<FieldType<M...>, double>);
  return {path, Kind::Number, r, {}, {}, nullptr, unit, def, doc, &store<M...>};
}

template <auto... M>
KeyDesc integer(std::string_view path, Range r, std::string_view unit, std::string_view def,
                std::string_view doc) {
  using T = FieldType<M...>;
  static_assert(std::is_integral_v<T>);
  // The range is what keeps a value inside the field's type.
  if (r.lo < static_cast<double>(std::numeric_limits<T>::min()) ||
      r.hi > static_cast<double>(std::numeric_limits<T>::max())) {
    throw std::logic_error("scene key table: range of " + std::string(path) + " exceeds its type");
  }
  return {path, Kind::Integer, r, {}, {}, nullptr, unit, def, doc, &store<M...>};
}

// An enum-typed field: the allowed spellings come from EnumNames.
template <auto... M>
KeyDesc enumeration(std::string_view path, std::string_view def, std::string_view doc) {
  std::vector<std::string_view> allowed;
  for (const auto& entry : EnumNames<FieldType<M...>>::values) allowed.push_back(entry.first);
  return {path, Kind::Enum, {}, std::move(allowed), {}, nullptr, {}, def, doc, &store<M...>};
}

// A string field restricted to a fixed list of words.
template <auto... M>
KeyDesc choice(std::string_view path, std::vector<std::string_view> allowed, std::string_view def,
               std::string_view doc) {
  static_assert(std::is_same_v<FieldType<M...>, std::string>);
  return {path, Kind::Enum, {}, std::move(allowed), {}, nullptr, {}, def, doc, &store<M...>};
}

template <auto... M>
KeyDesc text(std::string_view path, std::string_view what, bool (*ok)(std::string_view),
             std::string_view def, std::string_view doc) {
  return {path, Kind::String, {}, {}, what, ok, {}, def, doc, &store<M...>};
}

bool valid_utc(std::string_view s);

constexpr std::string_view kDegrees = "degrees";
constexpr std::string_view kUtcFormat = "ISO 8601 UTC time YYYY-MM-DDTHH:MM:SS[.fff]Z";

// Adding a key: one entry here, the field (with the same default) in scene.hpp, a row in
// docs/scene.md.
const std::vector<KeyDesc>& key_table() {
  using S = Scene;
  static const std::vector<KeyDesc> table = {
      integer<&S::image, &ImageSettings::width>("image.width", {1, kMaxImageSide}, "pixels", "960",
                                                "Width of the rendered image."),
      integer<&S::image, &ImageSettings::height>("image.height", {1, kMaxImageSide}, "pixels",
                                                 "540", "Height of the rendered image."),
      number<&S::image, &ImageSettings::exposure>(
          "image.exposure", {0, 1e6, true}, "1/(W m^-2 sr^-1 nm^-1)", "10",
          "Scale of radiance before the PNG tone curve 1 - exp(-exposure * L); the EXR is not "
          "scaled."),
      enumeration<&S::image, &ImageSettings::exr_type>("image.exr_type", "\"half\"",
                                                       "Pixel type of the EXR output."),

      number<&S::camera, &CameraSettings::lat>("camera.lat", {-90, 90}, kDegrees, "20",
                                               "Geodetic (WGS84) latitude of the camera."),
      number<&S::camera, &CameraSettings::lon>("camera.lon", {-180, 180}, kDegrees, "-150",
                                               "Longitude of the camera, east positive."),
      number<&S::camera, &CameraSettings::height>(
          "camera.height", {-11000, 1e9}, "m", "4",
          "Height of the camera above the ellipsoid (sea level)."),
      number<&S::camera, &CameraSettings::heading>(
          "camera.heading", {-360, 360}, kDegrees, "180",
          "Direction the camera looks, clockwise from north."),
      number<&S::camera, &CameraSettings::pitch>(
          "camera.pitch", {-90, 90}, kDegrees, "-5",
          "Elevation of the view direction above the horizontal; -90 looks straight down."),
      number<&S::camera, &CameraSettings::roll>(
          "camera.roll", {-180, 180}, kDegrees, "0",
          "Bank about the view direction; positive banks right, turning the horizon "
          "counterclockwise in the image."),
      number<&S::camera, &CameraSettings::fov_y>("camera.fov_y", {0.01, 179}, kDegrees, "45",
                                                 "Vertical field of view."),

      number<&S::sun, &SunSettings::zenith>(
          "sun.zenith", {0, 180}, kDegrees, "60",
          "Angle of the sun from the zenith at the camera's nadir (ignored with sun.utc)."),
      number<&S::sun, &SunSettings::azimuth>(
          "sun.azimuth", {-360, 360}, kDegrees, "180",
          "Direction of the sun, clockwise from north (ignored with sun.utc)."),
      text<&S::sun, &SunSettings::utc>(
          "sun.utc", kUtcFormat, &valid_utc, "",
          "A UTC instant that places the sun for the camera's position; excludes sun.zenith and "
          "sun.azimuth."),

      number<&S::time>("time", {0, kSceneMaxTime}, "s", "0",
                       "Simulation time, which moves the waves."),

      enumeration<&S::planet, &PlanetSettings::shape>(
          "planet.shape", "\"wgs84\"", "Shape of the planet: the WGS84 ellipsoid or a sphere."),
      number<&S::planet, &PlanetSettings::radius>(
          "planet.radius", {1e3, 1e8}, "m", "6371000",
          "Radius of the planet when planet.shape is sphere."),

      number<&S::ocean, &OceanSettings::wind_speed>("ocean.wind_speed", {0, 60}, "m/s", "10",
                                                    "Wind speed 19.5 m above the sea."),
      number<&S::ocean, &OceanSettings::wind_direction>(
          "ocean.wind_direction", {-360, 360}, kDegrees, "180",
          "Direction the wind blows from, clockwise from north."),
      enumeration<&S::ocean, &OceanSettings::spectrum>("ocean.spectrum", "\"pierson-moskowitz\"",
                                                       "Wave spectrum of the sea."),
      integer<&S::ocean, &OceanSettings::waves>("ocean.waves", {1, 4096}, "", "60",
                                                "Number of trochoidal waves."),
      number<&S::ocean, &OceanSettings::lambda_min>(
          "ocean.lambda_min", {1e-3, 1e4}, "m", "0.02",
          "Shortest wavelength drawn; must not exceed ocean.lambda_max."),
      number<&S::ocean, &OceanSettings::lambda_max>("ocean.lambda_max", {1e-3, 1e4}, "m", "30",
                                                    "Longest wavelength drawn."),
      integer<&S::ocean, &OceanSettings::seed>("ocean.seed", {0, 4294967295.0}, "", "1",
                                               "Random seed of the wave directions and phases."),
      number<&S::ocean, &OceanSettings::n_min>(
          "ocean.n_min", {0, 100}, "", "1",
          "N_min of the filter weights (paper sec. 3.2): waves shorter than n_min grid cells "
          "(or pixels) are filtered out; must be below ocean.n_max."),
      number<&S::ocean, &OceanSettings::n_max>(
          "ocean.n_max", {0, 100}, "", "2.5",
          "N_max of the filter weights: waves longer than n_max cells (or pixels) are kept "
          "whole."),
      number<&S::ocean, &OceanSettings::grid_cell>("ocean.grid_cell", {1, 64}, "pixels", "8",
                                                   "Size of a cell of the projected grid."),
      number<&S::ocean, &OceanSettings::fresnel_r>(
          "ocean.fresnel_r", {0, 1}, "", "0.02",
          "Fresnel reflectance of the sea at normal incidence (R of the paper's eq. 14)."),
      number<&S::ocean, &OceanSettings::deep_reflectance_r>(
          "ocean.deep_reflectance_r", {0, 1}, "", "0.004",
          "Irradiance reflectance of the water below the surface at 680 nm (red): the "
          "deep-water radiance behind L_sea is this times the downwelling irradiance / pi "
          "(eq. 28)."),
      number<&S::ocean, &OceanSettings::deep_reflectance_g>(
          "ocean.deep_reflectance_g", {0, 1}, "", "0.016",
          "Irradiance reflectance of the water below the surface at 550 nm (green)."),
      number<&S::ocean, &OceanSettings::deep_reflectance_b>(
          "ocean.deep_reflectance_b", {0, 1}, "", "0.047",
          "Irradiance reflectance of the water below the surface at 440 nm (blue)."),
      choice<&S::ocean, &OceanSettings::sky_filter>(
          "ocean.sky_filter", {"texture_grad", "nine_samples", "shrm"}, "\"texture_grad\"",
          "Filtered sky reflection: the paper's single anisotropic fetch (eq. 27), the average "
          "of nine samples inside the filter's support (sec. 7.2), or sky maps prefiltered in "
          "frequency space for rough seas seen from afar (Ramamoorthi & Hanrahan 2002; "
          "docs/spherical_harmonics.md)."),
      choice<&S::ocean, &OceanSettings::effective_fresnel>(
          "ocean.effective_fresnel", {"fit", "table"}, "\"fit\"",
          "Effective Fresnel reflectance of the reflected sky and the refracted light: the "
          "paper's fit (eq. 26) or eq. 24 itself, integrated in double and read from a table "
          "(within 1.2e-3 of it where the fit errs by up to 0.061; docs/ocean_fresnel.md)."),
      choice<&S::ocean, &OceanSettings::sky_lobe_centre>(
          "ocean.sky_lobe_centre", {"mirror", "fresnel_weighted"}, "\"mirror\"",
          "Where the filtered sky reflection is centred: the mirror direction of the mean normal "
          "(eq. 27) or that of the visible facets' mean slope weighted by their Fresnel "
          "reflectance, which eq. 21's product of averages leaves out "
          "(docs/ocean_fresnel.md)."),
      integer<&S::ocean, &OceanSettings::parallax_iterations>(
          "ocean.parallax_iterations", {0, 8}, "", "0",
          "Fixed-point steps of the parallax of the waves drawn in the normals alone (longer than "
          "a pixel, shorter than the grid's cells): each pixel takes their normals where its ray "
          "meets them, so that it sees their facets in proportion to their projected area, as "
          "the true surface shows them (0: none, the paper's normal mapping; 2 at resolutions of "
          "1024 x 576 and above; docs/ocean_fresnel.md)."),

      choice<&S::sky, &SkySettings::model>("sky.model", {"atmosphere"}, "\"atmosphere\"",
                                           "Sky model used when sky.exr is empty."),
      text<&S::sky, &SkySettings::exr>(
          "sky.exr", "a file path, or empty", nullptr, "\"\"",
          "Equirectangular HDR sky image to use instead of sky.model; relative to the working "
          "directory."),
  };
  return table;
}

const KeyDesc* find_key(std::string_view path) {
  for (const auto& k : key_table()) {
    if (k.path == path) return &k;
  }
  return nullptr;
}

// "camera" for "camera.height"; empty for top-level keys such as "time".
std::string_view section_of(std::string_view path) {
  const auto dot = path.find('.');
  return dot == std::string_view::npos ? std::string_view{} : path.substr(0, dot);
}

// Stores `v` in a nested document at a dotted key path ("camera.height" -> {"camera": {...}}).
void put_path(json& doc, std::string_view path, json v) {
  const auto section = section_of(path);
  if (section.empty()) {
    doc[std::string(path)] = std::move(v);
  } else {
    doc[std::string(section)][std::string(path.substr(section.size() + 1))] = std::move(v);
  }
}

// The top-level keys that hold arrays of features (issue 9) rather than one value each.
bool is_feature_key(std::string_view name) { return name == "wakes" || name == "calm_areas"; }

bool is_section(std::string_view name) {
  return std::any_of(key_table().begin(), key_table().end(),
                     [&](const KeyDesc& k) { return section_of(k.path) == name; });
}

// ---------------------------------------------------------------------------------------------
// Messages.

// Shortest text that reads back as the same double: 16384, 1e9, 0.001, 4294967295.
std::string format_number(double x) {
  if (x == std::floor(x) && std::fabs(x) < 1e6) {
    return std::to_string(static_cast<long long>(x));
  }
  char buf[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  // "1e+09" -> "1e9", "1e-03" -> "1e-3".
  std::string s = buf;
  const auto e = s.find('e');
  if (e != std::string::npos) {
    std::string mantissa = s.substr(0, e);
    std::string exponent = s.substr(e + 1);
    std::string sign;
    if (exponent[0] == '+' || exponent[0] == '-') {
      if (exponent[0] == '-') sign = "-";
      exponent.erase(0, 1);
    }
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    s = mantissa + "e" + sign + exponent;
  }
  return s;
}

std::string range_text(const KeyDesc& k) {
  switch (k.kind) {
    case Kind::Number:
    case Kind::Integer:
      return std::string(k.range.lo_open ? "(" : "[") + format_number(k.range.lo) + ", " +
             format_number(k.range.hi) + "]";
    case Kind::Enum: {
      std::string s;
      for (const auto& a : k.allowed) s += (s.empty() ? "" : ", ") + std::string(a);
      return s;
    }
    case Kind::String:
      return std::string(k.text_range);
  }
  return {};
}

std::string unit_suffix(const KeyDesc& k) {
  return k.unit.empty() ? std::string{} : " (" + std::string(k.unit) + ")";
}

std::string expectation(const KeyDesc& k) {
  switch (k.kind) {
    case Kind::Number:
      return "a number in " + range_text(k) + unit_suffix(k);
    case Kind::Integer:
      return "an integer in " + range_text(k) + unit_suffix(k);
    case Kind::Enum: {
      std::string s = "one of ";
      for (std::size_t i = 0; i < k.allowed.size(); ++i) {
        s += (i ? ", \"" : "\"") + std::string(k.allowed[i]) + "\"";
      }
      return s;
    }
    case Kind::String:
      return k.text_ok ? "an " + std::string(k.text_range) : "a string";
  }
  return {};
}

std::string dump(const json& v) { return v.dump(-1, ' ', false, json::error_handler_t::replace); }

// What was found, short and on one line.
std::string describe(const json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return "an array";
  if (v.is_number_float() && !std::isfinite(v.get<double>())) {
    const double x = v.get<double>();
    return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  }
  std::string s = dump(v);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

[[noreturn]] void fail(std::string_view source, std::string_view key, std::string_view expected,
                       std::string_view got) {
  throw SceneError(detail::input_message(source, key, expected, got));
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The known key or section closest to an unknown one, when it is close enough to be a typo.
std::string suggestion(std::string_view unknown) {
  std::string best;
  std::size_t best_distance = SIZE_MAX;
  auto consider = [&](std::string_view candidate, std::size_t distance) {
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  };
  for (std::string_view feature : {"wakes", "calm_areas"})
    consider(feature, edit_distance(unknown, feature));
  for (const auto& k : key_table()) {
    consider(k.path, edit_distance(unknown, k.path));
    // "height" at the top level is most likely camera.height put in the wrong place.
    const auto dot = k.path.find('.');
    if (dot != std::string_view::npos && k.path.substr(dot + 1) == unknown) consider(k.path, 1);
    const auto section = section_of(k.path);
    if (!section.empty()) consider(section, edit_distance(unknown, section));
  }
  const std::size_t limit = std::max<std::size_t>(2, unknown.size() / 4);
  return best_distance <= limit ? best : std::string{};
}

// `prefix` is put in front of the key path in the message (a scene nested in another file).
[[noreturn]] void fail_unknown(std::string_view source, std::string_view path,
                               std::string_view prefix = {}) {
  const std::string near = suggestion(path);
  fail(
      source, std::string(prefix) + std::string(path),
      near.empty() ? "a known key (see docs/scene.md)" : "a known key (did you mean " + near + "?)",
      "an unknown key");
}

// Checks one value against its key and returns it in canonical form (numbers as doubles,
// integers as integers), so that merged_json() does not depend on how a value was spelled.
// Messages name the key as `prefix` + its path.
json checked(const KeyDesc& k, const json& v, std::string_view source,
             std::string_view prefix = {}) {
  auto bad = [&]() {
    fail(source, std::string(prefix) + std::string(k.path), expectation(k), describe(v));
  };
  switch (k.kind) {
    case Kind::Number:
    case Kind::Integer: {
      // nlohmann keeps booleans apart from numbers, so true is not 1 here.
      if (!v.is_number()) bad();
      const double x = v.get<double>();
      if (!std::isfinite(x)) bad();
      if (k.kind == Kind::Integer && x != std::floor(x)) bad();
      if (x < k.range.lo || x > k.range.hi || (k.range.lo_open && x == k.range.lo)) bad();
      if (k.kind == Kind::Integer) return json(static_cast<std::int64_t>(x));
      return json(x);
    }
    case Kind::Enum: {
      if (!v.is_string()) bad();
      const auto& s = v.get_ref<const std::string&>();
      if (std::find(k.allowed.begin(), k.allowed.end(), s) == k.allowed.end()) bad();
      return v;
    }
    case Kind::String:
      if (!v.is_string()) bad();
      if (k.text_ok && !k.text_ok(v.get_ref<const std::string&>())) bad();
      return v;
  }
  return v;
}

// ---------------------------------------------------------------------------------------------
// UTC times and the solar position.

struct UtcTime {
  int year = 0, month = 0, day = 0, hour = 0, minute = 0;
  double second = 0.0;
};

bool is_leap(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

int days_in_month(int y, int m) {
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && is_leap(y) ? 29 : kDays[m - 1];
}

// "YYYY-MM-DDTHH:MM:SS[.fff]Z", with 1 to 9 fraction digits; no leap seconds.
std::optional<UtcTime> parse_utc(std::string_view s) {
  auto digits = [&](std::size_t at, std::size_t n, int& out) {
    if (at + n > s.size()) return false;
    out = 0;
    for (std::size_t i = at; i < at + n; ++i) {
      if (s[i] < '0' || s[i] > '9') return false;
      out = out * 10 + (s[i] - '0');
    }
    return true;
  };
  UtcTime t;
  int sec = 0;
  if (s.size() < 20 || !digits(0, 4, t.year) || s[4] != '-' || !digits(5, 2, t.month) ||
      s[7] != '-' || !digits(8, 2, t.day) || s[10] != 'T' || !digits(11, 2, t.hour) ||
      s[13] != ':' || !digits(14, 2, t.minute) || s[16] != ':' || !digits(17, 2, sec)) {
    return std::nullopt;
  }
  std::size_t at = 19;
  double fraction = 0.0;
  if (s[at] == '.') {
    double scale = 0.1;
    std::size_t n = 0;
    for (++at; at < s.size() && s[at] >= '0' && s[at] <= '9'; ++at, ++n) {
      fraction += scale * (s[at] - '0');
      scale *= 0.1;
    }
    if (n < 1 || n > 9) return std::nullopt;
  }
  if (at + 1 != s.size() || s[at] != 'Z') return std::nullopt;
  if (t.year < 1 || t.month < 1 || t.month > 12 || t.day < 1 ||
      t.day > days_in_month(t.year, t.month) || t.hour > 23 || t.minute > 59 || sec > 59) {
    return std::nullopt;
  }
  t.second = sec + fraction;
  return t;
}

bool valid_utc(std::string_view s) { return parse_utc(s).has_value(); }

// Days from 1970-01-01 to a proleptic Gregorian date (H. Hinnant's days_from_civil).
std::int64_t days_from_civil(int y, int m, int d) {
  y -= m <= 2;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const std::int64_t yoe = y - era * 400;
  const std::int64_t doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
  const std::int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

constexpr double kPi = 3.14159265358979323846;
constexpr double kRad = kPi / 180.0;

struct SunAngles {
  double zenith = 0.0;   // degrees, geometric (no refraction)
  double azimuth = 0.0;  // degrees clockwise from north, [0, 360)
};

// The NOAA solar calculator's algorithm (after Meeus, "Astronomical Algorithms", ch. 25): about
// 0.01 degree from 1800 to 2100. UT is used for dynamical time (their difference, about a
// minute, moves the sun by 0.0007 degree). The last step uses the east-north-up components of
// the sun direction instead of NOAA's acos formula, which is NaN at the poles and the zenith.
SunAngles solar_position(const UtcTime& t, double lat_deg, double lon_deg) {
  const double day_minutes = t.hour * 60.0 + t.minute + t.second / 60.0;
  const double jd = 2440587.5 + static_cast<double>(days_from_civil(t.year, t.month, t.day)) +
                    day_minutes / 1440.0;
  const double T = (jd - 2451545.0) / 36525.0;  // Julian centuries since J2000.0

  const double mean_long = std::fmod(280.46646 + T * (36000.76983 + T * 0.0003032), 360.0);
  const double mean_anom = 357.52911 + T * (35999.05029 - 0.0001537 * T);
  const double ecc = 0.016708634 - T * (0.000042037 + 0.0000001267 * T);
  const double m = mean_anom * kRad;
  const double center = std::sin(m) * (1.914602 - T * (0.004817 + 0.000014 * T)) +
                        std::sin(2 * m) * (0.019993 - 0.000101 * T) + std::sin(3 * m) * 0.000289;
  const double omega = (125.04 - 1934.136 * T) * kRad;
  const double app_long = (mean_long + center - 0.00569 - 0.00478 * std::sin(omega)) * kRad;
  const double mean_obliq =
      23.0 + (26.0 + (21.448 - T * (46.815 + T * (0.00059 - T * 0.001813))) / 60.0) / 60.0;
  const double obliq = (mean_obliq + 0.00256 * std::cos(omega)) * kRad;
  const double decl = std::asin(std::sin(obliq) * std::sin(app_long));

  const double y = std::tan(obliq / 2) * std::tan(obliq / 2);
  const double l0 = mean_long * kRad;
  const double eot_minutes =
      4.0 / kRad *
      (y * std::sin(2 * l0) - 2 * ecc * std::sin(m) + 4 * ecc * y * std::sin(m) * std::cos(2 * l0) -
       0.5 * y * y * std::sin(4 * l0) - 1.25 * ecc * ecc * std::sin(2 * m));
  double solar_minutes = std::fmod(day_minutes + eot_minutes + 4.0 * lon_deg, 1440.0);
  if (solar_minutes < 0) solar_minutes += 1440.0;
  const double hour_angle = (solar_minutes / 4.0 - 180.0) * kRad;  // 0 at local solar noon

  const double lat = lat_deg * kRad;
  const double east = -std::cos(decl) * std::sin(hour_angle);
  const double north =
      std::cos(lat) * std::sin(decl) - std::sin(lat) * std::cos(decl) * std::cos(hour_angle);
  const double up =
      std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(hour_angle);
  SunAngles a;
  a.zenith = std::atan2(std::hypot(east, north), up) / kRad;
  a.azimuth = std::atan2(east, north) / kRad;
  if (a.azimuth < 0) a.azimuth += 360.0;
  if (a.azimuth >= 360.0) a.azimuth -= 360.0;
  return a;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

struct SceneBuilder::Impl {
  struct Given {
    std::string source;
    std::uint64_t order = 0;  // later layers have larger numbers
  };
  std::map<std::string, json, std::less<>> values;  // key path -> canonical value
  std::map<std::string, Given, std::less<>> given;  // keys set by a file or --set
  std::uint64_t next_order = 1;

  // Lays a parsed document over `values`; all or nothing. Messages name keys as `prefix` + path
  // (a scene nested in another file, e.g. "scene.").
  void lay(const json& doc, std::string_view source, bool explicit_input,
           std::string_view prefix = {}) {
    if (!doc.is_object()) {
      fail(source, "", "a JSON object of sections at the top level", describe(doc));
    }
    const auto named = [&](const std::string& path) { return std::string(prefix) + path; };
    auto staged_values = values;
    auto staged_given = given;
    auto put = [&](const KeyDesc& k, const json& v) {
      staged_values[std::string(k.path)] = checked(k, v, source, prefix);
      if (explicit_input) staged_given[std::string(k.path)] = {std::string(source), next_order};
    };
    for (const auto& [name, value] : doc.items()) {
      if (is_feature_key(name)) {
        // Arrays of wakes / calm areas (scene_features.hpp): checked, GeoJSON files read, kept
        // in canonical form.
        staged_values[name] = name == "wakes"
                                  ? detail::check_wakes(value, source, named(name))
                                  : detail::check_calm_areas(value, source, named(name));
        if (explicit_input) staged_given[name] = {std::string(source), next_order};
        continue;
      }
      const KeyDesc* k = find_key(name);
      if (k && section_of(name).empty()) {
        put(*k, value);
      } else if (k) {
        // One spelling per key, so that a file cannot give a key twice.
        const auto section = std::string(section_of(name));
        fail(source, named(name),
             "the key inside its section, {\"" + section + "\": {\"" +
                 name.substr(section.size() + 1) + "\": ...}}",
             "a dotted name at the top level");
      } else if (is_section(name)) {
        if (!value.is_object()) {
          fail(source, named(name), "an object (a section of keys such as " + name + ".*)",
               describe(value));
        }
        for (const auto& [member, member_value] : value.items()) {
          const std::string path = name + "." + member;
          const KeyDesc* mk = find_key(path);
          if (!mk) fail_unknown(source, path, prefix);
          put(*mk, member_value);
        }
      } else {
        fail_unknown(source, name, prefix);
      }
    }
    values = std::move(staged_values);
    given = std::move(staged_given);
    ++next_order;
  }

  // The source of whichever of the two keys was given last ("defaults" if neither).
  std::string latest_source(std::string_view a, std::string_view b) const {
    const Given* best = nullptr;
    for (auto key : {a, b}) {
      auto it = given.find(key);
      if (it != given.end() && (!best || it->second.order > best->order)) best = &it->second;
    }
    return best ? best->source : "defaults";
  }
};

SceneBuilder::SceneBuilder() : impl_(new Impl) {
  impl_->lay(json::parse(default_scene_json()), "defaults", false);
}

SceneBuilder::~SceneBuilder() { delete impl_; }

SceneBuilder::SceneBuilder(const SceneBuilder& other) : impl_(new Impl(*other.impl_)) {}

SceneBuilder& SceneBuilder::operator=(const SceneBuilder& other) {
  if (this != &other) {
    Impl* copy = new Impl(*other.impl_);
    delete impl_;
    impl_ = copy;
  }
  return *this;
}

SceneBuilder::SceneBuilder(SceneBuilder&& other) noexcept : impl_(other.impl_) {
  other.impl_ = nullptr;
}

SceneBuilder& SceneBuilder::operator=(SceneBuilder&& other) noexcept {
  if (this != &other) {
    delete impl_;
    impl_ = other.impl_;
    other.impl_ = nullptr;
  }
  return *this;
}

void SceneBuilder::load_text(std::string_view json_text, std::string_view source) {
  load_text(json_text, source, {});
}

void SceneBuilder::load_text(std::string_view json_text, std::string_view source,
                             std::string_view key_prefix) {
  const json doc = detail::parse_strict_json<json>(json_text, source, key_prefix, &fail);
  impl_->lay(doc, source, true, key_prefix);
}

void SceneBuilder::load_file(const std::string& path) {
  const std::string text = detail::read_text_file(path, "scene file", "", "", &fail);
  load_text(text, path);
}

void SceneBuilder::set(std::string_view assignment) { set(assignment, "--set"); }

void SceneBuilder::set(std::string_view assignment, std::string_view source) {
  const auto eq = assignment.find('=');
  if (eq == std::string_view::npos) {
    fail(source, assignment, "key.path=value", "no '=' in \"" + std::string(assignment) + "\"");
  }
  std::string_view key = assignment.substr(0, eq);
  while (!key.empty() && key.front() == ' ') key.remove_prefix(1);
  while (!key.empty() && key.back() == ' ') key.remove_suffix(1);
  const std::string_view text = assignment.substr(eq + 1);
  if (key.empty()) {
    fail(source, "", "key.path=value", "\"" + std::string(assignment) + "\" (no key)");
  }
  if (is_feature_key(key)) {
    // The whole array (JSON), or a bare GeoJSON path: --set calm_areas=slicks.geojson.
    json value = json::parse(text, nullptr, false);
    if (value.is_discarded()) value = std::string(text);
    json doc = json::object();
    doc[std::string(key)] = std::move(value);
    impl_->lay(doc, source, true);
    return;
  }
  if (!find_key(key) && is_section(key)) {
    fail(source, key, "a key path such as " + std::string(key) + ".<name>", "a whole section");
  }
  if (!find_key(key)) fail_unknown(source, key);
  // Valid JSON (numbers, true, "quoted") is taken as such; anything else is a bare string.
  json value = json::parse(text, nullptr, false);
  if (value.is_discarded()) value = std::string(text);
  json doc = json::object();
  put_path(doc, key, std::move(value));
  impl_->lay(doc, source, true);
}

Scene SceneBuilder::build() const {
  Scene s;
  for (const auto& k : key_table()) {
    auto it = impl_->values.find(k.path);
    if (it != impl_->values.end()) k.store(s, it->second);
  }

  if (!(s.ocean.n_min < s.ocean.n_max)) {
    fail(impl_->latest_source("ocean.n_min", "ocean.n_max"), "ocean.n_min",
         "a value < ocean.n_max (" + format_number(s.ocean.n_max) + ")",
         format_number(s.ocean.n_min));
  }
  if (s.ocean.lambda_min > s.ocean.lambda_max) {
    fail(impl_->latest_source("ocean.lambda_min", "ocean.lambda_max"), "ocean.lambda_min",
         "a value <= ocean.lambda_max (" + format_number(s.ocean.lambda_max) + " m)",
         format_number(s.ocean.lambda_min));
  }

  if (auto it = impl_->values.find("wakes"); it != impl_->values.end())
    s.wakes = detail::wakes_from(it->second);
  if (auto it = impl_->values.find("calm_areas"); it != impl_->values.end())
    s.calm_areas = detail::calm_areas_from(it->second);

  const auto& given = impl_->given;
  if (auto utc = given.find("sun.utc"); utc != given.end()) {
    for (std::string_view other : {"sun.zenith", "sun.azimuth"}) {
      auto it = given.find(other);
      if (it == given.end()) continue;
      const bool same = it->second.source == utc->second.source;
      fail(impl_->latest_source("sun.utc", other), "sun.utc",
           "either sun.utc or sun.zenith/sun.azimuth",
           "both sun.utc" + (same ? "" : " (from " + utc->second.source + ")") + " and " +
               std::string(other) + (same ? "" : " (from " + it->second.source + ")"));
    }
  }
  if (s.sun.utc) {
    // Validated on input, so parse_utc succeeds.
    const SunAngles a = solar_position(*parse_utc(*s.sun.utc), s.camera.lat, s.camera.lon);
    s.sun.zenith = a.zenith;
    s.sun.azimuth = a.azimuth;
  }
  return s;
}

std::string SceneBuilder::source_of(std::string_view key) const {
  auto it = impl_->given.find(key);
  return it != impl_->given.end() ? it->second.source : std::string("defaults");
}

std::string SceneBuilder::merged_json() const {
  json doc = json::object();
  const bool has_utc = impl_->values.count("sun.utc") != 0;
  for (const auto& [path, value] : impl_->values) {
    // With sun.utc the sun's angles are computed; leaving them out keeps the document a valid
    // scene file that builds to the same Scene.
    if (has_utc && (path == "sun.zenith" || path == "sun.azimuth")) continue;
    put_path(doc, path, value);
  }
  return dump(doc);
}

std::string_view default_scene_json() {
  static const std::string text = [] {
    json doc = json::object();
    for (const auto& k : key_table()) {
      if (k.default_json.empty()) continue;
      put_path(doc, k.path, checked(k, json::parse(k.default_json), "defaults"));
    }
    return doc.dump(2) + "\n";
  }();
  return text;
}

void check_scene_value(std::string_view key, std::string_view value_json, std::string_view source,
                       std::string_view key_prefix) {
  const KeyDesc* k = find_key(key);
  if (!k) throw std::invalid_argument("check_scene_value: unknown scene key " + std::string(key));
  const json value = json::parse(value_json, nullptr, false);
  if (value.is_discarded()) {
    fail(source, std::string(key_prefix) + std::string(key), expectation(*k),
         "\"" + std::string(value_json) + "\" (not JSON)");
  }
  checked(*k, value, source, key_prefix);
}

std::optional<double> parse_utc_seconds(std::string_view utc) {
  const std::optional<UtcTime> t = parse_utc(utc);
  if (!t) return std::nullopt;
  constexpr double kSecondsPerDay = 86400.0;
  return static_cast<double>(days_from_civil(t->year, t->month, t->day)) * kSecondsPerDay +
         t->hour * 3600.0 + t->minute * 60.0 + t->second;
}

std::string format_utc(double seconds) {
  // Whole milliseconds, so that the text is exact and reads back to within 0.5 ms.
  const auto ms = static_cast<std::int64_t>(std::llround(seconds * 1e3));
  constexpr std::int64_t kMsPerDay = 86400000;
  std::int64_t days = ms / kMsPerDay;
  std::int64_t in_day = ms % kMsPerDay;
  if (in_day < 0) {
    in_day += kMsPerDay;
    --days;
  }
  // H. Hinnant's civil_from_days, the inverse of days_from_civil.
  const std::int64_t z = days + 719468;
  const std::int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const std::int64_t doe = z - era * 146097;
  const std::int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const std::int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const std::int64_t mp = (5 * doy + 2) / 153;
  const int day = static_cast<int>(doy - (153 * mp + 2) / 5 + 1);
  const int month = static_cast<int>(mp < 10 ? mp + 3 : mp - 9);
  const auto year = static_cast<long long>(yoe + era * 400 + (month <= 2));
  char text[48];
  std::snprintf(text, sizeof text, "%04lld-%02d-%02dT%02d:%02d:%02d.%03dZ", year, month, day,
                static_cast<int>(in_day / 3600000), static_cast<int>(in_day / 60000 % 60),
                static_cast<int>(in_day / 1000 % 60), static_cast<int>(in_day % 1000));
  return text;
}

const std::vector<SceneKeyInfo>& scene_keys() {
  static const std::vector<SceneKeyInfo> keys = [] {
    std::vector<SceneKeyInfo> out;
    for (const auto& k : key_table()) {
      SceneKeyInfo info;
      info.path = k.path;
      switch (k.kind) {
        case Kind::Number:
          info.type = "number";
          break;
        case Kind::Integer:
          info.type = "integer";
          break;
        case Kind::String:
          info.type = "string";
          break;
        case Kind::Enum:
          info.type = "enum";
          break;
      }
      info.unit = k.unit;
      info.range = range_text(k);
      info.default_value = k.default_json.empty()
                               ? "(none)"
                               : dump(checked(k, json::parse(k.default_json), "defaults"));
      info.doc = k.doc;
      out.push_back(std::move(info));
    }
    return out;
  }();
  return keys;
}

}  // namespace thalassa
