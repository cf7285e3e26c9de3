// thalassa — small file helpers shared by every writer: nothing is left half-written.
#pragma once

#include <stdexcept>
#include <string>

namespace thalassa {

class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `text` to a temporary file beside `path`, then renames it over `path`. Throws
// FileError naming the path; on failure no file is left at `path` or beside it.
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace thalassa
