#pragma once
// Running demfit on hostile inputs: a sandbox folder per input (work/ is the working
// folder of the command, outside/ stands for the rest of the user's disk), the command run from an
// argument vector (no shell), and a snapshot of every file so that a test can assert that nothing
// outside the output folder changed and that no partial output remained.
#include <sys/resource.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace trust {
namespace fs = std::filesystem;

struct Result {
  int status = -1;
  std::string out, err;
};

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

struct Sandbox {
  fs::path root, work, outside;
  explicit Sandbox(const std::string& name) {
    root = fs::path(DEMFIT_BINARY_DIR) / "trust_scratch" / name;
    fs::remove_all(root);
    work = root / "work";
    outside = root / "outside";
    fs::create_directories(work);
    fs::create_directories(outside);
    write_text(outside / "precious.txt", "a file of the user that no command may touch\n");
  }
  // demfit with `args` in work/; file_size_limit > 0 simulates a full disk (RLIMIT_FSIZE, SIGXFSZ
  // ignored so that write() fails with EFBIG as on a full disk).
  Result run(const std::vector<std::string>& args, long file_size_limit = 0) const {
    const fs::path out = root / "stdout.txt", err = root / "stderr.txt";
    const pid_t child = fork();
    if (child == 0) {
      chdir(work.c_str());
      const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(o, 1);
      dup2(e, 2);
      setenv("DEMFIT_CACHE_DIR", (root / "cache").c_str(), 1);
      if (file_size_limit > 0) {
        signal(SIGXFSZ, SIG_IGN);
        rlimit limit{static_cast<rlim_t>(file_size_limit), static_cast<rlim_t>(file_size_limit)};
        setrlimit(RLIMIT_FSIZE, &limit);
      }
      std::vector<char*> argv{const_cast<char*>(DEMFIT_EXE)};
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(DEMFIT_EXE, argv.data());
      _exit(127);
    }
    int status = 0;
    waitpid(child, &status, 0);
    Result r;
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
  }
};

// A folder name for a sandbox from a description.
inline std::string safe_name(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

// Every file and link below `dir` with its content (links: their target), skipping `skip`.
inline std::map<std::string, std::string> snapshot(const fs::path& dir, const fs::path& skip = {}) {
  std::map<std::string, std::string> files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    const fs::path p = it->path();
    if (!skip.empty() && (p == skip || p.string().rfind(skip.string() + "/", 0) == 0)) {
      it.disable_recursion_pending();
      continue;
    }
    const auto status = fs::symlink_status(p);
    if (fs::is_symlink(status))
      files[p.string()] = "link -> " + fs::read_symlink(p).string();
    else if (fs::is_regular_file(status))
      files[p.string()] = read_text(p);
    else if (fs::is_directory(status))
      files[p.string()] = "<dir>";
  }
  return files;
}

// Temporaries or staging folders anywhere below dir (partial output).
inline std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp") != std::string::npos || name.find(".partial-") != std::string::npos) found.push_back(name);
  }
  return found;
}

}  // namespace trust
