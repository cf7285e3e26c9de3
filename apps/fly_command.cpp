// `thalassa fly`: renders a scripted flight (docs/flight.md) frame by frame into a folder, skips
// frames already written, reports progress, and optionally encodes an MP4 with ffmpeg.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"
#include "thalassa/thalassa.hpp"

namespace thalassa::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kFrameDigits = 5;  // frame_00000.exr

std::string frame_name(int frame, const std::string& extension) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%0*d%s", kFrameDigits, frame, extension.c_str());
  return name;
}

// "A:B" (inclusive), "A:" (to the end), ":B" or "A" -> [first, last] within [0, count); an error
// message otherwise.
std::string parse_frames(const std::string& text, int count, int& first, int& last) {
  first = 0;
  last = count - 1;
  if (text.empty()) return "";
  const std::string expected = "--frames " + text +
                               ": expected A:B with 0 <= A <= B <= " + std::to_string(count - 1) +
                               " (the flight has " + std::to_string(count) + " frames, from 0)";
  const auto colon = text.find(':');
  auto integer = [](const std::string& s, int& out) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
      return false;
    out = std::stoi(s);
    return true;
  };
  if (colon == std::string::npos) {
    if (!integer(text, first)) return expected;
    last = first;
  } else {
    const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
    if ((!a.empty() && !integer(a, first)) || (!b.empty() && !integer(b, last))) return expected;
    if (a.empty() && b.empty()) return expected;
  }
  if (first < 0 || first > last || last >= count) return expected;
  return "";
}

// A frame is already written when its EXR holds this frame's scene (so that a changed flight or
// --set renders again) and both its files can be read whole.
bool already_written(const std::string& exr, const std::string& png,
                     const std::string& merged_json) {
  std::error_code ec;
  if (!fs::is_regular_file(exr, ec) || !fs::is_regular_file(png, ec)) return false;
  try {
    Metadata metadata;
    read_image(exr, &metadata);
    const auto scene = std::find_if(metadata.begin(), metadata.end(),
                                    [](const auto& m) { return m.first == "thalassa:scene"; });
    if (scene == metadata.end() || scene->second != merged_json) return false;
    read_image(png);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

std::string height_text(double metres) {
  char text[32];
  if (metres >= 1e4)
    std::snprintf(text, sizeof text, "%.0f km", metres / 1e3);
  else
    std::snprintf(text, sizeof text, "%.1f m", metres);
  return text;
}

Metadata frame_metadata(const Scene& scene, const std::string& merged_json,
                        const RenderStats& stats, const Flight& flight, int frame) {
  return render_metadata(scene, merged_json, stats,
                         {{"thalassa:flight", flight.source() + " frame=" + std::to_string(frame) +
                                                  " t=" + format_number(flight.frame_time(frame)) +
                                                  " fps=" + format_number(flight.fps())}});
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct FrameRecord {
  int frame = 0;
  double time = 0.0;        // s into the flight
  double scene_time = 0.0;  // s: the frame's scene `time` (the waves' clock)
  double height = 0.0;      // m
  // m: how far the camera is under the water at its nadir (camera_depth; 0 above it).
  double camera_depth = 0.0;
  bool skipped = false;
  RenderStats stats;
  // Wall-clock: creating the Renderer (the first frame rendered) or setting the frame's scene.
  double renderer_ms = 0.0;
  double wall_ms = 0.0;      // wall-clock: the whole frame, files included
};

std::string stats_json(const std::vector<FrameRecord>& records, double wall_seconds) {
  nlohmann::ordered_json json;
  const FrameRecord* first = nullptr;
  std::vector<double> frame_ms, renderer_ms, waves;
  std::map<std::string, std::vector<double>> passes;
  std::map<std::string, int> modes;
  std::set<std::string> built;
  int skipped = 0, kept = 0;
  for (const FrameRecord& r : records) {
    if (r.skipped) {
      ++skipped;
      continue;
    }
    if (!first) first = &r;
    frame_ms.push_back(r.stats.frame_ms);
    renderer_ms.push_back(r.renderer_ms);
    waves.push_back(r.stats.resolved_waves);
    for (const auto& [name, ms] : r.stats.passes) passes[name].push_back(ms);
    ++modes[r.stats.mode];
    built.insert(r.stats.built.begin(), r.stats.built.end());
    kept += r.stats.sky_provider_kept ? 1 : 0;
  }
  json["backend"] = first ? first->stats.backend : "";
  json["renderer"] = first ? first->stats.renderer : "";
  json["width"] = first ? first->stats.width : 0;
  json["height"] = first ? first->stats.height : 0;
  std::string mode;
  for (const auto& [name, count] : modes) mode += (mode.empty() ? "" : "+") + name;
  json["mode"] = mode;  // "surface", "space" or "space+surface"
  json["modes"] = modes;
  json["frames_rendered"] = static_cast<int>(frame_ms.size());
  json["frames_skipped"] = skipped;
  json["frame_ms"] = median(frame_ms);
  json["timing"] = first ? first->stats.timing : "";
  json["passes"] = nlohmann::ordered_json::object();
  for (const auto& [name, ms] : passes) json["passes"][name] = median(ms);
  json["resolved_waves"] = median(waves);
  json["renderer_setup_ms"] = median(renderer_ms);
  // Frames whose sky provider (tables, sky map, sun-zenith array) an earlier frame made.
  json["sky_provider_kept_frames"] = kept;
  json["wall_s"] = wall_seconds;
  json["built"] = built;
  json["frames"] = nlohmann::ordered_json::array();
  for (const FrameRecord& r : records) {
    nlohmann::ordered_json f;
    f["frame"] = r.frame;
    f["time"] = r.time;
    f["scene_time"] = r.scene_time;
    f["camera_height"] = r.height;
    f["skipped"] = r.skipped;
    if (r.camera_depth > 0.0) f["camera_depth"] = r.camera_depth;
    if (!r.skipped) {
      f["mode"] = r.stats.mode;
      f["frame_ms"] = r.stats.frame_ms;
      f["renderer_setup_ms"] = r.renderer_ms;
      f["sky_provider_kept"] = r.stats.sky_provider_kept;
      f["kept_nodes"] = r.stats.kept_nodes;
      double compile = 0.0;
      for (const auto& [name, ms] : r.stats.setup_ms)
        if (name == "shaders.compile") compile = ms;
      f["shaders_compile_ms"] = compile;
      f["wall_ms"] = r.wall_ms;
      f["resolved_waves"] = r.stats.resolved_waves;
    }
    json["frames"].push_back(std::move(f));
  }
  return json.dump(2) + "\n";
}

// Encodes frames [first, last] of `dir` into `video` (written under a pending name, then moved).
void encode_video(const std::string& ffmpeg, const std::string& dir, int first, int last,
                  double fps, const std::string& video) {
  PendingOutputs outputs;
  const std::string pending = outputs.add(video);
  const std::string log = (fs::path(pending).parent_path() /
                           ("." + fs::path(video).filename().string() + ".ffmpeg-log"))
                              .string();
  const std::vector<std::string> argv = {
      ffmpeg, "-nostdin", "-y", "-loglevel", "error", "-framerate", format_number(fps),
      "-start_number", std::to_string(first), "-i",
      (fs::path(dir) / ("frame_%0" + std::to_string(kFrameDigits) + "d.png")).string(), "-frames:v",
      std::to_string(last - first + 1),
      // libx264's 4:2:0 needs even sizes: pad an odd width or height by one pixel.
      "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p", pending};
  const int status = run_program(argv, log);
  std::string output;
  {
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    output = text.str();
  }
  std::error_code ec;
  fs::remove(log, ec);
  if (status != 0) {
    while (!output.empty() && (output.back() == '\n' || output.back() == '\r')) output.pop_back();
    std::replace(output.begin(), output.end(), '\n', ' ');
    throw std::runtime_error("--video " + video + ": ffmpeg failed (status " +
                             std::to_string(status) + ")" + (output.empty() ? "" : ": " + output));
  }
  outputs.commit();
}

}  // namespace

void add_fly_command(CLI::App& app, FlyArgs& args) {
  CLI::App* fly = app.add_subcommand(
      "fly",
      "Render a scripted flight (the embedded orbit-to-surface flight if none is given) into a "
      "folder of EXR and PNG frames, and optionally an MP4");
  fly->add_option("flight", args.flight, "Flight file (JSON, see docs/flight.md)");
  fly->add_option("-o,--output", args.dir, "Folder of the frames (created if missing)")->required();
  fly->add_option("--frames", args.frames,
                  "Render frames A to B only, inclusive, from 0 (A:B, A:, :B or A)");
  fly->add_option("--video", args.video, "Also encode the frames rendered into an MP4 (ffmpeg)");
  fly->add_option("--set", args.sets, "Override a key of the base scene: --set image.width=480")
      ->allow_extra_args(false);
  fly->add_option("--stats", args.stats, "Write per-frame statistics as JSON");
  fly->add_option("--backend", args.backend, "egl or osmesa (default: egl, else osmesa)")
      ->check(CLI::IsMember({"egl", "osmesa"}));
  fly->add_flag("--float", args.float_exr, "Write 32-bit float EXRs (default: half)");
  fly->add_option("--fps", args.fps,
                  "Frames per second instead of the flight's, its length in seconds kept");
}

int run_fly(const FlyArgs& args) {
  // 1. Everything the user typed is checked before any file is written or any GL work.
  std::optional<Flight> loaded;
  int first = 0, last = 0;
  try {
    loaded = args.flight.empty() ? Flight::default_flight() : Flight::load_file(args.flight);
    for (const std::string& assignment : args.sets) loaded->set(assignment);
    if (args.float_exr) loaded->set("image.exr_type=float");
    if (args.fps) loaded->set_fps(*args.fps);
    check_drawable(loaded->frame_scene(0), loaded->scene_source_of("sky.exr"));
  } catch (const SceneError& error) {
    print_error(error.what());
    return kExitInvalidInput;
  }
  const Flight& flight = *loaded;
  std::error_code ec;
  const std::vector<std::string> problems = {
      parse_frames(args.frames, flight.frame_count(), first, last),
      fs::exists(args.dir, ec) && !fs::is_directory(args.dir, ec)
          ? "-o " + args.dir + ": expected a folder, got a file"
          : "",
      args.video.empty() ? "" : check_output("--video", args.video, ".mp4"),
      args.stats.empty() ? "" : check_output("--stats", args.stats, ""),
      args.stats.empty() || args.video.empty()
          ? ""
          : check_distinct("--stats", args.stats, {args.video})};
  for (const std::string& problem : problems) {
    if (!problem.empty()) {
      print_error(problem);
      return kExitInvalidInput;
    }
  }
  std::string ffmpeg;
  if (!args.video.empty()) {
    ffmpeg = find_program("ffmpeg");
    if (ffmpeg.empty()) {
      print_error("--video " + args.video +
                  ": ffmpeg is not installed (not found on PATH; on Debian: apt-get install "
                  "ffmpeg); nothing rendered");
      return kExitRuntimeFailure;
    }
  }
  fs::create_directories(args.dir, ec);
  if (ec) {
    print_error("-o " + args.dir + ": cannot create the folder: " + ec.message());
    return kExitRuntimeFailure;
  }

  // 2. The frames: one Renderer, given each frame's scene (Renderer::set_scene), which keeps
  // what the frames share: the compiled programs, the sky provider (its tables uploaded once,
  // its sun-zenith array built once, its sky map again only when the sun moves), the sea's
  // nodes while the sea's settings stay. So a frame costs its drawing rather than its set-up.
  const Scene first_scene = flight.frame_scene(first);
  ContextOptions options;
  options.width = first_scene.image.width;
  options.height = first_scene.image.height;
  std::unique_ptr<GlContext> context = open_context(args.backend, options);
  std::unique_ptr<Renderer> renderer;
  // One wave chart for the whole flight (planet/nadir_frame.hpp), wherever a slice starts: the
  // lattice point under its last frame, where a flight to the surface is lowest and the waves show.
  RendererOptions renderer_options;
  {
    const Scene last_scene = flight.frame_scene(flight.frame_count() - 1);
    renderer_options.wave_anchor =
        nearest_wave_anchor(last_scene.camera.lat, last_scene.camera.lon);
  }
  SeaCache sea;  // the water under each frame's camera
  ProgressBar progress(last - first + 1, "frames");
  std::vector<FrameRecord> records;
  const auto start = Clock::now();
  for (int frame = first; frame <= last; ++frame) {
    const auto frame_start = Clock::now();
    std::string merged;
    const Scene scene = flight.frame_scene(frame, &merged);
    const std::string exr = (fs::path(args.dir) / frame_name(frame, ".exr")).string();
    const std::string png = (fs::path(args.dir) / frame_name(frame, ".png")).string();
    FrameRecord record;
    record.frame = frame;
    record.time = flight.frame_time(frame);
    record.scene_time = scene.time;
    record.height = scene.camera.height;
    if (already_written(exr, png, merged)) {
      record.skipped = true;
      records.push_back(record);
      progress.skipped(frame_name(frame, ""), "already written");
      continue;
    }
    const auto renderer_start = Clock::now();
    try {
      if (renderer)
        renderer->set_scene(scene);
      else
        renderer = std::make_unique<Renderer>(*context, scene, renderer_options);
    } catch (const SceneError& error) {  // e.g. a sky.exr that is not a usable sky
      progress.finish();
      print_error(error.what());
      return kExitInvalidInput;
    }
    record.renderer_ms = 1e3 * seconds_since(renderer_start);
    renderer->render();
    const Image image = renderer->image();
    record.stats = renderer->stats();
    record.camera_depth = camera_depth(sea, scene, record.stats.wave_anchor);
    if (const std::string problem = nonfinite_pixels(image); !problem.empty()) {
      progress.finish();
      print_error("frame " + std::to_string(frame) + ": " + problem +
                  "; not written (the frames before it are)");
      return kExitRuntimeFailure;
    }
    PendingOutputs outputs;
    write_exr(outputs.add(exr), image, scene.image.exr_type,
              frame_metadata(scene, merged, record.stats, flight, frame));
    write_png(outputs.add(png), image, scene.image.exposure, {{"Software", "thalassa"}});
    outputs.commit();
    record.wall_ms = 1e3 * seconds_since(frame_start);
    records.push_back(record);
    char detail[160];
    std::snprintf(detail, sizeof detail, "t=%.3f s, %s, %s: %.2f s", record.time,
                  height_text(scene.camera.height).c_str(), record.stats.mode.c_str(),
                  record.wall_ms / 1e3);
    progress.done(frame_name(frame, ""), detail, record.wall_ms / 1e3);
  }
  progress.finish();
  renderer.reset();
  const double wall = seconds_since(start);
  {
    int under = 0, first_under = -1, last_under = -1;
    double deepest = 0.0;
    for (const FrameRecord& r : records) {
      if (r.camera_depth <= 0.0) continue;
      ++under;
      if (first_under < 0) first_under = r.frame;
      last_under = r.frame;
      deepest = std::max(deepest, r.camera_depth);
    }
    if (under > 0) {
      char text[240];
      std::snprintf(text, sizeof text,
                    "warning: %d frames (%d to %d) have the camera under the water, up to %.3g m: "
                    "they show the wave from inside (`--stats` gives each frame's camera_depth, "
                    "`thalassa sea` the sea's height)",
                    under, first_under, last_under, deepest);
      print_error(text);
    }
  }
  std::fprintf(stderr, "thalassa: frames %d to %d: %d rendered, %d already written, in %s\n", first,
               last, progress.worked_count(), progress.skipped_count(),
               duration_text(wall).c_str());

  // 3. The video and the statistics.
  if (!args.video.empty()) encode_video(ffmpeg, args.dir, first, last, flight.fps(), args.video);
  if (!args.stats.empty()) write_text_atomically(args.stats, stats_json(records, wall));
  return kExitOk;
}

}  // namespace thalassa::cli
