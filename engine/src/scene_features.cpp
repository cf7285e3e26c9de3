// thalassa — wakes and calm areas in scene files and GeoJSON (scene_features.hpp).
//
// Geometry checks here are on a sphere of the Earth's mean radius (the engine has no geodesy):
// distances and speeds for the limits, great-circle arcs for self-intersections. The limits are
// set below the planet module's own (ShipWake: 10000 km segments; CalmArea: 5000 km from the
// centre) by more than the sphere's error (< 0.5 % of a distance, < 25 km of a centre), so a
// scene that passes here always builds there.
#include "scene_features.hpp"
#include "strict_json.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <optional>
#include <string>

namespace thalassa::detail {
namespace {

using json = nlohmann::json;

constexpr double kRad = std::numbers::pi / 180.0;
// IUGG mean radius of the Earth, m (R1 = (2a + b) / 3 of WGS84).
constexpr double kMeanRadius = 6371008.8;
// Limits (docs/scene.md): a track segment's length and speed, a calm area's extent from its
// centre, the vertices of a ring and the points of a track.
constexpr double kMaxSegment = 9.0e6;     // m
constexpr double kMaxSpeed = 100.0;       // m/s
constexpr double kMaxAreaRadius = 4.5e6;  // m
constexpr std::size_t kMaxRingVertices = 10000;
constexpr std::size_t kMaxTrackPoints = 1000000;

// ---------------------------------------------------------------------------------------------
// Messages (the format of scene.cpp's).

std::string dump(const json& v) { return v.dump(-1, ' ', false, json::error_handler_t::replace); }

std::string describe(const json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return "an array of " + std::to_string(v.size());
  std::string s = dump(v);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

[[noreturn]] void fail(std::string_view source, std::string_view key, std::string_view expected,
                       std::string_view got) {
  throw SceneError(input_message(source, key, expected, got));
}

// Where messages point: the source and the key path of the current object.
struct Where {
  std::string_view source;
  std::string key;
  Where operator/(const std::string& member) const { return {source, key + "." + member}; }
  Where operator[](std::size_t i) const { return {source, key + "[" + std::to_string(i) + "]"}; }
  [[noreturn]] void fail(const std::string& expected, const json& got) const {
    detail::fail(source, key, expected, describe(got));
  }
  [[noreturn]] void fail(const std::string& expected, const std::string& got) const {
    detail::fail(source, key, expected, got);
  }
};

struct NumberRule {
  double lo, hi;
  bool lo_open;
  const char* unit;
};

std::string rule_text(const NumberRule& r) {
  return std::string("a number in ") + (r.lo_open ? "(" : "[") + number_text(r.lo) + ", " +
         number_text(r.hi) + "]" + (r.unit[0] ? std::string(" (") + r.unit + ")" : "");
}

double number(const json& v, const Where& at, const NumberRule& r) {
  if (!v.is_number()) at.fail(rule_text(r), v);
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < r.lo || x > r.hi || (r.lo_open && x == r.lo))
    at.fail(rule_text(r), v);
  return x;
}

const NumberRule kLat{-90, 90, false, "degrees"};
const NumberRule kLon{-180, 180, false, "degrees"};
const NumberRule kTime{-1e12, 1e12, false, "s"};
const NumberRule kHeading{-360, 360, false, "degrees"};
const NumberRule kSpeed{0, kMaxSpeed, false, "m/s"};
const NumberRule kAmplitude{0, 10, false, "m"};
const NumberRule kDraft{0, 100, true, "m"};
const NumberRule kLength{0, 1e6, true, "m"};
const NumberRule kScale{0, 1, false, ""};
const NumberRule kFade{0, 1e6, false, "m"};

std::string text(const json& v, const Where& at) {
  if (!v.is_string()) at.fail("a string", v);
  return v.get<std::string>();
}

void only_keys(const json& obj, const Where& at, std::initializer_list<std::string_view> allowed,
               const std::string& what) {
  for (const auto& [name, value] : obj.items()) {
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      std::string list;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      (at / name).fail("a known key of " + what + " (" + list + ")", std::string("an unknown key"));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Geometry on the sphere.

struct Vec3 {
  double x, y, z;
};
Vec3 unit(double lat, double lon) {
  return {std::cos(lat * kRad) * std::cos(lon * kRad), std::cos(lat * kRad) * std::sin(lon * kRad),
          std::sin(lat * kRad)};
}
Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(Vec3 a) { return std::sqrt(dot(a, a)); }

// Great-circle distance, m (atan2 form: accurate at every distance).
double distance(const GeoPoint& a, const GeoPoint& b) {
  const Vec3 u = unit(a.lat, a.lon), v = unit(b.lat, b.lon);
  return kMeanRadius * std::atan2(norm(cross(u, v)), dot(u, v));
}

// Whether the minor great-circle arcs AB and CD share a point.
bool arcs_cross(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const Vec3 n1 = cross(a, b), n2 = cross(c, d);
  Vec3 x = cross(n1, n2);
  const double len = norm(x);
  const auto on_arc = [](Vec3 p, Vec3 s, Vec3 e, Vec3 n) {
    return dot(cross(s, p), n) >= 0.0 && dot(cross(p, e), n) >= 0.0 && dot(p, s) + dot(p, e) > 0.0;
  };
  if (len < 1e-15 * norm(n1) * norm(n2)) {
    // On one great circle: they overlap when an end of one lies on the other.
    return on_arc(c, a, b, n1) || on_arc(d, a, b, n1) || on_arc(a, c, d, n2);
  }
  x = {x.x / len, x.y / len, x.z / len};
  for (int s = 0; s < 2; ++s) {
    if (on_arc(x, a, b, n1) && on_arc(x, c, d, n2)) return true;
    x = {-x.x, -x.y, -x.z};
  }
  return false;
}

// The first pair of non-adjacent edges of a closed ring that cross, or nullopt.
std::optional<std::pair<std::size_t, std::size_t>> self_crossing(
    const std::vector<GeoPoint>& ring) {
  const std::size_t n = ring.size();
  std::vector<Vec3> v;
  for (const GeoPoint& p : ring) v.push_back(unit(p.lat, p.lon));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (arcs_cross(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) return std::make_pair(i, j);
    }
  }
  return std::nullopt;
}

std::string point_text(const GeoPoint& p) {
  return "(lat " + number_text(p.lat) + ", lon " + number_text(p.lon) + ")";
}

// ---------------------------------------------------------------------------------------------
// Checks of the typed values, shared by inline entries and GeoJSON features.

void check_track(const std::vector<TrackPoint>& track, const Where& at) {
  if (track.size() < 2)
    at.fail("a track of at least 2 points", "a track of " + std::to_string(track.size()));
  if (track.size() > kMaxTrackPoints)
    at.fail("at most 1000000 points", "a track of " + std::to_string(track.size()));
  for (std::size_t i = 1; i < track.size(); ++i) {
    const TrackPoint& a = track[i - 1];
    const TrackPoint& b = track[i];
    if (!(b.time > a.time)) {
      at[i].fail("a time later than point " + std::to_string(i - 1) + "'s (" + number_text(a.time) +
                     " s): times must increase strictly",
                 number_text(b.time) + " s");
    }
    const double d = distance({a.lat, a.lon}, {b.lat, b.lon});
    if (d > kMaxSegment)
      at[i].fail("a point within 9000 km of the previous one", number_text(d / 1000) + " km away");
    const double speed = d / (b.time - a.time);
    if (speed > kMaxSpeed)
      at[i].fail("a ship speed from point " + std::to_string(i - 1) + " of at most 100 m/s",
                 number_text(speed) + " m/s (" + number_text(d) + " m in " +
                     number_text(b.time - a.time) + " s)");
  }
}

// Removes a repeated closing vertex (required when `closed_required`) and consecutive
// duplicates, then checks the ring: at least 3 distinct vertices, no self-crossing.
std::vector<GeoPoint> check_ring(std::vector<GeoPoint> ring, const Where& at,
                                 bool closed_required) {
  if (closed_required) {
    if (ring.size() < 4)
      at.fail("a linear ring of at least 4 positions (the first repeated at the end)",
              "a ring of " + std::to_string(ring.size()));
    if (ring.front().lat != ring.back().lat || ring.front().lon != ring.back().lon)
      at.fail("a closed ring (its last position equal to its first)",
              "first " + point_text(ring.front()) + " and last " + point_text(ring.back()));
  }
  if (ring.size() > kMaxRingVertices + 1)
    at.fail("a ring of at most 10000 vertices", "a ring of " + std::to_string(ring.size()));
  std::vector<GeoPoint> clean;
  for (const GeoPoint& p : ring) {
    if (!clean.empty() && clean.back().lat == p.lat && clean.back().lon == p.lon) continue;
    clean.push_back(p);
  }
  if (clean.size() > 1 && clean.front().lat == clean.back().lat &&
      clean.front().lon == clean.back().lon)
    clean.pop_back();
  if (clean.size() < 3)
    at.fail("a ring of at least 3 distinct vertices", "a ring of " + std::to_string(clean.size()));
  if (const auto crossing = self_crossing(clean)) {
    at.fail("a ring that does not cross itself", "edge " + std::to_string(crossing->first) +
                                                     " crossing edge " +
                                                     std::to_string(crossing->second));
  }
  return clean;
}

void check_extent(const CalmAreaSettings& area, const Where& at) {
  Vec3 mean{0, 0, 0};
  for (const GeoPoint& p : area.exterior) {
    const Vec3 u = unit(p.lat, p.lon);
    mean = {mean.x + u.x, mean.y + u.y, mean.z + u.z};
  }
  const double len = norm(mean);
  if (!(len > 1e-9 * static_cast<double>(area.exterior.size())))
    at.fail("a polygon within 4500 km of its centre",
            std::string("vertices spread around the globe"));
  const GeoPoint centre{std::asin(std::clamp(mean.z / len, -1.0, 1.0)) / kRad,
                        std::atan2(mean.y, mean.x) / kRad};
  for (const auto* ring : {&area.exterior}) {
    for (const GeoPoint& p : *ring) {
      const double d = distance(centre, p);
      if (d > kMaxAreaRadius)
        at.fail("a polygon within 4500 km of its centre " + point_text(centre),
                "a vertex " + point_text(p) + " " + number_text(d / 1000) + " km away");
    }
  }
  for (const auto& hole : area.holes)
    for (const GeoPoint& p : hole)
      if (distance(centre, p) > kMaxAreaRadius)
        at.fail("holes within 4500 km of the polygon's centre", "a vertex " + point_text(p));
}

// ---------------------------------------------------------------------------------------------
// Canonical JSON.

json to_json(const WakeSettings& w) {
  json j = json::object();
  j["name"] = w.name;
  if (!w.track.empty()) {
    json t = json::array();
    for (const TrackPoint& p : w.track)
      t.push_back({{"lat", p.lat}, {"lon", p.lon}, {"time", p.time}});
    j["track"] = std::move(t);
  } else {
    j["lat"] = w.lat;
    j["lon"] = w.lon;
    j["time"] = w.time;
    j["heading"] = w.heading;
    j["speed"] = w.speed;
  }
  j["amplitude"] = w.amplitude;
  j["draft"] = w.draft;
  j["length"] = w.length;
  return j;
}

json ring_json(const std::vector<GeoPoint>& ring) {
  json r = json::array();
  for (const GeoPoint& p : ring) r.push_back({{"lat", p.lat}, {"lon", p.lon}});
  return r;
}

json to_json(const CalmAreaSettings& a) {
  json j = json::object();
  j["name"] = a.name;
  j["polygon"] = ring_json(a.exterior);
  json holes = json::array();
  for (const auto& h : a.holes) holes.push_back(ring_json(h));
  j["holes"] = std::move(holes);
  j["scale"] = a.scale;
  j["fade"] = a.fade;
  return j;
}

// ---------------------------------------------------------------------------------------------
// Inline entries.

GeoPoint inline_point(const json& v, const Where& at) {
  if (!v.is_object()) at.fail("a point {\"lat\": ..., \"lon\": ...} (degrees)", v);
  only_keys(v, at, {"lat", "lon"}, "a point");
  if (!v.contains("lat") || !v.contains("lon")) at.fail("a point with both lat and lon", v);
  return {number(v["lat"], at / "lat", kLat), number(v["lon"], at / "lon", kLon)};
}

std::vector<GeoPoint> inline_ring(const json& v, const Where& at) {
  if (!v.is_array()) at.fail("an array of points {\"lat\": ..., \"lon\": ...}", v);
  std::vector<GeoPoint> ring;
  for (std::size_t i = 0; i < v.size(); ++i) ring.push_back(inline_point(v[i], at[i]));
  return check_ring(std::move(ring), at, false);
}

// Reads a GeoJSON file: `path` as written, resolved from the scene's folder.
json read_geojson(const std::string& path, std::string_view source, const Where& at,
                  std::string& shown) {
  namespace fs = std::filesystem;
  fs::path p(path);
  const bool scene_file = source != "--set" && source != "defaults";
  if (p.is_relative() && scene_file) p = fs::path(std::string(source)).parent_path() / p;
  shown = p.lexically_normal().string();
  std::error_code ec;
  if (!fs::exists(p, ec) || fs::is_directory(p, ec))
    at.fail("a GeoJSON file", "no such file \"" + shown + "\"");
  std::ifstream in(p, std::ios::binary);
  if (!in) at.fail("a readable GeoJSON file", "\"" + shown + "\" that cannot be opened");
  std::string content{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  // Strict like a scene file: a syntax error at its line and column, each key once.
  return parse_strict_json<json>(content, shown, "", &fail);
}

// The features of a GeoJSON document: a FeatureCollection's, a single Feature, or a bare
// geometry (as a feature without properties). Each with its key path in the file.
struct Feature {
  json geometry;
  json properties;
  std::string key;   // "features[2] (\"ferry\")" or "" for a bare geometry
  std::string name;  // properties.name, else properties.id / the feature's id, else ""
};

std::vector<Feature> features_of(const json& doc, const std::string& file) {
  const Where top{file, ""};
  if (!doc.is_object() || !doc.contains("type") || !doc["type"].is_string())
    fail(file, "type", "a GeoJSON object with a \"type\"", describe(doc));
  const std::string type = doc["type"];
  std::vector<Feature> out;
  auto feature = [&](const json& f, const std::string& key) {
    if (!f.is_object() || f.value("type", json()) != "Feature")
      fail(file, key, "a GeoJSON Feature", describe(f));
    Feature r;
    r.geometry = f.value("geometry", json());
    r.properties = f.value("properties", json::object());
    if (r.properties.is_null()) r.properties = json::object();
    if (!r.properties.is_object())
      fail(file, key + ".properties", "an object", describe(r.properties));
    const json name = r.properties.value("name", r.properties.value("id", f.value("id", json())));
    if (name.is_string())
      r.name = name.get<std::string>();
    else if (name.is_number())
      r.name = dump(name);
    r.key = key + (r.name.empty() ? "" : " (\"" + r.name + "\")");
    out.push_back(std::move(r));
  };
  if (type == "FeatureCollection") {
    const json features = doc.value("features", json());
    if (!features.is_array()) fail(file, "features", "an array of Features", describe(features));
    for (std::size_t i = 0; i < features.size(); ++i)
      feature(features[i], "features[" + std::to_string(i) + "]");
  } else if (type == "Feature") {
    feature(doc, "feature");
  } else {
    Feature r;
    r.geometry = doc;
    r.properties = json::object();
    r.key = "geometry";
    out.push_back(std::move(r));
  }
  if (out.empty()) fail(file, "features", "at least one feature", "none");
  return out;
}

// A GeoJSON position [lon, lat] or [lon, lat, altitude] (RFC 7946 sec. 3.1.1).
GeoPoint position(const json& v, const Where& at) {
  if (!v.is_array() || v.size() < 2 || v.size() > 3)
    at.fail("a position [lon, lat] or [lon, lat, altitude] (degrees)", v);
  for (const auto& x : v)
    if (!x.is_number()) at.fail("a position of numbers [lon, lat]", v);
  const double lon = v[0].get<double>(), lat = v[1].get<double>();
  if (!std::isfinite(lon) || lon < -180 || lon > 180 || !std::isfinite(lat) || lat < -90 ||
      lat > 90)
    at.fail("a position [lon, lat] with lon in [-180, 180] and lat in [-90, 90] degrees", v);
  return {lat, lon};
}

std::vector<GeoPoint> geojson_ring(const json& v, const Where& at) {
  if (!v.is_array()) at.fail("a linear ring (an array of positions)", v);
  std::vector<GeoPoint> ring;
  for (std::size_t i = 0; i < v.size(); ++i) ring.push_back(position(v[i], at[i]));
  return check_ring(std::move(ring), at, true);
}

// A number property, or the entry's default.
double property(const json& props, const char* name, double fallback, const Where& at,
                const NumberRule& r) {
  if (!props.contains(name)) return fallback;
  return number(props[name], at / "properties" / name, r);
}

// The defaults an entry gives to the features of its GeoJSON file.
WakeSettings wake_defaults(const json& entry, const Where& at) {
  WakeSettings w;
  if (entry.contains("amplitude"))
    w.amplitude = number(entry["amplitude"], at / "amplitude", kAmplitude);
  if (entry.contains("draft")) w.draft = number(entry["draft"], at / "draft", kDraft);
  if (entry.contains("length")) w.length = number(entry["length"], at / "length", kLength);
  return w;
}

void wakes_from_geojson(const json& entry, std::string_view source, const Where& at,
                        std::vector<WakeSettings>& out) {
  only_keys(entry, at, {"geojson", "amplitude", "draft", "length"}, "a wake read from GeoJSON");
  const WakeSettings defaults = wake_defaults(entry, at);
  std::string file;
  const json doc =
      read_geojson(text(entry["geojson"], at / "geojson"), source, at / "geojson", file);
  for (const Feature& f : features_of(doc, file)) {
    const Where fa{file, f.key};
    WakeSettings w = defaults;
    w.name = f.name;
    const json& props = f.properties;
    w.amplitude = property(props, "amplitude", w.amplitude, fa, kAmplitude);
    w.draft = property(props, "draft", w.draft, fa, kDraft);
    w.length = property(props, "length", w.length, fa, kLength);
    const json& g = f.geometry;
    const std::string type = g.is_object() ? g.value("type", std::string()) : std::string();
    const Where ga = fa / "geometry";
    if (type == "LineString") {
      const json coords = g.value("coordinates", json());
      if (!coords.is_array()) (ga / "coordinates").fail("an array of positions", coords);
      const json times = props.value("times", json());
      if (!times.is_array())
        (fa / "properties" / "times")
            .fail("an array of times (s), one per position of the LineString", times);
      if (times.size() != coords.size())
        (fa / "properties" / "times")
            .fail("one time per position (" + std::to_string(coords.size()) + ")",
                  std::to_string(times.size()) + " times");
      for (std::size_t i = 0; i < coords.size(); ++i) {
        const GeoPoint p = position(coords[i], (ga / "coordinates")[i]);
        w.track.push_back(
            {p.lat, p.lon, number(times[i], (fa / "properties" / "times")[i], kTime)});
      }
      check_track(w.track, ga / "coordinates");
    } else if (type == "Point") {
      const GeoPoint p = position(g.value("coordinates", json()), ga / "coordinates");
      w.lat = p.lat;
      w.lon = p.lon;
      for (const char* key : {"heading", "speed"})
        if (!props.contains(key))
          (fa / "properties" / key)
              .fail(std::string("the ship's ") + key + " (a Point needs heading and speed)",
                    std::string("nothing"));
      w.heading = number(props["heading"], fa / "properties" / "heading", kHeading);
      w.speed = number(props["speed"], fa / "properties" / "speed", kSpeed);
      w.time = property(props, "time", 0.0, fa, kTime);
    } else {
      (ga / "type")
          .fail("\"LineString\" (a track) or \"Point\" (a position with heading and speed)",
                g.is_object() ? g.value("type", json()) : g);
    }
    out.push_back(std::move(w));
  }
}

void calm_areas_from_geojson(const json& entry, std::string_view source, const Where& at,
                             std::vector<CalmAreaSettings>& out) {
  only_keys(entry, at, {"geojson", "scale", "fade"}, "a calm area read from GeoJSON");
  CalmAreaSettings defaults;
  if (entry.contains("scale")) defaults.scale = number(entry["scale"], at / "scale", kScale);
  if (entry.contains("fade")) defaults.fade = number(entry["fade"], at / "fade", kFade);
  std::string file;
  const json doc =
      read_geojson(text(entry["geojson"], at / "geojson"), source, at / "geojson", file);
  for (const Feature& f : features_of(doc, file)) {
    const Where fa{file, f.key};
    CalmAreaSettings base = defaults;
    base.name = f.name;
    base.scale = property(f.properties, "scale", base.scale, fa, kScale);
    base.fade = property(f.properties, "fade", base.fade, fa, kFade);
    const json& g = f.geometry;
    const std::string type = g.is_object() ? g.value("type", std::string()) : std::string();
    const Where ga = fa / "geometry";
    const json coords = g.is_object() ? g.value("coordinates", json()) : json();
    auto polygon = [&](const json& rings, const Where& pa) {
      if (!rings.is_array() || rings.empty())
        pa.fail("an array of linear rings (exterior first)", rings);
      CalmAreaSettings a = base;
      a.exterior = geojson_ring(rings[0], pa[0]);
      for (std::size_t i = 1; i < rings.size(); ++i)
        a.holes.push_back(geojson_ring(rings[i], pa[i]));
      check_extent(a, pa);
      out.push_back(std::move(a));
    };
    if (type == "Polygon") {
      polygon(coords, ga / "coordinates");
    } else if (type == "MultiPolygon") {
      if (!coords.is_array() || coords.empty())
        (ga / "coordinates").fail("an array of polygons", coords);
      for (std::size_t i = 0; i < coords.size(); ++i) polygon(coords[i], (ga / "coordinates")[i]);
    } else {
      (ga / "type")
          .fail("\"Polygon\" or \"MultiPolygon\"", g.is_object() ? g.value("type", json()) : g);
    }
  }
}

// A key's value: an array of entries, or a string (one GeoJSON path, the shorthand for
// [{"geojson": path}]).
json entries(const json& value, const Where& at, const char* what) {
  if (value.is_string()) return json::array({{{"geojson", value}}});
  if (!value.is_array())
    at.fail(std::string("an array of ") + what + " (or a GeoJSON file's path)", value);
  return value;
}

}  // namespace

json check_wakes(const json& value, std::string_view source, std::string_view key) {
  const Where root{source, std::string(key)};
  const json list = entries(value, root, "wakes");
  std::vector<WakeSettings> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& e = list[i];
    const Where at = root[i];
    if (!e.is_object()) at.fail("a wake object (docs/scene.md)", e);
    if (e.contains("geojson")) {
      wakes_from_geojson(e, source, at, out);
      continue;
    }
    only_keys(e, at,
              {"name", "track", "lat", "lon", "time", "heading", "speed", "amplitude", "draft",
               "length", "geojson"},
              "a wake");
    WakeSettings w = wake_defaults(e, at);
    if (e.contains("name")) w.name = text(e["name"], at / "name");
    const bool position_form = e.contains("lat") || e.contains("lon") || e.contains("heading") ||
                               e.contains("speed") || e.contains("time");
    if (e.contains("track")) {
      if (position_form)
        at.fail("either a track or a position (lat, lon, time, heading, speed)",
                std::string("both"));
      const json& t = e["track"];
      if (!t.is_array()) (at / "track").fail("an array of points {\"lat\", \"lon\", \"time\"}", t);
      for (std::size_t j = 0; j < t.size(); ++j) {
        const Where pa = (at / "track")[j];
        if (!t[j].is_object())
          pa.fail("a point {\"lat\", \"lon\", \"time\"} (degrees, degrees, s)", t[j]);
        only_keys(t[j], pa, {"lat", "lon", "time"}, "a track point");
        for (const char* k : {"lat", "lon", "time"})
          if (!t[j].contains(k))
            (pa / k).fail("a number (a track point needs lat, lon and time)",
                          std::string("nothing"));
        w.track.push_back({number(t[j]["lat"], pa / "lat", kLat),
                           number(t[j]["lon"], pa / "lon", kLon),
                           number(t[j]["time"], pa / "time", kTime)});
      }
      check_track(w.track, at / "track");
    } else if (position_form) {
      for (const char* k : {"lat", "lon", "heading", "speed"})
        if (!e.contains(k))
          (at / k).fail("a number (a ship given by position needs lat, lon, heading and speed)",
                        std::string("nothing"));
      w.lat = number(e["lat"], at / "lat", kLat);
      w.lon = number(e["lon"], at / "lon", kLon);
      w.heading = number(e["heading"], at / "heading", kHeading);
      w.speed = number(e["speed"], at / "speed", kSpeed);
      if (e.contains("time")) w.time = number(e["time"], at / "time", kTime);
    } else {
      at.fail("a track, a position (lat, lon, heading, speed) or a geojson file", e);
    }
    out.push_back(std::move(w));
  }
  json canonical = json::array();
  for (const WakeSettings& w : out) canonical.push_back(to_json(w));
  return canonical;
}

json check_calm_areas(const json& value, std::string_view source, std::string_view key) {
  const Where root{source, std::string(key)};
  const json list = entries(value, root, "calm areas");
  std::vector<CalmAreaSettings> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& e = list[i];
    const Where at = root[i];
    if (!e.is_object()) at.fail("a calm area object (docs/scene.md)", e);
    if (e.contains("geojson")) {
      calm_areas_from_geojson(e, source, at, out);
      continue;
    }
    only_keys(e, at, {"name", "polygon", "holes", "scale", "fade", "geojson"}, "a calm area");
    CalmAreaSettings a;
    if (e.contains("name")) a.name = text(e["name"], at / "name");
    if (!e.contains("polygon"))
      (at / "polygon")
          .fail("the area's outline (an array of points {\"lat\", \"lon\"})",
                std::string("nothing"));
    a.exterior = inline_ring(e["polygon"], at / "polygon");
    if (e.contains("holes")) {
      const json& h = e["holes"];
      if (!h.is_array()) (at / "holes").fail("an array of rings", h);
      for (std::size_t j = 0; j < h.size(); ++j)
        a.holes.push_back(inline_ring(h[j], (at / "holes")[j]));
    }
    if (e.contains("scale")) a.scale = number(e["scale"], at / "scale", kScale);
    if (e.contains("fade")) a.fade = number(e["fade"], at / "fade", kFade);
    check_extent(a, at / "polygon");
    out.push_back(std::move(a));
  }
  json canonical = json::array();
  for (const CalmAreaSettings& a : out) canonical.push_back(to_json(a));
  return canonical;
}

std::vector<WakeSettings> wakes_from(const json& canonical) {
  std::vector<WakeSettings> out;
  for (const json& e : canonical) {
    WakeSettings w;
    w.name = e.at("name").get<std::string>();
    if (e.contains("track")) {
      for (const json& p : e["track"])
        w.track.push_back(
            {p.at("lat").get<double>(), p.at("lon").get<double>(), p.at("time").get<double>()});
    } else {
      w.lat = e.at("lat").get<double>();
      w.lon = e.at("lon").get<double>();
      w.time = e.at("time").get<double>();
      w.heading = e.at("heading").get<double>();
      w.speed = e.at("speed").get<double>();
    }
    w.amplitude = e.at("amplitude").get<double>();
    w.draft = e.at("draft").get<double>();
    w.length = e.at("length").get<double>();
    out.push_back(std::move(w));
  }
  return out;
}

std::vector<CalmAreaSettings> calm_areas_from(const json& canonical) {
  std::vector<CalmAreaSettings> out;
  const auto ring = [](const json& r) {
    std::vector<GeoPoint> v;
    for (const json& p : r) v.push_back({p.at("lat").get<double>(), p.at("lon").get<double>()});
    return v;
  };
  for (const json& e : canonical) {
    CalmAreaSettings a;
    a.name = e.at("name").get<std::string>();
    a.exterior = ring(e.at("polygon"));
    for (const json& h : e.at("holes")) a.holes.push_back(ring(h));
    a.scale = e.at("scale").get<double>();
    a.fade = e.at("fade").get<double>();
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace thalassa::detail
