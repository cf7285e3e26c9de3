#include "thalassa/engine/file_io.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace thalassa {

void write_text_atomically(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".tmp-" +
                                                     std::to_string(getpid()));
  std::error_code ec;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError(path + ": cannot write (folder missing or not writable)");
    out << text;
    out.flush();
    if (!out) {
      out.close();
      fs::remove(temporary, ec);
      throw FileError(path + ": write failed");
    }
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    fs::remove(temporary, ec);
    throw FileError(path + ": cannot rename into place: " + ec.message());
  }
}

}  // namespace thalassa
