// Running external programs (engine/include/thalassa/engine/program.hpp): the lookup in $PATH,
// the exit status, the log, and a working folder with a log path relative to the caller's.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "thalassa/engine/program.hpp"

namespace thalassa {
namespace {

namespace fs = std::filesystem;

TEST(Program, FindsProgramsOnThePathAndByPath) {
  const std::string sh = find_program("sh");
  ASSERT_FALSE(sh.empty());
  EXPECT_EQ(find_program(sh), sh);  // a path is taken as it is
  EXPECT_EQ(find_program("thalassa-no-such-program"), "");
  EXPECT_EQ(find_program("/no/such/folder/sh"), "");
}

TEST(Program, ReturnsTheExitStatusAndLogsBothStreamsRelativeToTheCaller) {
  const fs::path dir = fs::temp_directory_path() / ("thalassa_program_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "work");
  const fs::path previous = fs::current_path();
  fs::current_path(dir);
  // The child runs in work/ and writes there; its log is named relative to dir.
  const int status = run_program({"sh", "-c", "echo out; echo err >&2; pwd > where.txt; exit 3"},
                                 "log.txt", "work");
  fs::current_path(previous);
  EXPECT_EQ(status, 3);
  std::ifstream log(dir / "log.txt");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_EQ(text.str(), "out\nerr\n");
  EXPECT_TRUE(fs::is_regular_file(dir / "work" / "where.txt"));
  EXPECT_EQ(run_program({"thalassa-no-such-program"}, (dir / "log2.txt").string()), -1);
  EXPECT_EQ(run_program({}, (dir / "log3.txt").string()), -1);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thalassa
