// thalassa — running the cases of a validation suite (issue 6, point 4): each case rendered with
// each of its methods and light terms (and its flicker frames), its images written, every method
// measured against the case's reference (metrics.hpp) and timed apart (Suite::timing). What
// `thalassa validate` does for each case, for a program that runs suites itself and writes the
// report with write_report (report.hpp). Needs a current GL context (planet/renderer.hpp).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "thalassa/engine/context.hpp"
#include "thalassa/planet/renderer.hpp"
#include "thalassa/validation/report.hpp"
#include "thalassa/validation/suite.hpp"

namespace thalassa::validation {

// CaseResult::exit_status of a case, as `thalassa validate` would exit on it (DESIGN section 5).
inline constexpr int kCaseRendered = 0;
inline constexpr int kCaseRuntimeFailure = 1;  // a frame not finite, a GL or shader error
inline constexpr int kCaseInvalidInput = 2;    // a scene the checks refuse (SceneError)

// What a run tells as it goes, for a progress bar or a log; each may be left empty.
struct CaseProgress {
  // One render (a method's term, one frame) or one method's timing done in `seconds` of wall
  // clock, e.g. "full, sun, frame 0: 5 ms (1 samples)".
  std::function<void(const std::string& case_name, const std::string& detail, double seconds)> done;
  // A case refused before any render (its scene cannot be drawn), and why.
  std::function<void(const std::string& case_name, const std::string& why)> skipped;
  // A line of its own: what a render worked around (RenderStats::warnings).
  std::function<void(const std::string& message)> note;
};

struct CaseRunOptions {
  // The report's folder: each image goes to DIR/images/<case>_<method>_<term>.png (and .exr),
  // relative paths in the result. DIR/images must exist.
  std::string dir;
  bool write_exr = true;  // false: the PNGs alone (thalassa validate --no-exr)
  CaseProgress progress;
  // The sky provider kept between the renders (planet/renderer.hpp): give one to keep it from
  // case to case too (all in `context`); none: each case keeps its own.
  std::shared_ptr<SkyProviderCache> sky_cache;
};

// Renders case `c` of `suite` (its methods, the variants' own references, every term and the
// flicker frames), writes its images and measures them: a CaseResult without the fields the
// caller knows (fingerprint, sea_of, sea, gl_version). Failures end the case rather than throw:
// a scene the checks refuse with kCaseInvalidInput (before any render, told to
// progress.skipped), a frame that is not finite, a GL or shader error or an image that cannot
// be written with kCaseRuntimeFailure, each with its message (CaseResult::passed compares them
// with what the case expects).
CaseResult run_case(const Suite& suite, GlContext& context, const SuiteCase& c,
                    const CaseRunOptions& options);

// Times the methods of a case kept from an earlier report (thalassa validate --resume) again at
// the suite's timing settings, without rendering its images; a failure sets the result's exit
// status and message.
void retime_case(const Suite& suite, GlContext& context, const SuiteCase& c, CaseResult& result,
                 const CaseRunOptions& options);

// How many times run_case calls progress.done for `c` (one call to progress.skipped instead, for
// a case expected to be refused), for a progress bar's total.
int render_count(const Suite& suite, const SuiteCase& c);
// How many times retime_case calls progress.done for a kept case: 0 when it need not be timed
// again (Suite::timing is what it was timed at, or the suite times nothing).
int retime_count(const Suite& suite, const CaseResult& kept);

}  // namespace thalassa::validation
