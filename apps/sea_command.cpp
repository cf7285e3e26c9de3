// `thalassa sea`: the sea's surface at points and times as CSV (planet/sea_state.hpp), for a
// buoy's record, a hull's motion or a comparison with wave measurements. No GL.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "thalassa/thalassa.hpp"

namespace thalassa::cli {
namespace {

// Rows a run may write (--at points times --times steps): 1e7 rows are about 2 GB of CSV.
constexpr double kMaxRows = 1e7;

// The whole of `text` as one finite decimal number (no spaces, no hexadecimal); false otherwise.
bool parse_number(const std::string& text, double& value) {
  if (text.empty() || text.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    return used == text.size() && std::isfinite(value);
  } catch (const std::exception&) {
    return false;
  }
}

// `text` cut at each `separator` into `count` finite numbers; false otherwise.
bool parse_numbers(const std::string& text, char separator, std::size_t count,
                   std::vector<double>& values) {
  values.clear();
  std::size_t from = 0;
  for (;;) {
    const std::size_t to = text.find(separator, from);
    double value = 0;
    if (!parse_number(text.substr(from, to == std::string::npos ? to : to - from), value))
      return false;
    values.push_back(value);
    if (to == std::string::npos) break;
    from = to + 1;
  }
  return values.size() == count;
}

// "LAT,LON" (degrees) -> a place; nullopt for anything else or out of range.
std::optional<Geodetic> parse_place(const std::string& text) {
  std::vector<double> v;
  if (!parse_numbers(text, ',', 2, v) || !(v[0] >= -90.0 && v[0] <= 90.0) ||
      !(v[1] >= -180.0 && v[1] <= 180.0))
    return std::nullopt;
  return Geodetic{v[0], v[1], 0.0};
}

// "START:STOP:STEP" -> the times START, START + STEP, ... through STOP (STOP included when a
// step lands within a millionth of a step of it); "" or an error naming the option.
std::string parse_times(const std::string& text, std::vector<double>& times) {
  std::vector<double> v;
  if (!parse_numbers(text, ':', 3, v) || !(v[0] >= 0.0 && v[0] <= v[1] && v[1] <= kSceneMaxTime) ||
      !(v[2] > 0.0))
    return "--times " + text +
           ": expected START:STOP:STEP, seconds, 0 <= START <= STOP <= 1e12, STEP > 0";
  const double count = std::floor((v[1] - v[0]) / v[2] + 1e-6) + 1.0;
  if (!(count <= kMaxRows))
    return "--times " + text + ": expected at most 1e7 times, got " + format_number(count);
  for (long long i = 0; i < static_cast<long long>(count); ++i)
    times.push_back(std::min(v[0] + v[2] * i, v[1]));  // a last step within 1e-6 of one: STOP
  return "";
}

// `value` to `digits` significant digits.
std::string csv_number(double value, int digits) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace

void add_sea_command(CLI::App& app, SeaArgs& args) {
  CLI::App* sea = app.add_subcommand(
      "sea",
      "Write the sea's surface (height, normal, water velocity, rate of rise) at points and "
      "times as CSV, computed on the CPU as the renderer draws it (docs/sea_state.md)");
  sea->add_option("scene", args.scene, "Scene file (JSON, see docs/scene.md)");
  sea->add_option("--at", args.at, "LAT,LON in degrees; repeatable (default: the camera's nadir)")
      ->allow_extra_args(false);
  sea->add_option("--time", args.time, "Seconds on the scene's clock (default: the scene's time)");
  sea->add_option("--times", args.times, "START:STOP:STEP, seconds: a time series");
  sea->add_option("--footprint", args.footprint,
                  "Metres: weigh each wave by w(N_min, N_max, wavelength / footprint) as the "
                  "grid does, e.g. a hull's length (default 0: every wave); or `drawn`: at each "
                  "point the grid's cell there, so that the heights are the surface `render` "
                  "draws of the scene (refused where its grid draws no waves)")
      ->capture_default_str();
  sea->add_option("--anchor", args.anchor,
                  "LAT,LON of the waves' chart (default: the lattice point nearest the camera, "
                  "as `render` takes it; `fly` takes the one under its last frame)");
  sea->add_option("--set", args.sets, "Override a scene key: --set ocean.wind_speed=15")
      ->allow_extra_args(false);
  sea->add_option("-o,--output", args.output, "The CSV file (default: standard output)");
}

int run_sea(const SeaArgs& args) {
  LoadedScene loaded;
  try {
    loaded = load_scene(args.scene, args.sets, {}, /*drawn=*/false);  // no sky is drawn
  } catch (const SceneError& error) {
    print_error(error.what());
    return kExitInvalidInput;
  }
  const Scene& scene = loaded.scene;
  const auto refuse = [](const std::string& message) {
    print_error(message);
    return kExitInvalidInput;
  };
  std::vector<std::pair<double, double>> points;
  for (const std::string& text : args.at) {
    const std::optional<Geodetic> place = parse_place(text);
    if (!place)
      return refuse("--at " + text +
                    ": expected LAT,LON in degrees, LAT in [-90, 90], LON in "
                    "[-180, 180]");
    points.emplace_back(place->lat, place->lon);
  }
  if (points.empty()) points.emplace_back(scene.camera.lat, scene.camera.lon);
  std::vector<double> times;
  if (args.time && !args.times.empty()) return refuse("--time and --times: give one of them");
  if (args.time) {
    if (!(*args.time >= 0.0 && *args.time <= kSceneMaxTime))
      return refuse("--time " + format_number(*args.time) + ": expected seconds in [0, 1e12]");
    times.push_back(*args.time);
  } else if (!args.times.empty()) {
    const std::string problem = parse_times(args.times, times);
    if (!problem.empty()) return refuse(problem);
  } else {
    times.push_back(scene.time);
  }
  if (double(times.size()) * double(points.size()) > kMaxRows)
    return refuse("--at and --times: expected at most 1e7 rows, got " +
                  format_number(double(times.size()) * double(points.size())));
  const bool drawn = args.footprint == "drawn";
  double footprint = 0.0;
  if (!drawn && !(parse_number(args.footprint, footprint) && footprint >= 0.0))
    return refuse("--footprint " + args.footprint + ": expected metres >= 0 or `drawn`");
  std::optional<Geodetic> anchor;
  if (!args.anchor.empty()) {
    anchor = parse_place(args.anchor);
    if (!anchor)
      return refuse("--anchor " + args.anchor +
                    ": expected LAT,LON in degrees, LAT in [-90, "
                    "90], LON in [-180, 180]");
  }
  if (!args.output.empty()) {
    const std::string problem = check_output("-o", args.output, ".csv");
    if (!problem.empty()) return refuse(problem);
  }

  const SeaState sea(scene, anchor);
  // Each point's footprint, and its first row: every point drawn where `drawn` is asked for and
  // within the anchor's reach, before anything is written.
  std::vector<double> footprints(points.size(), footprint);
  std::vector<SeaPoint> first_rows(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::string where =
        args.at.empty() ? std::string("the camera's nadir") : "--at " + args.at[i];
    if (drawn) {
      const std::optional<double> cell = drawn_footprint(scene, points[i].first, points[i].second);
      if (!cell)
        return refuse("--footprint drawn: " + where +
                      ": the scene's grid draws no waves there (behind the camera or beyond its "
                      "horizon, or a camera under the sea or in space mode)");
      footprints[i] = *cell;
    }
    try {
      first_rows[i] = sea.at(points[i].first, points[i].second, times.front(), footprints[i]);
    } catch (const std::invalid_argument& error) {
      std::string why = error.what();
      why = why.substr(why.find("expected"));
      return refuse(where + ": " + why +
                    (args.anchor.empty() ? "; --anchor names one near it" : ""));
    }
  }
  // Row by row: a long series is not held in memory.
  PendingOutputs files;
  std::ofstream file;
  if (!args.output.empty()) {
    file.open(files.add(args.output));
    if (!file) throw std::runtime_error("-o " + args.output + ": cannot write beside it");
  }
  std::ostream& csv = args.output.empty() ? std::cout : file;
  csv << "time_s,lat_deg,lon_deg,height_m,normal_east,normal_north,normal_up,velocity_east_m_s,"
         "velocity_north_m_s,velocity_up_m_s,height_rate_m_s,rest_east_m,rest_north_m,"
         "calm_scale,wakes,converged\n";
  for (std::size_t t = 0; t < times.size(); ++t) {
    const double time = times[t];
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto [lat, lon] = points[i];
      const SeaPoint p = t == 0 ? first_rows[i] : sea.at(lat, lon, time, footprints[i]);
      // The place and time to 15 digits (1e-8 m; a time of 1e9 s to 1e-5 s, and 3 x 0.3 s
      // reads 0.9), the rest to ten.
      for (double value : {time, lat, lon}) csv << csv_number(value, 15) << ',';
      for (double value :
           {p.height, p.normal.x, p.normal.y, p.normal.z, p.velocity.x, p.velocity.y, p.velocity.z,
            p.height_rate, p.rest_offset.x, p.rest_offset.y, p.calm_scale})
        csv << csv_number(value, 10) << ',';
      csv << p.wakes << ',' << (p.converged ? 1 : 0) << '\n';
    }
  }
  csv.flush();
  if (!csv) throw std::runtime_error("writing the CSV failed");
  if (!args.output.empty()) {
    file.close();
    if (!file) throw std::runtime_error("-o " + args.output + ": writing failed");
    files.commit();
  }
  return kExitOk;
}

}  // namespace thalassa::cli
