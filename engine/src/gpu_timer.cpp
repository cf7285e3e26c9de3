#include "thalassa/engine/gl/gpu_timer.hpp"

namespace thalassa::gl {

namespace {
constexpr double kNanosecondsPerMillisecond = 1e6;
}

TimingSource GpuTimer::source_for_renderer(const std::string& gl_renderer) {
  const bool software = gl_renderer.find("llvmpipe") != std::string::npos ||
                        gl_renderer.find("softpipe") != std::string::npos;
  return software ? TimingSource::FinishWallClock : TimingSource::TimestampQuery;
}

void GpuTimer::mark() {
  if (source_ == TimingSource::FinishWallClock) glFinish();
  wall_.push_back(std::chrono::steady_clock::now());
  queries_.push_back(make_query(GL_TIMESTAMP));
  glQueryCounter(queries_.back().get(), GL_TIMESTAMP);
}

void GpuTimer::begin_frame() {
  queries_.clear();
  wall_.clear();
  names_.clear();
  mark();
}

void GpuTimer::end_pass(const std::string& name) {
  mark();
  names_.push_back(name);
}

std::vector<PassTime> GpuTimer::resolve(PassTime& frame) {
  std::vector<GLuint64> stamps(queries_.size(), 0);
  for (std::size_t i = 0; i < queries_.size(); ++i)
    glGetQueryObjectui64v(queries_[i].get(), GL_QUERY_RESULT, &stamps[i]);  // waits
  // Timestamps are monotonic; a driver that returns garbage must not give negative times.
  auto query_ms = [&](std::size_t from, std::size_t to) {
    return stamps[to] >= stamps[from]
               ? double(stamps[to] - stamps[from]) / kNanosecondsPerMillisecond
               : 0.0;
  };
  auto wall_ms = [&](std::size_t from, std::size_t to) {
    if (source_ != TimingSource::FinishWallClock) return 0.0;  // unsynchronised: meaningless
    return std::chrono::duration<double, std::milli>(wall_[to] - wall_[from]).count();
  };
  std::vector<PassTime> passes;
  for (std::size_t i = 1; i < stamps.size(); ++i)
    passes.push_back({names_[i - 1], query_ms(i - 1, i), wall_ms(i - 1, i)});
  frame = {"frame", 0.0, 0.0};
  if (stamps.size() > 1)
    frame = {"frame", query_ms(0, stamps.size() - 1), wall_ms(0, wall_.size() - 1)};
  return passes;
}

}  // namespace thalassa::gl
