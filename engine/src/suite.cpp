#include "thalassa/engine/suite.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>

namespace thalassa {
namespace {

using json = nlohmann::ordered_json;

[[noreturn]] void fail(std::string_view source, const std::string& path,
                       const std::string& expected, const std::string& got) {
  std::string message(source);
  if (!path.empty()) message += ": " + path;
  throw SuiteError(message + ": expected " + expected + ", got " + got);
}

// What a JSON value is, for messages: its type and, for scalars, its text.
std::string describe(const json& value) {
  if (value.is_object()) return "an object";
  if (value.is_array()) return "an array";
  if (value.is_null()) return "null";
  return value.dump();
}

bool is_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

bool is_scene_key(const std::string& key) {
  const auto& keys = scene_keys();
  return std::any_of(keys.begin(), keys.end(),
                     [&](const SceneKeyInfo& info) { return info.path == key; });
}

// Refuses any member of `object` not in `allowed`.
void check_members(const json& object, std::string_view source, const std::string& path,
                   const std::vector<std::string>& allowed) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string list;
    for (const auto& name : allowed) list += (list.empty() ? "" : ", ") + name;
    fail(source, path.empty() ? key : path + "." + key, "one of " + list, "an unknown member");
  }
}

std::string string_member(const json& object, std::string_view source, const std::string& path,
                          const char* key, bool required) {
  const auto it = object.find(key);
  const std::string where = path.empty() ? key : path + "." + key;
  if (it == object.end()) {
    if (required) fail(source, where, "a string", "nothing (it is required)");
    return "";
  }
  if (!it->is_string()) fail(source, where, "a string", describe(*it));
  return it->get<std::string>();
}

// An object of dotted scene keys to scalar JSON values.
std::vector<SuiteOverride> overrides(const json& object, std::string_view source,
                                     const std::string& path) {
  if (!object.is_object())
    fail(source, path, "an object of scene keys (\"camera.height\": 0.01)", describe(object));
  std::vector<SuiteOverride> result;
  for (const auto& [key, value] : object.items()) {
    const std::string where = path + "." + key;
    if (!is_scene_key(key)) fail(source, where, "a scene key (docs/scene.md)", "an unknown key");
    if (!value.is_primitive() || value.is_null())
      fail(source, where, "a number, string or boolean", describe(value));
    result.emplace_back(key, value.dump());
  }
  return result;
}

}  // namespace

Suite load_suite_text(std::string_view json_text, std::string_view source) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::exception& e) {
    fail(source, "", "valid JSON", e.what());
  }
  if (!doc.is_object()) fail(source, "", "a suite object", describe(doc));
  check_members(doc, source, "", {"suite", "description", "base", "cases"});
  Suite suite;
  suite.name = string_member(doc, source, "", "suite", true);
  if (!is_name(suite.name)) fail(source, "suite", "a name of [a-z0-9_]", json(suite.name).dump());
  suite.description = string_member(doc, source, "", "description", false);
  if (const auto base = doc.find("base"); base != doc.end())
    suite.base = overrides(*base, source, "base");

  const auto cases = doc.find("cases");
  if (cases == doc.end()) fail(source, "cases", "an array of cases", "nothing (it is required)");
  if (!cases->is_array() || cases->empty())
    fail(source, "cases", "a non-empty array of cases", describe(*cases));
  std::set<std::string> names;
  for (std::size_t i = 0; i < cases->size(); ++i) {
    const json& item = (*cases)[i];
    const std::string path = "cases[" + std::to_string(i) + "]";
    if (!item.is_object()) fail(source, path, "a case object", describe(item));
    check_members(item, source, path, {"name", "description", "set", "expect", "error"});
    SuiteCase c;
    c.name = string_member(item, source, path, "name", true);
    if (!is_name(c.name)) fail(source, path + ".name", "a name of [a-z0-9_]", json(c.name).dump());
    if (!names.insert(c.name).second)
      fail(source, path + ".name", "a name unique in the suite", json(c.name).dump());
    c.description = string_member(item, source, path, "description", false);
    const auto set = item.find("set");
    if (set == item.end()) fail(source, path + ".set", "an object of scene keys", "nothing");
    c.overrides = overrides(*set, source, path + ".set");
    if (const auto expect = item.find("expect"); expect != item.end()) {
      if (!expect->is_number_integer() || (*expect != 0 && *expect != 2))
        fail(source, path + ".expect", "0 or 2", describe(*expect));
      c.expected_exit = expect->get<int>();
    }
    c.expected_error = string_member(item, source, path, "error", false);
    if (c.expected_exit == 2 && c.expected_error.empty())
      fail(source, path + ".error", "the text the error message must contain (expect is 2)",
           item.contains("error") ? "an empty string" : "nothing");
    if (c.expected_exit == 0 && item.contains("error"))
      fail(source, path + ".error", "no error text where expect is 0", "an error text");
    suite.cases.push_back(std::move(c));
  }
  return suite;
}

Suite load_suite_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "", "a suite file", "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "", "a readable suite file", "a file that cannot be opened");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return load_suite_text(text, path);
}

std::vector<std::string> suite_case_assignments(const Suite& suite, const SuiteCase& c) {
  std::vector<std::string> assignments;
  for (const auto* list : {&suite.base, &c.overrides})
    for (const auto& [key, value] : *list) assignments.push_back(key + "=" + value);
  return assignments;
}

Scene build_suite_case_scene(const Suite& suite, const SuiteCase& c) {
  SceneBuilder builder;
  for (const std::string& assignment : suite_case_assignments(suite, c)) builder.set(assignment);
  return builder.build();
}

}  // namespace thalassa
