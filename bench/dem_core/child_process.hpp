#pragma once
// Run a helper program (LIGGGHTS, mpirun, this benchmark as a child) from an argument vector with
// fork/execvp: no shell, no quoting. Its stdout+stderr go to a file; its resources are measured.
#include <filesystem>
#include <string>
#include <vector>

namespace demfit::bench {

struct ChildResult {
  bool started = false;  ///< false when the program could not be executed
  int exit_code = -1;    ///< exit status, or -1 when killed by a signal / not started
  double wall_seconds = 0.0;
  double cpu_seconds = 0.0;    ///< user + system of the child (and its children)
  double max_rss_bytes = 0.0;  ///< peak resident set of the child (ru_maxrss)
};

/// Run argv[0] (looked up on PATH) with the arguments argv[1..] in `working_dir` (empty = ours),
/// stdout and stderr appended to `output` (truncated first). Waits for it.
ChildResult run_child(const std::vector<std::string>& argv, const std::filesystem::path& working_dir,
                      const std::filesystem::path& output);

/// Full path of a program on PATH, or empty.
std::string find_on_path(const std::string& name);

}  // namespace demfit::bench
