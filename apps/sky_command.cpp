#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "thalassa/thalassa.hpp"

namespace thalassa::cli {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The sun's zenith angle and azimuth (degrees, clockwise from north in [0, 360)) of a unit ENU
// direction.
std::pair<double, double> zenith_azimuth(const std::array<double, 3>& d) {
  const double zenith = std::acos(std::clamp(d[2], -1.0, 1.0)) / kDegree;
  double azimuth = std::atan2(d[0], d[1]) / kDegree;
  if (azimuth < 0.0) azimuth += 360.0;
  return {zenith, azimuth};
}

std::string sun_text(const Scene& scene, const SkyExport& sky) {
  if (!sky.sun_from_provider)
    return "zenith=" + format_number(scene.sun.zenith) +
           " azimuth=" + format_number(scene.sun.azimuth) +
           (scene.sun.utc ? " utc=" + *scene.sun.utc : "") + " source=scene";
  const auto [zenith, azimuth] = zenith_azimuth(sky.sun_direction);
  return "zenith=" + format_number(zenith) + " azimuth=" + format_number(azimuth) +
         " source=sky.exr";
}

std::string stats_json(const SkyExportStats& stats) {
  nlohmann::ordered_json json;
  json["backend"] = stats.backend;
  json["renderer"] = stats.renderer;
  json["sky_provider"] = stats.sky_provider;
  json["map_size"] = stats.map_size;
  json["panorama_width"] = stats.panorama_width;
  json["panorama_height"] = stats.panorama_height;
  json["setup_ms"] = nlohmann::ordered_json::object();
  for (const auto& [name, ms] : stats.setup_ms) json["setup_ms"][name] = ms;
  json["built"] = stats.built;
  return json.dump(2) + "\n";
}

}  // namespace

void add_sky_command(CLI::App& app, SkyArgs& args) {
  CLI::App* sky = app.add_subcommand(
      "sky",
      "Write the sky provider's stereographic sky map (the sky the ocean reflects) for a scene's "
      "sun and camera, and optionally an equirectangular panorama");
  sky->add_option("scene", args.scene, "Scene file (JSON, see docs/scene.md)");
  sky->add_option("-o,--output", args.exr, "The sky map, linear float EXR (.exr)")->required();
  sky->add_option("--png", args.png, "Tone-mapped map (.png); default: the EXR's name");
  sky->add_flag("--no-png", args.no_png, "Write no PNG (of the map or the panorama)");
  sky->add_option("--panorama", args.panorama,
                  "Also write an equirectangular panorama of the sky around the camera (.exr; "
                  "a PNG beside it unless --no-png)");
  sky->add_option("--panorama-width", args.panorama_width,
                  "Panorama width in texels, even (height: width / 2)")
      ->capture_default_str()
      ->each([&args](const std::string&) { args.panorama_width_given = true; });
  sky->add_option("--size", args.size, "Texels per side of the sky map")->capture_default_str();
  sky->add_option("--set", args.sets, "Override a scene key: --set sun.zenith=80")
      ->allow_extra_args(false);
  sky->add_option("--stats", args.stats, "Write statistics as JSON");
  sky->add_option("--backend", args.backend, "egl or osmesa (default: egl, else osmesa)")
      ->check(CLI::IsMember({"egl", "osmesa"}));
}

int run_sky(const SkyArgs& args) {
  // 1. Everything the user typed is checked before any GL work.
  LoadedScene loaded;
  try {
    loaded = load_scene(args.scene, args.sets);
  } catch (const SceneError& error) {
    print_error(error.what());
    return kExitInvalidInput;
  }
  const Scene& scene = loaded.scene;
  const std::string png = png_path(args.exr, args.png, args.no_png);
  const std::string panorama_png =
      args.panorama.empty() ? "" : png_path(args.panorama, std::nullopt, args.no_png);
  const std::string max = std::to_string(kSkyExportMaxSize);
  std::vector<std::string> problems = {
      args.size >= 1 && args.size <= kSkyExportMaxSize
          ? ""
          : "--size " + std::to_string(args.size) + ": expected an integer in [1, " + max + "]",
      args.panorama_width >= 2 && args.panorama_width <= kSkyExportMaxSize &&
              args.panorama_width % 2 == 0
          ? ""
          : "--panorama-width " + std::to_string(args.panorama_width) +
                ": expected an even integer in [2, " + max + "] (the height is width / 2)",
      args.panorama_width_given && args.panorama.empty()
          ? "--panorama-width: given without --panorama"
          : "",
      check_output("-o", args.exr, ".exr"),
      png.empty() ? "" : check_output("--png", png, ".png"),
      args.panorama.empty() ? "" : check_output("--panorama", args.panorama, ".exr"),
      args.stats.empty() ? "" : check_output("--stats", args.stats, "")};
  // Every output is a different file (the map's and the panorama's PNGs are derived names).
  const std::vector<std::pair<std::string, std::string>> outputs = {
      {"-o", args.exr},
      {"--png", png},
      {"--panorama", args.panorama},
      {"--panorama (its PNG)", panorama_png},
      {"--stats", args.stats}};
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    std::vector<std::string> earlier;
    for (std::size_t j = 0; j < i; ++j) earlier.push_back(outputs[j].second);
    if (!outputs[i].second.empty())
      problems.push_back(check_distinct(outputs[i].first, outputs[i].second, earlier));
  }
  for (const std::string& problem : problems) {
    if (!problem.empty()) {
      print_error(problem);
      return kExitInvalidInput;
    }
  }

  // 2. A context and the sky.
  std::unique_ptr<GlContext> context = open_context(args.backend);
  SkyExportOptions options;
  options.map_size = args.size;
  options.panorama_width = args.panorama.empty() ? 0 : args.panorama_width;
  const SkyExport sky = render_sky(*context, scene, options);

  // 3. Outputs, written together or not at all. Always float: a sky map is data for other
  // tools, and the sun's disc in the panorama (about 2e4 above the atmosphere) nears half's
  // largest value (65504).
  const auto& c = scene.camera;
  const Metadata common = {
      {"thalassa:version", THALASSA_VERSION_STRING},
      {"thalassa:scene", loaded.merged_json},
      {"thalassa:sun", sun_text(scene, sky)},
      {"thalassa:units", "spectral radiance, W m^-2 sr^-1 nm^-1, RGB at 680, 550, 440 nm"},
      {"thalassa:sky_provider", sky.stats.sky_provider},
      {"thalassa:backend", sky.stats.backend},
      {"thalassa:renderer", sky.stats.renderer},
  };
  Metadata map_metadata = common;
  const std::string e = format_number(sky.map_extent);
  const std::string e2 = format_number(2.0 * sky.map_extent);
  map_metadata.emplace_back(
      "thalassa:sky_map",
      "stereographic u=(r_x,r_y)/(1+r_z), r the ENU direction the light comes from; u in [-" + e +
          ", " + e + "]^2, the centre of texel (i, j) (column i, row j) of N x N at u=(-" + e +
          "+" + e2 + "*(i+0.5)/N, " + e + "-" + e2 +
          "*(j+0.5)/N); row 0 north, column 0 west; |u|>1 below the horizon (one constant); "
          "no sun disc");
  map_metadata.emplace_back("thalassa:viewpoint", "lat=" + format_number(c.lat) +
                                                      " lon=" + format_number(c.lon) +
                                                      " height=0 (the sea at the camera's nadir)");
  PendingOutputs files;
  write_exr(files.add(args.exr), sky.map, ExrPixelType::Float, map_metadata);
  if (!png.empty())
    write_png(files.add(png), sky.map, scene.image.exposure, {{"Software", "thalassa"}});
  if (!args.panorama.empty()) {
    Metadata panorama_metadata = common;
    panorama_metadata.emplace_back(
        "thalassa:panorama",
        "equirectangular W x W/2: texel (x, y) looks at azimuth 360*(x+0.5)/W degrees clockwise "
        "from north and zenith angle 180*(y+0.5)/(W/2) degrees; left edge north, top edge the "
        "zenith; sun disc drawn");
    panorama_metadata.emplace_back("thalassa:viewpoint",
                                   "lat=" + format_number(c.lat) + " lon=" + format_number(c.lon) +
                                       " height=" + format_number(sky.panorama_height));
    write_exr(files.add(args.panorama), sky.panorama, ExrPixelType::Float, panorama_metadata);
    if (!panorama_png.empty())
      write_png(files.add(panorama_png), sky.panorama, scene.image.exposure,
                {{"Software", "thalassa"}});
  }
  if (!args.stats.empty()) write_text_atomically(files.add(args.stats), stats_json(sky.stats));
  files.commit();
  return kExitOk;
}

}  // namespace thalassa::cli
