// thalassa — scripted flights: a base scene and keyframes of the camera (and optionally the sun,
// the exposure and the scene's clock) in time, interpolated smoothly into the scene of each frame
// (DESIGN section 5, `thalassa fly`; the file format is in docs/flight.md). CPU only, no GL: an
// engine can fly its own camera with it.
//
// Interpolation is per channel (each of camera.lat, .lon, .height, .heading, .pitch, .roll,
// .fov_y, sun.zenith, .azimuth, .utc, image.exposure and the scene's time has its own keys: the
// keyframes that give it), but for the camera's position where the keyframes give latitude and
// longitude together: then it follows great circles (the sphere of geodetic latitude and
// longitude), a C1 spherical Hermite curve through the keys whose velocity at a key takes the
// channels' rule below in its east and north parts (it stops where the camera holds a place),
// exactly the great circle at an even pace between two keys that span the flight. Every numeric
// channel is a monotone cubic Hermite spline (Fritsch-Carlson, the "PCHIP" of MATLAB and SciPy):
// C1 in time, exact at the keys, and never outside the range of its two neighbouring keys, so a
// camera never overshoots a keyframe (below the sea, past the pole, beyond straight down). A
// channel whose first key comes after the flight's start, or whose last key before its last
// frame, eases in or out there (zero speed), so that holding it beyond stays C1.
// Heights are interpolated in log(height + kFlightHeightOffset), so that a descent spends equal
// times on equal ratios of height; angles the short way round (a difference of exactly 180
// degrees turns clockwise), the exposure in its logarithm. sun.utc is interpolated linearly in
// time. Before a channel's first key and after its last it holds that key's value; a channel no
// keyframe gives keeps the base scene's value.
// The scene's time (`scene_time` in a keyframe: the waves' and the ships' clock) is interpolated
// linearly between its keys, so that a stopped clock (equal keys) stays stopped and a faster one
// keeps its rate, and runs at rate 1 before its first key and after its last; a flight that
// gives no scene_time runs it at rate 1 from the base scene's `time`.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "thalassa/engine/scene.hpp"

namespace thalassa {

// h0 of the height channel, metres: heights are interpolated as log(height + h0). It lets a
// keyframe sit on the sea (0 m) and makes the pacing logarithmic above a few metres: 400 km to
// 2 m spends as long between 400 km and 4 km as between 400 m and 4 m (to within h0).
inline constexpr double kFlightHeightOffset = 1.0;

// Limits of a flight file (docs/flight.md).
inline constexpr double kFlightMaxFps = 1000.0;    // frames per second
inline constexpr double kFlightMaxDuration = 1e6;  // seconds
inline constexpr int kFlightMaxFrames = 10000000;  // frames in one flight
inline constexpr double kFlightMaxHeight = 1e9;    // metres, as camera.height
inline constexpr std::size_t kFlightMaxKeyframes = 100000;

// The values a keyframe (or a sample of the flight) gives; absent: not given. Units as in scene
// files: degrees, metres, ISO 8601 UTC.
struct FlightValues {
  std::optional<double> lat;           // camera.lat, degrees
  std::optional<double> lon;           // camera.lon, degrees
  std::optional<double> height;        // camera.height, metres above the sea, >= 0 in a flight
  std::optional<double> heading;       // camera.heading, degrees clockwise from north
  std::optional<double> pitch;         // camera.pitch, degrees above the horizontal
  std::optional<double> roll;          // camera.roll, degrees
  std::optional<double> fov_y;         // camera.fov_y, degrees
  std::optional<double> sun_zenith;    // sun.zenith, degrees
  std::optional<double> sun_azimuth;   // sun.azimuth, degrees clockwise from north
  std::optional<std::string> sun_utc;  // sun.utc
  std::optional<double> exposure;      // image.exposure, 1/(W m^-2 sr^-1 nm^-1)
  std::optional<double> scene_time;    // the scene's `time`, s (a keyframe's `scene_time`)
};

struct FlightKeyframe {
  double time = 0.0;  // seconds from the start of the flight
  FlightValues values;
};

// A C1 monotone cubic Hermite interpolant of (t_i, v_i), t strictly increasing (Fritsch &
// Carlson 1980, SIAM J. Numer. Anal. 17(2); tangents as in Fritsch & Butland 1984: the weighted
// harmonic mean of the neighbouring secants inside, zero at a local extremum, and the
// shape-preserving three-point formula at the ends). On each interval the curve stays between
// its two end values. With two points it is the straight line. Constant outside [t_0, t_n].
class MonotoneCubic {
 public:
  // The slope at an end key: the three-point formula (the curve runs on at its own pace; with
  // two keys, the straight line), or zero (it eases in or out, so that holding the value beyond
  // that key keeps the curve C1).
  enum class End { Natural, Flat };

  MonotoneCubic() = default;
  // Throws std::invalid_argument unless t and v have the same size >= 1 and t strictly increases.
  MonotoneCubic(std::vector<double> t, std::vector<double> v, End start = End::Natural,
                End end = End::Natural);
  double operator()(double t) const;  // v_i exactly at t_i
  double derivative(double t) const;  // dv/dt (0 outside [t_0, t_n])

 private:
  std::vector<double> t_, v_, slope_;  // slope_: dv/dt at each t_i
};

// A flight: where the camera (and the sun) is at each time, and the scene of each frame.
// Errors in a flight file, a --set or a key the flight cannot use throw SceneError with one line
// "<file>: <key path>: expected ..., got ..." (e.g. "f.json: keyframes[3].camera.height: expected
// a number in [0, 1e9] (m), got \"x\"").
class Flight {
 public:
  // Parses a flight. `source` names it in messages; a "scene" given as a path is resolved against
  // `base_dir` (the flight file's folder; empty: the working directory).
  static Flight parse(std::string_view json_text, std::string_view source,
                      const std::string& base_dir = "");
  static Flight load_file(const std::string& path);
  // The flight embedded in the program (also data/flights/orbit_to_surface.json).
  static Flight default_flight();

  // Overrides a key of the base scene, like `--set` for a scene ("image.width=32"). Refuses a key
  // the keyframes animate (camera.height when a keyframe gives it; sun.* when the keyframes give
  // the sun; time when they give scene_time). Checked at once: a failed call changes nothing.
  void set(std::string_view assignment);

  // Renders the flight at another frame rate, its length in seconds kept (its `duration`; for a
  // flight given by `frames`, (frames - 1) / fps): frames at 0, 1/fps, ... up to that length.
  // Throws SceneError ("--fps: expected ...") for fps not in (0, kFlightMaxFps], more than
  // kFlightMaxFrames frames, or a last frame whose scene time would pass 1e12 s; a failed call
  // changes nothing.
  void set_fps(double fps);

  const std::string& source() const { return source_; }
  double fps() const { return fps_; }
  int frame_count() const { return frame_count_; }
  double frame_time(int frame) const { return frame / fps_; }  // seconds
  const std::vector<FlightKeyframe>& keyframes() const { return keyframes_; }
  // Scene keys that some keyframe gives ("camera.height", "sun.utc", ...).
  const std::vector<std::string>& animated_keys() const { return animated_; }

  // The animated channels at time t (seconds; any t, held constant outside the keys, but for
  // the scene's time, which runs at rate 1 there); channels no keyframe gives are absent.
  // Longitude in (-180, 180], heading and sun azimuth in [0, 360),
  // roll in (-180, 180], latitude, pitch, zenith and fov clamped to their scene ranges, height
  // within its neighbouring keys' range and >= 0.
  FlightValues sample(double t) const;
  // The scene at time t: the base scene (with its --set overrides), the sampled channels, and
  // `time` the sampled scene time, or when no keyframe gives it the base scene's time + t (the
  // waves move with the flight). `merged_json` (optional)
  // receives the scene as canonical JSON (SceneBuilder::merged_json), for metadata.
  Scene scene_at(double t, std::string* merged_json = nullptr) const;
  Scene frame_scene(int frame, std::string* merged_json = nullptr) const {
    return scene_at(frame_time(frame), merged_json);
  }
  // Where a base scene key's value came from (SceneBuilder::source_of), for messages.
  std::string scene_source_of(std::string_view key) const;

 private:
  struct Step {              // one layer of the base scene, replayed for each frame
    std::string text;        // JSON text of a scene (empty for an override)
    std::string source;      // its name in messages
    std::string prefix;      // key prefix in messages ("scene." for an inline scene)
    std::string assignment;  // a --set override when text is empty
  };
  SceneBuilder base_builder() const;
  void build_channels();
  // Builds the first and the last frame's scenes: throws what a frame's scene would.
  void check_ends() const;
  // The scene's time at the last frame, at `last_frame` s into the flight (the clock's greatest).
  double last_scene_time(double last_frame) const;

  std::string source_;
  std::vector<Step> steps_;
  double fps_ = 24.0;
  int frame_count_ = 1;
  double duration_ = 0.0;  // s: the flight's length, which set_fps keeps
  std::vector<FlightKeyframe> keyframes_;
  std::vector<std::string> animated_;
  double base_time_ = 0.0;  // the base scene's `time`, seconds
  // One spline per numeric channel, in interpolation space (log height, unwrapped angles), in
  // the order of the channel table in flight.cpp; unused entries for absent channels.
  std::vector<MonotoneCubic> splines_;
  std::vector<std::vector<double>> key_times_, key_values_;  // per channel, as given
  std::vector<double> utc_times_, utc_seconds_;              // sun.utc keys
  std::vector<double> clock_times_, clock_values_;           // scene_time keys, s
  // The camera's position along great circles, used where every keyframe that gives
  // camera.lat or camera.lon gives both (docs/flight.md): per key its time (s), the unit vector
  // of its latitude and longitude, and the path's velocity there (rad/s, tangent to the sphere).
  bool great_circles_ = false;
  std::vector<double> position_times_;
  std::vector<std::array<double, 3>> position_dirs_, position_velocities_;
  std::vector<std::pair<double, double>> position_lat_lon_;  // the keys' own, degrees
  void build_position_path();
  // The position at time t strictly between two position keys: latitude and longitude, degrees.
  std::pair<double, double> position_between(double t) const;
};

// The embedded default flight's JSON text.
std::string_view default_flight_json();

}  // namespace thalassa
