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
  current_.wall.push_back(std::chrono::steady_clock::now());
  current_.queries.push_back(make_query(GL_TIMESTAMP));
  glQueryCounter(current_.queries.back().get(), GL_TIMESTAMP);
}

void GpuTimer::begin_frame() {
  current_ = Marks{};
  mark();
}

void GpuTimer::end_pass(const std::string& name) {
  mark();
  current_.names.push_back(name);
}

std::vector<PassTime> GpuTimer::resolve(PassTime& frame) { return resolve(current_, frame); }

void GpuTimer::defer_frame() {
  deferred_.push_back(std::move(current_));
  current_ = Marks{};
}

std::vector<GpuTimer::FrameTimes> GpuTimer::resolve_deferred() {
  std::vector<FrameTimes> frames(deferred_.size());
  for (std::size_t i = 0; i < deferred_.size(); ++i)
    frames[i].passes = resolve(deferred_[i], frames[i].frame);
  deferred_.clear();
  return frames;
}

std::vector<PassTime> GpuTimer::resolve(const Marks& marks, PassTime& frame) {
  const auto& queries = marks.queries;
  const auto& wall = marks.wall;
  std::vector<GLuint64> stamps(queries.size(), 0);
  for (std::size_t i = 0; i < queries.size(); ++i)
    glGetQueryObjectui64v(queries[i].get(), GL_QUERY_RESULT, &stamps[i]);  // waits
  const double host_ms = wall.empty() ? 0.0
                                      : std::chrono::duration<double, std::milli>(
                                            std::chrono::steady_clock::now() - wall.front())
                                            .count();
  auto query_ms = [&](std::size_t from, std::size_t to) {
    return timestamp_span_ms(stamps[from], stamps[to], host_ms);
  };
  auto wall_ms = [&](std::size_t from, std::size_t to) {
    if (source_ != TimingSource::FinishWallClock) return 0.0;  // unsynchronised: meaningless
    return std::chrono::duration<double, std::milli>(wall[to] - wall[from]).count();
  };
  std::vector<PassTime> passes;
  for (std::size_t i = 1; i < stamps.size(); ++i)
    passes.push_back({marks.names[i - 1], query_ms(i - 1, i).value_or(0.0), wall_ms(i - 1, i)});
  frame = {"frame", 0.0, 0.0};
  if (stamps.size() > 1) {
    const std::optional<double> span = query_ms(0, stamps.size() - 1);
    if (!span && source_ == TimingSource::TimestampQuery) ++fallback_frames_;
    frame = {"frame", span.value_or(host_ms), wall_ms(0, wall.size() - 1)};
  }
  return passes;
}

}  // namespace thalassa::gl
