// Suite files (thalassa/validation/suite.hpp; the format is in docs/validation.md).
#include "thalassa/validation/suite.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "strict_json.hpp"
#include "thalassa/ocean/method.hpp"

namespace thalassa::validation {
namespace {

// Ordered: overrides are applied in file order, as the user wrote them.
using json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// Messages, in the form of scene and flight files' (engine/src/scene.cpp, planet/src/flight.cpp).

std::string dump(const json& v) { return v.dump(-1, ' ', false, json::error_handler_t::replace); }

std::string describe(const json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return v.empty() ? "an empty array" : "an array";
  if (v.is_null()) return "null";
  std::string s = dump(v);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

[[noreturn]] void fail(std::string_view source, std::string_view key, std::string_view expected,
                       std::string_view got) {
  throw SuiteError(detail::input_message(source, key, expected, got));
}

// The readers shared with scene and flight files (strict_json.hpp), refusing through fail().
json parse_strict(std::string_view text, std::string_view source) {
  return detail::parse_strict_json<json>(text, source, "", &fail);
}

std::string read_text_file(const std::string& path, std::string_view what, std::string_view source,
                           std::string_view key) {
  return detail::read_text_file(path, what, source, key, &fail);
}

std::string list_text(std::span<const std::string_view> items) {
  std::string s;
  for (auto k : items) s += (s.empty() ? "" : ", ") + std::string(k);
  return s;
}

void only_known(const json& object, std::span<const std::string_view> allowed,
                std::string_view source, const std::string& prefix) {
  for (const auto& [name, value] : object.items()) {
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
      fail(source, prefix + name,
           "a known key (" + list_text(allowed) + "; see docs/validation.md)", "an unknown key");
  }
}

bool is_name(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::string name_at(const json& v, std::string_view source, const std::string& key) {
  if (!v.is_string() || !is_name(v.get<std::string>()))
    fail(source, key, "a name of a-z, 0-9 and _", describe(v));
  return v.get<std::string>();
}

std::string string_at(const json& v, std::string_view source, const std::string& key) {
  if (!v.is_string()) fail(source, key, "a string", describe(v));
  return v.get<std::string>();
}

std::string one_of(const json& v, std::span<const std::string_view> allowed,
                   std::string_view source, const std::string& key) {
  const std::string expected = "one of " + list_text(allowed);
  if (!v.is_string()) fail(source, key, expected, describe(v));
  const std::string s = v.get<std::string>();
  if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
    fail(source, key, expected, describe(v));
  return s;
}

bool is_scene_key(std::string_view key) {
  const auto& keys = scene_keys();
  return std::any_of(keys.begin(), keys.end(), [&](const auto& k) { return k.path == key; });
}

// The overrides of a "set" (or "base") object. With check_values, each value gets the scene's
// own check of its key (type, range, format).
std::vector<SceneOverride> overrides_at(const json& v, std::string_view source,
                                        const std::string& key, bool check_values) {
  if (!v.is_object())
    fail(source, key, "an object of scene keys in the dotted --set form ({\"camera.height\": 10})",
         describe(v));
  std::vector<SceneOverride> out;
  for (const auto& [name, value] : v.items()) {
    const std::string at = key + "." + name;
    if (!is_scene_key(name)) fail(source, at, "a scene key (docs/scene.md)", "an unknown key");
    if (!(value.is_number() || value.is_string() || value.is_boolean()))
      fail(source, at, "a number, string or boolean", describe(value));
    if (check_values) {
      try {
        check_scene_value(name, dump(value), source, key + ".");
      } catch (const SceneError& e) {
        throw SuiteError(e.what());  // "<source>: <key>.<name>: expected ..., got ..."
      }
    }
    out.push_back({name, dump(value)});
  }
  return out;
}

// A number in [lo, hi] ((lo, hi] when lo_open).
double number_at(const json& v, std::string_view source, const std::string& key, double lo,
                 double hi, std::string_view unit, bool lo_open = false) {
  char range[96];
  std::snprintf(range, sizeof range, "a number in %s%g, %g]%s%s%s", lo_open ? "(" : "[", lo, hi,
                unit.empty() ? "" : " (", std::string(unit).c_str(), unit.empty() ? "" : ")");
  if (!v.is_number()) fail(source, key, range, describe(v));
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi || (lo_open && x == lo))
    fail(source, key, range, describe(v));
  return x;
}

int integer_at(const json& v, std::string_view source, const std::string& key, int lo, int hi) {
  const std::string expected =
      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!v.is_number_integer()) fail(source, key, expected, describe(v));
  const auto x = v.get<long long>();
  if (x < lo || x > hi) fail(source, key, expected, describe(v));
  return static_cast<int>(x);
}

bool bool_at(const json& v, std::string_view source, const std::string& key) {
  if (!v.is_boolean()) fail(source, key, "true or false", describe(v));
  return v.get<bool>();
}

SuiteMethod parse_method(const json& m, std::string_view source, const std::string& at) {
  SuiteMethod method;
  if (m.is_string()) {  // shorthand: "full" is {"name": "full", "method": "full"}
    method.method = one_of(m, kMethods, source, at);
    method.name = method.method;
    return method;
  }
  if (!m.is_object())
    fail(source, at, "a method name or an object {\"name\": ..., \"method\": ..., \"set\": {...}}",
         describe(m));
  static constexpr std::string_view kKeys[] = {"name", "method",        "description",
                                               "set",  "own_reference", "supersample"};
  only_known(m, kKeys, source, at + ".");
  if (!m.contains("name")) fail(source, at + ".name", "a name of a-z, 0-9 and _", "none");
  method.name = name_at(m["name"], source, at + ".name");
  if (!m.contains("method")) fail(source, at + ".method", "one of " + list_text(kMethods), "none");
  method.method = one_of(m["method"], kMethods, source, at + ".method");
  if (m.contains("description"))
    method.description = string_at(m["description"], source, at + ".description");
  if (m.contains("set")) method.set = overrides_at(m["set"], source, at + ".set", true);
  // The metrics compare each method's image with the reference's, pixel for pixel.
  for (const SceneOverride& o : method.set)
    if (o.key == "image.width" || o.key == "image.height")
      fail(source, at + ".set." + o.key,
           "the case's image size (\"supersample\" draws a method at a multiple of it)",
           "a method's own size");
  if (m.contains("own_reference")) {
    method.own_reference = bool_at(m["own_reference"], source, at + ".own_reference");
    if (method.own_reference && (method.set.empty() || method.method == "reference"))
      fail(source, at + ".own_reference",
           "true only for a variant (a `set`) of a method other than the reference",
           method.set.empty() ? "a method without a set" : "the reference");
  }
  if (m.contains("supersample")) {
    method.supersample =
        integer_at(m["supersample"], source, at + ".supersample", 1, kMaxSupersample);
    // The reference is what the others are box-filtered to: its pixels' samples are
    // reference.pixel_samples.
    if (method.supersample > 1 && method.method == "reference")
      fail(source, at + ".supersample",
           "1 for the reference (its samples per pixel are reference.pixel_samples)",
           std::to_string(method.supersample));
  }
  return method;
}

std::vector<std::string> terms_at(const json& v, std::string_view source, const std::string& key) {
  if (!v.is_array() || v.empty())
    fail(source, key, "a non-empty array of light terms (" + list_text(kTerms) + ")", describe(v));
  std::vector<std::string> terms;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string at = key + "[" + std::to_string(i) + "]";
    std::string t = one_of(v[i], kTerms, source, at);
    if (std::find(terms.begin(), terms.end(), t) != terms.end())
      fail(source, at, "each term once", "\"" + t + "\" a second time");
    terms.push_back(std::move(t));
  }
  return terms;
}

// An override with the part of the suite it comes from, which scene errors name in place of
// "--set": "suite.json: cases[2].set: camera.lat: expected ...".
struct LabelledOverride {
  std::string assignment;
  std::string source;
};

void append_labelled(std::vector<LabelledOverride>& out, const std::vector<SceneOverride>& set,
                     std::string_view source, const std::string& key) {
  for (const SceneOverride& o : set)
    out.push_back({o.assignment(), std::string(source) + ": " + key});
}

// "methods[i]": where a method is in the suite file (by its unique name).
std::string method_key(const Suite& suite, const SuiteMethod& method) {
  for (std::size_t i = 0; i < suite.methods.size(); ++i)
    if (suite.methods[i].name == method.name) return "methods[" + std::to_string(i) + "]";
  return "method " + method.name;
}

// Lays `method`'s supersampling (SuiteMethod::supersample) over `builder`: the image's width and
// height as the overrides so far leave them, times it, with the scene's checks, which name the
// method's key ("suite.json: methods[3].supersample: image.width: expected an integer in
// [1, 8192], got 16384"). Nothing for no method or a supersample of 1.
void set_supersampled_size(SceneBuilder& builder, const Suite& suite, const SuiteMethod* method) {
  if (!method || method->supersample <= 1) return;
  const ImageSettings image = builder.build().image;
  const std::string source = suite.source + ": " + method_key(suite, *method) + ".supersample";
  builder.set("image.width=" + std::to_string(image.width * method->supersample), source);
  builder.set("image.height=" + std::to_string(image.height * method->supersample), source);
}

// The base scene file's text (if any) under `overrides`, and `method`'s supersampling, built: a
// SceneError names the suite file and the part of it the bad value came from.
void build_or_fail(const std::string& scene_text, const Suite& suite,
                   const std::vector<LabelledOverride>& overrides,
                   const SuiteMethod* method = nullptr) {
  try {
    SceneBuilder builder;
    if (!suite.scene_file.empty()) builder.load_text(scene_text, suite.scene_file);
    for (const LabelledOverride& o : overrides) builder.set(o.assignment, o.source);
    set_supersampled_size(builder, suite, method);
    builder.build();
  } catch (const SceneError& e) {
    throw SuiteError(e.what());
  }
}

// "cases[i]": where a case is in the suite file (which `validate --case` may have filtered).
std::string case_key(const SuiteCase& c) {
  return c.index >= 0 ? "cases[" + std::to_string(c.index) + "]" : "case " + c.name;
}

// The overrides of case `c` rendered with `method` (null: the case's own scene): the suite's
// base, the case's set, then the method's set (case_assignments without the labels).
std::vector<LabelledOverride> case_overrides(const Suite& suite, const SuiteCase& c,
                                             const SuiteMethod* method) {
  std::vector<LabelledOverride> out;
  append_labelled(out, suite.base, suite.source, "base");
  append_labelled(out, c.set, suite.source, case_key(c) + ".set");
  if (method) append_labelled(out, method->set, suite.source, method_key(suite, *method) + ".set");
  return out;
}

}  // namespace

std::string terms_option(std::string_view term) {
  return term == "all" ? "sun,sky,sea,air" : std::string(term);
}

const SuiteMethod* Suite::find_method(std::string_view n) const {
  for (const SuiteMethod& m : methods)
    if (m.name == n) return &m;
  return nullptr;
}

const SuiteMethod* Suite::reference_method() const {
  for (const SuiteMethod& m : methods)
    if (m.method == "reference" && m.plain()) return &m;
  return nullptr;
}

Suite load_suite_text(std::string_view json_text, std::string_view source,
                      const std::string& base_dir) {
  Suite suite;
  suite.source = source;
  const json doc = parse_strict(json_text, source);
  if (!doc.is_object())
    fail(source, "", "a JSON object (a suite, see docs/validation.md)", describe(doc));
  static constexpr std::string_view kKeys[] = {"suite",     "description", "scene",   "base",
                                               "methods",   "terms",       "flicker", "timing",
                                               "reference", "horizon",     "cases"};
  only_known(doc, kKeys, source, "");
  if (!doc.contains("suite")) fail(source, "suite", "the suite's name (a-z, 0-9 and _)", "none");
  suite.name = name_at(doc["suite"], source, "suite");
  if (doc.contains("description"))
    suite.description = string_at(doc["description"], source, "description");

  // The base scene: a scene file relative to the suite's folder, then `base`'s overrides.
  std::string scene_text;
  if (doc.contains("scene")) {
    const std::filesystem::path given = string_at(doc["scene"], source, "scene");
    suite.scene_file =
        (given.is_absolute() || base_dir.empty() ? given : std::filesystem::path(base_dir) / given)
            .string();
    scene_text = read_text_file(
        suite.scene_file, "scene file (relative to the suite file's folder)", source, "scene");
    try {
      SceneBuilder().load_text(scene_text, suite.scene_file);
    } catch (const SceneError& e) {
      throw SuiteError(e.what());  // it names the scene file and the key
    }
  }
  if (doc.contains("base")) suite.base = overrides_at(doc["base"], source, "base", true);
  {
    std::vector<LabelledOverride> base;
    append_labelled(base, suite.base, source, "base");
    build_or_fail(scene_text, suite, base);
  }

  // Methods and variants.
  if (doc.contains("methods")) {
    const json& ms = doc["methods"];
    if (!ms.is_array() || ms.empty())
      fail(source, "methods", "a non-empty array of methods", describe(ms));
    for (std::size_t i = 0; i < ms.size(); ++i) {
      const std::string at = "methods[" + std::to_string(i) + "]";
      SuiteMethod m = parse_method(ms[i], source, at);
      if (suite.find_method(m.name))
        fail(source, at + (ms[i].is_object() ? ".name" : ""), "a name not used before in methods",
             "\"" + m.name + "\" a second time");
      suite.methods.push_back(std::move(m));
    }
    // An own reference is reported as the method "reference_<variant>": no method may have
    // that name.
    for (std::size_t i = 0; i < suite.methods.size(); ++i)
      if (suite.methods[i].own_reference && suite.find_method("reference_" + suite.methods[i].name))
        fail(source, "methods[" + std::to_string(i) + "].own_reference",
             "no method named \"reference_" + suite.methods[i].name +
                 "\" (the name of its own reference)",
             "one");
  } else {
    suite.methods.push_back({"full", "full", "", {}});
  }
  suite.terms = doc.contains("terms") ? terms_at(doc["terms"], source, "terms")
                                      : std::vector<std::string>{"all"};

  if (doc.contains("flicker")) {
    const json& f = doc["flicker"];
    if (!f.is_object())
      fail(source, "flicker", "an object {\"frames\", \"dt\", \"terms\"}", describe(f));
    static constexpr std::string_view kFlickerKeys[] = {"frames", "dt", "terms"};
    only_known(f, kFlickerKeys, source, "flicker.");
    if (f.contains("frames"))
      suite.flicker.frames = integer_at(f["frames"], source, "flicker.frames", 0, 100);
    if (f.contains("dt"))
      suite.flicker.dt = number_at(f["dt"], source, "flicker.dt", 0, 3600, "s", true);
    if (f.contains("terms")) {
      suite.flicker.terms = terms_at(f["terms"], source, "flicker.terms");
    }
  }
  for (std::size_t i = 0; i < suite.flicker.terms.size(); ++i) {
    const std::string& t = suite.flicker.terms[i];
    if (std::find(suite.terms.begin(), suite.terms.end(), t) == suite.terms.end())
      fail(source, "flicker.terms[" + std::to_string(i) + "]", "one of the suite's terms",
           "\"" + t + "\"");
  }

  if (doc.contains("timing")) {
    const json& t = doc["timing"];
    if (!t.is_object())
      fail(source, "timing", "an object {\"width\", \"height\", \"frames\"}", describe(t));
    static constexpr std::string_view kTimingKeys[] = {"width", "height", "frames"};
    only_known(t, kTimingKeys, source, "timing.");
    for (const char* key : {"width", "height"})
      if (!t.contains(key))
        fail(source, std::string("timing.") + key, "the timed frames' size in pixels", "none");
    suite.timing.width = integer_at(t["width"], source, "timing.width", 1, kMaxImageSide);
    suite.timing.height = integer_at(t["height"], source, "timing.height", 1, kMaxImageSide);
    if (t.contains("frames"))
      suite.timing.frames = integer_at(t["frames"], source, "timing.frames", 1, 100);
    // A supersampled method is timed at its multiple of the size (runner.cpp), which must be an
    // image the scene allows.
    for (const SuiteMethod& m : suite.methods) {
      const int most = std::max(suite.timing.width, suite.timing.height) * m.supersample;
      if (most > kMaxImageSide)
        fail(source, "timing",
             "a size that " + method_key(suite, m) + ".supersample (" +
                 std::to_string(m.supersample) + ") keeps within " + std::to_string(kMaxImageSide) +
                 " pixels a side",
             std::to_string(suite.timing.width) + "x" + std::to_string(suite.timing.height));
    }
  }

  if (doc.contains("reference")) {
    const json& r = doc["reference"];
    if (!r.is_object())
      fail(source, "reference",
           "an object {\"pixel_samples\", \"pixel_samples_without_sun\", "
           "\"sun_normal_samples\", \"sun_cells_per_wavelength\", "
           "\"sun_max_cells_per_wavelength\", \"sun\", \"sun_refine\", \"grid_cell\", "
           "\"check_convergence\"}",
           describe(r));
    static constexpr std::string_view kReferenceKeys[] = {"pixel_samples",
                                                          "pixel_samples_without_sun",
                                                          "sun_normal_samples",
                                                          "sun_cells_per_wavelength",
                                                          "sun_max_cells_per_wavelength",
                                                          "sun",
                                                          "sun_refine",
                                                          "grid_cell",
                                                          "check_convergence"};
    only_known(r, kReferenceKeys, source, "reference.");
    if (r.contains("pixel_samples"))
      suite.reference.pixel_samples =
          integer_at(r["pixel_samples"], source, "reference.pixel_samples", 1,
                     ocean::kReferenceMaxPixelSamples);
    if (r.contains("pixel_samples_without_sun"))
      suite.reference.pixel_samples_without_sun =
          integer_at(r["pixel_samples_without_sun"], source, "reference.pixel_samples_without_sun",
                     1, ocean::kReferenceMaxPixelSamples);
    if (r.contains("sun_normal_samples"))
      suite.reference.sun_normal_samples =
          integer_at(r["sun_normal_samples"], source, "reference.sun_normal_samples", 1,
                     ocean::kReferenceMaxSunCells * ocean::kReferenceMaxSunCells);
    if (r.contains("sun_cells_per_wavelength"))
      suite.reference.sun_cells_per_wavelength =
          number_at(r["sun_cells_per_wavelength"], source, "reference.sun_cells_per_wavelength", 1,
                    ocean::kReferenceMaxCellsPerWavelength, "cells", false);
    if (r.contains("sun_max_cells_per_wavelength")) {
      const double most = number_at(r["sun_max_cells_per_wavelength"], source,
                                    "reference.sun_max_cells_per_wavelength", 1,
                                    ocean::kReferenceMaxCellsPerWavelength, "cells", false);
      if (most < suite.reference.sun_cells_per_wavelength) {
        char expected[96];
        std::snprintf(expected, sizeof expected,
                      "at least reference.sun_cells_per_wavelength (%g)",
                      suite.reference.sun_cells_per_wavelength);
        fail(source, "reference.sun_max_cells_per_wavelength", expected,
             describe(r["sun_max_cells_per_wavelength"]));
      }
      suite.reference.sun_max_cells_per_wavelength = most;
    }
    if (r.contains("sun")) {
      const json& sun = r["sun"];
      if (!sun.is_string() || (sun != "scattered" && sun != "gathered"))
        fail(source, "reference.sun", "\"scattered\" or \"gathered\"", describe(sun));
      suite.reference.sun = sun.get<std::string>();
    }
    if (r.contains("sun_refine"))
      suite.reference.sun_refine =
          integer_at(r["sun_refine"], source, "reference.sun_refine", 1, 8);
    if (r.contains("grid_cell"))
      suite.reference.grid_cell =
          number_at(r["grid_cell"], source, "reference.grid_cell", ocean::kReferenceMinGridCell,
                    ocean::kReferenceGridCell, "pixels", false);
    if (r.contains("check_convergence"))
      suite.reference.check_convergence =
          bool_at(r["check_convergence"], source, "reference.check_convergence");
  }

  if (doc.contains("horizon")) {
    const json& h = doc["horizon"];
    if (!h.is_object())
      fail(source, "horizon", "an object {\"depth_deg\", \"bin_deg\"}", describe(h));
    static constexpr std::string_view kHorizonKeys[] = {"depth_deg", "bin_deg"};
    only_known(h, kHorizonKeys, source, "horizon.");
    // 90 degrees below the horizon is straight down at most.
    if (h.contains("depth_deg"))
      suite.horizon.depth_deg =
          number_at(h["depth_deg"], source, "horizon.depth_deg", 0, 90, "degrees", true);
    if (h.contains("bin_deg"))
      suite.horizon.bin_deg =
          number_at(h["bin_deg"], source, "horizon.bin_deg", 0, suite.horizon.depth_deg,
                    "degrees; at most depth_deg", true);
  }

  // Cases.
  if (!doc.contains("cases")) fail(source, "cases", "an array of cases", "none");
  const json& cases = doc["cases"];
  if (!cases.is_array() || cases.empty())
    fail(source, "cases", "a non-empty array of cases", describe(cases));
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string at = "cases[" + std::to_string(i) + "]";
    const json& c = cases[i];
    if (!c.is_object()) fail(source, at, "an object {\"name\": ..., \"set\": {...}}", describe(c));
    static constexpr std::string_view kCaseKeys[] = {"name",   "description", "set",
                                                     "expect", "error",       "methods"};
    only_known(c, kCaseKeys, source, at + ".");
    SuiteCase sc;
    if (!c.contains("name")) fail(source, at + ".name", "a name of a-z, 0-9 and _", "none");
    sc.name = name_at(c["name"], source, at + ".name");
    sc.index = static_cast<int>(i);
    for (const SuiteCase& earlier : suite.cases)
      if (earlier.name == sc.name)
        fail(source, at + ".name", "a name not used before in cases",
             "\"" + sc.name + "\" a second time");
    if (c.contains("description"))
      sc.description = string_at(c["description"], source, at + ".description");
    if (c.contains("expect")) {
      const json& e = c["expect"];
      if (!e.is_number_integer() || (e.get<long long>() != 0 && e.get<long long>() != 2))
        fail(source, at + ".expect", "0 or 2", describe(e));
      sc.expected_exit = e.get<int>();
    }
    if (c.contains("error")) {
      if (sc.expected_exit != 2)
        fail(source, at + ".error", "no error with expect 0 (an error only with \"expect\": 2)",
             describe(c["error"]));
      sc.expected_error = string_at(c["error"], source, at + ".error");
      if (sc.expected_error.empty())
        fail(source, at + ".error", "a non-empty part of the error message", "\"\"");
    } else if (sc.expected_exit == 2) {
      fail(source, at + ".error", "a part of the error message the case must give (expect 2)",
           "none");
    }
    if (!c.contains("set"))
      fail(source, at + ".set", "an object of scene keys ({} for none)", "none");
    sc.set = overrides_at(c["set"], source, at + ".set", sc.expected_exit == 0);
    if (c.contains("methods")) {
      const json& ms = c["methods"];
      if (!ms.is_array() || ms.empty())
        fail(source, at + ".methods", "a non-empty array of the suite's method names",
             describe(ms));
      for (const SuiteMethod& m : suite.methods) {  // the suite's order
        if (std::find(ms.begin(), ms.end(), json(m.name)) != ms.end()) sc.methods.push_back(m.name);
      }
      for (std::size_t k = 0; k < ms.size(); ++k) {
        const std::string mat = at + ".methods[" + std::to_string(k) + "]";
        if (!ms[k].is_string() || !suite.find_method(ms[k].get<std::string>()))
          fail(source, mat, "the name of one of the suite's methods", describe(ms[k]));
        if (std::count(ms.begin(), ms.end(), ms[k]) > 1)
          fail(source, mat, "each method once", describe(ms[k]) + " a second time");
      }
    } else {
      for (const SuiteMethod& m : suite.methods) sc.methods.push_back(m.name);
    }
    // A case expected to render: its scene, and its scene with each method's set and
    // supersampling, must build.
    if (sc.expected_exit == 0) {
      build_or_fail(scene_text, suite, case_overrides(suite, sc, nullptr));
      for (const std::string& name : sc.methods) {
        const SuiteMethod& m = *suite.find_method(name);
        if (!m.plain()) build_or_fail(scene_text, suite, case_overrides(suite, sc, &m), &m);
      }
    }
    suite.cases.push_back(std::move(sc));
  }
  return suite;
}

Suite load_suite_file(const std::string& path) {
  const std::string text = read_text_file(path, "suite file", "", "");
  return load_suite_text(text, path, std::filesystem::path(path).parent_path().string());
}

Suite default_suite() { return load_suite_text(default_suite_json(), "default suite"); }

void narrow_suite(Suite& suite, const std::vector<std::string>& methods,
                  const std::vector<std::string>& terms) {
  const auto listed = [](const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  const auto refuse = [&](std::string_view option, std::string_view what,
                          const std::vector<std::string>& have, const std::string& got) {
    std::string names;
    for (const std::string& n : have) names += (names.empty() ? "" : ", ") + n;
    throw SuiteError(std::string(option) + ": expected " + std::string(what) + " of " +
                     suite.source + " (" + names + "), got \"" + got + "\"");
  };
  if (!methods.empty()) {
    std::vector<std::string> have;
    for (const SuiteMethod& m : suite.methods) have.push_back(m.name);
    for (const std::string& name : methods)
      if (!listed(have, name)) refuse("--method", "a method", have, name);
    const SuiteMethod* reference = suite.reference_method();
    const std::string reference_name = reference ? reference->name : "";
    std::erase_if(suite.methods, [&](const SuiteMethod& m) {
      return m.name != reference_name && !listed(methods, m.name);
    });
    for (SuiteCase& c : suite.cases)
      std::erase_if(c.methods, [&](const std::string& name) { return !suite.find_method(name); });
  }
  if (!terms.empty()) {
    for (const std::string& term : terms)
      if (!listed(suite.terms, term)) refuse("--term", "a term", suite.terms, term);
    std::erase_if(suite.terms, [&](const std::string& t) { return !listed(terms, t); });
    std::erase_if(suite.flicker.terms, [&](const std::string& t) { return !listed(terms, t); });
  }
}

std::vector<std::size_t> expand_seas(Suite& suite, int seas) {
  if (seas < 1 || seas > kMaxSeas)
    throw SuiteError("--seas: expected a number of seas in [1, " + std::to_string(kMaxSeas) +
                     "], got " + std::to_string(seas));
  std::vector<std::size_t> origin;
  if (seas == 1) {
    for (std::size_t i = 0; i < suite.cases.size(); ++i) origin.push_back(i);
    return origin;
  }
  std::vector<SuiteCase> cases;
  for (std::size_t i = 0; i < suite.cases.size(); ++i) {
    const SuiteCase& c = suite.cases[i];
    if (c.expected_exit != 0) {
      cases.push_back(c);
      origin.push_back(i);
      continue;
    }
    const std::uint64_t first = case_scene(suite, c).ocean.seed;
    if (first + std::uint64_t(seas) - 1 > std::numeric_limits<std::uint32_t>::max())
      throw SuiteError("--seas: case " + c.name + ": expected its ocean.seed plus " +
                       std::to_string(seas - 1) + " within 4294967295, got " +
                       std::to_string(first + std::uint64_t(seas) - 1));
    for (int k = 1; k <= seas; ++k) {
      SuiteCase sea = c;
      const std::uint64_t seed = first + std::uint64_t(k) - 1;
      sea.name = c.name + "_sea" + std::to_string(k);
      sea.description = (c.description.empty() ? "" : c.description + "; ") + "sea " +
                        std::to_string(k) + " of " + std::to_string(seas) + " (ocean.seed " +
                        std::to_string(seed) + ")";
      sea.set.push_back({"ocean.seed", std::to_string(seed)});
      sea.sea_of = c.name;
      sea.sea = k;
      cases.push_back(std::move(sea));
      origin.push_back(i);
    }
  }
  std::set<std::string> names;
  for (const SuiteCase& c : cases)
    if (!names.insert(c.name).second)
      throw SuiteError("--seas: expected the seas' names to be new, got a second case \"" + c.name +
                       "\" in " + suite.source);
  suite.cases = std::move(cases);
  return origin;
}

std::vector<std::string> case_assignments(const Suite& suite, const SuiteCase& c,
                                          const SuiteMethod* method) {
  std::vector<std::string> out;
  for (const LabelledOverride& o : case_overrides(suite, c, method)) out.push_back(o.assignment);
  return out;
}

SceneBuilder case_scene_builder(const Suite& suite, const SuiteCase& c, const SuiteMethod* method) {
  SceneBuilder builder;
  if (!suite.scene_file.empty()) builder.load_file(suite.scene_file);
  for (const LabelledOverride& o : case_overrides(suite, c, method))
    builder.set(o.assignment, o.source);
  set_supersampled_size(builder, suite, method);
  return builder;
}

Scene case_scene(const Suite& suite, const SuiteCase& c, const SuiteMethod* method) {
  return case_scene_builder(suite, c, method).build();
}

std::optional<std::string> case_scene_error(const Suite& suite, const SuiteCase& c,
                                            const SuiteMethod* method) {
  try {
    case_scene(suite, c, method);
  } catch (const SceneError& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

std::string case_fingerprint(const Suite& suite, const SuiteCase& c, std::string_view environment) {
  // nlohmann::json (not ordered): keys sorted, so the text does not depend on the code's order.
  nlohmann::json inputs;
  inputs["environment"] = environment;
  inputs["suite"] = suite.name;
  inputs["terms"] = suite.terms;
  inputs["flicker"] = {
      {"frames", suite.flicker.frames}, {"dt", suite.flicker.dt}, {"terms", suite.flicker.terms}};
  const ReferenceSettings& r = suite.reference;
  inputs["reference"] = {{"pixel_samples", r.pixel_samples},
                         {"pixel_samples_without_sun", r.pixel_samples_without_sun},
                         {"sun_normal_samples", r.sun_normal_samples},
                         {"sun_cells_per_wavelength", r.sun_cells_per_wavelength},
                         {"sun", r.sun},
                         {"sun_refine", r.sun_refine},
                         {"check_convergence", r.check_convergence}};
  // Only when set, so that the reports of suites that never double keep their fingerprints.
  if (r.sun_max_cells_per_wavelength > 0.0)
    inputs["reference"]["sun_max_cells_per_wavelength"] = r.sun_max_cells_per_wavelength;
  // Likewise only when finer than the one-pixel grid every report before stop 44 was drawn on.
  if (r.grid_cell != ocean::kReferenceGridCell) inputs["reference"]["grid_cell"] = r.grid_cell;
  inputs["horizon"] = {{"depth_deg", suite.horizon.depth_deg}, {"bin_deg", suite.horizon.bin_deg}};
  inputs["expected_exit"] = c.expected_exit;
  inputs["expected_error"] = c.expected_error;
  const auto scene_text = [&](const SuiteMethod* method) {
    try {
      return case_scene_builder(suite, c, method).merged_json();
    } catch (const SceneError& e) {
      return std::string("refused: ") + e.what();
    }
  };
  inputs["scene"] = scene_text(nullptr);
  nlohmann::json methods = nlohmann::json::array();
  for (const std::string& name : c.methods) {
    const SuiteMethod* m = suite.find_method(name);
    if (!m) continue;  // load_suite_text refuses such a case
    // (A supersampled method's scene is drawn at its larger size, which its text holds.)
    methods.push_back({{"name", m->name},
                       {"method", m->method},
                       {"own_reference", m->own_reference},
                       {"scene", scene_text(m)}});
  }
  inputs["methods"] = methods;
  // FNV-1a, 64 bits: stable across compilers and runs, unlike std::hash.
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (const unsigned char byte : inputs.dump()) {
    hash ^= byte;
    hash *= 0x100000001b3ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

}  // namespace thalassa::validation
