// Output that never destroys a user's files (see safe_output.hpp; issue #13).
#include "demfit/identify/safe_output.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace demfit::identify {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail_write(const fs::path& path, const fs::path& temporary, int error, const char* step) {
  ::unlink(temporary.c_str());
  throw std::runtime_error("writing '" + path.string() + "' failed (" + step + ": " + std::strerror(error) +
                           "); check free disk space and permissions");
}

int open_exclusive(const fs::path& temporary) {
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC;
  int fd = ::open(temporary.c_str(), flags, 0644);
  if (fd < 0 && errno == EEXIST) {
    // A leftover of an earlier process with our pid (or a planted link): unlink removes the
    // entry itself, never what a link points to.
    ::unlink(temporary.c_str());
    fd = ::open(temporary.c_str(), flags, 0644);
  }
  return fd;
}

// Absolute, with symbolic links of the existing part resolved, so "." and "a/.." compare equal.
fs::path resolved(const fs::path& path) {
  std::error_code error;
  fs::path out = fs::weakly_canonical(fs::absolute(path, error), error);
  return error ? fs::absolute(path).lexically_normal() : out;
}

// True when `inner` is `outer` or lies below it.
bool is_within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

bool folder_is_empty(const fs::path& folder) {
  std::error_code error;
  return fs::directory_iterator(folder, error) == fs::directory_iterator() && !error;
}

// The rules every output folder obeys; returns true when the folder exists (and is allowed).
bool check_folder(const fs::path& folder, const std::vector<fs::path>& inputs, const std::string& option,
                  bool replace) {
  if (folder.empty()) throw std::runtime_error(option + ": empty folder name; give a new folder, e.g. results/run1");
  check_user_text(option, folder.string());
  const fs::path target = resolved(folder);
  const fs::path cwd = resolved(fs::current_path());
  std::string shown = "'";  // appended: GCC 12 warns (-Wrestrict) on "literal" + string
  shown += folder.string();
  shown += "'";
  if (target == cwd)
    throw std::runtime_error(option + ": " + shown +
                             " is the working folder; demfit writes into a folder of its own, "
                             "give a new name such as results/run1");
  if (is_within(cwd, target))
    throw std::runtime_error(option + ": " + shown + " is a parent of the working folder; give a new folder name");
  std::error_code error;
  const fs::file_status status = fs::symlink_status(folder, error);
  if (!fs::exists(status)) return false;
  if (fs::is_symlink(status))
    throw std::runtime_error(option + ": " + shown +
                             " is a symbolic link; give a real folder (demfit does not write through links)");
  if (!fs::is_directory(status))
    throw std::runtime_error(option + ": " + shown + " is an existing file, not a folder; choose another name");
  const bool marked = fs::exists(fs::symlink_status(folder / kOutputMarker, error));
  if (replace) {
    for (const fs::path& input : inputs)
      if (!input.empty() && is_within(resolved(input), target))
        throw std::runtime_error(option + ": " + shown + " holds the input '" + input.string() +
                                 "'; demfit would overwrite it: give a new output folder");
  }
  if (!marked && !folder_is_empty(folder))
    throw std::runtime_error(option + ": " + shown + " exists and was not created by demfit (no " + kOutputMarker +
                             " inside); choose a new folder, or add an empty " + kOutputMarker +
                             " file to let demfit replace its content");
  return true;
}

bool process_alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

}  // namespace

void write_file_atomically(const fs::path& path, const std::string& content) {
  if (path.filename().empty()) throw std::runtime_error("cannot write '" + path.string() + "': not a file name");
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  std::error_code error;
  if (fs::is_directory(fs::symlink_status(path, error)))
    throw std::runtime_error("cannot write '" + path.string() + "': it is a folder; give a file name");
  // The pid keeps concurrent processes, the sequence number concurrent threads of one process
  // (two evaluations caching the same fill) from sharing a temporary; remove_stale_temporaries
  // knows the form "<name>.tmp<pid>-<sequence>".
  static std::atomic<unsigned long> sequence{0};
  fs::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(sequence.fetch_add(1));
  const int fd = open_exclusive(temporary);
  if (fd < 0)
    throw std::runtime_error("cannot write '" + path.string() + "': " + std::strerror(errno) +
                             "; check the folder permissions");
  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = n < 0 ? errno : ENOSPC;
      ::close(fd);
      fail_write(path, temporary, e, "write");
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) fail_write(path, temporary, errno, "close");
  // rename() replaces the directory entry: a symbolic link at `path` is replaced, not followed.
  if (::rename(temporary.c_str(), path.c_str()) != 0) fail_write(path, temporary, errno, "rename");
}

void check_user_text(const std::string& field, const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02X", c);
      throw std::runtime_error(field + ": contains a control character (byte " + code + " at position " +
                               std::to_string(i) + "); use printable text");
    }
  }
}

std::string safe_slug(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool keep =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    out += keep ? c : '_';
    if (out.size() >= 80) break;
  }
  while (!out.empty() && out.front() == '.') out.front() = '_';
  return out.empty() ? "unnamed" : out;
}

fs::path path_inside(const fs::path& folder, const std::string& file_name) {
  check_user_text("file name", file_name);
  if (file_name.empty() || file_name == "." || file_name == ".." || file_name.find('/') != std::string::npos)
    throw std::runtime_error("file name '" + file_name + "' would leave the output folder '" + folder.string() + "'");
  return folder / file_name;
}

void prepare_output_folder(const fs::path& folder, const std::vector<fs::path>& inputs, const std::string& option) {
  const bool exists = check_folder(folder, inputs, option, /*replace=*/false);
  if (!exists) {
    std::error_code error;
    fs::create_directories(folder, error);
    if (error) throw std::runtime_error(option + ": cannot create '" + folder.string() + "': " + error.message());
  }
  if (!fs::exists(fs::symlink_status(folder / kOutputMarker))) mark_output_folder(folder, option);
  remove_stale_temporaries(folder);
}

void check_output_folder(const fs::path& folder, const std::vector<fs::path>& inputs, const std::string& option) {
  check_folder(folder, inputs, option, /*replace=*/false);
}

void check_replaceable_folder(const fs::path& folder, const std::vector<fs::path>& inputs, const std::string& option) {
  check_folder(folder, inputs, option, /*replace=*/true);
}

void mark_output_folder(const fs::path& folder, const std::string& command) {
  write_file_atomically(folder / kOutputMarker, "This folder was created by demfit (" + command +
                                                    "). demfit may replace it or the files in it on a later run.\n");
}

int remove_stale_temporaries(const fs::path& folder) {
  int removed = 0;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    const auto at = name.rfind(".tmp");
    if (at == std::string::npos || at + 4 >= name.size()) continue;
    std::string digits = name.substr(at + 4);
    const auto dash = digits.find('-');  // "<pid>-<sequence>" (older files: "<pid>")
    if (dash != std::string::npos) {
      if (dash == 0 || digits.find_first_not_of("0123456789", dash + 1) != std::string::npos) continue;
      digits.resize(dash);
    }
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
    const long pid = std::stol(digits);
    if (pid == static_cast<long>(::getpid()) || process_alive(pid)) continue;
    if (!fs::is_regular_file(entry.symlink_status()) && !fs::is_symlink(entry.symlink_status())) continue;
    std::error_code ignored;
    if (fs::remove(entry.path(), ignored)) ++removed;
  }
  return removed;
}

}  // namespace demfit::identify
