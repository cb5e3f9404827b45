// Output that never destroys a user's files (see safe_output.hpp): the atomic writer, user text
// and file names, bounded reading of input files.
#include "demfit/identify/safe_output.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace demfit::identify {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail_write(const fs::path& path, const fs::path& temporary, int error, const char* step) {
  ::unlink(temporary.c_str());
  throw std::runtime_error("writing " + quote_path(path) + " failed (" + step + ": " + std::strerror(error) +
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

// The code point of a Unicode bidirectional control (U+202A..U+202E, U+2066..U+2069) whose UTF-8
// form (E2 80 AA..AE, E2 81 A6..A9) starts at text[i], else 0.
unsigned bidi_control_at(const std::string& text, std::size_t i) {
  if (i + 2 >= text.size() || static_cast<unsigned char>(text[i]) != 0xE2) return 0;
  const auto b = static_cast<unsigned char>(text[i + 1]), d = static_cast<unsigned char>(text[i + 2]);
  if ((b == 0x80 && d >= 0xAA && d <= 0xAE) || (b == 0x81 && d >= 0xA6 && d <= 0xA9))
    return (b == 0x80 ? 0x2000u : 0x2040u) + (d - 0x80u);
  return 0;
}

bool process_alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

}  // namespace

void write_file_atomically(const fs::path& path, const std::string& content) {
  if (path.filename().empty()) throw std::runtime_error("cannot write " + quote_path(path) + ": not a file name");
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  std::error_code error;
  if (fs::is_directory(fs::symlink_status(path, error)))
    throw std::runtime_error("cannot write " + quote_path(path) + ": it is a folder; give a file name");
  // The pid keeps concurrent processes, the sequence number concurrent threads of one process
  // (two evaluations caching the same fill) from sharing a temporary; remove_stale_temporaries
  // knows the form "<name>.tmp<pid>-<sequence>".
  static std::atomic<unsigned long> sequence{0};
  fs::path temporary = path;
  temporary += ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(sequence.fetch_add(1));
  const int fd = open_exclusive(temporary);
  if (fd < 0)
    throw std::runtime_error("cannot write " + quote_path(path) + ": " + std::strerror(errno) +
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
    const unsigned bidi = bidi_control_at(text, i);
    if (c >= 0x20 && c != 0x7f && bidi == 0) continue;
    char code[24];
    if (bidi != 0)
      std::snprintf(code, sizeof code, "U+%04X", bidi);
    else
      std::snprintf(code, sizeof code, "byte 0x%02X", c);
    throw std::runtime_error(field + ": contains a " + (bidi != 0 ? "bidirectional " : "") + "control character (" +
                             code + " at position " + std::to_string(i) + "); use printable text");
  }
}

std::string safe_slug(const std::string& text) {
  constexpr std::size_t kMaxSlug = 80;
  std::string out;
  for (char c : text) {
    const bool keep =
        (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    out += keep ? c : '_';
  }
  while (!out.empty() && out.front() == '.') out.front() = '_';
  if (out.empty()) return "unnamed";
  if (out.size() <= kMaxSlug) return out;
  // Shortened: the extension kept (the file's type), a hash of the whole text (unique names).
  const auto dot = out.rfind('.');
  const std::string extension = dot != std::string::npos && out.size() - dot <= 8 ? out.substr(dot) : "";
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a, 64 bit
  for (char c : text) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  char digits[20];
  std::snprintf(digits, sizeof digits, "-%012llx", static_cast<unsigned long long>(hash & 0xffffffffffffull));
  return out.substr(0, kMaxSlug - extension.size() - std::strlen(digits)) + digits + extension;
}

std::string printable(const std::string& text) {
  std::string out;
  char code[12];
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      std::snprintf(code, sizeof code, "\\x%02X", c);
      out += code;
      continue;
    }
    if (const unsigned bidi = bidi_control_at(text, i)) {
      std::snprintf(code, sizeof code, "\\u%04X", bidi);
      out += code;
      i += 2;
      continue;
    }
    out += static_cast<char>(c);
  }
  return out;
}

std::string quote_path(const fs::path& path) {
  std::string out = "'";  // appended: GCC 12 warns (-Wrestrict) on "literal" + string
  out += printable(path.string());
  out += "'";
  return out;
}

std::string read_input_file(const fs::path& path, std::size_t max_bytes, const std::string& what) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then tells what the path is.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw std::runtime_error(what + " cannot be opened (" + std::strerror(errno) + "); check the path");
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    const bool folder = S_ISDIR(info.st_mode);
    ::close(fd);
    throw std::runtime_error(what + (folder ? " is a folder" : " is not a regular file (a device, pipe or socket)") +
                             "; give the path of a file");
  }
  if (static_cast<std::uint64_t>(info.st_size) > max_bytes) {
    ::close(fd);
    throw std::runtime_error(what + ": " + std::to_string(info.st_size) + " bytes, above the limit of " +
                             std::to_string(max_bytes) + " bytes");
  }
  std::string content;
  char buffer[65536];
  for (;;) {  // at most max_bytes + 1 bytes: a file that grows while read is refused, not followed
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      throw std::runtime_error(what + " cannot be read (" + std::strerror(e) + ")");
    }
    if (n == 0) break;
    content.append(buffer, static_cast<std::size_t>(n));
    if (content.size() > max_bytes) {
      ::close(fd);
      throw std::runtime_error(what + ": more than " + std::to_string(max_bytes) + " bytes, above the limit");
    }
  }
  ::close(fd);
  return content;
}

void check_user_file(const fs::path& path, bool overwrite, const std::string& option) {
  check_user_text(option, path.string());
  std::error_code error;
  const fs::file_status status = fs::symlink_status(path, error);
  if (fs::exists(status)) {
    if (fs::is_symlink(status))
      throw std::runtime_error(option + ": " + quote_path(path) +
                               " is a symbolic link; demfit replaces only regular files: give a new file name");
    if (!fs::is_regular_file(status))
      throw std::runtime_error(option + ": " + quote_path(path) +
                               " exists and is not a regular file (a folder, device or pipe); give a new file name");
    if (!overwrite)
      throw std::runtime_error(option + ": " + quote_path(path) +
                               " already exists; give a new file name, or add --force to replace it");
  }
  if (path.has_parent_path() && !fs::is_directory(path.parent_path(), error))
    throw std::runtime_error(option + ": the folder of " + quote_path(path) + " does not exist; create it first");
}

void write_user_file(const fs::path& path, const std::string& content, bool overwrite, const std::string& option) {
  check_user_file(path, overwrite, option);
  write_file_atomically(path, content);
}

fs::path path_inside(const fs::path& folder, const std::string& file_name) {
  check_user_text("file name", file_name);
  if (file_name.empty() || file_name == "." || file_name == ".." || file_name.find('/') != std::string::npos)
    throw std::runtime_error("file name " + quote_path(file_name) + " would leave the output folder " +
                             quote_path(folder));
  return folder / file_name;
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
