#include "thalassa/engine/gl/gpu_timer.hpp"

namespace thalassa::gl {

namespace {
constexpr double kNanosecondsPerMillisecond = 1e6;
// The GPU's and the host's clocks tick at rates that may differ by far less than this, and the
// host's bound is read after the last result: 1 % and 0.1 ms of slack keep a true span inside.
constexpr double kHostBoundRelativeSlack = 0.01;
constexpr double kHostBoundSlackMs = 0.1;
}  // namespace

std::optional<double> timestamp_span_ms(std::uint64_t from, std::uint64_t to,
                                        double host_bound_ms) {
  if (from == 0 || to == 0 || to < from) return std::nullopt;
  const double ms = double(to - from) / kNanosecondsPerMillisecond;
  if (!(ms <= host_bound_ms * (1.0 + kHostBoundRelativeSlack) + kHostBoundSlackMs))
    return std::nullopt;
  return ms;
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
  const double host_ms =
      wall_.empty() ? 0.0
                    : std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() -
                                                                wall_.front())
                          .count();
  auto query_ms = [&](std::size_t from, std::size_t to) {
    return timestamp_span_ms(stamps[from], stamps[to], host_ms);
  };
  auto wall_ms = [&](std::size_t from, std::size_t to) {
    if (source_ != TimingSource::FinishWallClock) return 0.0;  // unsynchronised: meaningless
    return std::chrono::duration<double, std::milli>(wall_[to] - wall_[from]).count();
  };
  std::vector<PassTime> passes;
  for (std::size_t i = 1; i < stamps.size(); ++i)
    passes.push_back({names_[i - 1], query_ms(i - 1, i).value_or(0.0), wall_ms(i - 1, i)});
  frame = {"frame", 0.0, 0.0};
  if (stamps.size() > 1) {
    const std::optional<double> span = query_ms(0, stamps.size() - 1);
    if (!span && source_ == TimingSource::TimestampQuery) ++fallback_frames_;
    frame = {"frame", span.value_or(host_ms), wall_ms(0, wall_.size() - 1)};
  }
  return passes;
}

}  // namespace thalassa::gl
