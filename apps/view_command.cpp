// `thalassa view`: the interactive viewer. A GLFW window whose OpenGL context thalassa draws
// into as a host application's (attach_host_context), one Renderer given each frame's scene
// (Renderer::set_scene), the camera flown with the keys and the mouse (planet/camera_controls.hpp)
// and the scene's main keys on a Dear ImGui panel. Every change goes through a SceneBuilder, so
// that it gets the scene file's checks (and a sun given by sun.utc follows the camera), and a
// screenshot writes, beside its EXR and PNG, the scene as a file that `thalassa render` draws
// again at any size. It records the flight flown as a flight file for `thalassa fly`, and plays
// one (`--flight`). docs/viewer.md.
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common.hpp"

namespace thalassa::cli {
namespace {

using Clock = std::chrono::steady_clock;

// The sun's keys turn it by these rates, degrees per second (a boost multiplies them).
constexpr double kSunZenithRate = 10.0;
constexpr double kSunAzimuthRate = 30.0;
// Where sun.utc places the sun, J / L move that time instead, seconds per second: an hour.
constexpr double kSunTimeRate = 3600.0;
constexpr double kSecondsPerDay = 86400.0;

// A mouse drag turns the view by the pixel's angle times this: 1 keeps the point under the
// cursor under it, as dragging a photograph would.
constexpr double kDragGain = 1.0;
// The wheel scales the field of view by exp(-kZoomStep) a notch.
constexpr double kZoomStep = 0.1;
// The longest step a frame may take, s: a stall (a window dragged, a scene remade) does not
// throw the camera across the planet.
constexpr double kLongestStep = 0.25;
constexpr double kBoost = 5.0;  // a held Shift
// m: the camera flown by hand stays this far above the water under it (the sea's height there,
// every wave: planet/sea_state.hpp), so that a crest passing under a camera flown low lifts it
// rather than swallow it. The grid draws the waves shorter than its cell filtered, centimetres
// below the height of every wave near the camera.
constexpr double kWaveClearance = 0.25;
// A recorded flight keeps the camera of a frame at most this often, s: 30 keyframes a second
// follow a hand-flown path closely (docs/flight.md's splines pass through every key), and a
// flight file's 100000 keys last 55 minutes.
constexpr double kRecordInterval = 1.0 / 30.0;
// The recorded flight's frames per second (`fly --fps` renders it at another rate, `--set` at
// another size).
constexpr double kRecordFps = 30.0;
// A recording's scene times that stay this close to the base scene's time plus the flight's, s,
// are those of a clock that ran at rate 1 all along (they differ by rounding: the two sums add
// the same steps in another order), and are left out of the file: its waves then run with the
// flight as in any flight file. A millisecond of the sea's motion is not visible.
constexpr double kRecordClockTolerance = 1e-3;

// sun.utc moved by `seconds` (the scene file's form, to the millisecond); unchanged if it does
// not parse (the scene's checks read it already).
std::string moved_utc(const std::string& utc, double seconds) {
  const std::optional<double> at = parse_utc_seconds(utc);
  return at ? format_utc(*at + seconds) : utc;
}

// "%.17g": a double written so that it reads back the same.
std::string exact(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// The viewer's scene: a SceneBuilder holding the loaded scene and every change since.
class ViewedScene {
 public:
  explicit ViewedScene(SceneBuilder builder) : builder_(std::move(builder)) {
    scene_ = builder_.build();
  }
  const Scene& scene() const { return scene_; }
  std::string merged_json() const { return builder_.merged_json(); }
  bool sun_from_utc() const { return scene_.sun.utc.has_value(); }

  // Sets the keys that differ from the scene's: throws SceneError, the scene unchanged, for a
  // value the scene file would refuse.
  void update(const Scene& next) {
    SceneBuilder trial = builder_;
    std::vector<std::string> sets;
    auto set = [&](const char* key, double now, double then) {
      if (now != then) sets.push_back(std::string(key) + "=" + exact(now));
    };
    const CameraSettings &c = next.camera, &o = scene_.camera;
    set("camera.lat", c.lat, o.lat);
    set("camera.lon", c.lon, o.lon);
    set("camera.height", c.height, o.height);
    set("camera.heading", c.heading, o.heading);
    set("camera.pitch", c.pitch, o.pitch);
    set("camera.roll", c.roll, o.roll);
    set("camera.fov_y", c.fov_y, o.fov_y);
    if (!sun_from_utc()) {
      set("sun.zenith", next.sun.zenith, scene_.sun.zenith);
      set("sun.azimuth", next.sun.azimuth, scene_.sun.azimuth);
    } else if (next.sun.utc && *next.sun.utc != *scene_.sun.utc) {
      sets.push_back("sun.utc=" + *next.sun.utc);  // a played flight's sun.utc channel
    }
    set("time", next.time, scene_.time);
    set("image.width", next.image.width, scene_.image.width);
    set("image.height", next.image.height, scene_.image.height);
    set("image.exposure", next.image.exposure, scene_.image.exposure);
    set("ocean.wind_speed", next.ocean.wind_speed, scene_.ocean.wind_speed);
    set("ocean.wind_direction", next.ocean.wind_direction, scene_.ocean.wind_direction);
    if (sets.empty()) return;
    for (const std::string& assignment : sets) trial.set(assignment);
    Scene built = trial.build();
    builder_ = std::move(trial);
    scene_ = std::move(built);
  }

 private:
  SceneBuilder builder_;
  Scene scene_;
};

// A file name in the working folder for now (UTC): `pattern` is strftime's, e.g.
// "thalassa_view_%Y%m%d_%H%M%S.exr".
std::string timestamped_name(const char* pattern) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[64];
  std::strftime(text, sizeof text, pattern, &utc);
  return text;
}

// Records the camera as it is flown into a flight file (docs/flight.md) that `thalassa fly`
// renders again, headless and at any size: the scene at the recording's first frame as the base
// scene (its `time` the clock's then), and a keyframe of the camera, the sun (its zenith and
// azimuth, or its sun.utc), the scene's time and the exposure at the recording's first and last
// frames and at most every kRecordInterval between.
// The flight's time advances with the frames' steps. The scene's time (the clock, which may have
// been stopped or run faster) is kept as each keyframe's scene_time, and the exposure as its
// image.exposure, unless they are what the flight would give without them (a clock at rate 1
// throughout, an exposure never changed): then each replayed frame's waves and tones are the
// viewer's. The wind is not keyframed (a flight cannot change its wave set).
class FlightRecorder {
 public:
  bool active() const { return !path_.empty(); }
  std::size_t keyframes() const { return keys_.size() + (pending_ ? 1 : 0); }
  double duration() const { return time_; }
  // Whether the next keyframe would pass a flight file's limit: the recording must stop.
  bool full() const { return keys_.size() + 1 >= kFlightMaxKeyframes; }

  void start(std::string path, const ViewedScene& viewed) {
    path_ = std::move(path);
    base_ = nlohmann::ordered_json::parse(viewed.merged_json());
    base_time_ = viewed.scene().time;
    base_exposure_ = viewed.scene().image.exposure;
    keys_ = nlohmann::ordered_json::array();
    time_ = 0.0;
    last_key_ = -kRecordInterval;
    pending_.reset();
  }
  // The frame drawn after a step of dt seconds (0 for the recording's first).
  void add(double dt, const ViewedScene& viewed) {
    if (keys_.size() > 0) time_ += dt;
    nlohmann::ordered_json key = keyframe(viewed);
    if (time_ - last_key_ >= kRecordInterval || keys_.empty()) {
      keys_.push_back(std::move(key));
      last_key_ = time_;
      pending_.reset();
    } else {
      pending_ = std::move(key);  // kept if this frame turns out to be the last
    }
  }
  // Writes the flight, checked by parsing it as `fly` will; returns the message for the panel
  // and stderr, which starts with "wrote" when it was written. Stops the recording either way.
  std::string finish() {
    if (pending_ && time_ > last_key_) keys_.push_back(std::move(*pending_));
    pending_.reset();
    drop_unchanged();
    nlohmann::ordered_json flight;
    char summary[96];
    std::snprintf(summary, sizeof summary, "%zu keyframes over %.2f s", keys_.size(), time_);
    flight["description"] = std::string("Recorded by thalassa view: ") + summary + ".";
    flight["scene"] = std::move(base_);
    flight["fps"] = kRecordFps;
    flight["duration"] = time_;
    flight["keyframes"] = std::move(keys_);
    const std::string path = std::exchange(path_, std::string());
    const std::string text = flight.dump(2) + "\n";
    try {
      Flight::parse(text, path);
      PendingOutputs outputs;
      write_text_atomically(outputs.add(path), text);
      outputs.commit();
    } catch (const std::exception& error) {
      return "flight not written: " + std::string(error.what());
    }
    return "wrote " + path + " (" + summary + "; `thalassa fly " + path + " -o DIR` renders it)";
  }

 private:
  nlohmann::ordered_json keyframe(const ViewedScene& viewed) const {
    const Scene& scene = viewed.scene();
    const CameraSettings& c = scene.camera;
    nlohmann::ordered_json key;
    key["time"] = time_;
    key["scene_time"] = scene.time;
    key["camera"] = {{"lat", c.lat},         {"lon", c.lon},     {"height", c.height},
                     {"heading", c.heading}, {"pitch", c.pitch}, {"roll", c.roll},
                     {"fov_y", c.fov_y}};
    if (viewed.sun_from_utc())
      key["sun"] = {{"utc", *scene.sun.utc}};  // J / L move it; the replay places the sun anew
    else
      key["sun"] = {{"zenith", scene.sun.zenith}, {"azimuth", scene.sun.azimuth}};
    key["image"] = {{"exposure", scene.image.exposure}};
    return key;
  }

  // Leaves out the scene times of a clock that ran at rate 1 throughout, and the exposure when
  // it never changed (the flight gives both without them).
  void drop_unchanged() {
    bool steady_clock = true, same_exposure = true;
    for (const auto& key : keys_) {
      const double flight_time = key["time"].get<double>();
      steady_clock = steady_clock && std::fabs(key["scene_time"].get<double>() -
                                               (base_time_ + flight_time)) <= kRecordClockTolerance;
      same_exposure = same_exposure && key["image"]["exposure"].get<double>() == base_exposure_;
    }
    for (auto& key : keys_) {
      if (steady_clock) key.erase("scene_time");
      if (same_exposure) key.erase("image");
    }
  }

  std::string path_;  // empty: not recording
  nlohmann::ordered_json base_, keys_;
  std::optional<nlohmann::ordered_json> pending_;
  double time_ = 0.0;      // s since the recording's first frame
  double last_key_ = 0.0;  // s: the last keyframe kept
  double base_time_ = 0.0;      // s: the scene's time at the first frame
  double base_exposure_ = 0.0;  // the exposure at the first frame
};

// What the keys held this frame ask of the camera (planet/camera_controls.hpp) and the sun.
struct HeldKeys {
  CameraMotion motion;
  double sun_zenith = 0.0;   // -1, 0 or 1 (1: lower, toward the horizon)
  double sun_azimuth = 0.0;  // -1, 0 or 1 (1: clockwise)
};

HeldKeys held_keys(GLFWwindow* window) {
  auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0 : 0.0; };
  auto either = [&](int a, int b) { return std::max(down(a), down(b)); };
  HeldKeys keys;
  keys.motion.forward = either(GLFW_KEY_W, GLFW_KEY_UP) - either(GLFW_KEY_S, GLFW_KEY_DOWN);
  keys.motion.right = either(GLFW_KEY_D, GLFW_KEY_RIGHT) - either(GLFW_KEY_A, GLFW_KEY_LEFT);
  keys.motion.climb = either(GLFW_KEY_R, GLFW_KEY_PAGE_UP) - either(GLFW_KEY_F, GLFW_KEY_PAGE_DOWN);
  keys.motion.boost = either(GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT) > 0.0 ? kBoost : 1.0;
  keys.sun_zenith = down(GLFW_KEY_K) - down(GLFW_KEY_I);
  keys.sun_azimuth = down(GLFW_KEY_L) - down(GLFW_KEY_J);
  return keys;
}

// A key pressed since the last frame (edges, not levels), from GLFW's key callback.
struct KeyPresses {
  bool screenshot = false;
  bool toggle_panel = false;
  bool toggle_time = false;
  bool toggle_record = false;
  bool quit = false;
};
KeyPresses g_presses;
GLFWkeyfun g_imgui_key_callback = nullptr;

void key_callback(GLFWwindow* window, int key, int scancode, int action, int mods) {
  if (g_imgui_key_callback) g_imgui_key_callback(window, key, scancode, action, mods);
  if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  if (key == GLFW_KEY_P || key == GLFW_KEY_F12) g_presses.screenshot = true;
  if (key == GLFW_KEY_H) g_presses.toggle_panel = true;
  if (key == GLFW_KEY_SPACE) g_presses.toggle_time = true;
  if (key == GLFW_KEY_C) g_presses.toggle_record = true;
  if (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q) g_presses.quit = true;
}

// The file beside a screenshot's EXR (NAME.exr, checked when parsed) with `extension`.
std::string beside_screenshot(const std::string& exr, const char* extension) {
  return exr.substr(0, exr.size() - 4) + extension;
}

// Writes the frame as EXR, PNG and the scene file that draws it again (`thalassa render
// NAME.json`); the messages go to stderr and the panel.
std::string write_screenshot(const std::string& exr, const Renderer& renderer,
                             const ViewedScene& viewed) {
  const Image image = renderer.image();
  const std::string png = beside_screenshot(exr, ".png");
  const std::string json = beside_screenshot(exr, ".json");
  if (const std::string problem = nonfinite_pixels(image); !problem.empty())
    return "screenshot not written: " + problem;
  PendingOutputs outputs;
  const Scene& scene = viewed.scene();
  write_exr(outputs.add(exr), image, scene.image.exr_type,
            render_metadata(scene, viewed.merged_json(), renderer.stats(),
                            {{"thalassa:command", "view"}}));
  write_png(outputs.add(png), image, scene.image.exposure, {{"Software", "thalassa"}});
  write_text_atomically(outputs.add(json), viewed.merged_json() + "\n");
  outputs.commit();
  return "wrote " + exr + ", " + png + " and " + json;
}

// A flight played in the window (`--flight`): its time, advanced by the clock, gives each
// frame's camera, sun and scene time (Flight::scene_at), and its exposure where it animates one,
// looping at its end, until the camera is flown by hand.
struct FlightPlayback {
  std::optional<Flight> flight;
  bool playing = false;
  double time = 0.0;  // s into the flight
  double duration() const { return flight ? flight->frame_time(flight->frame_count() - 1) : 0.0; }
  // Whether its keyframes give image.exposure, which then follows the flight.
  bool animates_exposure() const {
    if (!flight) return false;
    const auto& keys = flight->animated_keys();
    return std::find(keys.begin(), keys.end(), "image.exposure") != keys.end();
  }
};

// The panel: what is drawn and how fast, and the scene's main keys, edited into `next`.
void draw_panel(const RenderStats& stats, double wall_ms, const ViewedScene& viewed, Scene& next,
                bool& time_running, double& time_rate, bool& screenshot, bool& record,
                const FlightRecorder& recorder, FlightPlayback& playback,
                const std::string& message) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::Begin("thalassa", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("%s, %s mode, %dx%d", stats.renderer.c_str(), stats.mode.c_str(), stats.width,
              stats.height);
  ImGui::Text("frame %.2f ms (%s), %.1f frames/s, %d waves resolved", stats.frame_ms,
              stats.timing == "finish_wall_clock" ? "wall clock" : "GPU",
              wall_ms > 0.0 ? 1e3 / wall_ms : 0.0, stats.resolved_waves);
  if (ImGui::CollapsingHeader("passes")) {
    for (const auto& [name, ms] : stats.passes) ImGui::Text("%-28s %8.3f ms", name.c_str(), ms);
  }
  const ImGuiSliderFlags clamp = ImGuiSliderFlags_AlwaysClamp;
  auto drag = [&](const char* label, double& value, double speed, double lo, double hi,
                  const char* format, ImGuiSliderFlags flags = 0) {
    ImGui::DragScalar(label, ImGuiDataType_Double, &value, float(speed), &lo, &hi, format,
                      flags | clamp);
  };
  if (ImGui::CollapsingHeader("camera", ImGuiTreeNodeFlags_DefaultOpen)) {
    CameraSettings& c = next.camera;
    drag("latitude", c.lat, 0.001, -90.0, 90.0, "%.6f deg");
    drag("longitude", c.lon, 0.001, -180.0, 180.0, "%.6f deg");
    drag("height", c.height, 0.01, 0.01, 1e9, "%.2f m", ImGuiSliderFlags_Logarithmic);
    // The height flown; the frame's camera is higher where a crest under it lifted it.
    if (viewed.scene().camera.height > c.height)
      ImGui::Text("lifted by the waves to %.2f m", viewed.scene().camera.height);
    drag("heading", c.heading, 0.5, -360.0, 360.0, "%.1f deg");
    drag("pitch", c.pitch, 0.25, -90.0, 90.0, "%.2f deg");
    drag("field of view", c.fov_y, 0.25, 0.01, 179.0, "%.2f deg", ImGuiSliderFlags_Logarithmic);
  }
  if (ImGui::CollapsingHeader("sun and time")) {
    if (viewed.sun_from_utc()) {
      ImGui::Text("sun from sun.utc %s: zenith %.2f, azimuth %.2f deg",
                  viewed.scene().sun.utc->c_str(), next.sun.zenith, next.sun.azimuth);
      // The time of day, in UTC hours; the date stays.
      if (const std::optional<double> at = parse_utc_seconds(*next.sun.utc)) {
        const double day = std::floor(*at / kSecondsPerDay) * kSecondsPerDay;
        double hours = (*at - day) / 3600.0;
        drag("UTC hour", hours, 0.01, 0.0, 24.0, "%.3f h");
        if (hours != (*at - day) / 3600.0) next.sun.utc = format_utc(day + 3600.0 * hours);
      }
    } else {
      drag("sun zenith", next.sun.zenith, 0.25, 0.0, 180.0, "%.2f deg");
      drag("sun azimuth", next.sun.azimuth, 0.5, -360.0, 360.0, "%.1f deg");
    }
    ImGui::Checkbox("time runs", &time_running);
    ImGui::SameLine();
    drag("rate", time_rate, 0.05, 0.0, 100.0, "x%.2f");
    drag("time", next.time, 0.1, 0.0, kSceneMaxTime, "%.2f s");
  }
  if (playback.flight && ImGui::CollapsingHeader("flight", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Checkbox("play", &playback.playing);
    ImGui::SameLine();
    double duration = playback.duration();
    double zero = 0.0;
    if (ImGui::SliderScalar("flight time", ImGuiDataType_Double, &playback.time, &zero, &duration,
                            "%.2f s", ImGuiSliderFlags_AlwaysClamp))
      playback.playing = true;  // scrubbing shows the flight's frame
  }
  if (ImGui::CollapsingHeader("sea and image")) {
    drag("wind speed", next.ocean.wind_speed, 0.1, 0.0, 60.0, "%.1f m/s");
    drag("wind from", next.ocean.wind_direction, 0.5, -360.0, 360.0, "%.1f deg");
    drag("exposure", next.image.exposure, 0.05, 1e-3, 1e6, "%.3f", ImGuiSliderFlags_Logarithmic);
  }
  if (ImGui::Button("screenshot (P)")) screenshot = true;
  ImGui::SameLine();
  if (ImGui::Button(recorder.active() ? "stop recording (C)" : "record a flight (C)"))
    record = true;
  if (recorder.active())
    ImGui::Text("recording: %zu keyframes, %.1f s", recorder.keyframes(), recorder.duration());
  ImGui::TextWrapped(
      "W/S A/D or arrows: fly, R/F or PgUp/PgDn: climb, Shift: x%g, drag: look, wheel: zoom, "
      "I/K J/L: sun, Space: time, C: record, H: panel, Esc: quit",
      kBoost);
  if (!message.empty()) ImGui::TextWrapped("%s", message.c_str());
  ImGui::End();
}

}  // namespace

void add_view_command(CLI::App& app, ViewArgs& args) {
  CLI::App* view = app.add_subcommand(
      "view",
      "Open a window on a scene and fly through it (keys, mouse, a panel of the scene's keys); "
      "needs a display");
  view->add_option("scene", args.scene, "Scene file (JSON); default: the embedded scene");
  view->add_option("--set", args.sets, "Override a scene key: --set camera.height=100")
      ->allow_extra_args(false);
  view->add_option("--frames", args.frames, "Close after this many frames (0: when closed)")
      ->check(CLI::NonNegativeNumber);
  view->add_flag("--paused", args.paused, "Start with the clock stopped");
  view->add_flag("--no-panel", args.no_panel, "Start with the panel hidden (H shows it)");
  view->add_option("--screenshot", args.screenshot,
                   "Write the last frame to this EXR (with its PNG and scene JSON) on closing");
  view->add_option("--flight", args.flight,
                   "Play this flight file in the window (looping; flying by hand takes over); "
                   "--set then applies to its base scene");
  view->add_option("--record", args.record,
                   "Record the flight from the first frame into this flight file (JSON), written "
                   "on closing or when C stops it; `thalassa fly` renders it");
  view->footer(
      "Keys: W/S A/D or the arrows fly, R/F or PgUp/PgDn climb, Shift x5; drag to look, wheel to "
      "zoom; I/K J/L move the sun; Space stops the clock; C starts and stops recording a flight "
      "(thalassa_flight_*.json in the working folder); with --flight, flying by hand stops the "
      "flight; H hides the panel; P or F12 writes a "
      "screenshot (EXR, PNG, scene JSON) in the working folder; Esc or Q quits. docs/viewer.md");
}

int run_view(const ViewArgs& args) {
  // 1. Everything the user typed is checked before a window opens.
  if (!args.scene.empty() && !args.flight.empty()) {
    print_error("view: give a scene or a --flight, not both");
    return kExitInvalidInput;
  }
  std::optional<ViewedScene> loaded;
  FlightPlayback playback;
  try {
    SceneBuilder builder;
    if (!args.flight.empty()) {
      // The flight's scene at its start, as a scene file, is the viewer's scene.
      playback.flight = Flight::load_file(args.flight);
      for (const auto& assignment : args.sets) playback.flight->set(assignment);
      std::string merged;
      playback.flight->scene_at(0.0, &merged);
      builder.load_text(merged, args.flight);
      playback.playing = true;
    } else {
      if (!args.scene.empty()) builder.load_file(args.scene);
      for (const auto& assignment : args.sets) builder.set(assignment);
    }
    loaded.emplace(builder);
    check_drawable(loaded->scene(), playback.flight ? playback.flight->scene_source_of("sky.exr")
                                                    : builder.source_of("sky.exr"));
  } catch (const SceneError& error) {
    print_error(error.what());
    return kExitInvalidInput;
  }
  ViewedScene& viewed = *loaded;
  if (!args.screenshot.empty()) {
    if (const std::string problem = check_output("--screenshot", args.screenshot, ".exr");
        !problem.empty()) {
      print_error(problem);
      return kExitInvalidInput;
    }
  }
  if (!args.record.empty()) {
    // The screenshot writes its scene file beside its EXR: the flight must not be that file.
    const std::string screenshot_json =
        args.screenshot.empty() ? "" : beside_screenshot(args.screenshot, ".json");
    std::string problem = check_output("--record", args.record, ".json");
    if (problem.empty()) problem = check_distinct("--record", args.record, {screenshot_json});
    if (!problem.empty()) {
      print_error(problem);
      return kExitInvalidInput;
    }
  }
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) {
    print_error("view: no display (DISPLAY is not set); `thalassa render` draws without one");
    return kExitRuntimeFailure;
  }

  // 2. The window and its context, which thalassa draws into as a host's.
  glfwSetErrorCallback([](int code, const char* text) {
    std::fprintf(stderr, "thalassa: view: GLFW error %d: %s\n", code, text);
  });
  if (!glfwInit()) {
    print_error("view: glfwInit failed");
    return kExitRuntimeFailure;
  }
  struct Terminate {
    ~Terminate() { glfwTerminate(); }
  } terminate;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(viewed.scene().image.width, viewed.scene().image.height,
                                        "thalassa", nullptr, nullptr);
  if (!window) {
    print_error("view: no OpenGL 4.5 core window");
    return kExitRuntimeFailure;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(args.frames > 0 ? 0 : 1);  // a counted run (tests) does not wait for vsync
  std::unique_ptr<GlContext> context = attach_host_context(
      reinterpret_cast<GlProcAddressFn>(&glfwGetProcAddress), "GLFW window (thalassa view)");

  // The image is the window's framebuffer (pixels, which HiDPI screens make more than the
  // window's size).
  auto framebuffer_scene = [&](Scene scene) {
    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    if (width > 0 && height > 0) {
      scene.image.width = std::min(width, kMaxImageSide);
      scene.image.height = std::min(height, kMaxImageSide);
    }
    return scene;
  };
  std::unique_ptr<Renderer> renderer;
  try {
    viewed.update(framebuffer_scene(viewed.scene()));
    renderer = std::make_unique<Renderer>(*context, viewed.scene());
  } catch (const SceneError& error) {
    print_error(error.what());
    return kExitInvalidInput;
  }

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450");
  g_imgui_key_callback = glfwSetKeyCallback(window, key_callback);
  struct ShutDown {
    ~ShutDown() {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
  } shut_down;

  // 3. The frames.
  const Planet planet(viewed.scene().planet);
  bool panel = !args.no_panel;
  bool time_running = !args.paused;
  double time_rate = 1.0;
  // The height flown (keys, panel, scene): the camera's, unless the water under it lifts it.
  double flown_height = viewed.scene().camera.height;
  SeaCache sea;
  std::string message;
  FlightRecorder recorder;
  bool record_from_start = !args.record.empty();
  auto last = Clock::now();
  double wall_ms = 0.0;
  bool quit = false;
  for (int frame = 0;
       !glfwWindowShouldClose(window) && !quit && (args.frames == 0 || frame < args.frames);
       ++frame) {
    glfwPollEvents();
    const KeyPresses presses = std::exchange(g_presses, KeyPresses{});
    quit = presses.quit;
    const auto now = Clock::now();
    const double dt = std::min(std::chrono::duration<double>(now - last).count(), kLongestStep);
    wall_ms = 1e3 * std::chrono::duration<double>(now - last).count();
    last = now;
    if (presses.toggle_panel) panel = !panel;
    if (presses.toggle_time) time_running = !time_running;

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    const ImGuiIO& io = ImGui::GetIO();
    Scene next = framebuffer_scene(viewed.scene());
    next.camera.height = flown_height;
    HeldKeys keys = io.WantCaptureKeyboard ? HeldKeys{} : held_keys(window);
    if (!io.WantCaptureMouse) {
      // Dragging turns the view by the angle the cursor moved; the wheel zooms.
      const double pixel = next.camera.fov_y / std::max(next.image.height, 1);  // degrees
      if (io.MouseDown[0]) {
        keys.motion.turn_deg = -kDragGain * pixel * io.MouseDelta.x;
        keys.motion.pitch_deg = kDragGain * pixel * io.MouseDelta.y;
      }
      if (io.MouseWheel != 0.0f)
        next.camera.fov_y =
            std::clamp(next.camera.fov_y * std::exp(-kZoomStep * io.MouseWheel), 0.01, 179.0);
    }
    if (playback.playing &&
        (keys.motion.forward != 0.0 || keys.motion.right != 0.0 || keys.motion.climb != 0.0 ||
         keys.motion.turn_deg != 0.0 || keys.motion.pitch_deg != 0.0)) {
      playback.playing = false;
      char text[80];
      std::snprintf(text, sizeof text, "flight stopped at %.2f s: the camera is yours",
                    playback.time);
      message = text;
    }
    next.camera = move_camera(planet, next.camera, keys.motion, dt);
    if (!viewed.sun_from_utc()) {
      next.sun.zenith = std::clamp(
          next.sun.zenith + keys.sun_zenith * kSunZenithRate * keys.motion.boost * dt, 0.0, 180.0);
      next.sun.azimuth = std::remainder(
          next.sun.azimuth + keys.sun_azimuth * kSunAzimuthRate * keys.motion.boost * dt, 360.0);
    } else if (keys.sun_azimuth != 0.0) {
      next.sun.utc =
          moved_utc(*next.sun.utc, keys.sun_azimuth * kSunTimeRate * keys.motion.boost * dt);
    }
    if (time_running) next.time = std::min(next.time + dt * time_rate, kSceneMaxTime);
    bool screenshot = presses.screenshot;
    bool record = presses.toggle_record;
    // The last frame's statistics: the panel's, and the waves' anchor the renderer holds.
    const RenderStats last_stats = renderer->stats();
    if (panel)
      draw_panel(last_stats, wall_ms, viewed, next, time_running, time_rate, screenshot, record,
                 recorder, playback, message);
    if (playback.playing) {
      // The flight's camera, sun and time at its own time, which the clock moves, and its
      // exposure where it animates one; the sea's and the image's other keys stay the viewer's.
      if (time_running && frame > 0) playback.time += dt * time_rate;
      const double duration = playback.duration();
      if (playback.time > duration) playback.time = duration > 0.0 ? 0.0 : duration;  // loop
      const Scene flown = playback.flight->scene_at(playback.time);
      next.camera = flown.camera;
      next.sun = flown.sun;
      next.time = flown.time;
      if (playback.animates_exposure()) next.image.exposure = flown.image.exposure;
    }
    // A crest under the camera lifts it, and lets it down again as it passes: the camera rides
    // the waves at kWaveClearance. Not a flight played: that is `fly`'s camera, as keyed.
    flown_height = next.camera.height;
    if (!playback.playing && next.camera.height < kSpaceModeHeight)  // no wave reaches higher
      next.camera.height = std::max(
          next.camera.height, sea.under_camera(next, last_stats.wave_anchor) + kWaveClearance);
    try {
      viewed.update(next);
      renderer->set_scene(viewed.scene());
    } catch (const SceneError& error) {
      message = error.what();  // the last scene goes on being drawn
    }
    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    if (width > 0 && height > 0) {  // a minimised window has none
      renderer->render();
      renderer->present(0, width, height);
    }
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glfwSwapBuffers(window);
    // The recording follows the scenes drawn: it starts at this frame and stops after it.
    const bool start_now = std::exchange(record_from_start, false);
    const bool stop = record && recorder.active();
    if (!recorder.active() && (record || start_now))
      recorder.start(
          start_now ? args.record : timestamped_name("thalassa_flight_%Y%m%d_%H%M%S.json"), viewed);
    if (recorder.active()) {
      recorder.add(dt, viewed);
      if (stop || recorder.full()) {
        const std::string why = stop ? "" : "the flight file is full: ";
        message = why + recorder.finish();
        std::fprintf(stderr, "thalassa: %s\n", message.c_str());
      }
    }
    if (screenshot) {
      message =
          write_screenshot(timestamped_name("thalassa_view_%Y%m%d_%H%M%S.exr"), *renderer, viewed);
      std::fprintf(stderr, "thalassa: %s\n", message.c_str());
    }
  }
  int status = kExitOk;
  if (recorder.active()) {
    const std::string result = recorder.finish();
    std::fprintf(stderr, "thalassa: %s\n", result.c_str());
    if (result.rfind("wrote", 0) != 0) status = kExitRuntimeFailure;
  }
  for (const std::string& warning : renderer->stats().warnings) print_error("warning: " + warning);
  if (!args.screenshot.empty()) {
    const std::string result = write_screenshot(args.screenshot, *renderer, viewed);
    if (result.rfind("wrote", 0) != 0) {
      print_error(result);
      return kExitRuntimeFailure;
    }
  }
  return status;
}

}  // namespace thalassa::cli
