// Wall-clock milliseconds since a point of std::chrono::steady_clock (internal to the planet
// module): the set-up times RenderStats::setup_ms and the sky export report.
#pragma once

#include <chrono>

namespace thalassa {

inline double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace thalassa
