#pragma once
// Helper programs (gnuplot, mpirun) run from an argument vector through fork/exec: no shell ever
// sees a user string. Output of the helper goes to /dev/null.
#include <filesystem>
#include <string>
#include <vector>

namespace demfit::identify {

// True when `program` is an executable file in one of the folders of $PATH.
bool program_available(const std::string& program);

// Runs argv[0] (searched in $PATH) with the arguments argv[1..] in `working_dir` (empty = the
// current folder), waits, and returns its exit status (127 when it cannot be started, 128 + signal
// when it was killed).
int run_program(const std::vector<std::string>& argv, const std::filesystem::path& working_dir = {});

}  // namespace demfit::identify
