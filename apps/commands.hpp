// The subcommands of the `thalassa` program. Each returns the process exit status:
// 0 done, 2 invalid input, 1 failure at run time (DESIGN section 5).
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace thalassa::cli {

constexpr int kExitOk = 0;
constexpr int kExitRuntimeFailure = 1;
constexpr int kExitInvalidInput = 2;

struct RenderArgs {
  std::string scene;  // empty: the embedded default scene
  std::string exr = "thalassa.exr";
  std::optional<std::string> png;  // default: the EXR's path with .png
  bool no_png = false;
  std::vector<std::string> sets;
  std::string stats;
  std::string backend;  // empty: the default headless backend
  int repeat = 1;
  bool float_exr = false;
  std::string terms = "sun,sky,sea,air";    // the ocean's light terms, any subset
  std::string method = "full";              // the ocean's shading method (ocean/method.hpp)
  int samples = 1024;                       // the reference's most samples per pixel
  bool fixed_samples = false;  // the reference: exactly `samples`, no stop at convergence
  int sun_cells = 256;         // the reference's sun: most cells per pixel, squared (scattered)
  double sun_cells_per_wavelength = 16;     // the reference's sun: cells per shortest wavelength
  int sun_refine = 4;                       // the reference's sun: subcells per side near glints
  double reference_grid_cell = 1.0;         // the reference's grid cell, pixels, [1/8, 1]
  double sun_max_cells_per_wavelength = 0;  // the reference's sun: doubled up to this (0: never)
  bool sun_swap_atomics = false;  // the reference's sun: compare-and-swap, not float atomics
  int sun_segment = 0;  // the reference's sun: cells per scatter invocation (0: the renderer's)
  int sun_block_rows = 0;  // and rows of cells per scatter invocation (0: the renderer's)
  std::int64_t sun_refined_queue = -1;      // and its refined cells' queue (-1: default; 0: none)
  std::string reference_sun = "scattered";  // the reference's sun: scattered or gathered
  std::string sun_sums;  // the reference's scattered sun's per-pixel sums (.exr); empty: none
};

struct SkyArgs {
  std::string scene;  // empty: the embedded default scene
  std::string exr;
  std::optional<std::string> png;  // default: the EXR's path with .png
  bool no_png = false;
  std::string panorama;       // empty: no panorama
  int panorama_width = 2048;  // texels (height: width / 2)
  bool panorama_width_given = false;
  int size = 512;  // texels per side of the sky map
  std::vector<std::string> sets;
  std::string stats;
  std::string backend;  // empty: the default headless backend
};

struct FlyArgs {
  std::string flight;  // empty: the embedded default flight
  std::string dir;     // folder of the frames
  std::string frames;  // "A:B" (inclusive); empty: all
  std::string video;   // empty: no MP4
  std::vector<std::string> sets;
  std::string stats;
  std::string backend;  // empty: the default headless backend
  bool float_exr = false;
  std::optional<double> fps;  // frames per second instead of the flight's; its length kept
};

struct ValidateArgs {
  std::string suite;    // empty: the default suite (data/suites/validation.json)
  std::string dir;      // the report's folder
  std::string backend;  // empty: the default headless backend
  // --case: the names (or shell patterns, "wind10_*") of the cases to run; empty: every case.
  std::vector<std::string> cases;
  // --method, --term: the suite's methods (or variants) and terms to run; empty: all of them
  // (validation::narrow_suite; the reference is always rendered).
  std::vector<std::string> methods;
  std::vector<std::string> terms;
  // --reference-samples: overrides the suite's reference.pixel_samples; 0: the suite's.
  int reference_samples = 0;
  // --reference-sun-max-cells-per-wavelength: overrides the suite's
  // reference.sun_max_cells_per_wavelength; 0: the suite's.
  double reference_sun_max_cells = 0.0;
  // --reference-sun-cells: overrides the suite's reference.sun_normal_samples with its square;
  // 0: the suite's.
  int reference_sun_cells = 0;
  // --resume: keep the cases of the report already in `dir` that were run with the same inputs.
  bool resume = false;
  // --no-exr: the report's images as PNG only (no EXR written, none named), for a report that
  // must travel small (scripts/device/run).
  bool no_exr = false;
  // --seas: each selected case drawn over this many seas (validation::expand_seas); 1: once.
  int seas = 1;
  // --time-limit: seconds from the start after which no case is begun that the longest case
  // of this run says would end past them; 0: none.
  double time_limit = 0.0;
};

struct ViewArgs {
  std::string scene;  // empty: the embedded default scene
  std::vector<std::string> sets;
  int frames = 0;          // close after this many frames; 0: when the window is closed
  bool paused = false;     // the scene's clock stopped at the start
  bool no_panel = false;   // the panel hidden at the start
  std::string screenshot;  // the last frame's EXR (PNG and scene JSON beside it); empty: none
  std::string record;      // a flight file recorded from the first frame; empty: none
  std::string flight;      // a flight file played in the window; empty: none
};

struct SeaArgs {
  std::string scene;            // empty: the embedded default scene
  std::vector<std::string> at;  // "LAT,LON" each; empty: the camera's nadir
  std::optional<double> time;   // s; none: the scene's time (or --times)
  std::string times;            // "START:STOP:STEP", s; empty: one time
  std::string footprint = "0";  // metres (0: every wave), or "drawn" (drawn_footprint)
  std::string anchor;           // "LAT,LON" of the waves' chart; empty: the render's
  std::vector<std::string> sets;
  std::string output;  // empty: standard output
};

struct InfoArgs {
  std::string backend;
};

void add_render_command(CLI::App& app, RenderArgs& args);
void add_sky_command(CLI::App& app, SkyArgs& args);
void add_fly_command(CLI::App& app, FlyArgs& args);
void add_info_command(CLI::App& app, InfoArgs& args);
void add_sea_command(CLI::App& app, SeaArgs& args);
void add_validate_command(CLI::App& app, ValidateArgs& args);
int run_render(const RenderArgs& args);
int run_sky(const SkyArgs& args);
int run_fly(const FlyArgs& args);
int run_info(const InfoArgs& args);
int run_sea(const SeaArgs& args);
int run_validate(const ValidateArgs& args);
// The interactive viewer (apps/view_command.cpp): built with GLFW and Dear ImGui only
// (THALASSA_HAVE_VIEW).
void add_view_command(CLI::App& app, ViewArgs& args);
int run_view(const ViewArgs& args);

// Prints "thalassa: <message>" on stderr.
void print_error(const std::string& message);

}  // namespace thalassa::cli
