// The strict JSON reader shared by scene, flight, suite and GeoJSON files
// (engine/src/strict_json.hpp): repeated keys named by their full path, array elements included;
// syntax errors at their line and column; files refused with one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "strict_json.hpp"

namespace thalassa::detail {
namespace {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void throw_input_error(std::string_view source, std::string_view key,
                                    std::string_view expected, std::string_view got) {
  throw InputError(input_message(source, key, expected, got));
}

template <class Json = nlohmann::json>
std::string parse_error(const std::string& text, std::string_view prefix = "") {
  try {
    parse_strict_json<Json>(text, "t.json", prefix, &throw_input_error);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(StrictJson, ValidJsonIsParsedAsNlohmannDoes) {
  const std::string text = R"({"z": 1, "a": [1, {"b": [true, null]}, "s"], "m": {"k": 2.5}})";
  EXPECT_EQ(parse_strict_json<nlohmann::json>(text, "t.json", "", &throw_input_error),
            nlohmann::json::parse(text));
  // The ordered form keeps the file's key order.
  const auto ordered = parse_strict_json<nlohmann::ordered_json>(text, "t.json", "",
                                                                 &throw_input_error);
  EXPECT_EQ(ordered.begin().key(), "z");
  EXPECT_EQ(ordered, nlohmann::ordered_json::parse(text));
}

TEST(StrictJson, ARepeatedKeyIsNamedByItsFullPath) {
  EXPECT_EQ(parse_error(R"({"a": 1, "a": 2})"),
            "t.json: a: expected each key once, got \"a\" a second time");
  EXPECT_EQ(parse_error(R"({"a": {"b": 1, "c": {"d": 1}, "c": 2}})"),
            "t.json: a.c: expected each key once, got \"c\" a second time");
  // Elements of arrays, scalars and containers alike, count in the path.
  EXPECT_EQ(parse_error(R"({"a": [1, {"b": 1, "b": 2}]})"),
            "t.json: a[1].b: expected each key once, got \"b\" a second time");
  EXPECT_EQ(parse_error(R"({"x": [[1, 2], [3, [], {"k": {}, "k": 1}]]})"),
            "t.json: x[1][2].k: expected each key once, got \"k\" a second time");
  EXPECT_EQ(parse_error<nlohmann::ordered_json>(R"([{"q": 1}, {"q": 1, "q": 1}])"),
            "t.json: [1].q: expected each key once, got \"q\" a second time");
  // The same key in sibling objects is no repeat.
  EXPECT_EQ(parse_error(R"({"a": [{"b": 1}, {"b": 2}], "c": {"b": 3}})"), "");
  // A nested document's prefix (a scene inside a flight file).
  EXPECT_EQ(parse_error(R"({"camera": {"height": 1, "height": 2}})", "scene."),
            "t.json: scene.camera.height: expected each key once, got \"height\" a second time");
}

TEST(StrictJson, SyntaxErrorsGiveTheirLineAndColumn) {
  const std::string m = parse_error("{\n  \"a\": 1,\n  \"b\": ]\n}");
  EXPECT_EQ(m.rfind("t.json:3:8: expected valid JSON, got ", 0), 0u) << m;
  EXPECT_EQ(m.find("[json.exception"), std::string::npos) << m;
  EXPECT_EQ(parse_error("").rfind("t.json:1:1: expected valid JSON", 0), 0u);
  // An overflowing number has no position.
  EXPECT_EQ(parse_error(R"({"a": 1e999})").rfind("t.json: expected valid JSON, got ", 0), 0u);
}

TEST(StrictJson, MessagesAreOneLine) {
  EXPECT_EQ(input_message("a\nb.json", "k", "x", "y\r\nz"), "a b.json: k: expected x, got y  z");
  EXPECT_EQ(input_message("f.json", "", "valid JSON", "?"), "f.json: expected valid JSON, got ?");
}

TEST(StrictJson, FilesAreReadWholeOrRefused) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "thalassa_strict_json_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "folder.json");
  const std::string text = std::string("{\"a\": 1}\n") + std::string(100000, ' ');
  std::ofstream((dir / "f.json").string(), std::ios::binary) << text;
  EXPECT_EQ(read_text_file((dir / "f.json").string(), "flight file", "", "", &throw_input_error),
            text);
  const auto refusal = [&](const fs::path& path, std::string_view source, std::string_view key) {
    try {
      read_text_file(path.string(), "scene file", source, key, &throw_input_error);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string missing = (dir / "missing.json").string();
  EXPECT_EQ(refusal(missing, "", ""), missing + ": expected a readable scene file, got no such file");
  EXPECT_EQ(refusal(dir / "folder.json", "", ""),
            (dir / "folder.json").string() + ": expected a readable scene file, got a directory");
  EXPECT_EQ(refusal(missing, "s.json", "scene"),
            "s.json: scene: expected a readable scene file, got \"" + missing + "\", no such file");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thalassa::detail
