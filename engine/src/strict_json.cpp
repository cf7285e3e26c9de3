// thalassa — strict JSON input (strict_json.hpp).
#include "strict_json.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

namespace thalassa::detail {
namespace {

// "line:column" (1-based) of a byte offset reported by the JSON parser.
std::string line_column(std::string_view text, std::size_t byte) {
  // nlohmann counts the bytes read including the offending one.
  const std::size_t pos = std::min(byte > 0 ? byte - 1 : 0, text.size());
  std::size_t line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < pos; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return std::to_string(line) + ":" + std::to_string(pos - line_start + 1);
}

// The parser's reason without its "[json.exception...] " and "parse error at line 1, column 2: "
// (the position is given in front of the message instead).
std::string parse_reason(const nlohmann::json::exception& e) {
  std::string what = e.what();
  if (what.rfind("[json.exception.", 0) == 0) {
    const auto end = what.find("] ");
    if (end != std::string::npos) what.erase(0, end + 2);
  }
  if (what.rfind("parse error", 0) == 0) {
    const auto colon = what.find(": ");
    if (colon != std::string::npos) what.erase(0, colon + 2);
  }
  return what;
}

// `fail` is documented to throw; this keeps a reader that does not from going on.
[[noreturn]] void failed(FailFunction fail, std::string_view source, std::string_view key,
                         std::string_view expected, std::string_view got) {
  fail(source, key, expected, got);
  throw std::logic_error("strict_json: the reader's fail function returned");
}

}  // namespace

std::string input_message(std::string_view source, std::string_view key, std::string_view expected,
                          std::string_view got) {
  std::string msg = std::string(source) + ": " + (key.empty() ? "" : std::string(key) + ": ") +
                    "expected " + std::string(expected) + ", got " + std::string(got);
  std::replace_if(msg.begin(), msg.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return msg;
}

template <class Json>
Json parse_strict_json(std::string_view text, std::string_view source, std::string_view key_prefix,
                       FailFunction fail) {
  // One frame per object or array being parsed: an object's keys met so far (the last is the
  // current member), an array's count of elements begun (the last is the current element).
  struct Frame {
    bool array = false;
    std::vector<std::string> keys;
    std::size_t elements = 0;
  };
  std::vector<Frame> frames;
  // A value begins: inside an array it is the next element.
  const auto begin_value = [&] {
    if (!frames.empty() && frames.back().array) ++frames.back().elements;
  };
  // "a.b[2].c": each frame's current member or element, `key_prefix` in front.
  const auto current_path = [&] {
    std::string dotted(key_prefix);
    for (const Frame& f : frames) {
      if (f.array)
        dotted += "[" + std::to_string(f.elements - 1) + "]";
      else if (!f.keys.empty())
        dotted += (dotted.size() == key_prefix.size() ? "" : ".") + f.keys.back();
    }
    return dotted;
  };
  const typename Json::parser_callback_t no_repeated_keys =
      [&](int /*depth*/, typename Json::parse_event_t event, Json& parsed) {
        switch (event) {
          case Json::parse_event_t::object_start:
          case Json::parse_event_t::array_start:
            begin_value();
            frames.push_back({event == Json::parse_event_t::array_start, {}, 0});
            break;
          case Json::parse_event_t::object_end:
          case Json::parse_event_t::array_end:
            frames.pop_back();
            break;
          case Json::parse_event_t::key: {
            const std::string key = parsed.template get<std::string>();
            std::vector<std::string>& keys = frames.back().keys;
            const bool repeated = std::find(keys.begin(), keys.end(), key) != keys.end();
            keys.push_back(key);
            if (repeated)
              failed(fail, source, current_path(), "each key once",
                     "\"" + key + "\" a second time");
            break;
          }
          case Json::parse_event_t::value:
            // Called for scalars, and again for an object or array once it is complete, after
            // its *_end (whose frame is gone by then): only a scalar begins a value here.
            if (!parsed.is_structured()) begin_value();
            break;
        }
        return true;
      };
  try {
    return Json::parse(text, no_repeated_keys);
  } catch (const nlohmann::json::parse_error& e) {
    failed(fail, std::string(source) + ":" + line_column(text, e.byte), "", "valid JSON",
           parse_reason(e));
  } catch (const nlohmann::json::exception& e) {
    // A number literal too large for a double ("1e999") has no position.
    failed(fail, source, "", "valid JSON", parse_reason(e));
  }
}

template nlohmann::json parse_strict_json<nlohmann::json>(std::string_view, std::string_view,
                                                          std::string_view, FailFunction);
template nlohmann::ordered_json parse_strict_json<nlohmann::ordered_json>(std::string_view,
                                                                          std::string_view,
                                                                          std::string_view,
                                                                          FailFunction);

std::string read_text_file(const std::string& path, std::string_view what, std::string_view source,
                           std::string_view key, FailFunction fail) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string expected = "a readable " + std::string(what);
  const std::string where = source.empty() ? path : std::string(source);
  const std::string named = source.empty() ? "" : "\"" + path + "\", ";
  if (!fs::exists(path, ec)) failed(fail, where, key, expected, named + "no such file");
  if (fs::is_directory(path, ec)) failed(fail, where, key, expected, named + "a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) failed(fail, where, key, expected, named + "a file that cannot be opened");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) failed(fail, where, key, expected, named + "a read error");
  return text;
}

}  // namespace thalassa::detail
