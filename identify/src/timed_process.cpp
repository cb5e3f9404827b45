// External program runs with a wall-time limit (timed_process.hpp): fork + execve, own process
// group so that a timeout kills the program and every process it started.
#include "timed_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

extern char** environ;

namespace demfit::identify::detail {
namespace {

std::vector<std::string> merged_environment(const std::vector<std::string>& replacements) {
  std::vector<std::string> out;
  for (char** e = environ; e && *e; ++e) {
    const std::string entry(*e);
    const std::string name = entry.substr(0, entry.find('='));
    bool replaced = false;
    for (const auto& r : replacements) replaced = replaced || r.substr(0, r.find('=')) == name;
    if (!replaced) out.push_back(entry);
  }
  out.insert(out.end(), replacements.begin(), replacements.end());
  return out;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (auto& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

// Child side, between fork and exec: async-signal-safe calls only. On failure the errno goes
// through the close-on-exec pipe, so the parent can say why the program did not start.
[[noreturn]] void exec_child(const char* program, char* const* argv, char* const* envp, const char* dir, int report) {
  ::setpgid(0, 0);
  int error = 0;
  if (::chdir(dir) != 0) error = errno;
  const int in = ::open("/dev/null", O_RDONLY);
  const int out = ::open("stdout.txt", O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
  const int err = ::open("stderr.txt", O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
  if (!error && (in < 0 || out < 0 || err < 0)) error = errno;
  if (!error) {
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    ::execve(program, argv, envp);
    error = errno;
  }
  [[maybe_unused]] const ssize_t written = ::write(report, &error, sizeof error);
  ::_exit(127);
}

}  // namespace

TimedProcessResult run_timed_process(const std::string& program, const std::vector<std::string>& argv,
                                     const std::filesystem::path& working_dir, double time_limit_s,
                                     const std::vector<std::string>& environment) {
  TimedProcessResult result;
  std::vector<std::string> args = argv, env = merged_environment(environment);
  std::vector<char*> arg_pointers = pointers(args), env_pointers = pointers(env);
  const std::string dir = working_dir.string();
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) {
    result.start_error = std::strerror(errno);
    return result;
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child < 0) {
    result.start_error = std::strerror(errno);
    ::close(report[0]);
    ::close(report[1]);
    return result;
  }
  if (child == 0) exec_child(program.c_str(), arg_pointers.data(), env_pointers.data(), dir.c_str(), report[1]);
  ::setpgid(child, child);  // also here: the group exists whichever process runs first
  ::close(report[1]);
  const auto limit = std::chrono::duration<double>(time_limit_s);
  // The program's end is observed without reaping it (WNOWAIT): until it is reaped its pid, and so
  // its process group id, cannot be given to another process, so the group kill below can only
  // reach what the program started.
  bool timed_out = false;
  for (auto pause = std::chrono::milliseconds(1);;) {
    siginfo_t info{};
    const int waited = ::waitid(P_PID, static_cast<id_t>(child), &info, WEXITED | WNOHANG | WNOWAIT);
    if ((waited == 0 && info.si_pid == child) || (waited < 0 && errno != EINTR)) break;
    if (std::chrono::steady_clock::now() - start >= limit) {
      timed_out = true;
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
  ::kill(-child, SIGKILL);  // on timeout the program and its group; else what it left running
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  int exec_error = 0;
  if (::read(report[0], &exec_error, sizeof exec_error) == static_cast<ssize_t>(sizeof exec_error) && exec_error) {
    result.start_error = std::strerror(exec_error);
  } else if (timed_out) {
    result.ending = TimedProcessResult::Ending::timed_out;
  } else if (WIFEXITED(status)) {
    result.ending = TimedProcessResult::Ending::exited;
    result.code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.ending = TimedProcessResult::Ending::signalled;
    result.code = WTERMSIG(status);
  }
  ::close(report[0]);
  return result;
}

std::string describe_ending(const TimedProcessResult& result, double time_limit_s) {
  char text[128];
  switch (result.ending) {
    case TimedProcessResult::Ending::exited:
      std::snprintf(text, sizeof text, "exit status %d", result.code);
      return text;
    case TimedProcessResult::Ending::signalled:
      std::snprintf(text, sizeof text, "killed by signal %d", result.code);
      return text;
    case TimedProcessResult::Ending::timed_out:
      std::snprintf(text, sizeof text, "exceeded the time limit of %g s (killed)", time_limit_s);
      return text;
    case TimedProcessResult::Ending::not_started:
      return "could not be started: " + result.start_error;
  }
  return "?";
}

}  // namespace demfit::identify::detail
