// What the subcommands of the `thalassa` program share: reading the scene with its overrides,
// checking output paths before any work, opening the GL context and writing the outputs of a
// run together (DESIGN section 5).
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "thalassa/thalassa.hpp"

namespace thalassa::cli {

// Seconds of the steady clock since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A scene as the user gave it: the file (empty: the embedded default scene), then each --set
// in order, then `extra` assignments the command implies (e.g. image.exr_type=float).
struct LoadedScene {
  Scene scene;
  std::string merged_json;  // the merged scene as JSON, for the outputs' metadata
};
// Throws SceneError (exit status 2) for a bad file, override or, when `drawn`, an undrawable
// scene (check_drawable: its sky.exr missing). A command that draws nothing (`sea`) passes false.
LoadedScene load_scene(const std::string& path, const std::vector<std::string>& sets,
                       const std::vector<std::string>& extra = {}, bool drawn = true);

// Checks an output path before any work, so that a typo costs no render: the extension (none
// checked when `extension` is empty), an existing folder, not a folder itself. Returns an error
// message naming `option`, or "".
std::string check_output(const std::string& option, const std::string& path,
                         const std::string& extension);
// The PNG written beside an EXR: none with --no-png, the --png path if given, else the EXR's
// path with .png.
std::string png_path(const std::string& exr, const std::optional<std::string>& png, bool no_png);
// "" when `path` (given with `option`) is a different file from each of `others`; an error
// message otherwise.
std::string check_distinct(const std::string& option, const std::string& path,
                           const std::vector<std::string>& others);

// The context of --backend ("" for the default headless one, EGL else OSMesa).
std::unique_ptr<GlContext> open_context(const std::string& backend,
                                        const ContextOptions& options = {});

// The outputs of one run appear together or not at all: each is written whole to a pending
// name beside its final one, and only when all are written are they renamed into place. The
// pending files of a run that fails before commit() are removed.
class PendingOutputs {
 public:
  PendingOutputs() = default;
  ~PendingOutputs();
  PendingOutputs(const PendingOutputs&) = delete;
  PendingOutputs& operator=(const PendingOutputs&) = delete;
  // The name to write `final_path`'s content to.
  std::string add(const std::string& final_path);
  void commit();

 private:
  std::vector<std::pair<std::string, std::string>> outputs_;  // (pending, final)
};

// The sea of the scenes a command draws, answered on the CPU (planet/sea_state.hpp) in the
// renderer's waves' anchor (or, for a camera more than kWaveAnchorKeepDistance from it, the one
// the renderer will take: the lattice point nearest it); made again when the waves or the anchor
// change (a flight and the viewer change nothing else of the sea: not its wakes, calm areas or
// planet).
class SeaCache {
 public:
  // The water's height (m above the sea at rest) under the camera of `scene` at its time, every
  // wave.
  double under_camera(const Scene& scene, const Geodetic& anchor);

 private:
  std::optional<SeaState> sea_;
};

// How far (m, > 0) the camera of `scene` is under the water at its nadir, where the image shows
// the wave from inside (its back fills the sky); 0 above it, and from the space mode's heights
// up, where no wave reaches.
double camera_depth(SeaCache& sea, const Scene& scene, const Geodetic& anchor);

// --terms TEXT -> the terms (parse_light_terms); an error message naming the option otherwise.
std::string parse_terms(const std::string& text, LightTerms& terms);

// A number as the metadata print it: %.9g.
std::string format_number(double value);

// The EXR metadata of a rendered frame: the version, the merged scene, the camera and the sun,
// the radiance units, the backend, renderer, mode and timings, with the command's own entries
// (`extra`, e.g. the light terms or the flight frame) before the timings.
Metadata render_metadata(const Scene& scene, const std::string& merged_json,
                         const RenderStats& stats, const Metadata& extra = {});

}  // namespace thalassa::cli
