// The command line's progress reporter (apps/progress.hpp), shared by `thalassa fly` and
// `thalassa validate`: its log lines when stderr is not a terminal, and its durations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "progress.hpp"

namespace thalassa::cli {
namespace {

std::string contents(std::FILE* file) {
  std::fflush(file);
  std::rewind(file);
  std::string text;
  for (int c; (c = std::fgetc(file)) != EOF;) text += static_cast<char>(c);
  return text;
}

TEST(Progress, LogLinesCountStepsAndEstimateTheTimeLeftFromWorkedStepsOnly) {
  std::FILE* log = std::tmpfile();  // not a terminal: one line per step
  ASSERT_NE(log, nullptr);
  ProgressBar progress(4, "renders", log);
  progress.skipped("case_a/full", "already written");
  progress.done("case_a/basic", "sun: 0.50 s", 0.5);
  progress.note("case_a/basic: warning: a lattice scattered again");  // a line of its own
  progress.done("case_b/full", "sun: 1.50 s", 1.5);
  progress.finish();
  // 2 steps in 2 s: 1 step/s, 1 step left.
  EXPECT_EQ(contents(log),
            "case_a/full [1/4]: skipped (already written)\n"
            "case_a/basic [2/4] sun: 0.50 s | 2.00 renders/s, 1s left\n"
            "thalassa: case_a/basic: warning: a lattice scattered again\n"
            "case_b/full [3/4] sun: 1.50 s | 1.00 renders/s, 1s left\n");
  EXPECT_EQ(progress.done_count(), 3);
  EXPECT_EQ(progress.worked_count(), 2);
  EXPECT_EQ(progress.skipped_count(), 1);
  std::fclose(log);
}

TEST(Progress, DurationsReadAsHoursMinutesSeconds) {
  EXPECT_EQ(duration_text(42.4), "42s");
  EXPECT_EQ(duration_text(185), "3m05s");
  EXPECT_EQ(duration_text(3723), "1h02m03s");
  EXPECT_EQ(duration_text(-1), "?");
  EXPECT_EQ(duration_text(NAN), "?");
}

}  // namespace
}  // namespace thalassa::cli
