#pragma once
// Internal: one external program run from an argument vector (never a shell), in its own process
// group, with a wall-time limit after which the whole group is killed.
#include <filesystem>
#include <string>
#include <vector>

namespace demfit::identify::detail {

struct TimedProcessResult {
  enum class Ending { exited, signalled, timed_out, not_started };
  Ending ending = Ending::not_started;
  int code = 0;             // exit status (exited) or signal number (signalled)
  std::string start_error;  // not_started: why exec failed (strerror text)
  double wall_seconds = 0.0;
};

// Runs `program` (an absolute path) with argv (argv[0] as given) in `working_dir`; standard
// input is /dev/null, standard output and error go to stdout.txt and stderr.txt in working_dir.
// `environment` entries ("NAME=value") replace those of the same name in this process's
// environment. After time_limit_s [s] the process group receives SIGKILL; once the program has
// ended, whatever it left running in its group is killed too.
TimedProcessResult run_timed_process(const std::string& program, const std::vector<std::string>& argv,
                                     const std::filesystem::path& working_dir, double time_limit_s,
                                     const std::vector<std::string>& environment);

// One line for an error message: "exit status 3", "killed by signal 11", "exceeded the time limit
// of 600 s (killed)", "could not be started: No such file or directory".
std::string describe_ending(const TimedProcessResult& result, double time_limit_s);

}  // namespace demfit::identify::detail
