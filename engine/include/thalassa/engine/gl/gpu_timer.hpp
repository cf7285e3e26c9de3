// thalassa — time of each pass of a frame on the GPU.
//
// Every mark takes a GL timestamp query (ARB_timer_query): the GPU's own clock, the figure to
// trust on a hardware driver, read back at the end of the frame. Mesa's llvmpipe stamps a query
// when the command is queued, before its rasterisation threads run, so its query times miss most
// of the work; for it (TimingSource::FinishWallClock) each mark first waits with glFinish() and
// reads the CPU's steady clock, and the finish-to-finish wall time is the true cost. Only that
// mode serialises the passes.
//
// A timestamp is checked before it is used: NVIDIA's driver (580.159, H200, the first GPU run of
// the validation suite) returned 0 for the first mark of a few reference frames, whose frame
// time then read as the GPU clock itself, 1.8e12 ms (its stamps are nanoseconds since 1970).
#pragma once

#include "thalassa/engine/gl/objects.hpp"

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace thalassa::gl {

enum class TimingSource {
  TimestampQuery,   // GL_TIMESTAMP differences
  FinishWallClock,  // steady clock between glFinish() marks
};

struct PassTime {
  std::string name;
  double query_ms = 0;  // from GL timestamp queries
  double wall_ms = 0;   // from the steady clock between finished marks
};

// The span from timestamp `from` to `to` (ns, GL_TIMESTAMP), ms; none where it cannot be a span
// of the frame: either stamp is 0 (a query that stamped nothing), it runs backwards, or it is
// longer than `host_bound_ms`, the host's steady-clock time from the frame's first mark to its
// results read back, which bounds every GPU span of the frame from above.
std::optional<double> timestamp_span_ms(std::uint64_t from, std::uint64_t to,
                                        double host_bound_ms);

class GpuTimer {
 public:
  // The source that `frame_ms` of the statistics uses for this renderer string: the wall clock
  // for Mesa's software rasterisers (llvmpipe, softpipe), the queries otherwise.
  static TimingSource source_for_renderer(const std::string& gl_renderer);

  explicit GpuTimer(TimingSource source = TimingSource::TimestampQuery) : source_(source) {}
  TimingSource source() const { return source_; }

  // Starts a frame.
  void begin_frame();
  // Marks the end of the pass called `name` (the pass ran since the previous mark).
  void end_pass(const std::string& name);
  // Waits for the queries; the passes in order. `frame` gets the whole frame's times. wall_ms
  // is 0 in TimestampQuery mode. Where the frame's timestamps are unusable (timestamp_span_ms),
  // its query_ms is the host's time from the first mark to the results read back, an upper
  // bound, a pass's unusable span is 0, and fallback_frames() counts the frame.
  std::vector<PassTime> resolve(PassTime& frame);
  // Frames resolved so far whose timestamps were unusable (TimestampQuery mode).
  int fallback_frames() const { return fallback_frames_; }

  // Frames in flight: defer_frame() keeps the frame since begin_frame() with its queries unread,
  // so that the next frame can be queued without waiting for this one's results (the
  // reference's thousands of samples a frame); resolve_deferred() waits for them all and gives
  // each frame's times as resolve() would, oldest first. A deferred frame's host bound runs from
  // its first mark to the time its results were read back, which is later than resolve()'s and so
  // still an upper bound of its spans.
  struct FrameTimes {
    PassTime frame;
    std::vector<PassTime> passes;
  };
  void defer_frame();
  std::size_t deferred_frames() const { return deferred_.size(); }
  std::vector<FrameTimes> resolve_deferred();

 private:
  struct Marks {
    std::vector<Query> queries;  // one per mark: frame start, then one per pass
    std::vector<std::chrono::steady_clock::time_point> wall;
    std::vector<std::string> names;
  };
  void mark();
  std::vector<PassTime> resolve(const Marks& marks, PassTime& frame);
  TimingSource source_;
  Marks current_;
  std::vector<Marks> deferred_;
  int fallback_frames_ = 0;
};

}  // namespace thalassa::gl
