// Scripted flights: the flight file, its checks, and the interpolation of each channel.
#include "thalassa/planet/flight.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/glm.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "strict_json.hpp"

namespace thalassa {
namespace {

using json = nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Messages, in the form of scene files' (thalassa/engine/scene.hpp).

std::string dump(const json& v) { return v.dump(-1, ' ', false, json::error_handler_t::replace); }

// What was found, short and on one line.
std::string describe(const json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return v.empty() ? "an empty array" : "an array";
  std::string s = dump(v);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

// Shortest round-trip text of a number, as scene messages write it: 20, 0.5, 1e9.
std::string number_text(double x) {
  if (x == std::floor(x) && std::fabs(x) < 1e6) return std::to_string(static_cast<long long>(x));
  char buf[40];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  std::string s = buf;
  const auto e = s.find('e');
  if (e != std::string::npos) {  // "1e+09" -> "1e9", "1e-05" -> "1e-5"
    std::string exponent = s.substr(e + 1);
    const std::string sign = exponent[0] == '-' ? "-" : "";
    if (exponent[0] == '+' || exponent[0] == '-') exponent.erase(0, 1);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    s = s.substr(0, e) + "e" + sign + exponent;
  }
  return s;
}

// The frames of a flight of `duration` seconds at `fps`: at 0, 1/fps, ... up to the duration
// itself; the epsilon keeps 20 s x 24 fps at 481 frames despite rounding.
double frames_over(double duration, double fps) {
  constexpr double kFrameEpsilon = 1e-9;
  return std::floor(duration * fps + kFrameEpsilon) + 1.0;
}

[[noreturn]] void fail(std::string_view source, std::string_view key, std::string_view expected,
                       std::string_view got) {
  throw SceneError(detail::input_message(source, key, expected, got));
}

// A finite number in [lo, hi] (lo_open: (lo, hi]), or a SceneError naming `key`.
double number_in(const json& v, std::string_view source, std::string_view key, double lo, double hi,
                 std::string_view unit, bool lo_open = false) {
  const std::string expected = "a number in " + std::string(lo_open ? "(" : "[") + number_text(lo) +
                               ", " + number_text(hi) + "]" +
                               (unit.empty() ? "" : " (" + std::string(unit) + ")");
  if (!v.is_number()) fail(source, key, expected, describe(v));
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi || (lo_open && x == lo))
    fail(source, key, expected, describe(v));
  return x;
}

// ---------------------------------------------------------------------------------------------
// Channels.

enum class ChannelKind {
  Linear,     // interpolated as is, clamped to [lo, hi]
  LogHeight,  // interpolated as log(height + kFlightHeightOffset)
  Log,        // interpolated as log(x), x > 0: equal times cover equal ratios
  Angle,      // interpolated unwrapped (the short way), wrapped into [lo, lo + 360) or (lo, hi]
};

struct Channel {
  std::string_view section;  // "camera"
  std::string_view name;     // "height"
  std::optional<double> FlightValues::*member;
  ChannelKind kind;
  double lo, hi;      // clamp range (Linear), the result's range (Angle)
  bool upper_closed;  // Angle: (lo, hi] rather than [lo, hi)
};

constexpr double kFullTurn = 360.0;  // degrees

// The numeric channels; sun.utc and the scene's time are handled apart (linear in time).
const std::vector<Channel>& channels() {
  static const std::vector<Channel> table = {
      {"camera", "lat", &FlightValues::lat, ChannelKind::Linear, -90, 90, false},
      {"camera", "lon", &FlightValues::lon, ChannelKind::Angle, -180, 180, true},
      {"camera", "height", &FlightValues::height, ChannelKind::LogHeight, 0, kFlightMaxHeight,
       false},
      {"camera", "heading", &FlightValues::heading, ChannelKind::Angle, 0, 360, false},
      {"camera", "pitch", &FlightValues::pitch, ChannelKind::Linear, -90, 90, false},
      {"camera", "roll", &FlightValues::roll, ChannelKind::Angle, -180, 180, true},
      {"camera", "fov_y", &FlightValues::fov_y, ChannelKind::Linear, 0.01, 179, false},
      {"sun", "zenith", &FlightValues::sun_zenith, ChannelKind::Linear, 0, 180, false},
      {"sun", "azimuth", &FlightValues::sun_azimuth, ChannelKind::Angle, 0, 360, false},
      // The exposure in its logarithm, so that it changes steadily in stops (between two keys
      // that span the flight, 1 and 100 two seconds apart, it passes 10 half way). The scene's
      // range is (0, 1e6]; the lower clamp only keeps exp's underflow positive.
      {"image", "exposure", &FlightValues::exposure, ChannelKind::Log,
       std::numeric_limits<double>::min(), 1e6, false},
  };
  return table;
}

std::string key_of(const Channel& c) { return std::string(c.section) + "." + std::string(c.name); }

// An angle in degrees moved by whole turns into [lo, lo + 360), or into (lo, lo + 360] when
// `upper_closed` (longitude and roll: 180 rather than -180).
double wrap_angle(double x, double lo, bool upper_closed) {
  double r = std::fmod(x - lo, kFullTurn);  // (-360, 360)
  if (r < 0.0) r += kFullTurn;
  if (r >= kFullTurn) r -= kFullTurn;  // -tiny + 360 rounds to 360
  if (upper_closed && r == 0.0) r = kFullTurn;
  return lo + r;
}

// ---------------------------------------------------------------------------------------------
// The camera's position on great circles: unit vectors of (geodetic latitude, longitude).

using Vec3 = glm::dvec3;
constexpr double kRadian = 3.14159265358979323846 / 180.0;
// Two consecutive position keys may be at most this far apart (degrees of arc): the great circle
// between antipodes is undefined, and near them its direction is lost in rounding.
constexpr double kMaxKeyArc = 179.0;
// A key's distance from the polar axis (unit sphere) under which it counts as at a pole, where
// the east direction is lost: 1e-9 rad, 6 mm.
constexpr double kPoleTolerance = 1e-9;

Vec3 direction_of(double lat, double lon) {
  const double phi = lat * kRadian, lambda = lon * kRadian;
  return {std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda), std::sin(phi)};
}

// The tangent at unit p toward unit q whose length is their arc (rad): the sphere's log map.
Vec3 log_map(const Vec3& p, const Vec3& q) {
  if (p == q) return Vec3(0.0);  // exactly: a held point stays where it is
  const double c = glm::dot(p, q);
  const Vec3 w = q - c * p;
  const double sine = glm::length(w);
  if (!(sine > 0.0)) return Vec3(0.0);  // the same point (antipodes are refused when parsed)
  return w * (std::atan2(sine, c) / sine);
}

// The point reached from unit p along the tangent v (its length the arc, rad): the exp map.
Vec3 exp_map(const Vec3& p, const Vec3& v) {
  const double arc = glm::length(v);
  if (!(arc > 0.0)) return p;
  return glm::normalize(std::cos(arc) * p + std::sin(arc) / arc * v);
}

// The arc between unit a and b, radians (antipodes included, where log_map has no direction).
double arc_between(const Vec3& a, const Vec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The great circle from a to b at fraction u of its arc.
Vec3 slerp(const Vec3& a, const Vec3& b, double u) { return exp_map(a, u * log_map(a, b)); }

Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

// Whether the keyframes give the position as pairs (every keyframe that gives camera.lat or
// camera.lon gives both), and at least one: it then follows great circles.
bool positions_paired(const std::vector<FlightKeyframe>& keys) {
  bool any = false;
  for (const FlightKeyframe& k : keys) {
    if (k.values.lat.has_value() != k.values.lon.has_value()) return false;
    any = any || k.values.lat.has_value();
  }
  return any;
}

// The value of channel `c` in interpolation space.
double to_space(const Channel& c, double x) {
  switch (c.kind) {
    case ChannelKind::LogHeight:
      return std::log(x + kFlightHeightOffset);
    case ChannelKind::Log:
      return std::log(x);
    default:
      return x;
  }
}

// Back from interpolation space into the channel's range.
double from_space(const Channel& c, double y) {
  switch (c.kind) {
    case ChannelKind::Linear:
      return std::clamp(y, c.lo, c.hi);
    case ChannelKind::LogHeight:
      return std::clamp(std::exp(y) - kFlightHeightOffset, c.lo, c.hi);
    case ChannelKind::Log:
      return std::clamp(std::exp(y), c.lo, c.hi);
    case ChannelKind::Angle:
      return wrap_angle(y, c.lo, c.upper_closed);
  }
  return y;
}

// ---------------------------------------------------------------------------------------------
// Parsing.

// The readers shared with scene and flight files (strict_json.hpp), refusing through fail().
json parse_strict(std::string_view text, std::string_view source) {
  return detail::parse_strict_json<json>(text, source, "", &fail);
}

std::string read_text_file(const std::string& path, std::string_view what, std::string_view source,
                           std::string_view key) {
  return detail::read_text_file(path, what, source, key, &fail);
}

std::string known_keys(const std::vector<std::string_view>& keys) {
  std::string s;
  for (auto k : keys) s += (s.empty() ? "" : ", ") + std::string(k);
  return s;
}

// Refuses keys of `object` outside `allowed`; `prefix` is the object's key path with its dot.
void only_known(const json& object, const std::vector<std::string_view>& allowed,
                std::string_view source, const std::string& prefix) {
  for (const auto& [name, value] : object.items()) {
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
      fail(source, prefix + name, "a known key (" + known_keys(allowed) + "; see docs/flight.md)",
           "an unknown key");
  }
}

FlightKeyframe parse_keyframe(const json& k, std::string_view source, const std::string& at) {
  if (!k.is_object())
    fail(source, at, "an object {\"time\": ..., \"camera\": {...}, \"sun\": {...}}", describe(k));
  only_known(k, {"time", "scene_time", "camera", "sun", "image"}, source, at + ".");
  FlightKeyframe keyframe;
  if (!k.contains("time")) fail(source, at + ".time", "a number (s)", "no time");
  keyframe.time = number_in(k["time"], source, at + ".time", 0, kFlightMaxDuration, "s");
  if (k.contains("scene_time")) {
    // The scene's `time` at this keyframe, in the scene's range.
    // (The prefix ".scene_" makes the message's key "keyframes[i].scene_time".)
    check_scene_value("time", dump(k["scene_time"]), source, at + ".scene_");
    keyframe.values.scene_time = k["scene_time"].get<double>();
  }
  std::vector<std::string_view> camera_keys, sun_keys, image_keys;
  for (const Channel& c : channels())
    (c.section == "camera" ? camera_keys
     : c.section == "sun"  ? sun_keys
                           : image_keys)
        .push_back(c.name);
  sun_keys.push_back("utc");
  for (const auto& [section, allowed] :
       {std::pair{"camera", camera_keys}, {"sun", sun_keys}, {"image", image_keys}}) {
    if (!k.contains(section)) continue;
    const json& object = k[section];
    const std::string prefix = at + "." + section + ".";
    if (!object.is_object())
      fail(source, at + "." + section, "an object of " + std::string(section) + " keys",
           describe(object));
    only_known(object, allowed, source, prefix);
    for (const Channel& c : channels()) {
      if (c.section != section || !object.contains(c.name)) continue;
      const json& v = object[std::string(c.name)];
      const std::string key = key_of(c);
      if (c.kind == ChannelKind::LogHeight) {
        // Narrower than the scene's range: a flight stays at or above the sea, which the
        // logarithm of the height needs.
        keyframe.values.*c.member = number_in(v, source, prefix + std::string(c.name), 0,
                                              kFlightMaxHeight, "m; a flight stays above the sea");
      } else {
        check_scene_value(key, dump(v), source, at + ".");
        keyframe.values.*c.member = v.get<double>();
      }
    }
    if (section == std::string_view("sun") && object.contains("utc")) {
      check_scene_value("sun.utc", dump(object["utc"]), source, at + ".");
      keyframe.values.sun_utc = object["utc"].get<std::string>();
    }
  }
  const FlightValues& v = keyframe.values;
  if (v.sun_utc && (v.sun_zenith || v.sun_azimuth))
    fail(source, at + ".sun.utc", "either sun.utc or sun.zenith/sun.azimuth",
         "both in one keyframe");
  return keyframe;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// MonotoneCubic

MonotoneCubic::MonotoneCubic(std::vector<double> t, std::vector<double> v, End start, End end)
    : t_(std::move(t)), v_(std::move(v)) {
  const std::size_t n = t_.size();
  if (n == 0 || v_.size() != n)
    throw std::invalid_argument("MonotoneCubic: expected as many values as times, at least one");
  for (std::size_t i = 1; i < n; ++i)
    if (!(t_[i] > t_[i - 1]))
      throw std::invalid_argument("MonotoneCubic: times must increase strictly");
  slope_.assign(n, 0.0);
  if (n == 1) return;
  std::vector<double> h(n - 1), secant(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = t_[i + 1] - t_[i];
    secant[i] = (v_[i + 1] - v_[i]) / h[i];
  }
  if (n == 2) {
    // The straight line, unless an end is flat (any slope between 0 and the secant's sign keeps
    // the piece monotone).
    slope_[0] = start == End::Flat ? 0.0 : secant[0];
    slope_[1] = end == End::Flat ? 0.0 : secant[0];
    return;
  }
  // Inside: the weighted harmonic mean of the two secants (Fritsch & Butland), 0 at an extremum
  // or a flat step. It never exceeds 3 times either secant, which keeps each piece monotone.
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double a = secant[i - 1], b = secant[i];
    if (a * b <= 0.0) continue;
    const double w1 = 2.0 * h[i] + h[i - 1], w2 = h[i] + 2.0 * h[i - 1];
    slope_[i] = (w1 + w2) / (w1 / a + w2 / b);
  }
  // Ends: the three-point formula, kept on the secant's side and within 3 times it.
  const auto end_slope = [](double h0, double h1, double s0, double s1) {
    double m = ((2.0 * h0 + h1) * s0 - h0 * s1) / (h0 + h1);
    const auto sign = [](double x) { return (x > 0.0) - (x < 0.0); };
    if (sign(m) != sign(s0)) {
      m = 0.0;
    } else if (sign(s0) != sign(s1) && std::fabs(m) > 3.0 * std::fabs(s0)) {
      m = 3.0 * s0;
    }
    return m;
  };
  slope_[0] = start == End::Flat ? 0.0 : end_slope(h[0], h[1], secant[0], secant[1]);
  slope_[n - 1] =
      end == End::Flat ? 0.0 : end_slope(h[n - 2], h[n - 3], secant[n - 2], secant[n - 3]);
}

namespace {

// The interval [t_i, t_{i+1}) holding t, with t inside [t_0, t_n).
std::size_t interval_of(const std::vector<double>& t, double x) {
  return static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin()) - 1;
}

}  // namespace

double MonotoneCubic::operator()(double t) const {
  if (t_.empty()) return 0.0;
  if (!(t > t_.front())) return v_.front();  // NaN too: the first key
  if (t >= t_.back()) return v_.back();
  const std::size_t i = interval_of(t_, t);
  const double h = t_[i + 1] - t_[i];
  const double s = (t - t_[i]) / h;
  const double s2 = s * s, s3 = s2 * s;
  // Cubic Hermite basis on [0, 1].
  const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = s3 - 2.0 * s2 + s;
  const double h01 = -2.0 * s3 + 3.0 * s2, h11 = s3 - s2;
  const double v = h00 * v_[i] + h10 * h * slope_[i] + h01 * v_[i + 1] + h11 * h * slope_[i + 1];
  // Rounding aside the piece stays between its ends; make that exact.
  return std::clamp(v, std::min(v_[i], v_[i + 1]), std::max(v_[i], v_[i + 1]));
}

double MonotoneCubic::derivative(double t) const {
  if (t_.size() < 2 || !(t >= t_.front()) || t > t_.back()) return 0.0;
  const std::size_t i = t >= t_.back() ? t_.size() - 2 : interval_of(t_, t);
  const double h = t_[i + 1] - t_[i];
  const double s = (t - t_[i]) / h;
  const double d00 = 6.0 * s * s - 6.0 * s, d10 = 3.0 * s * s - 4.0 * s + 1.0;
  const double d01 = -d00, d11 = 3.0 * s * s - 2.0 * s;
  return (d00 * v_[i] + d01 * v_[i + 1]) / h + d10 * slope_[i] + d11 * slope_[i + 1];
}

// ---------------------------------------------------------------------------------------------
// Flight

Flight Flight::parse(std::string_view json_text, std::string_view source,
                     const std::string& base_dir) {
  Flight f;
  f.source_ = source;
  const json doc = parse_strict(json_text, source);
  if (!doc.is_object())
    fail(source, "", "a JSON object (a flight, see docs/flight.md)", describe(doc));
  only_known(doc, {"description", "scene", "fps", "duration", "frames", "keyframes"}, source, "");
  if (doc.contains("description") && !doc["description"].is_string())
    fail(source, "description", "a string", describe(doc["description"]));

  // The base scene: inline, or a scene file relative to the flight's folder.
  if (doc.contains("scene")) {
    const json& scene = doc["scene"];
    if (scene.is_object()) {
      f.steps_.push_back({dump(scene), std::string(source), "scene.", ""});
    } else if (scene.is_string()) {
      const std::filesystem::path given = scene.get<std::string>();
      const std::string path =
          (given.is_absolute() || base_dir.empty() ? given
                                                   : std::filesystem::path(base_dir) / given)
              .string();
      f.steps_.push_back({read_text_file(path, "scene file (relative to the flight file's folder)",
                                         source, "scene"),
                          path, "", ""});
    } else {
      fail(source, "scene", "a scene object or the path of a scene file", describe(scene));
    }
  }

  if (doc.contains("fps"))
    f.fps_ = number_in(doc["fps"], source, "fps", 0, kFlightMaxFps, "frames per second", true);

  // Keyframes: times strictly increasing; the sun given one way only.
  if (!doc.contains("keyframes")) fail(source, "keyframes", "an array of keyframes", "none");
  const json& keys = doc["keyframes"];
  if (!keys.is_array() || keys.empty() || keys.size() > kFlightMaxKeyframes)
    fail(source, "keyframes",
         "an array of 1 to " + std::to_string(kFlightMaxKeyframes) + " keyframes", describe(keys));
  std::optional<std::size_t> first_utc, first_angles;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string at = "keyframes[" + std::to_string(i) + "]";
    FlightKeyframe k = parse_keyframe(keys[i], source, at);
    if (i > 0 && !(k.time > f.keyframes_.back().time))
      fail(source, at + ".time",
           "a time after keyframes[" + std::to_string(i - 1) + "].time (" +
               number_text(f.keyframes_.back().time) + " s)",
           number_text(k.time));
    if (k.values.sun_utc && !first_utc) first_utc = i;
    if ((k.values.sun_zenith || k.values.sun_azimuth) && !first_angles) first_angles = i;
    if (first_utc && first_angles) {
      const std::size_t later = std::max(*first_utc, *first_angles);
      const std::size_t earlier = std::min(*first_utc, *first_angles);
      const bool utc_later = later == *first_utc;
      fail(source, "keyframes[" + std::to_string(later) + "].sun." + (utc_later ? "utc" : "zenith"),
           std::string("the sun given one way in all keyframes, as ") +
               (utc_later ? "sun.zenith/sun.azimuth" : "sun.utc") + " in keyframes[" +
               std::to_string(earlier) + "]",
           utc_later ? "sun.utc" : "sun.zenith/sun.azimuth");
    }
    f.keyframes_.push_back(std::move(k));
  }

  // Positions on great circles: no two consecutive ones (nearly) antipodal.
  if (positions_paired(f.keyframes_)) {
    std::optional<std::size_t> before;
    for (std::size_t i = 0; i < f.keyframes_.size(); ++i) {
      const FlightValues& v = f.keyframes_[i].values;
      if (!v.lat) continue;
      if (before) {
        const FlightValues& w = f.keyframes_[*before].values;
        const double arc =
            arc_between(direction_of(*w.lat, *w.lon), direction_of(*v.lat, *v.lon)) / kRadian;
        if (arc > kMaxKeyArc)
          fail(source, "keyframes[" + std::to_string(i) + "].camera",
               "a position at most " + number_text(kMaxKeyArc) + " degrees of arc from keyframes[" +
                   std::to_string(*before) +
                   "]'s (the great circle between antipodes is undefined)",
               number_text(std::ceil(arc * 1e3) / 1e3) + " degrees");  // rounded up
      }
      before = i;
    }
  }

  // Length: a duration (default: the last keyframe's time) or a number of frames.
  if (doc.contains("duration") && doc.contains("frames"))
    fail(source, "frames", "either duration or frames", "both");
  if (doc.contains("frames")) {
    const json& n = doc["frames"];
    if (!n.is_number_integer() || n.get<double>() < 1 || n.get<double>() > kFlightMaxFrames)
      fail(source, "frames", "an integer in [1, " + std::to_string(kFlightMaxFrames) + "]",
           describe(n));
    f.frame_count_ = n.get<int>();
    f.duration_ = f.frame_time(f.frame_count_ - 1);
  } else {
    const double duration =
        doc.contains("duration")
            ? number_in(doc["duration"], source, "duration", 0, kFlightMaxDuration, "s")
            : f.keyframes_.back().time;
    const double frames = frames_over(duration, f.fps_);
    if (frames > kFlightMaxFrames)
      fail(source, "duration",
           "at most " + std::to_string(kFlightMaxFrames) + " frames (duration x fps + 1)",
           number_text(frames) + " frames");
    f.frame_count_ = static_cast<int>(frames);
    f.duration_ = duration;
  }

  f.build_channels();
  // The base scene and its agreement with the keyframes' sun, then one frame: every problem
  // is found now rather than at some frame of a long flight.
  SceneBuilder base = f.base_builder();
  const bool utc_animated = first_utc.has_value();
  const bool angles_animated = first_angles.has_value();
  for (std::string_view key : {"sun.zenith", "sun.azimuth", "sun.utc"}) {
    const std::string from = base.source_of(key);
    if (from == "defaults") continue;
    const bool conflict = key == std::string_view("sun.utc") ? angles_animated : utc_animated;
    if (!conflict) continue;
    const std::size_t at = utc_animated ? *first_utc : *first_angles;
    fail(source, "keyframes[" + std::to_string(at) + "].sun." + (utc_animated ? "utc" : "zenith"),
         "the sun given as the base scene gives it (" + std::string(key) + " in " + from + ")",
         utc_animated ? "sun.utc" : "sun.zenith/sun.azimuth");
  }
  f.base_time_ = base.build().time;
  if (!f.clock_times_.empty()) {
    // The keyframes that give the first and the last scene_time, for messages.
    std::size_t first = 0, last = f.keyframes_.size() - 1;
    while (!f.keyframes_[first].values.scene_time) ++first;
    while (!f.keyframes_[last].values.scene_time) --last;
    if (f.clock_values_.front() < f.clock_times_.front())
      fail(source, "keyframes[" + std::to_string(first) + "].scene_time",
           "at least its keyframe's time (" + number_text(f.clock_times_.front()) +
               " s): before its first key the scene's time runs at rate 1, and may not be "
               "negative at the flight's start",
           number_text(f.clock_values_.front()));
    const double last_frame = f.frame_time(f.frame_count_ - 1);
    if (f.last_scene_time(last_frame) > kSceneMaxTime)
      fail(source, "keyframes[" + std::to_string(last) + "].scene_time",
           "at most " + number_text(kSceneMaxTime - (last_frame - f.clock_times_.back())) +
               " (s): after its last key the scene's time runs at rate 1, and may not pass " +
               number_text(kSceneMaxTime) + " s by the flight's last frame (" +
               number_text(last_frame) + " s)",
           number_text(f.clock_values_.back()));
  }
  f.check_ends();
  return f;
}

Flight Flight::load_file(const std::string& path) {
  const std::string text = read_text_file(path, "flight file", "", "");
  return parse(text, path, std::filesystem::path(path).parent_path().string());
}

Flight Flight::default_flight() { return parse(default_flight_json(), "default flight"); }

void Flight::build_channels() {
  animated_.clear();
  splines_.assign(channels().size(), {});
  key_times_.assign(channels().size(), {});
  key_values_.assign(channels().size(), {});
  for (std::size_t c = 0; c < channels().size(); ++c) {
    const Channel& channel = channels()[c];
    std::vector<double> space;
    for (const FlightKeyframe& k : keyframes_) {
      const std::optional<double>& value = k.values.*channel.member;
      if (!value) continue;
      double y = to_space(channel, *value);
      // Angles unwrapped: each key differs from the one before by (-180, 180] degrees.
      if (channel.kind == ChannelKind::Angle && !space.empty())
        y = space.back() + wrap_angle(*value - key_values_[c].back(), -180.0, true);
      key_times_[c].push_back(k.time);
      key_values_[c].push_back(*value);
      space.push_back(y);
    }
    if (space.empty()) continue;
    animated_.push_back(key_of(channel));
    // Held before the first key or after the last within the flight: ease in or out there.
    const double last_frame = frame_time(frame_count_ - 1);
    const auto start =
        key_times_[c].front() > 0.0 ? MonotoneCubic::End::Flat : MonotoneCubic::End::Natural;
    const auto end =
        key_times_[c].back() < last_frame ? MonotoneCubic::End::Flat : MonotoneCubic::End::Natural;
    splines_[c] = MonotoneCubic(key_times_[c], std::move(space), start, end);
  }
  utc_times_.clear();
  utc_seconds_.clear();
  for (const FlightKeyframe& k : keyframes_) {
    if (!k.values.sun_utc) continue;
    utc_times_.push_back(k.time);
    utc_seconds_.push_back(*parse_utc_seconds(*k.values.sun_utc));  // checked when parsed
  }
  if (!utc_times_.empty()) animated_.push_back("sun.utc");
  clock_times_.clear();
  clock_values_.clear();
  for (const FlightKeyframe& k : keyframes_) {
    if (!k.values.scene_time) continue;
    clock_times_.push_back(k.time);
    clock_values_.push_back(*k.values.scene_time);
  }
  if (!clock_times_.empty()) animated_.push_back("time");
  build_position_path();
}

// The position's spherical Hermite curve: at each key its velocity, the analogue of the
// channels' monotone cubic (docs/flight.md). Inside, from the velocities in from the key before
// and out to the key after (the great circles' secants, tangent at the key): their east and
// north parts each take the channels' rule (Fritsch & Butland's weighted harmonic mean where
// the two agree in sign, zero where they do not), so that the path turns at a key as the
// latitude and longitude channels did, without passing its keys' latitudes or longitudes
// where a leg is slow after a fast one (a weighted arithmetic mean there carried the fast leg's
// direction 30 km past the next key). At a pole, where east is undefined, the parts along the
// bisector of the two and across it. At an end, the secant's velocity, or zero where the path is
// held beyond that key within the flight (it eases in or out, as the channels do).
void Flight::build_position_path() {
  great_circles_ = positions_paired(keyframes_);
  position_times_.clear();
  position_dirs_.clear();
  position_velocities_.clear();
  position_lat_lon_.clear();
  if (!great_circles_) return;
  std::vector<Vec3> p;
  for (const FlightKeyframe& k : keyframes_) {
    if (!k.values.lat) continue;
    position_times_.push_back(k.time);
    position_lat_lon_.push_back({*k.values.lat, wrap_angle(*k.values.lon, -180.0, true)});
    p.push_back(direction_of(*k.values.lat, *k.values.lon));
  }
  const std::vector<double>& t = position_times_;
  const std::size_t n = p.size();
  std::vector<Vec3> m(n, Vec3(0.0));
  if (n >= 2) {
    const auto out = [&](std::size_t i) { return log_map(p[i], p[i + 1]) / (t[i + 1] - t[i]); };
    const auto in = [&](std::size_t i) { return -log_map(p[i], p[i - 1]) / (t[i] - t[i - 1]); };
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const Vec3 a = in(i), b = out(i);
      const double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
      // The rates' weighted harmonic mean, as MonotoneCubic's inside (at most three times the
      // smaller), zero where they differ in sign.
      const auto rate = [&](double x, double y) {
        if (!(x * y > 0.0)) return 0.0;
        const double w1 = 2.0 * h1 + h0, w2 = h1 + 2.0 * h0;
        return (w1 + w2) / (w1 / x + w2 / y);
      };
      Vec3 east = glm::cross(Vec3(0.0, 0.0, 1.0), p[i]);
      if (glm::length(east) > kPoleTolerance) {
        east = glm::normalize(east);
      } else {
        // At a pole: along the bisector of the two secants and across it.
        const double la = glm::length(a), lb = glm::length(b);
        if (!(la > 0.0) || !(lb > 0.0)) continue;  // a stop: zero
        const Vec3 bisector = a / la + b / lb;
        if (!(glm::length(bisector) > 0.0)) continue;  // turning straight back
        east = glm::normalize(bisector);
      }
      const Vec3 north = glm::cross(p[i], east);
      m[i] = rate(glm::dot(a, east), glm::dot(b, east)) * east +
             rate(glm::dot(a, north), glm::dot(b, north)) * north;
    }
    const double last_frame = frame_time(frame_count_ - 1);
    if (!(t.front() > 0.0)) m[0] = out(0);
    if (!(t.back() < last_frame)) m[n - 1] = in(n - 1);
  }
  for (std::size_t i = 0; i < n; ++i) {
    position_dirs_.push_back({p[i].x, p[i].y, p[i].z});
    position_velocities_.push_back({m[i].x, m[i].y, m[i].z});
  }
}

std::pair<double, double> Flight::position_between(double t) const {
  const std::size_t i = interval_of(position_times_, t);
  const double h = position_times_[i + 1] - position_times_[i];
  const double u = (t - position_times_[i]) / h;
  // The spherical Bezier of the Hermite data (De Casteljau with great-circle steps): its
  // velocity at each end is the key's, and between two keys on one great circle whose
  // velocities are its secant's, it is that great circle at an even pace.
  const Vec3 b0 = vec(position_dirs_[i]), b3 = vec(position_dirs_[i + 1]);
  // Held between two keyframes at one place: that place's own latitude and longitude (the unit
  // vector's round trip would move it by 1e-14 degrees).
  if (b0 == b3 && vec(position_velocities_[i]) == Vec3(0.0) &&
      vec(position_velocities_[i + 1]) == Vec3(0.0))
    return position_lat_lon_[i];
  const Vec3 b1 = exp_map(b0, vec(position_velocities_[i]) * (h / 3.0));
  const Vec3 b2 = exp_map(b3, -vec(position_velocities_[i + 1]) * (h / 3.0));
  const Vec3 q0 = slerp(b0, b1, u), q1 = slerp(b1, b2, u), q2 = slerp(b2, b3, u);
  const Vec3 r0 = slerp(q0, q1, u), r1 = slerp(q1, q2, u);
  const Vec3 d = slerp(r0, r1, u);
  const double lat = std::atan2(d.z, std::hypot(d.x, d.y)) / kRadian;
  const double lon = std::atan2(d.y, d.x) / kRadian;
  return {std::clamp(lat, -90.0, 90.0), wrap_angle(lon, -180.0, true)};
}

double Flight::last_scene_time(double last_frame) const {
  if (clock_times_.empty()) return base_time_ + last_frame;
  return clock_values_.back() + std::max(0.0, last_frame - clock_times_.back());
}

void Flight::check_ends() const {
  scene_at(0.0);
  scene_at(frame_time(frame_count_ - 1));
}

SceneBuilder Flight::base_builder() const {
  SceneBuilder b;
  for (const Step& step : steps_) {
    if (step.text.empty())
      b.set(step.assignment);
    else
      b.load_text(step.text, step.source, step.prefix);
  }
  return b;
}

void Flight::set_fps(double fps) {
  if (!std::isfinite(fps) || !(fps > 0.0) || fps > kFlightMaxFps)
    throw SceneError("--fps: expected a number in (0, " + number_text(kFlightMaxFps) +
                     "] (frames per second), got " + number_text(fps));
  const double frames = frames_over(duration_, fps);
  if (frames > kFlightMaxFrames)
    throw SceneError("--fps: expected at most " + std::to_string(kFlightMaxFrames) +
                     " frames (duration x fps + 1), got " + number_text(frames) + " frames");
  const double last_frame = (frames - 1.0) / fps;
  if (last_scene_time(last_frame) > kSceneMaxTime)
    throw SceneError("--fps: expected a rate whose last frame (at " + number_text(last_frame) +
                     " s) keeps the scene's time at most " + number_text(kSceneMaxTime) +
                     " s, got " + number_text(fps) + " (it would be " +
                     number_text(last_scene_time(last_frame)) + " s)");
  const double old_fps = fps_;
  const int old_count = frame_count_;
  fps_ = fps;
  frame_count_ = static_cast<int>(frames);
  build_channels();  // the ends' easing depends on the last frame's time
  try {
    check_ends();  // every frame's scene is still one a scene file allows
  } catch (...) {
    fps_ = old_fps;
    frame_count_ = old_count;
    build_channels();
    throw;
  }
}

void Flight::set(std::string_view assignment) {
  std::string_view key = assignment.substr(0, assignment.find('='));
  while (!key.empty() && key.front() == ' ') key.remove_prefix(1);
  while (!key.empty() && key.back() == ' ') key.remove_suffix(1);
  const bool sun_animated = std::any_of(animated_.begin(), animated_.end(),
                                        [](const auto& k) { return k.rfind("sun.", 0) == 0; });
  const bool animated = std::find(animated_.begin(), animated_.end(), key) != animated_.end() ||
                        (sun_animated && key.rfind("sun.", 0) == 0);
  if (animated)
    fail("--set", key,
         "a key the flight's keyframes do not animate (" + source_ + " gives " +
             (sun_animated && key.rfind("sun.", 0) == 0 ? std::string("the sun")
                                                        : std::string(key)) +
             " in its keyframes)",
         "an override of it");
  steps_.push_back({"", "--set", "", std::string(assignment)});
  try {
    base_time_ = base_builder().build().time;
    check_ends();
  } catch (...) {
    steps_.pop_back();
    base_time_ = base_builder().build().time;
    throw;
  }
}

FlightValues Flight::sample(double t) const {
  FlightValues out;
  std::optional<std::pair<double, double>> position;  // on great circles, between two keys
  for (std::size_t c = 0; c < channels().size(); ++c) {
    const Channel& channel = channels()[c];
    const std::vector<double>& times = key_times_[c];
    if (times.empty()) continue;
    // At a key, its own value (the logarithm's round trip would change a height by an ulp).
    const auto hit = std::lower_bound(times.begin(), times.end(), t);
    double value;
    // NaN falls on the first key, as in MonotoneCubic.
    if (!(t > times.front()) || t >= times.back() || (hit != times.end() && *hit == t)) {
      const std::size_t i = !(t > times.front()) ? 0
                            : t >= times.back()  ? times.size() - 1
                                                 : static_cast<std::size_t>(hit - times.begin());
      value = key_values_[c][i];
      if (channel.kind == ChannelKind::Angle)
        value = wrap_angle(value, channel.lo, channel.upper_closed);
    } else if (great_circles_ &&
               (channel.member == &FlightValues::lat || channel.member == &FlightValues::lon)) {
      if (!position) position = position_between(t);  // once for both
      value = channel.member == &FlightValues::lat ? position->first : position->second;
    } else {
      value = from_space(channel, splines_[c](t));
      if (channel.kind == ChannelKind::LogHeight || channel.kind == ChannelKind::Log) {
        // The neighbouring keys bound it exactly (the spline piece does, up to exp's rounding).
        const std::size_t i = static_cast<std::size_t>(hit - times.begin());
        const double a = key_values_[c][i - 1], b = key_values_[c][i];
        value = std::clamp(value, std::min(a, b), std::max(a, b));
      }
    }
    out.*channel.member = value;
  }
  if (!utc_times_.empty()) {
    const auto hit = std::lower_bound(utc_times_.begin(), utc_times_.end(), t);
    std::size_t key = utc_times_.size();  // a key's own text, when t is at or beyond one
    if (!(t > utc_times_.front()))        // NaN too
      key = 0;
    else if (t >= utc_times_.back())
      key = utc_times_.size() - 1;
    else if (*hit == t)
      key = static_cast<std::size_t>(hit - utc_times_.begin());
    if (key < utc_times_.size()) {
      std::size_t seen = 0;
      for (const FlightKeyframe& k : keyframes_) {
        if (!k.values.sun_utc) continue;
        if (seen++ == key) out.sun_utc = k.values.sun_utc;
      }
    } else {
      const std::size_t i = static_cast<std::size_t>(hit - utc_times_.begin());
      const double s = (t - utc_times_[i - 1]) / (utc_times_[i] - utc_times_[i - 1]);
      out.sun_utc = format_utc(utc_seconds_[i - 1] + s * (utc_seconds_[i] - utc_seconds_[i - 1]));
    }
  }
  if (!clock_times_.empty()) {
    // Linear between keys (a stopped or steady clock kept exactly), rate 1 beyond them, the
    // keys' own values at the keys.
    const std::vector<double>&tk = clock_times_, &vk = clock_values_;
    const auto hit = std::lower_bound(tk.begin(), tk.end(), t);
    if (std::isnan(t)) {
      out.scene_time = vk.front();  // the first key, as every channel's
    } else if (t <= tk.front()) {
      out.scene_time = vk.front() - (tk.front() - t);
    } else if (t >= tk.back()) {
      out.scene_time = vk.back() + (t - tk.back());
    } else {
      const std::size_t i = static_cast<std::size_t>(hit - tk.begin());
      if (tk[i] == t) {
        out.scene_time = vk[i];
      } else {
        const double s = (t - tk[i - 1]) / (tk[i] - tk[i - 1]);
        out.scene_time = vk[i - 1] + s * (vk[i] - vk[i - 1]);
      }
    }
  }
  return out;
}

Scene Flight::scene_at(double t, std::string* merged_json) const {
  SceneBuilder b = base_builder();
  const FlightValues v = sample(t);
  json doc = json::object();
  for (const Channel& c : channels())
    if (const auto& value = v.*c.member) doc[std::string(c.section)][std::string(c.name)] = *value;
  if (v.sun_utc) doc["sun"]["utc"] = *v.sun_utc;
  doc["time"] = v.scene_time ? *v.scene_time : base_time_ + t;
  b.load_text(doc.dump(), source_ + " at t=" + number_text(t) + " s");
  Scene scene = b.build();
  if (merged_json) *merged_json = b.merged_json();
  return scene;
}

std::string Flight::scene_source_of(std::string_view key) const {
  return base_builder().source_of(key);
}

// The flight `thalassa fly` renders with no file; data/flights/orbit_to_surface.json holds the
// same document (tests/unit/flight_test.cpp checks it). Over the Pacific at sunset: the sun 2
// degrees above the western horizon; the camera descends from 400 km to 2 m, evenly in the
// logarithm of its height, facing west. Its pitch follows the horizon's dip (20 degrees at
// 400 km, 4.5 at 20 km) so that the limb, the sky and the sun's glint stay in view all the way:
// -22 degrees in orbit, -3 at the end.
std::string_view default_flight_json() {
  return R"json({
  "description": "From orbit to the sea at sunset: 400 km down to 2 m in 20 s, facing the setting sun, from the planet's limb and the glint seen from orbit down to the waves.",
  "scene": {
    "camera": {"lat": 20, "lon": -150, "heading": 270, "roll": 0, "fov_y": 45},
    "sun": {"zenith": 88, "azimuth": 270},
    "ocean": {"wind_speed": 8, "wind_direction": 270}
  },
  "fps": 24,
  "duration": 20,
  "keyframes": [
    {"time": 0, "camera": {"height": 400000, "pitch": -22}},
    {"time": 6, "camera": {"pitch": -15}},
    {"time": 14, "camera": {"pitch": -6}},
    {"time": 20, "camera": {"height": 2, "pitch": -3}}
  ]
}
)json";
}

}  // namespace thalassa
