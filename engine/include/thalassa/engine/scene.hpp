// thalassa — scene description: the typed form of a scene file (DESIGN section 5).
//
// A scene is built in three steps: start from the defaults embedded in the program (or a file,
// which is laid over them), apply `--set key.path=value` overrides, then validate everything
// into a typed `Scene`. Every error is a `SceneError` whose message is one line naming the
// source (file name or "--set"), the key path and what was expected; the command-line program
// turns it into exit status 2. Units in the struct are those of the file (degrees, metres,
// seconds); conversion to radians happens where the values are used.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace thalassa {

// Invalid scene input. what() is the complete one-line message
//   "<source>: <key.path>: expected <what>, got <what was found>", e.g.
//   "scene.json: camera.height: expected a number in [-11000, 1e9] (m), got \"high\"".
// <source> is the path given to load_text/load_file, or "--set" for overrides. Errors about the
// whole input have no key path: "scene.json:3:14: expected valid JSON, got ..." (line:column of
// a syntax error), "missing.json: expected a scene file, got no such file".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ExrPixelType { Half, Float };
enum class PlanetShape { Wgs84, Sphere };
enum class WaveSpectrum { PiersonMoskowitz, OmegaMinus2 };

// The largest image side a scene allows (image.width, image.height), pixels: the scene's check,
// and the sizes other inputs lead to (a window's framebuffer, a suite's supersampled methods).
inline constexpr int kMaxImageSide = 8192;

struct ImageSettings {
  int width = 960;                             // pixels, [1, kMaxImageSide]
  int height = 540;                            // pixels, [1, kMaxImageSide]
  double exposure = 10.0;                      // 1 / (W m^-2 sr^-1 nm^-1), (0, 1e6]; docs/scene.md
  ExrPixelType exr_type = ExrPixelType::Half;  // "half" or "float"
};

struct CameraSettings {
  double lat = 20.0;       // geodetic latitude, degrees, [-90, 90]
  double lon = -150.0;     // longitude, degrees, [-180, 180]
  double height = 4.0;     // metres above the ellipsoid (sea level), [-11000, 1e9]
  double heading = 180.0;  // degrees clockwise from north, [-360, 360]
  double pitch = -5.0;     // degrees above the horizontal, [-90, 90]
  double roll = 0.0;       // degrees, [-180, 180]
  double fov_y = 45.0;     // vertical field of view, degrees, [0.01, 179]
  bool operator==(const CameraSettings&) const = default;
};

struct SunSettings {
  double zenith = 60.0;    // degrees from the zenith at the camera's nadir, [0, 180]
  double azimuth = 180.0;  // degrees clockwise from north, [-360, 360]
  // ISO 8601 UTC time ("2026-06-21T18:30:00Z"). When present in the input, zenith and azimuth
  // are computed from it for the camera's nadir and the file must not also give them.
  std::optional<std::string> utc;
};

struct PlanetSettings {
  PlanetShape shape = PlanetShape::Wgs84;
  double radius = 6371000.0;  // metres, sphere only, [1e3, 1e8]
  bool operator==(const PlanetSettings&) const = default;
};

struct OceanSettings {
  double wind_speed = 10.0;       // m/s at 19.5 m above the sea, [0, 60]
  double wind_direction = 180.0;  // degrees clockwise from north the wind blows FROM, [-360, 360]
  WaveSpectrum spectrum = WaveSpectrum::PiersonMoskowitz;  // "pierson-moskowitz" or "omega-2"
  int waves = 60;                                          // number of trochoids, [1, 4096]
  double lambda_min = 0.02;  // shortest wavelength, m, [1e-3, 1e4], <= lambda_max
  double lambda_max = 30.0;  // longest wavelength, m, [1e-3, 1e4]
  std::uint32_t seed = 1;    // random seed for directions and phases, [0, 4294967295]
  double n_min = 1.0;        // N_min of the filter weights w (paper sec. 3.2), [0, 100], < n_max
  double n_max = 2.5;        // N_max, [0, 100]
  double grid_cell = 8.0;    // projected grid cell, pixels, [1, 64]
  double fresnel_r = 0.02;   // Fresnel reflectance at normal incidence (eq. 14), [0, 1]
  // Irradiance reflectance of the water body just below the surface (L_sea = R E / pi, eq. 28),
  // per channel (680, 550, 440 nm), [0, 1]: the defaults are clear open ocean's order of
  // magnitude (see shaders/ocean/ross_brdf.glsl, OCEAN_DEFAULT_DEEP_REFLECTANCE).
  double deep_reflectance_r = 0.004;
  double deep_reflectance_g = 0.016;
  double deep_reflectance_b = 0.047;
  // The sky reflection's filter: "texture_grad" (eq. 27), "nine_samples" (sec. 7.2) or "shrm"
  // (sky maps prefiltered in spherical harmonics, Ramamoorthi & Hanrahan 2002).
  std::string sky_filter = "texture_grad";
  // The effective Fresnel reflectance of the sky and refracted terms: "fit" (the paper's eq. 26)
  // or "table" (eq. 24 itself, tabulated; docs/ocean_fresnel.md).
  std::string effective_fresnel = "fit";
  // Where the reflected sky's lobe is centred: "mirror" (eq. 27: the mirror direction of the mean
  // normal) or "fresnel_weighted" (the visible facets' Fresnel-weighted mean slope;
  // ocean_fresnel.md).
  std::string sky_lobe_centre = "mirror";
  // Fixed-point steps of the parallax of the waves drawn in the normals alone, [0, 8]; 0: none,
  // the paper's normal mapping (shaders/ocean/parallax.glsl, docs/ocean_fresnel.md).
  int parallax_iterations = 0;
  bool operator==(const OceanSettings&) const = default;
};

struct SkySettings {
  std::string model = "atmosphere";  // the sky model; "atmosphere" is the only one so far
  std::string exr;                   // path of an equirectangular HDR sky; empty = use `model`
};

// Wakes and calm areas (issue 9; docs/wakes.md, docs/scene.md "Wakes and calm areas"). The
// scene keys `wakes` and `calm_areas` are arrays; GeoJSON files named there are read and checked
// when the scene is loaded and arrive here in the same form as inline entries.
struct GeoPoint {
  double lat = 0.0;  // geodetic latitude, degrees, [-90, 90]
  double lon = 0.0;  // longitude, degrees, [-180, 180]
  bool operator==(const GeoPoint&) const = default;
};

struct TrackPoint {
  double lat = 0.0;   // degrees, [-90, 90]
  double lon = 0.0;   // degrees, [-180, 180]
  double time = 0.0;  // simulation time (the scene's `time` axis) when the ship is here, s
};

// A ship and its Kelvin wake. Either a track (>= 2 points, strictly increasing times; the ship
// sails the geodesic between successive points at constant speed, and exists only between the
// first and the last time) or, with `track` empty, a position, heading and speed (the ship is at
// lat/lon at `time` and sails the geodesic of that initial heading at that speed, forever).
struct WakeSettings {
  std::string name;               // from the entry or the GeoJSON feature; may be empty
  std::vector<TrackPoint> track;  // the track form; empty for the position form
  double lat = 0.0;               // position form: degrees, [-90, 90]
  double lon = 0.0;               // position form: degrees, [-180, 180]
  double time = 0.0;              // position form: s, when the ship is at lat/lon
  double heading = 0.0;           // position form: degrees clockwise from north, [-360, 360]
  double speed = 0.0;             // position form: m/s, [0, 100]
  double amplitude = 0.3;         // m, [0, 10]: transverse wave amplitude one wavelength astern
  double draft = 3.0;             // m, (0, 100]: depth of the equivalent source
  double length = 3000.0;         // m, (0, 1e6]: how far astern the wake reaches
};

// A calm area: a polygon (an exterior ring and holes, each at least 3 distinct vertices, the
// closing vertex not repeated; edges are geodesics) inside which wave amplitudes are scaled by
// `scale`, faded over `fade` metres inside the edge.
struct CalmAreaSettings {
  std::string name;
  std::vector<GeoPoint> exterior;
  std::vector<std::vector<GeoPoint>> holes;
  double scale = 0.2;   // amplitude factor inside, [0, 1]
  double fade = 100.0;  // m, [0, 1e6]: the factor is reached this far inside the edge
  bool operator==(const CalmAreaSettings&) const = default;
};

// The largest scene `time`, s: the key's range is [0, kSceneMaxTime].
inline constexpr double kSceneMaxTime = 1e12;

struct Scene {
  ImageSettings image;
  CameraSettings camera;
  SunSettings sun;
  double time = 0.0;  // simulation time, seconds, [0, 1e12]
  PlanetSettings planet;
  OceanSettings ocean;
  SkySettings sky;
  std::vector<WakeSettings> wakes;           // scene key `wakes` (none by default)
  std::vector<CalmAreaSettings> calm_areas;  // scene key `calm_areas` (none by default)
};

// Builds a Scene from defaults, an optional file and overrides, with the checks of DESIGN
// section 4 ("Bad input"). Errors throw SceneError.
class SceneBuilder {
 public:
  SceneBuilder();  // starts from the embedded defaults
  ~SceneBuilder();
  SceneBuilder(SceneBuilder&&) noexcept;
  SceneBuilder& operator=(SceneBuilder&&) noexcept;
  // A copy to try changes on: several sets that must take together or not at all.
  SceneBuilder(const SceneBuilder&);
  SceneBuilder& operator=(const SceneBuilder&);

  // Lays a JSON document over the current values. `source` names it in messages (a path).
  void load_text(std::string_view json_text, std::string_view source);
  // Like load_text, for a scene nested in another file (a flight's "scene" object): messages name
  // each key with `key_prefix` in front, e.g. "flight.json: scene.camera.height: expected ...".
  void load_text(std::string_view json_text, std::string_view source, std::string_view key_prefix);
  // Reads and lays a file over the current values; a missing or unreadable file is a SceneError.
  void load_file(const std::string& path);
  // "key.path=value": value is parsed as JSON when it is valid JSON (numbers, true, "str"),
  // otherwise taken as a bare string (so `--set ocean.spectrum=omega-2` works unquoted).
  // Messages name the source "--set". Like load_text, a failed call changes nothing.
  void set(std::string_view assignment);
  // The same, for an override read from another file: messages name `source` instead of
  // "--set", e.g. "suite.json: cases[1].set: camera.lat: expected ...".
  void set(std::string_view assignment, std::string_view source);

  // Checks the constraints between keys (ocean.lambda_min <= ocean.lambda_max; sun.utc not given
  // together with sun.zenith or sun.azimuth, where the built-in defaults do not count as given)
  // and returns the typed scene, with sun.zenith/azimuth computed from sun.utc when it is set.
  // Each key's own checks already ran in load_text/load_file/set.
  Scene build() const;
  // Where the current value of `key` came from: the file path, "--set", or "defaults" — for
  // messages about a valid scene that a later stage cannot use.
  std::string source_of(std::string_view key) const;
  // The merged document (defaults + file + overrides) as canonical JSON text, for metadata:
  // compact, keys sorted, numbers as doubles and integers as integers. With sun.utc it leaves
  // out sun.zenith and sun.azimuth, so that the text is itself a valid scene of the same Scene.
  std::string merged_json() const;

 private:
  struct Impl;
  Impl* impl_;
};

// The embedded default scene's JSON text (what `render` uses with no scene file).
std::string_view default_scene_json();

// Checks one value, given as JSON text, against scene key `key` as a scene file's value is
// checked (type, range, format), for files that hold scene values elsewhere (a flight's
// keyframes). Throws SceneError "<source>: <key_prefix><key>: expected ..., got ...";
// std::invalid_argument for a key that is not a scene key.
void check_scene_value(std::string_view key, std::string_view value_json, std::string_view source,
                       std::string_view key_prefix = {});

// Seconds since 1970-01-01T00:00:00Z (proleptic Gregorian, no leap seconds) of a time as sun.utc
// accepts it; nullopt when it is malformed.
std::optional<double> parse_utc_seconds(std::string_view utc);
// The sun.utc text of `seconds` since the epoch, rounded to the millisecond:
// "2026-06-21T18:30:00.250Z". parse_utc_seconds reads it back to within 0.5 ms.
std::string format_utc(double seconds);

// One documented scene key: used to validate, to generate docs/scene.md and to test that the
// documentation lists every key.
struct SceneKeyInfo {
  std::string path;           // "camera.height"
  std::string type;           // "number", "integer", "string", "enum"
  std::string unit;           // "m", "degrees", "" ...
  std::string range;          // human-readable valid range, e.g. "[-11000, 1e9]" or "half, float"
  std::string default_value;  // canonical JSON text ("4.0", "\"half\""); "(none)" if no default
  std::string doc;            // one sentence
};
const std::vector<SceneKeyInfo>& scene_keys();

}  // namespace thalassa
