// thalassa — running the external programs the command line and the report use (ffmpeg for a
// flight's video, gnuplot for the validation report's plots).
#pragma once

#include <string>
#include <vector>

namespace thalassa {

// The executable `program` names: itself when it contains a '/' (and is executable), else the
// first executable of that name in $PATH's folders; "" when there is none.
std::string find_program(const std::string& program);

// Runs argv[0] (a path, or a name looked up in $PATH) with argv, stdin from /dev/null and stdout
// and stderr into the file `log`, in `working_dir` when it is not empty (`log` is taken relative
// to the caller's folder, not that one). Returns its exit status, or -1 when it could not be
// started or did not exit normally.
int run_program(const std::vector<std::string>& argv, const std::string& log,
                const std::string& working_dir = "");

}  // namespace thalassa
