#include "common.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "commands.hpp"

namespace thalassa::cli {
namespace {

namespace fs = std::filesystem;

bool has_extension(const std::string& path, const std::string& extension) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == extension;
}

// A name beside `path` for an output that is complete but not yet in place.
std::string pending_path(const std::string& path) {
  const fs::path target(path);
  return (target.parent_path() / ("." + target.stem().string() + ".pending-" +
                                  std::to_string(getpid()) + target.extension().string()))
      .string();
}

}  // namespace

void print_error(const std::string& message) {
  std::fprintf(stderr, "thalassa: %s\n", message.c_str());
}

LoadedScene load_scene(const std::string& path, const std::vector<std::string>& sets,
                       const std::vector<std::string>& extra, bool drawn) {
  SceneBuilder builder;
  if (!path.empty()) builder.load_file(path);
  for (const auto& assignment : sets) builder.set(assignment);
  for (const auto& assignment : extra) builder.set(assignment);
  LoadedScene loaded;
  loaded.scene = builder.build();
  loaded.merged_json = builder.merged_json();
  if (drawn) check_drawable(loaded.scene, builder.source_of("sky.exr"));  // before any GL work
  return loaded;
}

std::string check_output(const std::string& option, const std::string& path,
                         const std::string& extension) {
  if (!extension.empty() && !has_extension(path, extension))
    return option + " " + path + ": expected a file name ending in " + extension;
  const fs::path folder = fs::path(path).parent_path();
  std::error_code ec;
  if (!folder.empty() && !fs::is_directory(folder, ec))
    return option + " " + path + ": folder " + folder.string() + " does not exist";
  if (fs::is_directory(path, ec)) return option + " " + path + ": is a folder, expected a file";
  return "";
}

std::string png_path(const std::string& exr, const std::optional<std::string>& png, bool no_png) {
  if (no_png) return "";
  return png ? *png : fs::path(exr).replace_extension(".png").string();
}

std::string check_distinct(const std::string& option, const std::string& path,
                           const std::vector<std::string>& others) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  for (const std::string& other : others)
    if (!other.empty() && canonical == fs::weakly_canonical(other, ec))
      return option + " " + path + ": the same file as another output";
  return "";
}

std::unique_ptr<GlContext> open_context(const std::string& backend, const ContextOptions& options) {
  return backend.empty() ? create_headless_context(options)
                         : create_context(*parse_backend(backend), options);
}

PendingOutputs::~PendingOutputs() {
  std::error_code ec;
  for (const auto& [pending, final_path] : outputs_) fs::remove(pending, ec);
}

std::string PendingOutputs::add(const std::string& final_path) {
  outputs_.emplace_back(pending_path(final_path), final_path);
  return outputs_.back().first;
}

void PendingOutputs::commit() {
  for (const auto& [pending, final_path] : outputs_) {
    std::error_code ec;
    fs::rename(pending, final_path, ec);
    if (ec) throw FileError(final_path + ": cannot move into place: " + ec.message());
  }
  outputs_.clear();
}

std::string format_number(double value) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.9g", value);
  return text;
}

Metadata render_metadata(const Scene& scene, const std::string& merged_json,
                         const RenderStats& stats, const Metadata& extra) {
  const auto& c = scene.camera;
  Metadata metadata = {
      {"thalassa:version", THALASSA_VERSION_STRING},
      {"thalassa:scene", merged_json},
      {"thalassa:camera",
       "lat=" + format_number(c.lat) + " lon=" + format_number(c.lon) +
           " height=" + format_number(c.height) + " heading=" + format_number(c.heading) +
           " pitch=" + format_number(c.pitch) + " roll=" + format_number(c.roll) +
           " fov_y=" + format_number(c.fov_y)},
      // The sun as drawn (computed from sun.utc when the scene gives a time).
      {"thalassa:sun", "zenith=" + format_number(scene.sun.zenith) +
                           " azimuth=" + format_number(scene.sun.azimuth) +
                           (scene.sun.utc ? " utc=" + *scene.sun.utc : "")},
      {"thalassa:units", "spectral radiance, W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm"},
      {"thalassa:backend", stats.backend},
      {"thalassa:renderer", stats.renderer},
      {"thalassa:mode", stats.mode},
  };
  metadata.insert(metadata.end(), extra.begin(), extra.end());
  metadata.emplace_back("thalassa:frame_ms", format_number(stats.frame_ms));
  std::string passes;
  for (const auto& [name, ms] : stats.passes)
    passes += (passes.empty() ? "" : " ") + name + "=" + format_number(ms);
  metadata.emplace_back("thalassa:passes_ms", passes);
  return metadata;
}

double SeaCache::under_camera(const Scene& scene, const Geodetic& anchor) {
  // An anchor the camera has left behind (a viewer's frame before the renderer takes the new
  // scene) is replaced as the renderer replaces it: past kWaveAnchorKeepDistance, the lattice
  // point nearest the camera.
  const Geodetic chart =
      kept_wave_anchor(Planet(scene.planet), anchor, scene.camera.lat, scene.camera.lon);
  if (!sea_ || !(sea_->scene().ocean == scene.ocean) || sea_->wave_anchor().lat != chart.lat ||
      sea_->wave_anchor().lon != chart.lon)
    sea_.emplace(scene, chart);
  return sea_->at(scene.camera.lat, scene.camera.lon, scene.time).height;
}

double camera_depth(SeaCache& sea, const Scene& scene, const Geodetic& anchor) {
  if (scene.camera.height >= kSpaceModeHeight) return 0.0;
  return std::max(sea.under_camera(scene, anchor) - scene.camera.height, 0.0);
}

std::string parse_terms(const std::string& text, LightTerms& terms) {
  const std::string problem = parse_light_terms(text, terms);
  return problem.empty() ? "" : "--terms" + (text.empty() ? "" : " " + text) + ": " + problem;
}

}  // namespace thalassa::cli
